// A stem's vane as triangles, and the check of a state for vanes that meet.
#include "hirsute/hairs/dynamics/stem_vane.h"

#include <algorithm>
#include <limits>

#include "hirsute/hairs/dynamics/closest_points.h"
#include "hirsute/hairs/dynamics/static_intersection.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

bool hasQuad(const FeatherStem& stem, int segment, int side) {
  return segment >= 0 && segment + 1 < static_cast<int>(stem.vaneWidths.size()) &&
         stem.vaneWidths[segment][side] > 0 && stem.vaneWidths[segment + 1][side] > 0;
}

double pointTriangleDistance(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                             const Vector3d& c) {
  const auto w = closestOnTriangle(p, a, b, c);
  return (p - (w[0] * a + w[1] * b + w[2] * c)).norm();
}

double segmentDistance(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0,
                       const Vector3d& q1) {
  const auto [s, u] = closestOnSegments(p0, p1, q0, q1);
  return ((p0 + s * (p1 - p0)) - (q0 + u * (q1 - q0))).norm();
}

// The farthest of `points` from the plane of the triangle (a, b, c); 0 for a triangle with no
// plane (a segment or a point: it has no face to pass through, only edges).
template <std::size_t N>
double heightAbove(const std::array<Vector3d, N>& points, const Vector3d& a, const Vector3d& b,
                   const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a);
  if (!(n.norm() > 0)) return 0;
  const Vector3d unit = n.normalized();
  double h = 0;
  for (const Vector3d& p : points) h = std::max(h, std::abs(unit.dot(p - a)));
  return h;
}

// Whether the exact test may be skipped for two primitives whose nearest vertex-face and
// edge-edge features are `distance` apart: an edge that passed through the other's face within
// h of its plane (both ends within h) would come within h of a vertex-face or edge-edge pair
// (where it enters the face's shadow, from an end over the face or across one of its edges), so
// features farther apart than both primitives' heights over the other's plane cannot meet. This
// keeps the exact arithmetic for what it decides: vanes that lie in one plane (neighbours of a
// row) would otherwise take it for every pair, at nearly zero orientations.
bool apartByFeatures(double distance, double heights, const Vector3d& scale) {
  return distance > heights + 1e-9 * (1 + scale.cwiseAbs().maxCoeff());
}

// Whether every one of `points` is farther than `margin` from the plane of the triangle (a, b,
// c), all on one side: then all they span is, and nothing of it comes within `margin` of the
// triangle. The cheap answer for the layered vanes of a coat, a plane's width apart; a margin
// of 1e-9 of the coordinates covers the rounding. False for a triangle with no plane.
template <std::size_t N>
bool beyondPlane(const std::array<Vector3d, N>& points, const Vector3d& a, const Vector3d& b,
                 const Vector3d& c, double margin) {
  const Vector3d n = (b - a).cross(c - a);
  if (!(n.norm() > 0)) return false;
  const Vector3d unit = n.normalized();
  const double m = margin + 1e-9 * (1 + a.cwiseAbs().maxCoeff());
  bool above = true, below = true;
  for (const Vector3d& p : points) {
    const double h = unit.dot(p - a);
    above = above && h > m;
    below = below && h < -m;
  }
  return above || below;
}

bool trianglesBeyond(const std::array<Vector3d, 3>& u, const std::array<Vector3d, 3>& t,
                     double margin) {
  return beyondPlane(u, t[0], t[1], t[2], margin) || beyondPlane(t, u[0], u[1], u[2], margin);
}

}  // namespace

bool hasVaneQuad(const FeatherStem& stem, int segment, int side) {
  return hasQuad(stem, segment, side);
}

bool hasVaneCorner(const FeatherStem& stem, int node, int side) {
  return hasQuad(stem, node - 1, side) || hasQuad(stem, node, side);
}

std::vector<VaneTriangle> vaneTrianglesOf(const FeatherStem& stem) {
  std::vector<VaneTriangle> out;
  for (int i = 0; i + 1 < static_cast<int>(stem.vaneWidths.size()); ++i)
    for (int side = 0; side < 2; ++side) {
      if (!hasQuad(stem, i, side)) continue;
      out.push_back({i, side, {VaneVertex{i, -1}, VaneVertex{i + 1, -1}, VaneVertex{i + 1, side}}});
      out.push_back({i, side, {VaneVertex{i, -1}, VaneVertex{i + 1, side}, VaneVertex{i, side}}});
    }
  return out;
}

const Vector3d& positionOf(const FeatherStem& stem, VaneVertex v) {
  return v.side < 0 ? stem.positions[v.node] : stem.vaneCorners[v.node][v.side];
}

