// The surface editor (vlab's bezieredit): the model's `.s` bicubic patches in a projection
// (front, side or top), their 16 control points each dragged in the projection's plane or set in
// numbers, the patches drawn as cpfg's bicubic Bézier surfaces; the leaf on the plant follows as
// the file is written during the drag.
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "hirsute/viewer/window/shape_panels.h"
#include "plot_canvas.h"

namespace hirsute {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kDragWriteInterval = std::chrono::milliseconds(200);
// The lines drawn across each patch, each way.
constexpr int kPatchLines = 10;
constexpr ImU32 kPatchColour = IM_COL32(110, 220, 120, 200);

// The file's coordinates each projection shows across and up.
constexpr std::array<std::array<int, 2>, 3> kAxes = {{{0, 1}, {2, 1}, {0, 2}}};
constexpr const char* kProjections[] = {"front (x, y)", "side (z, y)", "top (x, z)"};

// A point of a bicubic Bézier patch (cpfg-features.md "Bicubic surface .s"): rows of the file
// along t, points within a row along s, blended by the cubic Bernstein polynomials.
glm::dvec3 patchPoint(const BezierPatch& patch, double s, double t) {
  const auto bernstein = [](double u) {
    const double v = 1 - u;
    return std::array<double, 4>{v * v * v, 3 * u * v * v, 3 * u * u * v, u * u * u};
  };
  const std::array<double, 4> bs = bernstein(s), bt = bernstein(t);
  glm::dvec3 p(0.0);
  for (int row = 0; row < 4; ++row) {
    for (int k = 0; k < 4; ++k) p += bt[row] * bs[k] * patch.points[row * 4 + k];
  }
  return p;
}

}  // namespace

