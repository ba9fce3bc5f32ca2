#include "hirsute/hairs/feathers/feather_instances.h"

#include <glm/geometric.hpp>

#include "hirsute/hairs/feathers/feather_blend.h"

namespace hirsute {

bool hasFeatherTypes(const Scene& scene, const Feather& feather) {
  const std::size_t n = scene.featherTypes.size();
  return feather.type >= 1 && feather.type <= n && feather.blendType >= 1 && feather.blendType <= n;
}

FeatherType featherTypeOf(const Scene& scene, const Feather& feather) {
  const FeatherType& first = scene.featherTypes[feather.type - 1u];
  const bool blended = feather.blendType != feather.type && feather.blend != 0;
  if (!blended && feather.age >= 1) return first;
  FeatherType type =
      blended ? blendFeatherTypes(first, scene.featherTypes[feather.blendType - 1u], feather.blend)
              : first;
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
