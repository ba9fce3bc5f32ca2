// Closest points on segments and triangles, for contacts, repulsion and binding roots.
#include "hirsute/hairs/dynamics/closest_points.h"

#include <algorithm>

namespace hirsute::dynamics {

using Eigen::Vector3d;

// Closest points of segments p0p1 and q0q1: p0 + s (p1 - p0) and q0 + u (q1 - q0), s, u in [0, 1]
// (the usual clamped solution of the 2x2 normal equations, degenerate segments included).
std::pair<double, double> closestOnSegments(const Vector3d& p0, const Vector3d& p1,
                                            const Vector3d& q0, const Vector3d& q1) {
  const Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kTiny = 1e-300;
  if (a <= kTiny && e <= kTiny) return {0, 0};
  if (a <= kTiny) return {0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e <= kTiny) return {std::clamp(-c / a, 0.0, 1.0), 0};
  const double b = d1.dot(d2), denominator = a * e - b * b;
  double s = denominator > 0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  double u = (b * s + f) / e;
  if (u < 0) {
    u = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (u > 1) {
    u = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, u};
}

// Barycentric weights of the point of triangle abc closest to p (Voronoi regions of the corners,
// edges and face).
std::array<double, 3> closestOnTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                                        const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};  // a degenerate triangle
  return {va / sum, vb / sum, vc / sum};
}

}  // namespace hirsute::dynamics
