#include "hirsute/hairs/feathers/feather_instances.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "hirsute/hairs/feathers/feather_blend.h"

namespace hirsute {

bool hasFeatherTypes(const Scene& scene, const Feather& feather) {
  const std::size_t n = scene.featherTypes.size();
  return std::all_of(feather.types.begin(), feather.types.end(),
                     [n](std::uint16_t type) { return type >= 1 && type <= n; });
}

namespace {

// Types a and b (1-based) blended by t, without blending when there is nothing to blend.
FeatherType blendOf(const Scene& scene, std::uint16_t a, std::uint16_t b, float t) {
  const FeatherType& first = scene.featherTypes[a - 1u];
  if (a == b || t <= 0) return first;
  const FeatherType& second = scene.featherTypes[b - 1u];
  if (t >= 1) return second;
  return blendFeatherTypes(first, second, t);
}

}  // namespace

FeatherType featherTypeOf(const Scene& scene, const Feather& feather) {
  const auto& k = feather.types;
  // The bilinear coat of Sec. 4.4: across the girth, then along the axis.
  const bool samePairs = k[0] == k[2] && k[1] == k[3] && feather.across[0] == feather.across[1];
  FeatherType type = blendOf(scene, k[0], k[1], feather.across[0]);
  if (!samePairs && feather.along > 0) {
    const FeatherType upper = blendOf(scene, k[2], k[3], feather.across[1]);
    type = feather.along >= 1 ? upper : blendFeatherTypes(type, upper, feather.along);
  }
  return feather.age >= 1 ? type : grownFeatherType(type, feather.age);
}

glm::mat4 featherToWorld(const Feather& feather) {
  const glm::vec3 x = feather.up * feather.size;
  const glm::vec3 y = feather.left() * feather.size;
  const glm::vec3 z = feather.heading * feather.size;
  return glm::mat4(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0),
                   glm::vec4(feather.position, 1));
}

FeatherGeometry featherGeometryOf(const Scene& scene, const Feather& feather,
                                  const FeatherDetail& detail) {
  return buildFeatherGeometry(featherTypeOf(scene, feather), detail);
}

}  // namespace hirsute
