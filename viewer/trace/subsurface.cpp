#include "hirsute/viewer/trace/subsurface.h"

#include <algorithm>
#include <cmath>

namespace hirsute::trace {

SlabWalk walkThroughSlab(const SubsurfaceMaterial& material, Random& random) {
  SlabWalk walk;
  if (!material.present()) return walk;
  // Only the depth matters in a slab infinite across, and with isotropic scattering the cosine
  // of a new direction with the normal is uniform in [−1, 1]: the walk is one-dimensional.
  const float thickness = material.thickness;
  float depth = 0;
  float cosine = std::sqrt(random.uniform());  // a diffuse entry: density 2μ
  glm::vec3 weight(1.0f);
  for (int step = 0;; ++step) {
    const float path = -std::log1p(-random.uniform()) * material.meanFreePath;
    depth += path * cosine;
    if (depth <= 0 || depth >= thickness) {
      walk.transmitted = depth >= thickness;
      walk.weight = weight;
      walk.steps = step;
      return walk;
    }
    if (step >= kMaxWalkSteps) return walk;  // counted as absorbed
    weight *= material.albedo;
    if (std::max(weight.r, std::max(weight.g, weight.b)) <= 0) return walk;
    cosine = 2 * random.uniform() - 1;
  }
}

void walkIntoSheet(const SubsurfaceMaterial& material, const SurfaceMaterial& base,
                   SurfaceMaterial& surface, Random& random) {
  const glm::vec3 before = base.reflectance + base.transmittance;
  const glm::vec3 now = surface.reflectance + surface.transmittance;
  glm::vec3 modulation(1.0f);
  for (int c = 0; c < 3; ++c) modulation[c] = before[c] > 0 ? now[c] / before[c] : 1.0f;
  const float entering =
      1 - std::clamp(std::max(surface.specular.r, std::max(surface.specular.g, surface.specular.b)),
                     0.0f, 1.0f);
  glm::vec3 reflected(0.0f), passed(0.0f);
  for (int k = 0; k < kWalksPerHit; ++k) {
    const SlabWalk walk = walkThroughSlab(material, random);
    (walk.transmitted ? passed : reflected) += walk.weight;
  }
  const float share = entering / static_cast<float>(kWalksPerHit);
  surface.reflectance = glm::clamp(reflected * modulation * share, 0.0f, 1.0f);
  surface.transmittance = glm::clamp(passed * modulation * share, 0.0f, 1.0f);
}

glm::vec3 singleScatteringAlbedo(const glm::vec3& colour) {
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) {
    const float a = std::clamp(colour[c], 0.0f, 1.0f);
    const float s = 4.09712f + 4.20863f * a - std::sqrt(9.59217f + 41.6808f * a + 17.7126f * a * a);
    out[c] = std::clamp(1 - s * s, 0.0f, 1.0f);
  }
  return out;
}

}  // namespace hirsute::trace