double segmentTriangleDistance(const Vector3d& p, const Vector3d& q, const Vector3d& a,
                               const Vector3d& b, const Vector3d& c) {
  // Apart, the nearest points are an end of the segment and the triangle, or the segment and an
  // edge; a segment through the triangle is found by the exact test, not by this.
  double d = std::min(pointTriangleDistance(p, a, b, c), pointTriangleDistance(q, a, b, c));
  d = std::min(
      {d, segmentDistance(p, q, a, b), segmentDistance(p, q, b, c), segmentDistance(p, q, c, a)});
  return d;
}

double triangleTriangleDistance(const std::array<Vector3d, 3>& s,
                                const std::array<Vector3d, 3>& t) {
  double d = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    d = std::min(d, pointTriangleDistance(s[k], t[0], t[1], t[2]));
    d = std::min(d, pointTriangleDistance(t[k], s[0], s[1], s[2]));
    for (int m = 0; m < 3; ++m)
      d = std::min(d, segmentDistance(s[k], s[(k + 1) % 3], t[m], t[(m + 1) % 3]));
  }
  return d;
}

VaneOverlaps::VaneOverlaps(const std::vector<FeatherStem>& stems) {
  int next = 0;
  for (int s = 0; s < static_cast<int>(stems.size()); ++s) {
    offset_.push_back(next);
    for (int i = 0; i + 1 < static_cast<int>(stems[s].nodeCount()); ++i) of_.push_back({s, i});
    next += static_cast<int>(stems[s].nodeCount()) - 1;
  }
}

std::size_t VaneOverlaps::release(const std::vector<FeatherStem>& stems, double clearance) {
  std::size_t released = 0;
  // Each segment with its vane, as the check sees it: the rachis segment (a calamus aside) and
  // its quads' triangles, built once for all the pairs.
  std::vector<std::vector<std::array<Vector3d, 3>>> ribbon(of_.size());
  for (int s = 0; s < static_cast<int>(stems.size()); ++s) {
    const FeatherStem& stem = stems[s];
    for (int i = 1; i + 1 < static_cast<int>(stem.nodeCount()); ++i)
      ribbon[offset_[s] + i].push_back(
          {stem.positions[i], stem.positions[i + 1], stem.positions[i + 1]});
    for (const VaneTriangle& t : vaneTrianglesOf(stem))
      ribbon[offset_[s] + t.segment].push_back({positionOf(stem, t.vertices[0]),
                                                positionOf(stem, t.vertices[1]),
                                                positionOf(stem, t.vertices[2])});
  }
  for (auto it = pairs_.begin(); it != pairs_.end();) {
    const auto& p = ribbon[*it >> 32];
    const auto& q = ribbon[*it & 0xffffffffu];
    bool apart = true;
    for (const auto& u : p)
      for (const auto& t : q) {
        // The distance first: overlapping vanes lie in one plane, where the exact test needs
        // exact arithmetic.
        if (!apart) break;
        if (trianglesBeyond(u, t, clearance)) continue;
        const double d = triangleTriangleDistance(u, t);
        apart =
            d > clearance &&
            (apartByFeatures(
                 d, std::max(heightAbove(u, t[0], t[1], t[2]), heightAbove(t, u[0], u[1], u[2])),
                 u[0]) ||
             !trianglesIntersect(u[0], u[1], u[2], t[0], t[1], t[2]));
      }
    if (apart) {
      it = pairs_.erase(it);
      ++released;
    } else {
      ++it;
    }
  }
  return released;
}

std::size_t countVaneIntersections(const std::vector<FeatherStem>& stems, double minimumDistance,
                                   const VaneOverlaps* skip) {
  BoxTree tree;
  return countVaneIntersections(stems, minimumDistance, tree, skip);
}

