#include "hirsute/hairs/feathers/bezier_curve.h"

#include <algorithm>
#include <array>
#include <glm/vec3.hpp>

namespace hirsute {

glm::dvec3 bezierPoint(std::span<const glm::vec3> vertices, double t) {
  if (vertices.empty()) return glm::dvec3(0);
  // de Casteljau: stable at every degree, unlike the Bernstein sum with binomials. Barbs have a
  // handful of vertices and are evaluated for every polyline vertex: no allocation for those.
  constexpr std::size_t kOnStack = 16;
  std::array<glm::dvec3, kOnStack> small;
  std::vector<glm::dvec3> large;
  glm::dvec3* points = small.data();
  if (vertices.size() > kOnStack) {
    large.resize(vertices.size());
    points = large.data();
  }
  std::copy(vertices.begin(), vertices.end(), points);
  for (std::size_t level = vertices.size() - 1; level > 0; --level) {
    for (std::size_t i = 0; i < level; ++i) points[i] = (1 - t) * points[i] + t * points[i + 1];
  }
  return points[0];
}

glm::dvec3 bezierDerivative(std::span<const glm::vec3> vertices, double t) {
  if (vertices.size() < 2) return glm::dvec3(0);
  // The derivative of a degree-n curve is n times the curve of the vertex differences.
  const std::size_t n = vertices.size() - 1;
  std::vector<glm::vec3> differences(n);
  for (std::size_t i = 0; i < n; ++i) differences[i] = vertices[i + 1] - vertices[i];
  return static_cast<double>(n) * bezierPoint(differences, t);
}

std::vector<glm::vec3> elevateBezierDegree(std::span<const glm::vec3> vertices) {
  if (vertices.empty()) return {};
  const std::size_t n = vertices.size() - 1;
  std::vector<glm::vec3> out(n + 2);
  out[0] = vertices[0];
  out[n + 1] = vertices[n];
  for (std::size_t i = 1; i <= n; ++i) {
    const double a = static_cast<double>(i) / static_cast<double>(n + 1);
    out[i] = glm::vec3(a * glm::dvec3(vertices[i - 1]) + (1 - a) * glm::dvec3(vertices[i]));
  }
  return out;
}

std::vector<glm::vec3> elevateBezierTo(std::span<const glm::vec3> vertices, std::size_t count) {
  std::vector<glm::vec3> out(vertices.begin(), vertices.end());
  while (!out.empty() && out.size() < count) out = elevateBezierDegree(out);
  return out;
}

}  // namespace hirsute
