// The viewer's shape editors (docs/viewer.md, "Function curves", "Contours", "Surfaces"), drawn
// with Dear ImGui inside the window's frame: vlab's funcedit, cuspy and bezieredit as panels
// beside the plant. Each edits the workbench's documents (shape_workbench.h) and writes them as
// it goes; the window then has the live model re-derive (LiveModel::shapesEdited).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include "hirsute/viewer/interaction/shape_workbench.h"

namespace hirsute {

// What one editor keeps between frames: which file (and function) is shown, the point dragged,
// the plot's range held still during a drag, and the last message.
// Which file (and function) is shown, and whether the editor is open, are the workbench's
// (ShapeWorkbench::EditorView), so that the view script opens them too.
struct ShapePanelState {
  int selected = -1, dragging = -1;
  bool moved = false;  // the drag has changed the point (its first move is a new step)
  bool rangeHeld = false;
  float low[2] = {0, 0}, high[2] = {1, 1};
  int projection = 0;  // surfaces: 0 front (x, y), 1 side (z, y), 2 top (x, z)
  std::chrono::steady_clock::time_point lastWrite;
  std::string message;
};

// The three editors' states, and which one the script or a key opened.
struct ShapePanels {
  ShapePanelState function, contour, surface;
};

// Each draws its editor when open and applies what the user did to `workbench`.
void drawFunctionPanel(ShapeWorkbench& workbench, ShapePanelState& state);
void drawContourPanel(ShapeWorkbench& workbench, ShapePanelState& state);
void drawSurfacePanel(ShapeWorkbench& workbench, ShapePanelState& state);

}  // namespace hirsute
