// The window's Dear ImGui overlays over the plant, drawn inside its frame: the status line
// (bottom left: the model, its step, the frame time, a line for each organ drawn with its own
// words, a long build's progress), the last error (top right, over the last good plant) and the key
// map (F1). They only show; the window acts on the keys.
#pragma once

#include <string>

#include "hirsute/viewer/gl/gl_renderer.h"
#include "hirsute/viewer/interaction/live_model.h"

namespace hirsute {

// `thinned`: the frame was drawn with a part of the instances of the organs that thin (hairs)
// only, the camera moving.
void drawStatusOverlay(const LiveModel& live, const GlRenderer& renderer,
                       const std::string& modelName, double frameMs, bool thinned);
void drawErrorOverlay(const std::string& error);
// `open` is cleared when the user closes it.
void drawHelpOverlay(bool* open);

}  // namespace hirsute
