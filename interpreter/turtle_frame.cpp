#include "turtle_frame.h"

#include <cmath>

namespace hirsute {

namespace {
constexpr double kParallel = 1e-12;  // |a × b|² below this: the vectors are (anti)parallel
}

void rotatePair(glm::dvec3& a, glm::dvec3& b, double radians) {
  const double c = std::cos(radians), s = std::sin(radians);
  const glm::dvec3 na = a * c + b * s;
  const glm::dvec3 nb = b * c - a * s;
  a = na;
  b = nb;
}

void rotateFrame(TurtleState& state, const glm::dvec3& axis, double radians) {
  const double c = std::cos(radians), s = std::sin(radians);
  auto rotate = [&](const glm::dvec3& v) {
    return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1 - c));
  };
  state.heading = rotate(state.heading);
  state.left = rotate(state.left);
  state.up = rotate(state.up);
  orthonormalize(state);
}

void orthonormalize(TurtleState& state) {
  state.heading = glm::normalize(state.heading);
  glm::dvec3 left = state.left - state.heading * glm::dot(state.left, state.heading);
  if (glm::dot(left, left) < kParallel) {
    // L collapsed onto H (cannot happen through rotations; guards @R with odd input): rebuild
    // it from U.
    left = glm::cross(state.heading, state.up);
  }
  state.left = glm::normalize(left);
  state.up = glm::cross(state.left, state.heading);
}

void turnHeadingTo(TurtleState& state, const glm::dvec3& heading) {
  const glm::dvec3 axis = glm::cross(state.heading, heading);
  const double sine = glm::length(axis);
  const double cosine = glm::dot(state.heading, heading);
  if (sine * sine < kParallel) {
    if (cosine > 0) return;
    // Opposite: any half turn works; turning about U keeps U, as `|` does.
    state.heading = -state.heading;
    state.left = -state.left;
    orthonormalize(state);
    return;
  }
  rotateFrame(state, axis / sine, std::atan2(sine, cosine));
  state.heading = heading;
  orthonormalize(state);
}

void rollToVertical(TurtleState& state) {
  const glm::dvec3 vertical(0, 1, 0);
  glm::dvec3 up = vertical - state.heading * glm::dot(vertical, state.heading);
  if (glm::dot(up, up) < kParallel) return;
  state.up = glm::normalize(up);
  state.left = glm::cross(state.heading, state.up);
  orthonormalize(state);
}

}  // namespace hirsute
