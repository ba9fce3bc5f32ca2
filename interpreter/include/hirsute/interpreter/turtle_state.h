// The turtle's state, saved and restored by `[` and `]` (cpfg-features.md (d),
// cpfg-generalized-cylinders.md §1).
#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "hirsute/interpreter/organ_attributes.h"

namespace hirsute {

struct TurtleState {
  // Frame: cpfg's initial turtle has H = +y, L = -x, U = -z.
  glm::dvec3 position{0.0};
  glm::dvec3 heading{0, 1, 0};
  glm::dvec3 left{-1, 0, 0};
  glm::dvec3 up{0, 0, -1};

  double lineWidth = 1;           // diameter (after scale)
  int color = 128;                // index into the Scene's materials (bank offset included)
  int backColor = -1;             // -1: the front colour
  double scale = 1;               // sub-L-system scale and @D
  double texCoordT = 0;           // texture coordinate along the axis

  // Generalized cylinders.
  int contour = 0;                // 0: circle
  int cylinderSides = 8;
  std::array<double, 2> tangentParameter{1.2, 1.2};
  std::array<glm::dvec2, 2> radiusTangent{glm::dvec2(0.0), glm::dvec2(0.0)};
  bool scaleRadiusTangents = false;
  int texture = 0;                // 1-based, 0 none

  // Tropisms: elasticity per view-file tropism, and the old `_` elasticity.
  std::array<double, 8> elasticity{};
  double oldElasticity = 0;
  glm::dvec3 previousUp{0, 0, -1};  // for @Tf/@Tp

  // Organ attributes (docs/design.md, "Organs"; the @H modules): per organ an index into its Scene
  // vector, -1 for the defaults (none). The turtle copies a record before a module changes it
  // once a segment or a saved state refers to it, so `[` and `]` save and restore them for free.
  OrganAttributeIndices organs;
};

}  // namespace hirsute
