#include "hirsute/hairs/fur/fur_strands.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_strand.h"
#include "hirsute/hairs/fur/wetness_mask.h"

namespace hirsute::fur {
namespace {

// Barycentric coordinates of p in the triangle (a, b, c) of the plane; false when degenerate.
bool barycentric(const glm::vec2& p, const glm::vec2& a, const glm::vec2& b, const glm::vec2& c,
                 glm::vec3& weights) {
  const glm::vec2 e1 = b - a, e2 = c - a, d = p - a;
  const float det = e1.x * e2.y - e1.y * e2.x;
  if (std::abs(det) < 1e-20f) return false;
  const float w1 = (d.x * e2.y - d.y * e2.x) / det;
  const float w2 = (e1.x * d.y - e1.y * d.x) / det;
  weights = glm::vec3(1 - w1 - w2, w1, w2);
  return true;
}

// Visits every strand texel of the tiled texture whose centre lies in one of the surface's
// triangles (each centre in one triangle: the edge opposite the first vertex is left to the
// triangle beyond it), with the triangle and the barycentric weights.
template <class Visit>
void visitTexels(const Scene& scene, const FurSurface& surface, Visit&& visit) {
  const FurTexture& texture =
      scene.organ<FurPart>().textures[static_cast<std::size_t>(surface.furTexture)];
  const int n = texture.size;
  if (n <= 0) return;
  const float texel = 1.0f / static_cast<float>(n);
  for (std::size_t t = 0; t + 2 < surface.indices.size(); t += 3) {
    const std::array<std::uint32_t, 3> tri{surface.indices[t], surface.indices[t + 1], surface.indices[t + 2]};
    const glm::vec2 a = surface.texcoords[tri[0]], b = surface.texcoords[tri[1]], c = surface.texcoords[tri[2]];
    const glm::vec2 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    const int x0 = static_cast<int>(std::floor(lo.x * n - 0.5f)), x1 = static_cast<int>(std::ceil(hi.x * n - 0.5f));
    const int y0 = static_cast<int>(std::floor(lo.y * n - 0.5f)), y1 = static_cast<int>(std::ceil(hi.y * n - 0.5f));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const std::uint8_t length =
            texture.lengths[static_cast<std::size_t>(((y % n) + n) % n) * n +
                            static_cast<std::size_t>(((x % n) + n) % n)];
        if (length == 0) continue;
        const glm::vec2 centre((static_cast<float>(x) + 0.5f) * texel, (static_cast<float>(y) + 0.5f) * texel);
        glm::vec3 w;
        if (!barycentric(centre, a, b, c, w)) continue;
        if (!(w.x > 0 && w.y >= 0 && w.z >= 0)) continue;
        visit(tri, w, length);
      }
    }
  }
}

}  // namespace

std::size_t countStrands(const Scene& scene, const FurSurface& surface) {
  std::size_t n = 0;
  visitTexels(scene, surface, [&n](const auto&, const glm::vec3&, std::uint8_t) { ++n; });
  return n;
}

