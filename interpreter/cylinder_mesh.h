// Meshes the turtle draws itself: the cylinders and cones of F and G in `line style: cylinder`,
// and the rings of @bc and @bo. (Generalized cylinders are generalized_cylinder.cpp's.)
#pragma once

#include <glm/glm.hpp>

#include "hirsute/interpreter/scene.h"

namespace hirsute {

struct CylinderEnds {
  glm::dvec3 from{0.0}, to{0.0};
  double radiusFrom = 0, radiusTo = 0;
  glm::dvec3 left{-1, 0, 0}, up{0, 0, -1};  // the turtle's L and U at the start of the segment
  int sides = 8;
  double textureFrom = 0, textureTo = 0;  // t at each end (meshes with texture coordinates)
};

// An open truncated cone (no caps: cpfg draws none, and its rayshade output writes `cylinder`
// and `cone`, which are open). As cpfg's F cylinders (cpfg-generalized-cylinders.md §4), ring
// vertex j lies at angle 2πj/sides from L towards U and has s = j/sides; the seam vertex is
// repeated so that s runs to 1. Adds 2·sides triangles.
void appendCylinder(TriangleMesh& mesh, const CylinderEnds& ends);

// A flat ring between radii `inner` and `outer` in the plane spanned by the unit vectors a and b,
// facing a × b (@bc, @bo). Adds 2·sides triangles; `inner` 0 gives a disc.
void appendAnnulus(TriangleMesh& mesh, const glm::dvec3& center, const glm::dvec3& a,
                   const glm::dvec3& b, double inner, double outer, int sides);

}  // namespace hirsute
