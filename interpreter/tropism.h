// Tropisms: how the turtle's frame bends as it moves (cpfg-features.md (d), manual §6.8 and
// §8.1.8).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "hirsute/interpreter/turtle_state.h"
#include "hirsute/interpreter/view_settings.h"

namespace hirsute {

// The view file's `tropism:` and `torque:` lines, applied before each move with the turtle's
// elasticity for each (state.elasticity, numbered as the lines). A tropism turns H about H × T
// towards the cone of half-angle A around T by the angle whose sine is e·I·sin(φ − A), φ the
// angle between H and T (for A = 0, e·I·|H × T| as ABOP's eq. 2.3 and the old tropism below),
// never past the cone. The turn carries U over from
// the previous segment (state.previousUp), which is why a roll between two bent segments has no
// effect unless @Tf accepts it (manual §6.8). A torque turns the frame about H, bringing U
// towards T by e·I·(T·L), and leaves H alone.
void applyTropisms(TurtleState& state, const std::vector<Tropism>& tropisms);

// The old tropism of `_` (view `tropism direction:`, normalised), applied after each move: H
// turns about H × T towards T by the angle whose sine is state.oldElasticity · |H × T| (ABOP
// §2.2, eq. 2.3, has the angle itself; cpfg's rayshade output has the sine). cpfg normalises T:
// cpfg-Lilac's direction (0,-2,0) and cpfg-Sedge's (0.2,1,0) bend as unit vectors.
void applyOldTropism(TurtleState& state, const glm::dvec3& direction);

// @Tp: removes the twist relative to the previous segment: U becomes previousUp made
// perpendicular to H (nothing happens when they are parallel).
void removeTwist(TurtleState& state);

}  // namespace hirsute
