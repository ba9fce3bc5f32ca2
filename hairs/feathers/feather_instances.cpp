#include "hirsute/hairs/feathers/feather_instances.h"

#include <algorithm>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "hirsute/hairs/feathers/feather_blend.h"
#include "hirsute/hairs/feathers/feather_part.h"

namespace hirsute {

bool hasFeatherTypes(const Scene& scene, const Feather& feather) {
  const std::size_t n = scene.organ<FeatherPart>().types.size();
  return std::all_of(feather.types.begin(), feather.types.end(),
                     [n](std::uint16_t type) { return type >= 1 && type <= n; });
}

namespace {

// Types a and b (1-based) blended by t, without blending when there is nothing to blend.
FeatherType blendOf(const Scene& scene, std::uint16_t a, std::uint16_t b, float t) {
  const FeatherType& first = scene.organ<FeatherPart>().types[a - 1u];
  if (a == b || t <= 0) return first;
  const FeatherType& second = scene.organ<FeatherPart>().types[b - 1u];
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

FeatherMap::FeatherMap(const glm::mat4& rigid)
    : rigid_(rigid), rigidNormals_(glm::transpose(glm::inverse(glm::mat3(rigid)))) {}

FeatherMap::FeatherMap(const FeatherPose& pose) : pose_(&pose) {
  if (pose.heights.empty() || pose.heights.size() != pose.toWorld.size())
    throw std::invalid_argument("a feather pose needs one map per node");
}

FeatherMap FeatherMap::of(const Scene& scene, std::size_t feather) {
  if (feather < scene.organ<FeatherPart>().poses.size() &&
      !scene.organ<FeatherPart>().poses[feather].heights.empty())
    return FeatherMap(scene.organ<FeatherPart>().poses[feather]);
  return FeatherMap(featherToWorld(scene.organ<FeatherPart>().feathers[feather]));
}

FeatherMap::Blend FeatherMap::blendAt(const glm::vec3& local) const {
  const std::vector<float>& z = pose_->heights;
  const std::vector<glm::mat4>& maps = pose_->toWorld;
  if (local.z <= z.front()) return {&maps.front(), &maps.front(), 0};
  if (local.z >= z.back()) return {&maps.back(), &maps.back(), 0};
  const auto above = std::upper_bound(z.begin(), z.end(), local.z);
  const std::size_t i = static_cast<std::size_t>(above - z.begin()) - 1;
  const float span = z[i + 1] - z[i];
  return {&maps[i], &maps[i + 1], span > 0 ? (local.z - z[i]) / span : 0.0f};
}

glm::vec3 FeatherMap::point(const glm::vec3& local) const {
  if (!pose_) return glm::vec3(rigid_ * glm::vec4(local, 1));
  const Blend b = blendAt(local);
  const glm::vec4 p(local, 1);
  return glm::vec3((1 - b.t) * (*b.lower * p) + b.t * (*b.upper * p));
}

glm::vec3 FeatherMap::direction(const glm::vec3& local, const glm::vec3& v) const {
  if (!pose_) return glm::mat3(rigid_) * v;
  const Blend b = blendAt(local);
  return (1 - b.t) * (glm::mat3(*b.lower) * v) + b.t * (glm::mat3(*b.upper) * v);
}

glm::vec3 FeatherMap::normal(const glm::vec3& local, const glm::vec3& n) const {
  glm::vec3 m;
  if (!pose_) {
    m = rigidNormals_ * n;
  } else {
    const Blend b = blendAt(local);
    const glm::mat3 linear = (1 - b.t) * glm::mat3(*b.lower) + b.t * glm::mat3(*b.upper);
    m = glm::transpose(glm::inverse(linear)) * n;
  }
  const float length = glm::length(m);
  return length > 0 ? m / length : glm::vec3(1, 0, 0);
}

FeatherGeometry featherGeometryOf(const Scene& scene, const Feather& feather,
                                  const FeatherDetail& detail) {
  return buildFeatherGeometry(featherTypeOf(scene, feather), detail);
}

}  // namespace hirsute
