// The viewer's constants panel (beyond cpfg): the `#define` constants of the .l with a slider
// each, drawn with Dear ImGui inside the window's frame. It only reports what the user did; the
// window applies it (re-derives, and with `--save` writes the file).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "hirsute/viewer/interaction/define_editor.h"

namespace hirsute {

struct DefinePanel {
  struct Edit {
    std::string name, value;  // the value as it will be written into the .l
    bool finished = false;    // the slider was let go (or a typed value entered)
  };
  std::vector<Edit> edits;
  bool save = false;       // "Save into the .l"
  bool revert = false;     // "Revert": back to the file's values
  bool makePanel = false;  // "Make a .pnl": a vlab control panel of these constants
};

// Draws the panel for this frame: `constants` as the file has them, `changed` the values set
// since; without `saveAtOnce` it has the Save and Revert buttons. `open` is cleared when the
// user closes it.
DefinePanel drawDefinePanel(const std::vector<DefineConstant>& constants,
                            const std::map<std::string, std::string>& changed, bool saveAtOnce,
                            bool* open);

}  // namespace hirsute
