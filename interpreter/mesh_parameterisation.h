// (u, v) for a mesh whose file has none (docs/meshes.md): CGAL's least-squares conformal map
// (Lévy, Petitjean, Ray & Maillot 2002), its border free, for a mesh that is a topological disc
// (a scanned leaf, a patch of skin); and, for any other (a closed body, a mesh with holes), an
// atlas of charts cut where the surface turns, each mapped the same way (Lévy et al. 2002,
// Sec. 5: charts grown over nearly flat regions, then packed).
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

// A texture atlas of any mesh: its triangles cut into charts (connected regions whose normals
// stay within 30° of their first triangle's, split further until each is a disc of at most 4 096
// triangles that the conformal map lays flat without folding), each chart mapped by the
// least-squares conformal map, scaled so that its (u, v) area is proportional to its area on the
// surface, turned so that v grows with the mesh's y where the chart has a slope in y, and packed
// into [0, 1]² in rows. A vertex on a cut has a (u, v) in each chart it belongs to: `cornerUv` gets
// one (u, v) per corner of `indices` and `chartOf` one chart number per triangle. Returns the
// number of charts.
std::size_t parameteriseCharts(const std::vector<glm::dvec3>& positions,
                               const std::vector<std::uint32_t>& indices,
                               const std::vector<std::uint32_t>& welded,
                               std::vector<glm::vec2>& cornerUv,
                               std::vector<std::uint32_t>& chartOf);

}  // namespace hirsute
