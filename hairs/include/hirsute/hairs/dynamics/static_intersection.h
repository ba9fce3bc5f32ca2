// Exact intersection tests of closed segments and triangles at one instant: the final check that
// a simulation step ends in a state without intersection (docs/design.md, "Feather-coat dynamics").
// Every decision is a sign of an exact orientation predicate (exact_predicates.h), so the answer
// is that of exact arithmetic on the given doubles, degenerate cases included: touching at a
// vertex or along an edge counts as intersecting, coplanar configurations are decided in the
// plane, and degenerate triangles (collinear or coincident corners) are the segment or point
// they cover.
#pragma once

#include <Eigen/Core>

namespace hirsute::dynamics {

// Whether the closed segment pq and the closed triangle abc share a point.
bool segmentIntersectsTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                               const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c);

// Whether the closed segments pq and rs share a point.
bool segmentsIntersect(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                       const Eigen::Vector3d& s);

// Whether the closed triangles abc and def share a point. Two closed triangles meet exactly when
// an edge of one meets the other: the ends of the segment their planes' line cuts from the
// intersection lie on edges, and of two coplanar triangles either the boundaries cross or one
// holds the other's edges.
bool trianglesIntersect(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c, const Eigen::Vector3d& d,
                        const Eigen::Vector3d& e, const Eigen::Vector3d& f);

}  // namespace hirsute::dynamics
