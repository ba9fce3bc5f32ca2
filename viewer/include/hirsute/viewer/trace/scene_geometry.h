// The Scene in the path tracer: its own elements as GL draws them (meshes as triangles,
// lines as tubes, spheres and discs as Embree's points), then each organ's part through
// organTracers() (organ_tracer.h).
#pragma once

#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/trace/trace_scene.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute::trace {

// The Scene's own elements (meshes, lines, spheres, discs), then every organ's, into `out`, as
// `camera` sees them (the width of a pixel for pixel-wide lines, organs' levels of detail).
void addSceneGeometry(const Scene& scene, const Camera& camera, TraceScene& out);

}  // namespace hirsute::trace