std::size_t countVaneIntersections(const std::vector<FeatherStem>& stems, double minimumDistance,
                                   BoxTree& tree, const VaneOverlaps* skip, VaneOverlaps* found,
                                   double slack) {
  // Stem segments other than calami, then vane triangles.
  struct Item {
    int stem, segment;
    std::array<Vector3d, 3> points;
    bool triangle;
  };
  std::vector<Item> items;
  std::vector<Box> boxes;
  bool anyVane = false;
  for (const FeatherStem& stem : stems) anyVane = anyVane || stem.hasVane();
  if (!anyVane) return 0;
  for (int s = 0; s < static_cast<int>(stems.size()); ++s)
    for (int i = 1; i + 1 < static_cast<int>(stems[s].nodeCount()); ++i) {
      const Vector3d &p = stems[s].positions[i], &q = stems[s].positions[i + 1];
      items.push_back({s, i, {p, q, q}, false});
      boxes.push_back(boxOf({p, q}, minimumDistance));
    }
  const std::size_t firstTriangle = items.size();
  for (int s = 0; s < static_cast<int>(stems.size()); ++s)
    for (const VaneTriangle& t : vaneTrianglesOf(stems[s])) {
      const std::array<Vector3d, 3> points{positionOf(stems[s], t.vertices[0]),
                                           positionOf(stems[s], t.vertices[1]),
                                           positionOf(stems[s], t.vertices[2])};
      items.push_back({s, t.segment, points, true});
      boxes.push_back(boxOf({points[0], points[1], points[2]}, minimumDistance));
    }
  const auto left = [&](const Item& p, const Item& q) {
    return skip != nullptr && skip->contains(skip->segmentIndex(p.stem, p.segment),
                                             skip->segmentIndex(q.stem, q.segment));
  };
  // Segments pair only with triangles: two segments are the stems' check.
  BoxGroups groups;
  for (std::size_t k = 0; k < items.size(); ++k) groups.of.push_back(k < firstTriangle ? 0 : 1);
  groups.pairsWith[0] = 0b10;
  groups.pairsWith[1] = 0b11;
  groups.moving = 0b11;
  std::vector<std::pair<int, int>> pairs;
  if (slack > 0) {
    // A point that moves at most `stray` in each coordinate moves at most sqrt(3) stray along
    // a unit normal: a pair one of whose planes keeps the other farther than the distance and
    // that for both sides' strays stays clear.
    constexpr double kAlongNormal = 1.75;
    std::vector<Box> vertices;
    std::vector<int> boxParts, vertexParts;  // each feather a part
    vertices.reserve(3 * items.size());
    for (const Item& item : items) {
      boxParts.push_back(item.stem);
      for (const Vector3d& x : item.points) {
        vertices.push_back({x, x});
        vertexParts.push_back(item.stem);
      }
    }
    BoxTree::KeptList list;
    list.slack = slack;
    list.tested = [&](int a, int b) { return items[a].stem != items[b].stem; };
    list.apart = [&](int a, int b, double strays) {
      const Item &p = items[a], &q = items[b];
      const auto& t = q.points;
      const double margin = minimumDistance + kAlongNormal * strays;
      return p.triangle ? trianglesBeyond(p.points, t, margin)
                        : beyondPlane(std::array<Vector3d, 2>{p.points[0], p.points[1]}, t[0], t[1],
                                      t[2], margin);
    };
    list.vertices = &vertices;
    list.boxParts = &boxParts;
    list.vertexParts = &vertexParts;
    pairs = tree.coherentPairs(boxes, groups, list,
                               [&](int a, int b) { return !left(items[a], items[b]); });
  } else {
    pairs = tree.overlappingPairs(boxes, groups, [&](int a, int b) {
      return items[a].stem != items[b].stem && !left(items[a], items[b]);
    });
  }
  // Whether box a's item and box b's triangle meet or come too near.
  const auto meet = [&](int a, int b) {
    const Item &p = items[a], &q = items[b];  // q is a triangle (triangles come last)
    const auto& t = q.points;
    if (!p.triangle) {
      const Vector3d &p0 = p.points[0], &p1 = p.points[1];
      if (beyondPlane(std::array<Vector3d, 2>{p0, p1}, t[0], t[1], t[2], minimumDistance))
        return false;
      const double d = segmentTriangleDistance(p0, p1, t[0], t[1], t[2]);
      return d < minimumDistance ||
             (!apartByFeatures(d, heightAbove(std::array<Vector3d, 2>{p0, p1}, t[0], t[1], t[2]),
                               p0) &&
              segmentIntersectsTriangle(p0, p1, t[0], t[1], t[2]));
    }
    const auto& u = p.points;
    if (trianglesBeyond(u, t, minimumDistance)) return false;
    // The distance first: it decides most pairs without the exact test.
    const double d = triangleTriangleDistance(u, t);
    return d < minimumDistance ||
           (!apartByFeatures(
                d, std::max(heightAbove(u, t[0], t[1], t[2]), heightAbove(t, u[0], u[1], u[2])),
                u[0]) &&
            trianglesIntersect(u[0], u[1], u[2], t[0], t[1], t[2]));
  };
  // The pairs are tested on the tree's threads, each into its own flag; counted in order.
  std::vector<char> meets(pairs.size(), 0);
  forEach(tree.pool(), pairs.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) meets[k] = meet(pairs[k].first, pairs[k].second);
  });
  std::size_t count = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (!meets[k]) continue;
    ++count;
    if (found != nullptr) {
      const Item &p = items[pairs[k].first], &q = items[pairs[k].second];
      found->insert(found->segmentIndex(p.stem, p.segment), found->segmentIndex(q.stem, q.segment));
    }
  }
  return count;
}

}  // namespace hirsute::dynamics
