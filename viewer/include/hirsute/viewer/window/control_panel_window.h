// The model's vlab control panels (.pnl, control_panel.h) as windows (docs/viewer.md,
// "Editors"): sliders, toggle and monostable buttons, button groups (one on at a time), labels,
// pages and menu items, each sending its message as vlab's panel manager does, and below them
// the panel's editor: a slider's range, a slider added for a constant or removed, undo, redo and
// save.
#pragma once

#include "hirsute/viewer/interaction/live_model.h"

namespace hirsute {

void drawControlPanels(LiveModel& live);

}  // namespace hirsute
