// Surfaces and polygons laid out in (U, V) for the placement engine (patch_unfolding.h).
#include "hirsute/hairs/placement/patch_unfolding.h"

#include <algorithm>
#include <cmath>

#include "hirsute/hairs/placement/corner_frame.h"

namespace hirsute {

PatchUnfolding::PatchUnfolding(const OrganSurface& surface, const TriangleMesh& mesh)
    : surface_(surface), mesh_(mesh) {
  const std::size_t count = triangles();
  glm::vec2 high(-1e30f);
  low_ = glm::vec2(1e30f);
  for (const glm::vec2& uv : surface.uv) {
    low_ = glm::min(low_, uv);
    high = glm::max(high, uv);
  }
  span_ = glm::max(high - low_, glm::vec2(1e-30f));
  if (surface.kind == OrganSurfaceKind::Mesh) {
    // A mesh's atlas may pinch whole rows of (u, v) into a point (a sphere's poles), where a fit
    // over edges would follow the few pinched triangles: the scales are the root mean squares of
    // the triangles' ∂P/∂u and ∂P/∂v over the atlas, each triangle weighted by its (u, v) area.
    double su = 0, sv = 0, weight = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t i0 = corner(i, 0), i1 = corner(i, 1), i2 = corner(i, 2);
      const glm::dvec2 d1 = glm::dvec2(surface.uv[i1] - surface.uv[i0]);
      const glm::dvec2 d2 = glm::dvec2(surface.uv[i2] - surface.uv[i0]);
      const double det = d1.x * d2.y - d1.y * d2.x;
      if (det == 0) continue;
      const glm::dvec3 e1 = glm::dvec3(position(i1) - position(i0));
      const glm::dvec3 e2 = glm::dvec3(position(i2) - position(i0));
      const glm::dvec3 dU = (d2.y * e1 - d1.y * e2) / det, dV = (-d2.x * e1 + d1.x * e2) / det;
      const double w = 0.5 * std::abs(det);
      su += w * glm::dot(dU, dU);
      sv += w * glm::dot(dV, dV);
      weight += w;
    }
    if (weight > 0 && su > 0 && sv > 0) {
      scale_ = glm::vec2(static_cast<float>(std::sqrt(su / weight)),
                         static_cast<float>(std::sqrt(sv / weight)));
    }
  } else if (surface.kind != OrganSurfaceKind::Polygon) {
    // The scales for which the triangles' edges have, in the least-squares sense, their world
    // lengths: |e|² ≈ Lu²·Δu² + Lv²·Δv² over every edge, solved for Lu² and Lv².
    double a = 0, b = 0, c = 0, ru = 0, rv = 0;
    for (std::size_t i = 0; i < count; ++i) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t p = corner(i, k), q = corner(i, (k + 1) % 3);
        const glm::dvec2 d = glm::dvec2(surface.uv[q] - surface.uv[p]);
        const double length2 =
            glm::dot(glm::dvec3(position(q) - position(p)), glm::dvec3(position(q) - position(p)));
        const double x = d.x * d.x, y = d.y * d.y;
        a += x * x;
        b += x * y;
        c += y * y;
        ru += x * length2;
        rv += y * length2;
      }
    }
    const double det = a * c - b * b;
    double lu2 = det != 0 ? (ru * c - rv * b) / det : 0,
           lv2 = det != 0 ? (rv * a - ru * b) / det : 0;
    // A degenerate fit (a patch flat in one direction) falls back to the mean edge scales.
    if (!(lu2 > 0)) lu2 = a > 0 ? ru / a : 1;
    if (!(lv2 > 0)) lv2 = c > 0 ? rv / c : 1;
    scale_ = glm::vec2(static_cast<float>(std::sqrt(lu2)), static_cast<float>(std::sqrt(lv2)));
  }
  ratio_.assign(count, 0.0f);
  height_.assign(count, glm::vec3(0.0f));
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t i0 = corner(i, 0), i1 = corner(i, 1), i2 = corner(i, 2);
    const glm::vec3 e1 = position(i1) - position(i0), e2 = position(i2) - position(i0);
    const double world = 0.5 * glm::length(glm::cross(glm::dvec3(e1), glm::dvec3(e2)));
    area_ += world;
    const glm::vec2 d1 = plane(i1) - plane(i0), d2 = plane(i2) - plane(i0);
    const float det = d1.x * d2.y - d1.y * d2.x;
    if (std::abs(det) > 0.0f) {
      ratio_[i] = static_cast<float>(world / (0.5 * std::abs(static_cast<double>(det))));
      // ∂P/∂V of the triangle's affine map (U, V) → P.
      const glm::vec3 dV = (-d2.x * e1 + d1.x * e2) / det;
      height_[i] = normalizedOr(dV, glm::vec3(0.0f));
    }
    maxRatio_ = std::max(maxRatio_, ratio_[i]);
  }
}

}  // namespace hirsute
