// `hirsute view`: the interactive window (GLFW, libGL), drawing with the same GlRenderer as the
// headless path what a LiveModel (live_model.h) shows: the model built off the render thread,
// re-derived when its files change, animated, its organs in motion (live_organ.h), a script's
// commands. The window keeps the window itself, the mouse and keys, which are cpfg's
// (cpfg-manual §1.3), the drawing, and ImGui overlays for help, progress, errors and the
// `#define` panel.
#pragma once

#include <cstddef>

#include "hirsute/viewer/interaction/live_model.h"
#include "hirsute/viewer/window/key_map.h"

namespace hirsute {

// The model's files, the first step, the script, --save and the watching are the live model's
// (live_model.h); the rest is the window's.
struct ViewerOptions : LiveModelOptions {
  int width = 800, height = 600;
  int samples = 4;
  bool showPanel = true;
  // Hairs drawn while the camera moves: at most this many (level of detail).
  std::size_t movingHairBudget = 20000;
};

// Opens the window and runs until it is closed or the script ends. Returns the exit code: 0; 1
// when the window cannot be opened or a scripted action fails (a screenshot that cannot be
// written, a wait that times out); 2 when the model shown last has an error.
int runViewer(const ViewerOptions& options, ModelBuilder builder);

}  // namespace hirsute
