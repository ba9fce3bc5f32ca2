#include "hirsute/hairs/fur/fur_motion.h"

#include <algorithm>
#include <cmath>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_strand.h"
#include "hirsute/hairs/fur/wetness_mask.h"

namespace hirsute::fur {

void FurMotion::reset(Scene& scene, const Scene* previousScene) {
  FurPart& fur = scene.organ<FurPart>();
  const FurPart* previous = previousScene ? &previousScene->organ<FurPart>() : nullptr;
  const bool carry = previous != nullptr && previous->surfaces.size() == fur.surfaces.size() &&
                     velocities_.size() == fur.surfaces.size();
  std::vector<std::vector<glm::vec3>> velocities(fur.surfaces.size());
  for (std::size_t s = 0; s < fur.surfaces.size(); ++s) {
    FurSurface& surface = fur.surfaces[s];
    velocities[s].assign(surface.positions.size(), glm::vec3(0.0f));
    if (!carry) continue;
    const FurSurface& before = previous->surfaces[s];
    if (before.positions.size() == surface.positions.size() &&
        velocities_[s].size() == surface.positions.size()) {
      for (std::size_t i = 0; i < surface.positions.size(); ++i) {
        // The particle stays where it was in the world; the spring pulls it after its root.
        surface.tips[i] = before.tips[i];
        velocities[s][i] = velocities_[s][i];
      }
    }
    if (before.wetnessSize == surface.wetnessSize) surface.wetness = before.wetness;
  }
  velocities_ = std::move(velocities);
}

bool FurMotion::step(Scene& scene, float seconds, const glm::vec3& force) {
  seconds = std::clamp(seconds, 0.0f, 0.1f);  // a stalled frame does not throw the fur
  return step(scene, seconds, [&force](const glm::vec3&) { return force; });
}

bool FurMotion::step(Scene& scene, float seconds,
                     const std::function<glm::vec3(const glm::vec3&)>& forceAt) {
  FurPart& fur = scene.organ<FurPart>();
  if (velocities_.size() != fur.surfaces.size()) reset(scene);
  seconds = std::max(seconds, 0.0f);
  const int steps = std::max(1, static_cast<int>(std::ceil(seconds / kMaxStep)));
  const float dt = seconds / static_cast<float>(steps);
  for (std::size_t s = 0; s < fur.surfaces.size(); ++s) {
    FurSurface& surface = fur.surfaces[s];
    if (surface.attributes < 0) continue;
    const FurAttributes& a = fur.attributes[static_cast<std::size_t>(surface.attributes)];
    for (std::size_t i = 0; i < surface.positions.size(); ++i) {
      const StrandRoot strand{surface.positions[i], surface.normals[i], a.length};
      const glm::vec3 force = forceAt(surface.positions[i]);
      StrandState state{surface.tips[i], velocities_[s][i]};
      for (int k = 0; k < steps; ++k) stepStrand(strand, a.stiffness, a.mass, kDamping, force, dt, state);
      surface.tips[i] = state.tip;
      velocities_[s][i] = state.velocity;
    }
  }
  return moving(scene);
}

bool FurMotion::moving(const Scene& scene, float speed) const {
  const FurPart& fur = scene.organ<FurPart>();
  for (std::size_t s = 0; s < fur.surfaces.size() && s < velocities_.size(); ++s) {
    const FurSurface& surface = fur.surfaces[s];
    if (surface.attributes < 0) continue;
    const float length = fur.attributes[static_cast<std::size_t>(surface.attributes)].length;
    for (const glm::vec3& v : velocities_[s]) {
      if (glm::length(v) > speed * length) return true;
    }
  }
  return false;
}

FurMeasures measureFur(const Scene& scene, const FurMotion* motion) {
  const FurPart& fur = scene.organ<FurPart>();
  FurMeasures m;
  double bends = 0, wetness = 0;
  for (std::size_t s = 0; s < fur.surfaces.size(); ++s) {
    const FurSurface& surface = fur.surfaces[s];
    if (surface.attributes < 0) continue;
    const float length = fur.attributes[static_cast<std::size_t>(surface.attributes)].length;
    if (!(length > 0)) continue;
    for (std::size_t i = 0; i < surface.positions.size() && i < surface.tips.size(); ++i) {
      const glm::vec3 rest = surface.positions[i] + length * surface.normals[i];
      const double bend = glm::length(surface.tips[i] - rest) / length;
      bends += bend;
      m.largestBend = std::max(m.largestBend, bend);
      ++m.strands;
    }
    if (motion != nullptr && s < motion->velocities().size()) {
      for (const glm::vec3& v : motion->velocities()[s])
        m.largestSpeed = std::max(m.largestSpeed, static_cast<double>(glm::length(v) / length));
    }
    m.texels += surface.wetness.size();
    for (const glm::vec4& texel : surface.wetness) {
      if (texel.w <= 0) continue;
      ++m.wetTexels;
      wetness += texel.w;
    }
  }
  if (m.strands > 0) m.meanBend = bends / static_cast<double>(m.strands);
  if (m.wetTexels > 0) m.meanWetness = wetness / static_cast<double>(m.wetTexels);
  return m;
}

bool dryFur(Scene& scene, float rate, float seconds) {
  FurPart& fur = scene.organ<FurPart>();
  bool wet = false;
  for (FurSurface& surface : fur.surfaces) wet = dry(surface, rate * seconds) || wet;
  return wet;
}

std::optional<FurHit> pickFur(const Scene& scene, const glm::vec3& origin,
                              const glm::vec3& direction) {
  const FurPart& fur = scene.organ<FurPart>();
  std::optional<FurHit> best;
  for (std::size_t s = 0; s < fur.surfaces.size(); ++s) {
    const FurSurface& surface = fur.surfaces[s];
    for (std::size_t t = 0; t + 2 < surface.indices.size(); t += 3) {
      const std::uint32_t a = surface.indices[t], b = surface.indices[t + 1], c = surface.indices[t + 2];
      // Möller-Trumbore.
      const glm::vec3 e1 = surface.positions[b] - surface.positions[a];
      const glm::vec3 e2 = surface.positions[c] - surface.positions[a];
      const glm::vec3 p = glm::cross(direction, e2);
      const float det = glm::dot(e1, p);
      if (std::abs(det) < 1e-20f) continue;
      const glm::vec3 q = origin - surface.positions[a];
      const float u = glm::dot(q, p) / det;
      if (u < 0 || u > 1) continue;
      const glm::vec3 r = glm::cross(q, e1);
      const float v = glm::dot(direction, r) / det;
      if (v < 0 || u + v > 1) continue;
      const float distance = glm::dot(e2, r) / det;
      if (distance < 0 || (best && distance >= best->distance)) continue;
      // (u, v) of the surface, the short way round across a wrapping seam.
      const glm::vec2 ua = surface.uv[a];
      const glm::vec2 ub = ua + parameterDifference(surface, surface.uv[b], ua);
      const glm::vec2 uc = ua + parameterDifference(surface, surface.uv[c], ua);
      glm::vec2 uv = (1 - u - v) * ua + u * ub + v * uc;
      if (surface.wrapsU) uv.x -= std::floor(uv.x);
      best = FurHit{s, glm::clamp(uv, glm::vec2(0.0f), glm::vec2(1.0f)), distance};
    }
  }
  return best;
}

}  // namespace hirsute::fur
