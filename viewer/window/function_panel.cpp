// The function editor (vlab's funcedit): the model's `.func`/`.fset` curves on a plot, their
// control points dragged, added (double click) and removed (right click), the curve drawn with
// the derivation's own evaluation (FunctionCurve::evaluate) of the file as it will be written.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hirsute/viewer/window/shape_panels.h"
#include "plot_canvas.h"

namespace hirsute {
namespace {

using Clock = std::chrono::steady_clock;
// A drag writes the file (and so re-derives) at most this often; its end always writes.
constexpr auto kDragWriteInterval = std::chrono::milliseconds(200);

std::string functionLabel(const CurveDocument& document, std::size_t block) {
  const std::string& name = document.history.current().blocks()[block].name;
  const std::string file = document.path.filename().string();
  return name.empty() ? file : name + "  (" + file + ")";
}

// Samples of the curve drawn: enough that the table's linear pieces show.
constexpr int kCurveSamples = 240;

}  // namespace

void drawFunctionPanel(ShapeWorkbench& workbench, ShapePanelState& state) {
  ShapeWorkbench::EditorView& view = workbench.functionView;
  if (!view.open) return;
  std::vector<CurveDocument>& documents = workbench.functions();
  if (!beginShapeWindow("Function curves", &view.open, 430, documents.empty(),
                        "The view file names no function (function: or function set:).")) {
    return;
  }
  view.document = std::min(view.document, documents.size() - 1);
  CurveDocument& document = documents[view.document];
  view.block = std::min(view.block, document.history.current().blocks().size() - 1);

  if (ImGui::BeginCombo("function", functionLabel(document, view.block).c_str())) {
    for (std::size_t d = 0; d < documents.size(); ++d) {
      for (std::size_t b = 0; b < documents[d].history.current().blocks().size(); ++b) {
        const bool chosen = d == view.document && b == view.block;
        if (ImGui::Selectable(functionLabel(documents[d], b).c_str(), chosen)) {
          view.document = d;
          view.block = b;
          state.selected = state.dragging = -1;
        }
      }
    }
    ImGui::EndCombo();
  }
  CurveDocument& shown = documents[view.document];
  const CurveFile& file = shown.history.current();
  // A copy: an edit below replaces the state `file` refers to.
  const std::vector<CurveFileRow> rows = file.blocks()[view.block].rows;
  if (state.selected >= static_cast<int>(rows.size())) state.selected = -1;

  // x spans [0, 1]; y the points' range with 0 and 1, held still while a point is dragged.
  if (state.dragging < 0) {
    float low = 0, high = 1;
    for (const CurveFileRow& row : rows) {
      low = std::min(low, static_cast<float>(row.point[1]));
      high = std::max(high, static_cast<float>(row.point[1]));
    }
    const float margin = 0.08f * (high - low);
    state.low[0] = -0.04f;
    state.high[0] = 1.04f;
    state.low[1] = low - margin;
    state.high[1] = high + margin;
  }
  const PlotCanvas canvas = beginCanvas("##function", 260, state.low, state.high, false);
  const bool active = ImGui::IsItemActive();
  const bool hovered = ImGui::IsItemHovered();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->PushClipRect(canvas.origin,
                     ImVec2(canvas.origin.x + canvas.size.x, canvas.origin.y + canvas.size.y),
                     true);
  // The control polygon, then the curve as func() evaluates it.
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    draw->AddLine(canvas.toScreen(rows[i].point[0], rows[i].point[1]),
                  canvas.toScreen(rows[i + 1].point[0], rows[i + 1].point[1]), kPolygonColour);
  }
  // With the view file's sample count, which a version 0 file's table takes.
  const FunctionCurve curve = file.function(view.block, shown.viewSamples);
  std::vector<ImVec2> line;
  for (int i = 0; i <= kCurveSamples; ++i) {
    const double x = static_cast<double>(i) / kCurveSamples;
    line.push_back(canvas.toScreen(static_cast<float>(x), static_cast<float>(curve.evaluate(x))));
  }
  draw->AddPolyline(line.data(), static_cast<int>(line.size()), kCurveColour, ImDrawFlags_None,
                    2.0f);
  drawControlPoints(draw, canvas, rows, state.selected);
  draw->PopClipRect();

