// Closest points on segments and triangles (docs/dynamics.md, "Collisions").
#pragma once
#include <Eigen/Core>
#include <array>
#include <utility>

namespace hirsute::dynamics {

// Closest points of segments p0p1 and q0q1: p0 + s (p1 - p0) and q0 + u (q1 - q0), s, u in [0, 1]
// (the clamped solution of the 2x2 normal equations, degenerate segments included).
std::pair<double, double> closestOnSegments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                            const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);

// Barycentric weights of the point of triangle abc closest to p (by the Voronoi regions of its
// corners, edges and face).
std::array<double, 3> closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace hirsute::dynamics
