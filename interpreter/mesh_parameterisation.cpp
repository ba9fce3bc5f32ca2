// A mesh without texture coordinates parameterised by CGAL's least-squares conformal map: whole
// when it is a disc, chart by chart otherwise (mesh_parameterisation.h).
#include "mesh_parameterisation.h"

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

namespace hirsute {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Vertex = Mesh::Vertex_index;
namespace SMP = CGAL::Surface_mesh_parameterization;

using Triangle = std::array<std::uint32_t, 3>;

// The least-squares conformal map of `points` joined by `triangles` (counter-clockwise about the
// surface's outside), unscaled: one (u, v) per point. False when the triangles are not a
// manifold disc (one border, V − E + F = 1) or the solver fails.
bool conformalMap(const std::vector<glm::dvec3>& points, const std::vector<Triangle>& triangles,
                  std::vector<glm::dvec2>& uv) {
  Mesh mesh;
  std::vector<Vertex> vertices;
  vertices.reserve(points.size());
  for (const glm::dvec3& p : points)
    vertices.push_back(mesh.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
  for (const Triangle& t : triangles) {
    if (mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]) == Mesh::null_face())
      return false;  // not a manifold
  }
  std::vector<Mesh::Halfedge_index> borders;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(mesh, std::back_inserter(borders));
  const long euler = static_cast<long>(mesh.number_of_vertices()) -
                     static_cast<long>(mesh.number_of_edges()) +
                     static_cast<long>(mesh.number_of_faces());
  if (borders.size() != 1 || euler != 1) return false;
  auto map = mesh.add_property_map<Vertex, Kernel::Point_2>("v:uv").first;
  if (SMP::parameterize(mesh, SMP::LSCM_parameterizer_3<Mesh>(), borders.front(), map) != SMP::OK)
    return false;
  uv.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Kernel::Point_2& q = map[vertices[i]];
    uv[i] = glm::dvec2(q.x(), q.y());
    if (!std::isfinite(uv[i].x) || !std::isfinite(uv[i].y)) return false;
  }
  return true;
}