void forEachStrand(const Scene& scene, const FurSurface& surface, int samples,
                   const std::function<void(const FurStrandView&)>& emit) {
  if (surface.attributes < 0) return;
  const FurAttributes& fur =
      scene.organ<FurPart>().attributes[static_cast<std::size_t>(surface.attributes)];
  samples = std::max(2, samples);
  const int layers = surface.layers;
  const float radius = surface.strandRadius;
  std::vector<glm::vec3> points(static_cast<std::size_t>(samples));
  visitTexels(scene, surface, [&](const std::array<std::uint32_t, 3>& tri, const glm::vec3& w,
                                  std::uint8_t length) {
    auto mix3 = [&](const std::vector<glm::vec3>& v) {
      return w.x * v[tri[0]] + w.y * v[tri[1]] + w.z * v[tri[2]];
    };
    const glm::vec3 root = mix3(surface.positions);
    const glm::vec3 normal = glm::normalize(mix3(surface.normals));
    glm::vec3 u = mix3(surface.tangents);
    u = glm::normalize(u - glm::dot(u, normal) * normal);
    const glm::vec3 v = glm::cross(normal, u);
    // The particles' displacements from their rest tips, interpolated: a strand at rest stays
    // at its own p_0 however the normals turn across the triangle.
    glm::vec3 moved(0.0f);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t at = tri[static_cast<std::size_t>(k)];
      moved += w[k] * (surface.tips[at] - (surface.positions[at] + fur.length * surface.normals[at]));
    }
    const StrandRoot strand{root, normal, fur.length};
    const glm::vec3 tip = constrainTip(strand, strand.restTip() + moved);
    // The (u, v) at the root, and the world motion per unit of (u, v) over the triangle.
    const glm::vec2 uv = w.x * surface.uv[tri[0]] + w.y * surface.uv[tri[1]] + w.z * surface.uv[tri[2]];
    const glm::vec2 du1 = parameterDifference(surface, surface.uv[tri[1]], surface.uv[tri[0]]);
    const glm::vec2 du2 = parameterDifference(surface, surface.uv[tri[2]], surface.uv[tri[0]]);
    const glm::vec3 dp1 = surface.positions[tri[1]] - surface.positions[tri[0]];
    const glm::vec3 dp2 = surface.positions[tri[2]] - surface.positions[tri[0]];
    const float det = du1.x * du2.y - du1.y * du2.x;
    glm::vec3 perU(0.0f), perV(0.0f);
    if (std::abs(det) > 1e-20f) {
      perU = (dp1 * du2.y - dp2 * du1.y) / det;
      perV = (dp2 * du1.x - dp1 * du2.x) / det;
    }
    const glm::vec4 mask = wetnessAt(surface, uv);
    const float wetness = mask.w;
    const glm::vec2 clumpCentre(mask.x, mask.y);
    const bool clumped = wetness > 0;
    // Algorithm 2 discards a wet pixel farther from its clump's centre than the clump's radius
    // (it belongs to another clump) at every layer: no strand grows there.
    if (clumped && glm::length(parameterDifference(surface, uv, clumpCentre)) > mask.z) return;
    const float top = static_cast<float>(length) / 255.0f;
    for (int i = 0; i < samples; ++i) {
      const float h = top * static_cast<float>(i) / static_cast<float>(samples - 1);
      glm::vec3 p = bendPoint(strand, tip, h) +
                    curlOffset(h, wetness, fur.curlRadius, fur.curlFrequency, fur.length, u, v);
      if (clumped) {
        const float scale = clumpScale(h, fur.clumpShape, layers, wetness, mask.z);
        const glm::vec2 seen = clumpedPosition(clumpCentre + parameterDifference(surface, uv, clumpCentre),
                                               clumpCentre, scale);
        const glm::vec2 shift = seen - (clumpCentre + parameterDifference(surface, uv, clumpCentre));
        p += shift.x * perU + shift.y * perV;
      }
      points[static_cast<std::size_t>(i)] = p;
    }
    emit(FurStrandView{points, normal, uv, top, radius});
  });
}

const Texture* colourTexture(const Scene& scene, const FurAttributes& attributes) {
  const int index = attributes.sceneTexture();
  if (index < 0 || static_cast<std::size_t>(index) >= scene.textures.size()) return nullptr;
  const Texture& t = scene.textures[static_cast<std::size_t>(index)];
  return t.width > 0 && t.height > 0 && !t.rgba.empty() ? &t : nullptr;
}

namespace {

// The points a strand of `attributes` needs, before the cap.
double neededSamples(const FurAttributes& attributes) {
  if (attributes.curlRadius <= 0) return kMinStrandSamples;
  const double turns = std::abs(static_cast<double>(attributes.curlFrequency)) / (2 * 3.14159265358979);
  return std::ceil(turns * kSamplesPerTurn) + 1;
}

}  // namespace

int strandSamples(const FurAttributes& attributes) {
  const double needed = neededSamples(attributes);
  if (!(needed <= kMaxStrandSamples)) return kMaxStrandSamples;  // also a NaN frequency
  return std::max(kMinStrandSamples, static_cast<int>(needed));
}

bool strandSamplesCapped(const FurAttributes& attributes) {
  return !(neededSamples(attributes) <= kMaxStrandSamples);
}

int StrandBudget::charge(const Scene& scene, const FurSurface& surface, std::size_t index) {
  const FurPart& part = scene.organ<FurPart>();
  const int samples =
      surface.attributes < 0
          ? kMinStrandSamples
          : strandSamples(part.attributes[static_cast<std::size_t>(surface.attributes)]);
  used_ += countStrands(scene, surface) * static_cast<std::size_t>(samples);
  if (used_ > limit_) {
    throw GeometryLimitError("the fur's strands grew past " + std::to_string(limit_) +
                             " points (--max-vertices) at fur surface " +
                             std::to_string(index + 1) + " of " +
                             std::to_string(part.surfaces.size()) + " (" +
                             std::to_string(samples) + " points a strand for its curl)");
  }
  return samples;
}

}  // namespace hirsute::fur
