// An organ's part in the path tracer (docs/design.md, "Organs": the ray tracer's
// geometry and materials): addSceneGeometry() (trace_scene.h) visits organTracers() after the
// Scene's own elements, and each organ adds its shapes and materials from its own folder
// (hairs/NAME/trace/). The tracer never names an organ; adding one adds a class derived from
// OrganTracer in its folder, returned by its nameTracer() (hairs/organs/organ_list.h).
#pragma once

#include <span>

#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/trace/trace_scene.h"

namespace hirsute::trace {

class OrganTracer {
 public:
  virtual ~OrganTracer() = default;
  // Adds the organ's shapes in `scene` (none when it has none) to `out`, at the detail of their
  // size in `camera`'s picture where the organ has levels of detail.
  virtual void addTo(const Scene& scene, const Camera& camera, TraceScene& out) const = 0;
};

// Every organ's tracer, in the order of hairs/organs/organ_list.h (organ_tracers.cpp).
std::span<const OrganTracer* const> organTracers();

}  // namespace hirsute::trace