void drawSurfacePanel(ShapeWorkbench& workbench, ShapePanelState& state) {
  ShapeWorkbench::EditorView& view = workbench.surfaceView;
  if (!view.open) return;
  std::vector<SurfaceDocument>& documents = workbench.surfaces();
  if (!beginShapeWindow("Surfaces", &view.open, 470, documents.empty(),
                        "The view file names no bicubic surface (surface: with a .s file).")) {
    return;
  }
  view.document = std::min(view.document, documents.size() - 1);
  if (chooseDocument("surface", documents, view.document)) state.selected = state.dragging = -1;
  ImGui::SetNextItemWidth(160);
  if (ImGui::Combo("projection", &state.projection, kProjections, 3)) state.dragging = -1;
  const std::array<int, 2> axes = kAxes[static_cast<std::size_t>(state.projection)];

  SurfaceDocument& shown = documents[view.document];
  const Surface surface = shown.history.current().surface();  // a copy: an edit replaces it
  const int count = static_cast<int>(surface.patches.size()) * 16;
  if (state.selected >= count) state.selected = -1;
  const auto pointOf = [&](int i) -> const glm::dvec3& {
    return surface.patches[static_cast<std::size_t>(i / 16)]
        .points[static_cast<std::size_t>(i % 16)];
  };

  if (state.dragging < 0) {
    float low[2] = {INFINITY, INFINITY}, high[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i < count; ++i) {
      for (int k = 0; k < 2; ++k) {
        const float v = static_cast<float>(pointOf(i)[axes[static_cast<std::size_t>(k)]]);
        low[k] = std::min(low[k], v);
        high[k] = std::max(high[k], v);
      }
    }
    const float margin = 0.15f * std::max(high[0] - low[0], high[1] - low[1]) + 1e-3f;
    for (int k = 0; k < 2; ++k) {
      state.low[k] = low[k] - margin;
      state.high[k] = high[k] + margin;
    }
  }
  const PlotCanvas canvas = beginCanvas("##surface", 300, state.low, state.high, true);
  const bool active = ImGui::IsItemActive();
  const auto screen = [&](const glm::dvec3& p) {
    return canvas.toScreen(static_cast<float>(p[axes[0]]), static_cast<float>(p[axes[1]]));
  };
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->PushClipRect(canvas.origin,
                     ImVec2(canvas.origin.x + canvas.size.x, canvas.origin.y + canvas.size.y),
                     true);
  for (const BezierPatch& patch : surface.patches) {
    // The patch: lines of constant s and of constant t.
    for (int a = 0; a <= kPatchLines; ++a) {
      std::vector<ImVec2> alongS, alongT;
      for (int b = 0; b <= 2 * kPatchLines; ++b) {
        const double u = static_cast<double>(a) / kPatchLines;
        const double v = static_cast<double>(b) / (2 * kPatchLines);
        alongS.push_back(screen(patchPoint(patch, v, u)));
        alongT.push_back(screen(patchPoint(patch, u, v)));
      }
      draw->AddPolyline(alongS.data(), static_cast<int>(alongS.size()), kPatchColour,
                        ImDrawFlags_None, 1.0f);
      draw->AddPolyline(alongT.data(), static_cast<int>(alongT.size()), kPatchColour,
                        ImDrawFlags_None, 1.0f);
    }
    // The control net.
    for (int row = 0; row < 4; ++row) {
      for (int k = 0; k < 4; ++k) {
        const ImVec2 p = screen(patch.points[row * 4 + k]);
        if (k < 3) draw->AddLine(p, screen(patch.points[row * 4 + k + 1]), kPolygonColour);
        if (row < 3) draw->AddLine(p, screen(patch.points[(row + 1) * 4 + k]), kPolygonColour);
      }
    }
  }
  for (int i = 0; i < count; ++i) {
    draw->AddCircleFilled(screen(pointOf(i)), 4.0f,
                          i == state.selected ? kSelectedColour : kPointColour);
  }
  draw->PopClipRect();

  float mouse[2] = {0, 0};
  canvas.toPlane(ImGui::GetIO().MousePos, mouse[0], mouse[1]);
  if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    // Of points on top of each other in this projection, the one drawn last (the later patch).
    int under = -1;
    const ImVec2 m = ImGui::GetIO().MousePos;
    for (int i = 0; i < count; ++i) {
      const ImVec2 p = screen(pointOf(i));
      if ((p.x - m.x) * (p.x - m.x) + (p.y - m.y) * (p.y - m.y) <= kGrabPixels * kGrabPixels)
        under = i;
    }
    state.dragging = state.selected = under;
    state.moved = false;
  }
  const auto setPoint = [&](int i, const glm::dvec3& point, bool newStep, bool write) {
    const std::size_t patch = static_cast<std::size_t>(i / 16);
    const std::size_t index = static_cast<std::size_t>(i % 16);
    state.message = workbench.edit(
        shown, [&](SurfaceFile& f) { return f.setPoint(patch, index, point); }, newStep, write);
  };
  if (state.dragging >= 0 && active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 1.0f)) {
    glm::dvec3 point = pointOf(state.dragging);
    point[axes[0]] = roundToMicro(mouse[0]);
    point[axes[1]] = roundToMicro(mouse[1]);
    const Clock::time_point now = Clock::now();
    const bool write = now - state.lastWrite >= kDragWriteInterval;
    setPoint(state.dragging, point, !state.moved, write);
    state.moved = true;
    if (write) state.lastWrite = now;
  }
  if (state.dragging >= 0 && !active) {
    state.dragging = -1;
    if (state.moved) state.message = workbench.save(shown);
  }

  if (state.selected >= 0) {
    const glm::dvec3& p = pointOf(state.selected);
    float values[3] = {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
    const std::string label = "patch " + std::to_string(state.selected / 16 + 1) + " point " +
                              std::to_string(state.selected % 16 + 1);
    ImGui::SetNextItemWidth(240);
    const bool changed = ImGui::DragFloat3(label.c_str(), values, 0.005f, 0, 0, "%.3f");
    if (ImGui::IsItemActivated()) state.moved = false;
    if (changed) {
      const glm::dvec3 point(roundToMicro(values[0]), roundToMicro(values[1]),
                             roundToMicro(values[2]));
      const Clock::time_point now = Clock::now();
      const bool write = now - state.lastWrite >= kDragWriteInterval;
      setPoint(state.selected, point, !state.moved, write);
      state.moved = true;
      if (write) state.lastWrite = now;
    }
    if (ImGui::IsItemDeactivated() && state.moved) state.message = workbench.save(shown);
  } else {
    ImGui::TextDisabled("drag a point in this plane, or pick one for x y z");
  }
  ImGui::BeginDisabled(!shown.history.canUndo());
  if (ImGui::Button("Undo")) state.message = workbench.undo(shown);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!shown.history.canRedo());
  if (ImGui::Button("Redo")) state.message = workbench.redo(shown);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("%s, %zu patch%s", shown.path.filename().string().c_str(),
                      surface.patches.size(), surface.patches.size() == 1 ? "" : "es");
  if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
  ImGui::End();
}

}  // namespace hirsute