  const auto screenOf = [&](int i) {
    return canvas.toScreen(rows[static_cast<std::size_t>(i)].point[0],
                           rows[static_cast<std::size_t>(i)].point[1]);
  };
  float mouseX = 0, mouseY = 0;
  canvas.toPlane(ImGui::GetIO().MousePos, mouseX, mouseY);
  if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    state.dragging = state.selected = pointUnderMouse(static_cast<int>(rows.size()), screenOf);
    state.moved = false;
  }
  if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && state.dragging < 0) {
    // A new point where the mouse is, between the points either side of its x.
    const std::size_t at = static_cast<std::size_t>(
        std::upper_bound(rows.begin(), rows.end(), static_cast<double>(mouseX),
                         [](double v, const CurveFileRow& row) { return v < row.point[0]; }) -
        rows.begin());
    const std::array<double, 3> point{roundToMicro(mouseX), roundToMicro(mouseY), 0.0};
    state.message = workbench.edit(
        shown, [&](CurveFile& f) { return f.insertPoint(view.block, at, point); }, true);
    if (state.message.empty()) state.selected = static_cast<int>(at);
  }
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
    const int under = pointUnderMouse(static_cast<int>(rows.size()), screenOf);
    if (under >= 0) {
      state.message = workbench.edit(
          shown,
          [&](CurveFile& f) { return f.removePoint(view.block, static_cast<std::size_t>(under)); },
          true);
      state.selected = -1;
    }
  }
  if (state.dragging >= 0 && active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 1.0f)) {
    const std::size_t i = static_cast<std::size_t>(state.dragging);
    // funcedit's rules: x between the neighbours', the ends' x fixed.
    double x = mouseX;
    if (i == 0 || i + 1 == rows.size()) {
      x = rows[i].point[0];
    } else {
      x = std::clamp(x, rows[i - 1].point[0], rows[i + 1].point[0]);
    }
    const std::array<double, 3> point{roundToMicro(x), roundToMicro(mouseY), 0.0};
    const Clock::time_point now = Clock::now();
    const bool write = now - state.lastWrite >= kDragWriteInterval;
    state.message = workbench.edit(
        shown, [&](CurveFile& f) { return f.setPoint(view.block, i, point); }, !state.moved, write);
    state.moved = true;
    if (write) state.lastWrite = now;
  }
  if (state.dragging >= 0 && !active) {
    state.dragging = -1;
    if (state.moved) state.message = workbench.save(shown);
  }

  // The chosen point in numbers.
  if (state.selected >= 0) {
    const CurveFileRow& row = rows[static_cast<std::size_t>(state.selected)];
    float values[2] = {static_cast<float>(row.point[0]), static_cast<float>(row.point[1])};
    ImGui::SetNextItemWidth(200);
    if (ImGui::InputFloat2(("point " + std::to_string(state.selected + 1)).c_str(), values, "%.6f",
                           ImGuiInputTextFlags_EnterReturnsTrue)) {
      const std::array<double, 3> point{roundToMicro(values[0]), roundToMicro(values[1]), 0.0};
      const std::size_t i = static_cast<std::size_t>(state.selected);
      state.message = workbench.edit(
          shown, [&](CurveFile& f) { return f.setPoint(view.block, i, point); }, true);
    }
  } else {
    ImGui::TextDisabled("drag a point; double click: add; right click: remove");
  }
  ImGui::BeginDisabled(!shown.history.canUndo());
  if (ImGui::Button("Undo")) state.message = workbench.undo(shown);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!shown.history.canRedo());
  if (ImGui::Button("Redo")) state.message = workbench.redo(shown);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("%s, %zu points", shown.path.filename().string().c_str(), rows.size());
  if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
  ImGui::End();
}

}  // namespace hirsute
