// `~X`: a predefined bicubic surface (cpfg's .s file, view `surface:`) placed at the turtle and
// tessellated into the Scene (cpfg-features.md (d) and "Bicubic surface .s").
#pragma once

#include <cstddef>
#include <functional>

#include <glm/glm.hpp>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/surface.h"

namespace hirsute {

struct SurfacePlacement {
  glm::dvec3 position{0.0};
  glm::dvec3 heading{0, 1, 0}, left{-1, 0, 0}, up{0, 0, -1};
  glm::dvec3 scale{1.0};  // along L, H and U: ~X(s) or ~X(sx,sy,sz), times the turtle's scale
  std::size_t frame = 0;  // a moving mesh's frame (SurfaceMeshData::positionsAt)
};

// Where a point of the surface file lands. cpfg's transform: with H_f and U_f the file's
// HEADING and UP (normalised), L_f = H_f × U_f, c the CONTACT POINT and s = view size / SIZE,
// p' = s·(x−cx)·L_f + s·(y−cy)·H_f + s·(z−cz)·U_f, then p' is drawn in the turtle's frame
// (x along L, y along H, z along U) scaled per axis. The turtle moves to the image of END POINT.
glm::dvec3 placeSurfacePoint(const Surface& surface, const SurfacePlacement& placement,
                             const glm::dvec3& point);

struct SurfaceAppearance {
  std::function<int(int patchColor)> material;  // colour index (0: the turtle's) → material
  int texture = -1;                             // Scene texture index, -1 none
  // The texture's `S:`: one mapping over the whole surface, from the bounding box of its points
  // in the x,y plane of p' (cpfg's rayshade output shows u = (x − xmin)/(xmax − xmin)); otherwise
  // each patch carries its own parameters (u, v).
  bool perSurfaceTexture = false;
};

// Tessellates every Bézier patch into sPrecision × tPrecision quads (two triangles each) in the
// mesh of its colour; normals from the patch derivatives. Where `organs` sets any organ's
// attributes, each patch is also recorded in Scene::organSurfaces with its (u, v). Returns the
// number of triangles.
std::size_t appendSurface(Scene& scene, const Surface& surface, const SurfacePlacement& placement,
                          const SurfaceAppearance& appearance,
                          const OrganAttributeIndices& organs = {});

}  // namespace hirsute
