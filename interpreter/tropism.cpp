#include "tropism.h"

#include <algorithm>
#include <cmath>

#include "turtle_frame.h"

namespace hirsute {

namespace {
constexpr double kParallel = 1e-12;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

void removeTwist(TurtleState& state) {
  glm::dvec3 up = state.previousUp - state.heading * glm::dot(state.previousUp, state.heading);
  if (glm::dot(up, up) < kParallel) return;
  state.up = glm::normalize(up);
  state.left = glm::cross(state.heading, state.up);
  orthonormalize(state);
}

void applyTropisms(TurtleState& state, const std::vector<Tropism>& tropisms) {
  bool headingTurned = false;
  const std::size_t n = std::min(tropisms.size(), state.elasticity.size());
  // Heading tropisms first, then torques: a torque's twist is what it is for, so the twist
  // removal of the heading tropisms must not undo it.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < n; ++i) {
      const Tropism& t = tropisms[i];
      const double e = state.elasticity[i] * t.intensity;
      if (e == 0 || t.torque != (pass == 1)) continue;
      glm::dvec3 direction(t.direction);
      const double length = glm::length(direction);
      if (length == 0) continue;
      direction /= length;
      if (!t.torque) {
        const double phi = std::acos(std::clamp(glm::dot(state.heading, direction), -1.0, 1.0));
        const double target = t.angle * kPi / 180;
        glm::dvec3 axis = glm::cross(state.heading, direction);
        const double sine = glm::length(axis);
        // H along T: any axis perpendicular to H turns it off the line; L is the turtle's own.
        axis = sine * sine < kParallel ? state.left : axis / sine;
        // As for the old tropism, e·sin(φ − A) is the sine of the turn.
        double turn = std::asin(std::clamp(e * std::sin(phi - target), -1.0, 1.0));
        // Never past the cone: the bend approaches it and stops there.
        if (std::abs(turn) > std::abs(phi - target)) turn = phi - target;
        if (turn == 0) continue;
        rotateFrame(state, axis, turn);
        headingTurned = true;
      } else {
        // Rodrigues about H: U ← U·cos + (H × U)·sin = U·cos + L·sin, so a positive turn brings
        // U towards T when T·L > 0.
        rotateFrame(state, state.heading, e * glm::dot(direction, state.left));
      }
    }
    if (pass == 0 && headingTurned) removeTwist(state);
  }
}

void applyOldTropism(TurtleState& state, const glm::dvec3& direction) {
  if (state.oldElasticity == 0 || glm::length(direction) == 0) return;
  glm::dvec3 axis = glm::cross(state.heading, glm::normalize(direction));
  const double sine = glm::length(axis);
  if (sine * sine < kParallel) return;
  // The bend's sine is e·|H × T| (cpfg-WeepingBirch's rayshade output, whose elasticities reach
  // 0.4, matches this to 1e-6 of its size; the angle e·|H × T| itself is 0.08% off).
  rotateFrame(state, axis / sine, std::asin(std::clamp(state.oldElasticity * sine, -1.0, 1.0)));
}

}  // namespace hirsute
