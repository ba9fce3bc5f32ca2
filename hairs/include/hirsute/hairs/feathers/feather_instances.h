// What every output needs to draw a Scene's feathers (docs/design.md, "Feathers"): the type each
// is built from (its two types blended, then grown) and the map from the geometry's local frame to
// the world. Each output builds the geometry itself, at the level of detail it needs.
#pragma once

#include <glm/mat4x4.hpp>

#include "hirsute/hairs/feathers/feather_geometry.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

// Whether `feather` names types the scene has.
bool hasFeatherTypes(const Scene& scene, const Feather& feather);

// The feather's own type: its four types blended bilinearly (Sec. 4.2.3, 4.4; Feather::types),
// then grown to `age` (Sec. 4.2.4). The feather must name types the scene has.
FeatherType featherTypeOf(const Scene& scene, const Feather& feather);

// Local geometry (x front, y left, z rachis) to world: x → up, y → left, z → heading, scaled by
// size, the origin at the calamus base.
glm::mat4 featherToWorld(const Feather& feather);

// The map of a feather's local geometry to the world: its frame (featherToWorld), or the pose the
// dynamics bent it into (FeatherPart::poses, FeatherPose), node maps blended by height.
class FeatherMap {
 public:
  explicit FeatherMap(const glm::mat4& rigid);
  explicit FeatherMap(const FeatherPose& pose);
  // The map of the i-th feather of `scene`: its pose when it has one, else its frame.
  static FeatherMap of(const Scene& scene, std::size_t feather);

  glm::vec3 point(const glm::vec3& local) const;
  // A direction at `local` (its length scaled as the map scales it).
  glm::vec3 direction(const glm::vec3& local, const glm::vec3& v) const;
  // A unit normal at `local`.
  glm::vec3 normal(const glm::vec3& local, const glm::vec3& n) const;

 private:
  // The node maps at `local` and the weight of the second.
  struct Blend {
    const glm::mat4* lower;
    const glm::mat4* upper;
    float t;
  };
  Blend blendAt(const glm::vec3& local) const;

  glm::mat4 rigid_{1.0f};
  glm::mat3 rigidNormals_{1.0f};  // the inverse transpose of the rigid map's linear part
  const FeatherPose* pose_ = nullptr;
};

// The feather's geometry at `detail`, in its local frame.
FeatherGeometry featherGeometryOf(const Scene& scene, const Feather& feather,
                                  const FeatherDetail& detail);

// Calls `visit(geometry, isAfterfeather)` for the feather's geometry and each afterfeather in it.
template <class Visit>
void forEachFeatherPart(const FeatherGeometry& geometry, Visit&& visit, bool after = false) {
  visit(geometry, after);
  for (const FeatherGeometry& part : geometry.afterfeathers) forEachFeatherPart(part, visit, true);
}

}  // namespace hirsute
