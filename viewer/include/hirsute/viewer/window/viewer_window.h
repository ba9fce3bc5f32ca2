// `hirsute view`: the interactive window (GLFW, libGL), drawing with the same GlRenderer as the
// headless path. The model is built off the render thread by a ModelWorker; the window watches
// the model's files and re-derives when they change, keeping the camera; the mouse and keys are
// cpfg's (cpfg-manual §1.3), with an ImGui overlay for help, progress, errors and the `#define`
// panel. A script (view_script.h) drives the same actions without a person.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/viewer/interaction/animation_file.h"
#include "hirsute/viewer/interaction/model_worker.h"
#include "hirsute/viewer/interaction/view_script.h"

namespace hirsute {

struct ViewerOptions {
  std::filesystem::path lsystemFile;
  std::filesystem::path viewFile;                 // may be empty
  std::filesystem::path animationFile;            // may be empty: cpfg's defaults
  std::vector<std::filesystem::path> extraFiles;  // colour files and others to watch
  int width = 800, height = 600;
  int samples = 4;
  std::optional<int> steps;  // the step shown first; none: the derivation length
  // Scripted mode: the commands run in order; the window closes after the last one.
  std::optional<std::vector<ViewCommand>> script;
  // Constants changed in the panel are written back into the .l at once (`--save`).
  bool saveDefines = false;
  bool watch = true;  // live reloading
  bool showPanel = true;
  // Hairs drawn while the camera moves: at most this many (level of detail).
  std::size_t movingHairBudget = 20000;
};

// The key map, one line a key, as the help overlay and `docs/viewer.md` show it.
const std::vector<std::pair<std::string, std::string>>& viewerKeyMap();

// Opens the window and runs until it is closed or the script ends. Returns the exit code: 0; 1
// when the window cannot be opened or a scripted action fails (a screenshot that cannot be
// written, a wait that times out); 2 when the model shown last has an error.
int runViewer(const ViewerOptions& options, ModelBuilder builder);

}  // namespace hirsute
