// The palette and material editor's window (docs/viewer.md, "Editors"; vlab's `palette` and
// `medit`): the 256 colours of a colour file as a grid, the selected entry's colour or its
// material's ambient, diffuse, specular and emission colours, shininess and transparency, with
// undo, redo and save; each change is drawn on the plant at once (LiveModel::editPalette).
#pragma once

#include <cstddef>

#include "hirsute/viewer/interaction/live_model.h"

namespace hirsute {

// What the window remembers between frames.
struct PaletteUiState {
  std::size_t file = 0;  // of PaletteEditor::files()
  int selected = 1;      // the entry edited, 0..255
  bool editing = false;  // a widget is being dragged: its changes are one edit
  int scripted = -1;     // the script's entry last selected (LiveModel::scriptedEntry)
};

void drawPalettePanel(LiveModel& live, PaletteUiState& state, bool* open);

}  // namespace hirsute
