#include "polygon_triangulation.h"

#include <cmath>

namespace hirsute {

namespace {

double cross2(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Inside or on the boundary of the counter-clockwise triangle abc.
bool inTriangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                double tolerance) {
  return cross2(a, b, p) >= -tolerance && cross2(b, c, p) >= -tolerance &&
         cross2(c, a, p) >= -tolerance;
}

}  // namespace

PolygonTriangulation triangulatePolygon(const std::vector<glm::dvec3>& points) {
  PolygonTriangulation result;
  // Vertices with repeats (consecutive, and last = first) removed; indices into `points`.
  std::vector<std::uint32_t> ring;
  double extent = 0;
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    if (!ring.empty() && points[i] == points[ring.back()]) continue;
    ring.push_back(i);
    extent = std::max(extent, glm::length(points[i] - points[ring.front()]));
  }
  while (ring.size() > 1 && points[ring.back()] == points[ring.front()]) ring.pop_back();
  if (ring.size() < 3) return result;

  // Newell's normal: robust for non-planar and concave polygons.
  glm::dvec3 normal(0.0);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const glm::dvec3& a = points[ring[i]];
    const glm::dvec3& b = points[ring[(i + 1) % ring.size()]];
    normal +=
        glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  const double length = glm::length(normal);
  if (!(length > 1e-12 * extent * extent)) return result;  // collinear: no area to fill
  normal /= length;
  result.normal = normal;

  // Project on the coordinate plane the normal is closest to; the cyclic choice of the two
  // remaining axes keeps the winding when that normal component is positive.
  int drop = 0;
  if (std::abs(normal.y) > std::abs(normal[drop])) drop = 1;
  if (std::abs(normal.z) > std::abs(normal[drop])) drop = 2;
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  const bool flipped = normal[drop] < 0;
  std::vector<glm::dvec2> flat(points.size());
  for (std::uint32_t i : ring)
    flat[i] = glm::dvec2(points[i][u], flipped ? -points[i][v] : points[i][v]);

  const double tolerance = 1e-12 * extent * extent;
  auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    result.triangles.push_back({a, b, c});
  };
  // Ear clipping over the remaining ring, O(n²): a vertex is an ear when it is convex and no
  // other remaining vertex lies in its triangle.
  std::size_t misses = 0;
  std::size_t i = 0;
  while (ring.size() > 3) {
    const std::size_t n = ring.size();
    const std::uint32_t a = ring[(i + n - 1) % n], b = ring[i % n], c = ring[(i + 1) % n];
    const double turn = cross2(flat[a], flat[b], flat[c]);
    bool ear = false;
    bool dropVertex = false;
    if (std::abs(turn) <= tolerance) {
      // Collinear with its neighbours (or a spike folding back on itself): the vertex bounds no
      // area, so it goes without a triangle.
      dropVertex = true;
    } else if (turn > 0) {
      ear = true;
      for (std::uint32_t k : ring) {
        if (k == a || k == b || k == c) continue;
        if (flat[k] == flat[a] || flat[k] == flat[b] || flat[k] == flat[c]) continue;
        if (inTriangle(flat[k], flat[a], flat[b], flat[c], tolerance)) {
          ear = false;
          break;
        }
      }
    }
    if (ear || dropVertex || misses >= n) {
      if (!dropVertex) emit(a, b, c);
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i % n));
      misses = 0;
      if (i >= ring.size()) i = 0;
      // Step back so that the previous vertex, whose ear may have changed, is tried next. (After
      // a full round without an ear, which only a self-intersecting polygon allows, the vertex at
      // hand is clipped anyway so that the triangulation ends.)
      i = (i + ring.size() - 1) % ring.size();
    } else {
      ++misses;
      i = (i + 1) % n;
    }
  }
  if (std::abs(cross2(flat[ring[0]], flat[ring[1]], flat[ring[2]])) > tolerance)
    emit(ring[0], ring[1], ring[2]);

  // Triangles face the normal (a self-intersecting remainder may have produced reversed ones).
  for (auto& t : result.triangles) {
    const glm::dvec3 n = glm::cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
    if (glm::dot(n, normal) < 0) std::swap(t[1], t[2]);
  }
  return result;
}

std::vector<glm::vec2> polygonPlaneCoordinates(const std::vector<glm::dvec3>& points,
                                               const glm::dvec3& normal) {
  std::vector<glm::vec2> uv(points.size(), glm::vec2(0.0f));
  if (points.empty() || !(glm::length(normal) > 0.0)) return uv;
  glm::dvec3 u(0.0);
  for (std::size_t i = 1; i < points.size() && !(glm::length(u) > 0.0); ++i) {
    const glm::dvec3 edge = points[i] - points[0];
    u = edge - normal * glm::dot(edge, normal);
  }
  if (!(glm::length(u) > 0.0)) return uv;
  u = glm::normalize(u);
  const glm::dvec3 v = glm::cross(normal, u);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 d = points[i] - points[0];
    uv[i] = glm::vec2(static_cast<float>(glm::dot(d, u)), static_cast<float>(glm::dot(d, v)));
  }
  return uv;
}

}  // namespace hirsute