double signedArea(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

// The charts' cone: a chart's triangles face within this angle of its first one's, so that
// the conformal map stretches its area by at most some 15% from its middle to its rim (a
// spherical cap of 30° laid flat conformally).
constexpr double kChartCone = 30.0 * 3.14159265358979323846 / 180.0;

// The most triangles a chart holds: the conformal map's sparse solve grows faster than its
// size, so that a fine mesh is cut into more charts of bounded cost.
constexpr std::size_t kMaxChartTriangles = 4096;

class ChartBuilder {
 public:
  ChartBuilder(const std::vector<glm::dvec3>& positions, const std::vector<std::uint32_t>& indices,
               const std::vector<std::uint32_t>& welded)
      : positions_(positions),
        indices_(indices),
        welded_(welded),
        faces_(indices.size() / 3),
        normal_(faces_),
        centre_(faces_),
        area_(faces_),
        neighbour_(3 * faces_, kNone),
        mark_(faces_, 0),
        distance_(faces_, kFar) {
    for (std::size_t f = 0; f < faces_; ++f) {
      const glm::dvec3 &a = corner(f, 0), &b = corner(f, 1), &c = corner(f, 2);
      const glm::dvec3 n = glm::cross(b - a, c - a);
      area_[f] = 0.5 * glm::length(n);
      normal_[f] = area_[f] > 0 ? n / (2 * area_[f]) : glm::dvec3(0.0);
      centre_[f] = (a + b + c) / 3.0;
    }
    // Neighbours across edges that two triangles share, in opposite directions (a consistently
    // oriented manifold edge); any other edge is a cut.
    struct Use {
      std::uint64_t key;
      std::uint32_t face;
      std::uint8_t side;
      bool forward;
    };
    std::vector<Use> uses;
    uses.reserve(3 * faces_);
    for (std::size_t f = 0; f < faces_; ++f)
      for (std::uint8_t k = 0; k < 3; ++k) {
        const std::uint32_t p = welded_[indices_[3 * f + k]],
                            q = welded_[indices_[3 * f + (k + 1) % 3]];
        uses.push_back({static_cast<std::uint64_t>(std::min(p, q)) << 32 | std::max(p, q),
                        static_cast<std::uint32_t>(f), k, p < q});
      }
    std::sort(uses.begin(), uses.end(), [](const Use& a, const Use& b) { return a.key < b.key; });
    for (std::size_t i = 0; i < uses.size();) {
      std::size_t j = i;
      while (j < uses.size() && uses[j].key == uses[i].key) ++j;
      if (j - i == 2 && uses[i].forward != uses[i + 1].forward &&
          uses[i].face != uses[i + 1].face) {
        neighbour_[3 * uses[i].face + uses[i].side] = uses[i + 1].face;
        neighbour_[3 * uses[i + 1].face + uses[i + 1].side] = uses[i].face;
      }
      i = j;
    }
  }

  double area(std::size_t f) const { return area_[f]; }

  // Every chart, laid flat: corner (u, v) in each chart's own units, its number per triangle.
  std::size_t build(std::vector<glm::dvec2>& cornerUv, std::vector<std::uint32_t>& chartOf) {
    cornerUv.assign(3 * faces_, glm::dvec2(0.0));
    chartOf.assign(faces_, 0);
    std::vector<std::uint8_t> taken(faces_, 0);
    std::vector<std::vector<std::uint32_t>> pending;
    for (std::size_t seed = 0; seed < faces_; ++seed) {
      if (taken[seed]) continue;
      pending.push_back(grow(static_cast<std::uint32_t>(seed), taken));
    }
    std::size_t charts = 0;
    while (!pending.empty()) {
      std::vector<std::uint32_t> faces = std::move(pending.back());
      pending.pop_back();
      if (faces.size() > kMaxChartTriangles || !flatten(faces, cornerUv)) {
        auto [first, second] = split(faces);
        pending.push_back(std::move(first));
        pending.push_back(std::move(second));
        continue;
      }
      for (std::uint32_t f : faces) chartOf[f] = static_cast<std::uint32_t>(charts);
      ++charts;
    }
    return charts;
  }

 private:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  static constexpr double kFar = std::numeric_limits<double>::infinity();

  const glm::dvec3& corner(std::size_t f, int k) const { return positions_[indices_[3 * f + k]]; }

  // The triangles reached from `seed` across shared edges, nearest first, whose normals lie
  // within the cone about the seed's.
  std::vector<std::uint32_t> grow(std::uint32_t seed, std::vector<std::uint8_t>& taken) {
    const double least = std::cos(kChartCone);
    std::vector<std::uint32_t> faces;
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    queue.push({0.0, seed});
    taken[seed] = 1;
    while (!queue.empty()) {
      const auto [d, f] = queue.top();
      queue.pop();
      faces.push_back(f);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t g = neighbour_[3 * f + k];
        if (g == kNone || taken[g] || glm::dot(normal_[g], normal_[seed]) < least) continue;
        taken[g] = 1;
        queue.push({d + glm::distance(centre_[f], centre_[g]), g});
      }
    }
    return faces;
  }

  // Distances over the triangles of the current set (mark_ == stamp_) from `from`, across
  // shared edges between their centres; the farthest reached.
  std::uint32_t spread(std::uint32_t from, const std::vector<std::uint32_t>& faces,
                       std::vector<double>& out) {
    for (std::uint32_t f : faces) distance_[f] = kFar;
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    distance_[from] = 0;
    queue.push({0.0, from});
    std::uint32_t farthest = from;
    while (!queue.empty()) {
      const auto [d, f] = queue.top();
      queue.pop();
      if (d > distance_[f]) continue;
      if (d > distance_[farthest]) farthest = f;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t g = neighbour_[3 * f + k];
        if (g == kNone || mark_[g] != stamp_) continue;
        const double e = d + glm::distance(centre_[f], centre_[g]);
        if (e < distance_[g]) {
          distance_[g] = e;
          queue.push({e, g});
        }
      }
    }
    out.clear();
    for (std::uint32_t f : faces) out.push_back(distance_[f]);
    return farthest;
  }

  // A set that is no disc (a ring around a bump, a band around a handle) or that the map folds,
  // in two: the triangles nearer to one or the other of two far-apart triangles (each part
  // connected, as the nearer one's shortest path stays in its part).
  std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> split(
      const std::vector<std::uint32_t>& faces) {
    ++stamp_;
    for (std::uint32_t f : faces) mark_[f] = stamp_;
    std::vector<double> fromA, fromB;
    const std::uint32_t a = spread(faces.front(), faces, fromA);
    const std::uint32_t b = spread(a, faces, fromA);
    spread(b, faces, fromB);
    std::vector<std::uint32_t> first, second;
    for (std::size_t i = 0; i < faces.size(); ++i)
      (fromA[i] <= fromB[i] ? first : second).push_back(faces[i]);
    if (first.empty() || second.empty()) {
      // One triangle reached (the rest cut off at its vertices): it alone, and the rest.
      first.assign(faces.begin(), faces.begin() + 1);
      second.assign(faces.begin() + 1, faces.end());
    }
    return {std::move(first), std::move(second)};
  }

  // The conformal map of one set of triangles into cornerUv, oriented counter-clockwise like the
  // triangles; false when it is no disc or the map folds a triangle over.
  bool flatten(const std::vector<std::uint32_t>& faces, std::vector<glm::dvec2>& cornerUv) {
    if (faces.size() == 1) {
      // One triangle: laid flat as it is.
      const std::uint32_t f = faces.front();
      const glm::dvec3 &a = corner(f, 0), &b = corner(f, 1), &c = corner(f, 2);
      const double ab = glm::length(b - a);
      const glm::dvec3 x = ab > 0 ? (b - a) / ab : glm::dvec3(1, 0, 0);
      const glm::dvec3 y = glm::cross(normal_[f], x);
      cornerUv[3 * f] = glm::dvec2(0.0);
      cornerUv[3 * f + 1] = glm::dvec2(ab, 0);
      cornerUv[3 * f + 2] = glm::dvec2(glm::dot(c - a, x), glm::dot(c - a, y));
      return true;
    }
    std::unordered_map<std::uint32_t, std::uint32_t> local;
    std::vector<glm::dvec3> points;
    std::vector<Triangle> triangles;
    for (std::uint32_t f : faces) {
      Triangle t{};
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = indices_[3 * f + k];
        const auto [at, added] =
            local.emplace(welded_[v], static_cast<std::uint32_t>(points.size()));
        if (added) points.push_back(positions_[v]);
        t[k] = at->second;
      }
      triangles.push_back(t);
    }
    std::vector<glm::dvec2> uv;
    if (!conformalMap(points, triangles, uv)) return false;
    double total = 0;
    for (const Triangle& t : triangles) total += signedArea(uv[t[0]], uv[t[1]], uv[t[2]]);
    if (!(std::abs(total) > 0)) return false;
    if (total < 0) {
      for (glm::dvec2& q : uv) q.x = -q.x;
      total = -total;
    }
    for (const Triangle& t : triangles)
      if (signedArea(uv[t[0]], uv[t[1]], uv[t[2]]) < -1e-9 * total) return false;  // folded
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (int k = 0; k < 3; ++k) cornerUv[3 * faces[i] + k] = uv[triangles[i][k]];
    return true;
  }

  const std::vector<glm::dvec3>& positions_;
  const std::vector<std::uint32_t>& indices_;
  const std::vector<std::uint32_t>& welded_;
  std::size_t faces_;
  std::vector<glm::dvec3> normal_, centre_;
  std::vector<double> area_;
  std::vector<std::uint32_t> neighbour_;  // across each triangle's edge k (corner k to k + 1)
  std::vector<std::uint32_t> mark_;
  std::uint32_t stamp_ = 0;
  std::vector<double> distance_;
};

}  // namespace

