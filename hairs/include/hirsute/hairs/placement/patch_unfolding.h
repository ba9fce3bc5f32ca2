// A `~` surface patch or a `{ }` polygon (scene.h, OrganSurface) laid out for the placement
// engine (docs/design.md, "Placement"): its triangles in its own (u, v), scaled to a plane
// (U, V) = (u·Lu, v·Lv) in which lengths are the surface's own on average (a polygon's (u, v)
// are world distances already: Lu = Lv = 1; a mesh's are the root mean squares of ∂P/∂u and
// ∂P/∂v over its atlas), with the ratio of each triangle's surface area to its (U, V)
// area, by which an organ thins a tile laid over (U, V) so that the count follows the surface.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "hirsute/interpreter/scene.h"

namespace hirsute {

class PatchUnfolding {
 public:
  PatchUnfolding(const OrganSurface& surface, const TriangleMesh& mesh);

  const OrganSurface& surface() const { return surface_; }
  std::size_t triangles() const { return surface_.indexCount / 3; }
  // Corner c (0 to 2) of triangle i: the index of its vertex in the surface's uv.
  std::uint32_t corner(std::size_t i, int c) const {
    return mesh_.indices[surface_.firstIndex + 3 * i + static_cast<std::size_t>(c)] -
           surface_.firstVertex;
  }
  const glm::vec3& position(std::uint32_t vertex) const {
    return mesh_.positions[surface_.firstVertex + vertex];
  }
  const glm::vec3& normal(std::uint32_t vertex) const {
    return mesh_.normals[surface_.firstVertex + vertex];
  }
  glm::vec2 plane(std::uint32_t vertex) const { return surface_.uv[vertex] * scale_; }
  // The position of a vertex for an organ's attributes: u and v over their ranges on the
  // surface, each in [0, 1] (s, the girth position of a cylinder, is the u one).
  glm::vec2 normalized(std::uint32_t vertex) const { return (surface_.uv[vertex] - low_) / span_; }
  // Surface area over (U, V) area, of triangle i and the largest (0 for a triangle without
  // (U, V) area).
  float areaRatio(std::size_t i) const { return ratio_[i]; }
  float maxAreaRatio() const { return maxRatio_; }
  // The surface's area.
  double area() const { return area_; }
  // The world direction in which V grows on triangle i (the height vector h of its corner
  // frames, as the axis is on a cylinder).
  const glm::vec3& heightVector(std::size_t i) const { return height_[i]; }

 private:
  const OrganSurface& surface_;
  const TriangleMesh& mesh_;
  glm::vec2 scale_{1.0f}, low_{0.0f}, span_{1.0f};
  std::vector<float> ratio_;
  std::vector<glm::vec3> height_;
  float maxRatio_ = 0;
  double area_ = 0;
};

}  // namespace hirsute
