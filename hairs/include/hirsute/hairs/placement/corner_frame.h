// The frames organs are oriented by at the corners of a segment's faces (Fuhrer, Jensen &
// Prusinkiewicz 2004, Sec. 4.4; docs/design.md, "Placement"): the frame (d, d × h, d × (d × h)) of
// a direction d (the shading normal, or the edge vector h × n on an edge) and the face's height
// vector h, reoriented by incline and wrap.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace hirsute {

// Rotation of v about the unit axis by angle (radians), Rodrigues' formula.
inline glm::vec3 rotate(const glm::vec3& v, const glm::vec3& axis, float angle) {
  if (angle == 0.0f) return v;
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0f - c));
}

inline glm::vec3 normalizedOr(const glm::vec3& v, const glm::vec3& otherwise) {
  const float length = glm::length(v);
  return length > 1e-12f && std::isfinite(length) ? v / length : otherwise;
}

// A perpendicular of the unit vector n (for frames where h runs along n).
inline glm::vec3 anyPerpendicular(const glm::vec3& n) {
  const glm::vec3 other = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(n, other));
}

// The vectors an organ's direction is interpolated from, at one face corner: its direction after
// incline and wrap, and the incline axis carried with it (the organ's second axis before twist).
struct CornerVectors {
  glm::vec3 direction;
  glm::vec3 across;
};

// Sec. 4.4: incline about the incline axis, then wrap about the wrapping axis, of the frame
// (d, d × h, d × (d × h)). Positive incline tilts the direction toward h (the segment's end);
// positive wrap tilts it toward d × h. Angles in radians.
inline CornerVectors reorient(const glm::vec3& d, const glm::vec3& h, float incline, float wrap) {
  glm::vec3 x = glm::cross(d, h);
  x = normalizedOr(x, anyPerpendicular(d));
  const glm::vec3 y = glm::cross(d, x);  // d × (d × h), normalised since d ⟂ x
  glm::vec3 direction = rotate(d, x, incline);
  direction = rotate(direction, y, wrap);
  const glm::vec3 across = rotate(x, y, wrap);
  return {direction, across};
}

}  // namespace hirsute
