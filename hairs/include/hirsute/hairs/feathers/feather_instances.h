// What every output needs to draw a Scene's feathers (DESIGN.md, "Feathers"): the type a feather
// is built from (its two types blended, then grown) and the map from the geometry's local frame to
// the world. Each output builds the geometry itself, at the level of detail it needs.
#pragma once

#include <glm/mat4x4.hpp>

#include "hirsute/hairs/feathers/feather_geometry.h"
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