bool parameteriseDisc(const std::vector<glm::dvec3>& positions,
                      const std::vector<std::uint32_t>& indices,
                      const std::vector<std::uint32_t>& welded, std::vector<glm::vec2>& uv) {
  std::unordered_map<std::uint32_t, std::uint32_t> local;
  std::vector<glm::dvec3> points;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (local.emplace(welded[v], static_cast<std::uint32_t>(points.size())).second)
      points.push_back(positions[v]);
  }
  std::vector<Triangle> triangles;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    triangles.push_back({local.at(welded[indices[t]]), local.at(welded[indices[t + 1]]),
                         local.at(welded[indices[t + 2]])});
  }
  std::vector<glm::dvec2> flat;
  if (!conformalMap(points, triangles, flat)) return false;
  // Into [0, 1]², scaled alike along both (a conformal map stays one).
  glm::dvec2 low(1e300), high(-1e300);
  for (const glm::dvec2& q : flat) {
    low = glm::min(low, q);
    high = glm::max(high, q);
  }
  const double extent = std::max(high.x - low.x, high.y - low.y);
  if (!(extent > 0) || !std::isfinite(extent)) return false;
  uv.resize(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v)
    uv[v] = glm::vec2((flat[local.at(welded[v])] - low) / extent);
  return true;
}

