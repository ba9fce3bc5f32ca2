// One segment of a uniform cubic B-spline in basis-function form, the polynomial cpfg uses for
// generalized-cylinder contours (reference/cpfg-generalized-cylinders.md §5:
// a0 = (c0+4c1+c2)/6, a1 = (c2−c0)/2, a2 = (c0−2c1+c2)/2, a3 = (−c0+3c1−3c2+c3)/6), used by the
// contour resampling of the interpreter. (curveX/Y/Z follow cpfg's curve code instead, with its
// Cox–de Boor evaluation and parameter scale: function_curve.cpp.)
#pragma once

#include <array>

namespace hirsute {

using SplinePoint = std::array<double, 3>;

// The point at t ∈ [0, 1] of the segment whose control points are p0…p3.
inline SplinePoint uniformBSplinePoint(const SplinePoint& p0, const SplinePoint& p1,
                                       const SplinePoint& p2, const SplinePoint& p3, double t) {
  const double t2 = t * t;
  const double t3 = t2 * t;
  const double b0 = (1.0 - t) * (1.0 - t) * (1.0 - t) / 6.0;
  const double b1 = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
  const double b2 = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
  const double b3 = t3 / 6.0;
  SplinePoint out{};
  for (int k = 0; k < 3; ++k) out[k] = b0 * p0[k] + b1 * p1[k] + b2 * p2[k] + b3 * p3[k];
  return out;
}

// The derivative with respect to t of the same segment.
inline SplinePoint uniformBSplineTangent(const SplinePoint& p0, const SplinePoint& p1,
                                         const SplinePoint& p2, const SplinePoint& p3, double t) {
  const double t2 = t * t;
  const double d0 = -(1.0 - t) * (1.0 - t) / 2.0;
  const double d1 = (9.0 * t2 - 12.0 * t) / 6.0;
  const double d2 = (-9.0 * t2 + 6.0 * t + 3.0) / 6.0;
  const double d3 = t2 / 2.0;
  SplinePoint out{};
  for (int k = 0; k < 3; ++k) out[k] = d0 * p0[k] + d1 * p1[k] + d2 * p2[k] + d3 * p3[k];
  return out;
}

}  // namespace hirsute
