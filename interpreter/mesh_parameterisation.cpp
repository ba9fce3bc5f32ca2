// A disc-shaped mesh without texture coordinates parameterised by CGAL's least-squares conformal
// map (mesh_parameterisation.h).
#include "mesh_parameterisation.h"

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace hirsute {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Vertex = Mesh::Vertex_index;
namespace SMP = CGAL::Surface_mesh_parameterization;

}  // namespace

bool parameteriseDisc(const std::vector<glm::dvec3>& positions,
                      const std::vector<std::uint32_t>& indices,
                      const std::vector<std::uint32_t>& welded, std::vector<glm::vec2>& uv) {
  Mesh mesh;
  std::unordered_map<std::uint32_t, Vertex> vertexOf;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (vertexOf.contains(welded[v])) continue;
    const glm::dvec3& p = positions[v];
    vertexOf.emplace(welded[v], mesh.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
  }
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const Vertex a = vertexOf.at(welded[indices[t]]), b = vertexOf.at(welded[indices[t + 1]]),
                 c = vertexOf.at(welded[indices[t + 2]]);
    if (mesh.add_face(a, b, c) == Mesh::null_face()) return false;  // not a manifold
  }
  // A topological disc: one border, and V − E + F = 1.
  std::vector<Mesh::Halfedge_index> borders;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(mesh, std::back_inserter(borders));
  const long euler = static_cast<long>(mesh.number_of_vertices()) -
                     static_cast<long>(mesh.number_of_edges()) +
                     static_cast<long>(mesh.number_of_faces());
  if (borders.size() != 1 || euler != 1) return false;
  auto map = mesh.add_property_map<Vertex, Kernel::Point_2>("v:uv").first;
  const SMP::Error_code result =
      SMP::parameterize(mesh, SMP::LSCM_parameterizer_3<Mesh>(), borders.front(), map);
  if (result != SMP::OK) return false;
  // Into [0, 1]², scaled alike along both (a conformal map stays one).
  glm::dvec2 low(1e300), high(-1e300);
  for (const Vertex v : mesh.vertices()) {
    low = glm::min(low, glm::dvec2(map[v].x(), map[v].y()));
    high = glm::max(high, glm::dvec2(map[v].x(), map[v].y()));
  }
  const double extent = std::max(high.x - low.x, high.y - low.y);
  if (!(extent > 0) || !std::isfinite(extent)) return false;
  uv.resize(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const Kernel::Point_2& q = map[vertexOf.at(welded[v])];
    uv[v] = glm::vec2((glm::dvec2(q.x(), q.y()) - low) / extent);
  }
  return true;
}

}  // namespace hirsute
