// The turtle's frame (heading H, left L, up U) and the rotations cpfg applies to it
// (cpfg-features.md (d); ABOP §1.5): U = L × H and L = H × U, so the initial frame H = +y,
// L = -x, U = -z is right-handed in that order.
#pragma once

#include <glm/glm.hpp>

#include "hirsute/interpreter/turtle_state.h"

namespace hirsute {

// Rotates the pair (a, b) by `radians` in their plane: a ← a·cos + b·sin, b ← −a·sin + b·cos.
// `+` is rotatePair(H, L), `&` rotatePair(H, U), `/` rotatePair(L, U) (ABOP's R_U, R_L, R_H).
void rotatePair(glm::dvec3& a, glm::dvec3& b, double radians);

// Rodrigues' rotation of the whole frame about a unit `axis`.
void rotateFrame(TurtleState& state, const glm::dvec3& axis, double radians);

// Makes the frame orthonormal again after a rotation: H normalised, L made perpendicular to
// it, U = L × H. Rounding would otherwise shear the frame over long strings.
void orthonormalize(TurtleState& state);

// Turns the frame by the smallest rotation that takes H to `heading` (unit), so that L and U
// move as little as possible (cpfg's @R without an up vector).
void turnHeadingTo(TurtleState& state, const glm::dvec3& heading);

// cpfg's @v: rolls about H so that U lies in the vertical plane through H, on the side of +y.
// Nothing changes while H is vertical.
void rollToVertical(TurtleState& state);

}  // namespace hirsute
