// Exact orientation predicates on double-precision points: the sign of a determinant computed as
// if in exact arithmetic. A floating-point filter answers when the rounded determinant is larger
// than its proven error bound (Shewchuk 1997, "Adaptive precision floating-point arithmetic and
// fast robust geometric predicates", the static bounds of orient2dfast/orient3dfast); otherwise
// the determinant is evaluated in GMP rationals, in which every double is exact.
#pragma once

#include <Eigen/Core>

namespace hirsute::dynamics {

// +1, 0 or -1: the sign of det[a - d; b - d; c - d]. Positive when d lies below the plane through
// a, b, c oriented so that a, b, c appear counter-clockwise from above; 0 exactly when the four
// points are coplanar. Throws std::invalid_argument for a coordinate that is not finite.
int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d);

// +1, 0 or -1: the orientation of a, b, c projected onto the plane of coordinates i and j
// (counter-clockwise positive); 0 exactly when the projections are collinear. Throws
// std::invalid_argument for a coordinate that is not finite.
int orient2d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int i,
             int j);

}  // namespace hirsute::dynamics
