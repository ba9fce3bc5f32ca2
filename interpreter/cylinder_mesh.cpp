#include "cylinder_mesh.h"

#include <cmath>
#include <cstdint>

namespace hirsute {

namespace {
constexpr double kTwoPi = 6.28318530717958647692;

void addTriangle(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}
}  // namespace

void appendCylinder(TriangleMesh& mesh, const CylinderEnds& ends) {
  const glm::dvec3 axis = ends.to - ends.from;
  const double length = glm::length(axis);
  const glm::dvec3 heading = length > 0 ? axis / length : glm::dvec3(0, 1, 0);
  // The turtle's L and U, made exactly perpendicular to the drawn axis.
  glm::dvec3 left = ends.left - heading * glm::dot(ends.left, heading);
  if (glm::dot(left, left) < 1e-24) left = glm::cross(heading, ends.up);
  left = glm::normalize(left);
  const glm::dvec3 up = glm::cross(left, heading);
  const bool textured = mesh.texture >= 0;
  const int sides = std::max(3, ends.sides);
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (int j = 0; j <= sides; ++j) {
    const double angle = kTwoPi * j / sides;
    const glm::dvec3 radial = left * std::cos(angle) + up * std::sin(angle);
    // A cone's normal leans along the axis by the radius change over the length.
    const glm::dvec3 normal =
        glm::normalize(radial * length + heading * (ends.radiusFrom - ends.radiusTo));
    mesh.positions.push_back(glm::vec3(ends.from + radial * ends.radiusFrom));
    mesh.positions.push_back(glm::vec3(ends.to + radial * ends.radiusTo));
    mesh.normals.push_back(glm::vec3(normal));
    mesh.normals.push_back(glm::vec3(normal));
    if (textured) {
      const float s = static_cast<float>(j) / static_cast<float>(sides);
      mesh.texcoords.push_back({s, static_cast<float>(ends.textureFrom)});
      mesh.texcoords.push_back({s, static_cast<float>(ends.textureTo)});
    }
  }
  for (int j = 0; j < sides; ++j) {
    const std::uint32_t b0 = base + 2 * static_cast<std::uint32_t>(j), t0 = b0 + 1, b1 = b0 + 2,
                        t1 = b0 + 3;
    // Counter-clockwise seen from outside (H × U = L points out at j = 0).
    addTriangle(mesh, b0, t1, b1);
    addTriangle(mesh, b0, t0, t1);
  }
}

void appendAnnulus(TriangleMesh& mesh, const glm::dvec3& center, const glm::dvec3& a,
                   const glm::dvec3& b, double inner, double outer, int sides) {
  sides = std::max(3, sides);
  const glm::vec3 normal(glm::normalize(glm::cross(a, b)));
  const bool textured = mesh.texture >= 0;
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (int j = 0; j <= sides; ++j) {
    const double angle = kTwoPi * j / sides;
    const glm::dvec3 radial = a * std::cos(angle) + b * std::sin(angle);
    mesh.positions.push_back(glm::vec3(center + radial * inner));
    mesh.positions.push_back(glm::vec3(center + radial * outer));
    mesh.normals.push_back(normal);
    mesh.normals.push_back(normal);
    if (textured) {
      const float s = static_cast<float>(j) / static_cast<float>(sides);
      mesh.texcoords.push_back({s, 0.0f});
      mesh.texcoords.push_back({s, 1.0f});
    }
  }
  for (int j = 0; j < sides; ++j) {
    const std::uint32_t i0 = base + 2 * static_cast<std::uint32_t>(j), o0 = i0 + 1, i1 = i0 + 2,
                        o1 = i0 + 3;
    addTriangle(mesh, i0, o0, o1);
    addTriangle(mesh, i0, o1, i1);
  }
}

}  // namespace hirsute
