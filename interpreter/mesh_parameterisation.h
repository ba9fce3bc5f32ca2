// (u, v) for a mesh whose file has none (docs/meshes.md): CGAL's least-squares conformal map
// (Lévy, Petitjean, Ray & Maillot 2002), its border free, for a mesh that is a topological disc
// (a scanned leaf, a patch of skin).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace hirsute {

// (u, v) in [0, 1]² (the larger extent fills it) for every vertex, the vertices of one place (`welded`: the same number for
// vertices at one position) sharing theirs. False, `uv` untouched, when the welded mesh is not a
// manifold disc (one border, Euler characteristic 1) or the solver fails.
bool parameteriseDisc(const std::vector<glm::dvec3>& positions,
                      const std::vector<std::uint32_t>& indices,
                      const std::vector<std::uint32_t>& welded, std::vector<glm::vec2>& uv);

}  // namespace hirsute