std::size_t parameteriseCharts(const std::vector<glm::dvec3>& positions,
                               const std::vector<std::uint32_t>& indices,
                               const std::vector<std::uint32_t>& welded,
                               std::vector<glm::vec2>& cornerUv,
                               std::vector<std::uint32_t>& chartOf) {
  ChartBuilder builder(positions, indices, welded);
  std::vector<glm::dvec2> flat;
  const std::size_t charts = builder.build(flat, chartOf);
  const std::size_t faces = indices.size() / 3;

  // Each chart turned so that v grows with the mesh's y (the area-weighted gradient of y over
  // the chart's (u, v)), and scaled so that its (u, v) area is its area on the surface.
  std::vector<glm::dvec2> gradient(charts, glm::dvec2(0.0));
  std::vector<double> world(charts, 0.0), flatArea(charts, 0.0);
  for (std::size_t f = 0; f < faces; ++f) {
    const glm::dvec2 &a = flat[3 * f], &b = flat[3 * f + 1], &c = flat[3 * f + 2];
    const double area = signedArea(a, b, c);
    const std::uint32_t chart = chartOf[f];
    world[chart] += builder.area(f);
    flatArea[chart] += std::abs(area);
    if (area == 0) continue;
    // y over the triangle is linear in (u, v): its gradient solves d1 · g = Δy1, d2 · g = Δy2.
    const glm::dvec2 d1 = b - a, d2 = c - a;
    const double y0 = positions[indices[3 * f]].y, y1 = positions[indices[3 * f + 1]].y,
                 y2 = positions[indices[3 * f + 2]].y;
    const double det = d1.x * d2.y - d1.y * d2.x;
    const glm::dvec2 g(((y1 - y0) * d2.y - (y2 - y0) * d1.y) / det,
                       ((y2 - y0) * d1.x - (y1 - y0) * d2.x) / det);
    gradient[chart] += std::abs(area) * g;
  }
  std::vector<glm::dmat2> transform(charts, glm::dmat2(1.0));
  for (std::size_t k = 0; k < charts; ++k) {
    const double scale = flatArea[k] > 0 ? std::sqrt(world[k] / flatArea[k]) : 1.0;
    const glm::dvec2 g = gradient[k];
    const double length = glm::length(g);
    // The rotation taking g to +v: columns (g⊥, g) / |g| transposed.
    glm::dmat2 turn(1.0);
    if (length > 0 && std::isfinite(length)) {
      const glm::dvec2 v = g / length, u(v.y, -v.x);
      turn = glm::transpose(glm::dmat2(u, v));
    }
    transform[k] = scale * turn;
  }
  std::vector<glm::dvec2> low(charts, glm::dvec2(1e300)), high(charts, glm::dvec2(-1e300));
  for (std::size_t f = 0; f < faces; ++f) {
    const std::uint32_t chart = chartOf[f];
    for (int k = 0; k < 3; ++k) {
      glm::dvec2& q = flat[3 * f + k];
      q = transform[chart] * q;
      low[chart] = glm::min(low[chart], q);
      high[chart] = glm::max(high[chart], q);
    }
  }

  // Packed in rows, tallest first, each chart's box apart from the next by a gap.
  std::vector<std::size_t> order(charts);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double ha = high[a].y - low[a].y, hb = high[b].y - low[b].y;
    return ha != hb ? ha > hb : a < b;
  });
  double boxes = 0, widest = 0;
  for (std::size_t k = 0; k < charts; ++k) {
    boxes += (high[k].x - low[k].x) * (high[k].y - low[k].y);
    widest = std::max(widest, high[k].x - low[k].x);
  }
  const double gap = 0.005 * std::sqrt(boxes);
  const double rowWidth = std::max(widest, 1.1 * std::sqrt(boxes));
  std::vector<glm::dvec2> offset(charts, glm::dvec2(0.0));
  double x = 0, y = 0, rowHeight = 0, right = 0;
  for (std::size_t k : order) {
    const glm::dvec2 size = high[k] - low[k];
    if (x > 0 && x + size.x > rowWidth) {
      x = 0;
      y += rowHeight + gap;
      rowHeight = 0;
    }
    offset[k] = glm::dvec2(x, y) - low[k];
    x += size.x + gap;
    right = std::max(right, x);
    rowHeight = std::max(rowHeight, size.y);
  }
  const double extent = std::max(right, y + rowHeight);
  cornerUv.resize(3 * faces);
  for (std::size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k)
      cornerUv[3 * f + k] =
          glm::vec2(extent > 0 ? (flat[3 * f + k] + offset[chartOf[f]]) / extent : glm::dvec2(0.0));
  return charts;
}

}  // namespace hirsute
