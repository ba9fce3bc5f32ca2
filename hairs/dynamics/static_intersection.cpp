// Exact segment-triangle, segment-segment and triangle-triangle intersection from orientation
// signs alone.
#include "hirsute/hairs/dynamics/static_intersection.h"

#include <algorithm>

#include "hirsute/hairs/dynamics/exact_predicates.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// The coordinate pairs of the three axis-aligned projections.
constexpr int kProjections[3][2] = {{1, 2}, {2, 0}, {0, 1}};

// Whether x lies in the closed box spanned by p and q in coordinates i and j (exact comparisons).
bool inBox2d(const Vector3d& p, const Vector3d& q, const Vector3d& x, int i, int j) {
  return std::min(p[i], q[i]) <= x[i] && x[i] <= std::max(p[i], q[i]) &&
         std::min(p[j], q[j]) <= x[j] && x[j] <= std::max(p[j], q[j]);
}

// Closed segments pq and rs in the projection (i, j), degenerate segments included.
bool segmentsIntersect2d(const Vector3d& p, const Vector3d& q, const Vector3d& r, const Vector3d& s,
                         int i, int j) {
  const int d1 = orient2d(r, s, p, i, j), d2 = orient2d(r, s, q, i, j);
  const int d3 = orient2d(p, q, r, i, j), d4 = orient2d(p, q, s, i, j);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;  // a proper crossing
  // Otherwise they meet only where an end of one lies on the other.
  return (d1 == 0 && inBox2d(r, s, p, i, j)) || (d2 == 0 && inBox2d(r, s, q, i, j)) ||
         (d3 == 0 && inBox2d(p, q, r, i, j)) || (d4 == 0 && inBox2d(p, q, s, i, j));
}

// Point x in the closed, non-degenerate triangle abc of the projection (i, j).
bool pointInTriangle2d(const Vector3d& x, const Vector3d& a, const Vector3d& b, const Vector3d& c,
                       int i, int j) {
  const int area = orient2d(a, b, c, i, j);
  if (area == 0) return false;  // degenerate: its points are on its edges, tested there
  const int s1 = orient2d(a, b, x, i, j), s2 = orient2d(b, c, x, i, j),
            s3 = orient2d(c, a, x, i, j);
  return s1 * area >= 0 && s2 * area >= 0 && s3 * area >= 0;
}

// Closed segment pq and closed triangle abc in the projection (i, j): an end inside the triangle,
// or the segment meeting an edge. A degenerate projected triangle is the union of its edges.
bool segmentIntersectsTriangle2d(const Vector3d& p, const Vector3d& q, const Vector3d& a,
                                 const Vector3d& b, const Vector3d& c, int i, int j) {
  return pointInTriangle2d(p, a, b, c, i, j) || pointInTriangle2d(q, a, b, c, i, j) ||
         segmentsIntersect2d(p, q, a, b, i, j) || segmentsIntersect2d(p, q, b, c, i, j) ||
         segmentsIntersect2d(p, q, c, a, i, j);
}

// For points known to lie in one plane (or on one line, or at one point), some axis-aligned
// projection is one-to-one on that plane; intersecting in every projection is then the same as
// intersecting in space, and intersecting in space implies it in every projection.
template <typename Test>
bool inEveryProjection(Test test) {
  for (const auto& axes : kProjections) {
    if (!test(axes[0], axes[1])) return false;
  }
  return true;
}

}  // namespace

bool segmentIntersectsTriangle(const Vector3d& p, const Vector3d& q, const Vector3d& a,
                               const Vector3d& b, const Vector3d& c) {
  const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
  if (sp * sq > 0) return false;  // both ends strictly on one side of the plane
  const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  if (sp != 0 || sq != 0) {
    // The triangle is not degenerate (a degenerate one has every orient3d zero) and the segment
    // reaches its plane at one point; the line pq passes through the closed triangle exactly when
    // it passes no edge on the outer side of another, the three volumes not of mixed signs.
    const bool positive = s1 > 0 || s2 > 0 || s3 > 0;
    const bool negative = s1 < 0 || s2 < 0 || s3 < 0;
    return !(positive && negative);
  }
  // Both ends in the plane of abc, or abc degenerate. In the latter case the segment and the
  // triangle's line are coplanar exactly when the three volumes vanish; otherwise they are skew
  // (or the segment misses the triangle's plane entirely) and do not meet.
  if (s1 != 0 || s2 != 0 || s3 != 0) return false;
  return inEveryProjection(
      [&](int i, int j) { return segmentIntersectsTriangle2d(p, q, a, b, c, i, j); });
}

bool segmentsIntersect(const Vector3d& p, const Vector3d& q, const Vector3d& r, const Vector3d& s) {
  if (orient3d(p, q, r, s) != 0) return false;  // not coplanar: skew
  return inEveryProjection([&](int i, int j) { return segmentsIntersect2d(p, q, r, s, i, j); });
}

bool trianglesIntersect(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d,
                        const Vector3d& e, const Vector3d& f) {
  return segmentIntersectsTriangle(a, b, d, e, f) || segmentIntersectsTriangle(b, c, d, e, f) ||
         segmentIntersectsTriangle(c, a, d, e, f) || segmentIntersectsTriangle(d, e, a, b, c) ||
         segmentIntersectsTriangle(e, f, a, b, c) || segmentIntersectsTriangle(f, d, a, b, c);
}

}  // namespace hirsute::dynamics
