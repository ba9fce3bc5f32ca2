// Bézier curves of any degree, the curve of every barb and of the rachis (Streit & Heidrich
// 2002, Sec. 4.2.1, 4.3.1). Computed in double and stored in float.
#pragma once

#include <cstddef>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

namespace hirsute {

// The point at parameter t in [0, 1], by de Casteljau's algorithm. Empty control polygons give
// the origin, one vertex gives that vertex.
glm::dvec3 bezierPoint(std::span<const glm::vec3> vertices, double t);

// The first derivative at t (zero for fewer than two vertices).
glm::dvec3 bezierDerivative(std::span<const glm::vec3> vertices, double t);

// Sec. 4.2.1 (after Rockwood & Chambers 1996): the same curve with one more control vertex,
// cv'_0 = cv_0, cv'_{n+1} = cv_n and cv'_i = i/(n+1) cv_{i-1} + (1 - i/(n+1)) cv_i. Exact: the
// curve does not change.
std::vector<glm::vec3> elevateBezierDegree(std::span<const glm::vec3> vertices);

// Elevated repeatedly to `count` vertices (no change when it already has that many or more).
std::vector<glm::vec3> elevateBezierTo(std::span<const glm::vec3> vertices, std::size_t count);

}  // namespace hirsute
