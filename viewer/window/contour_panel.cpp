// The contour editor (vlab's cuspy): the model's `.con` cross-sections and curves in their plane,
// their control points dragged, added (double click: after the nearest point) and removed (right
// click). It draws the B-spline as curveX/Y/Z measure it (ContourCurve) and the polygon the
// generalized cylinders are built of: the contour resampled to the view's `contour sides:`
// (ContourLibrary), as the plant's stems and leaves show it.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/interpreter/contour.h"
#include "hirsute/viewer/window/shape_panels.h"
#include "plot_canvas.h"

namespace hirsute {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kDragWriteInterval = std::chrono::milliseconds(200);
constexpr int kCurveSamples = 240;
constexpr ImU32 kRingColour = IM_COL32(110, 220, 120, 255);

}  // namespace

void drawContourPanel(ShapeWorkbench& workbench, ShapePanelState& state) {
  ShapeWorkbench::EditorView& view = workbench.contourView;
  if (!view.open) return;
  std::vector<CurveDocument>& documents = workbench.contours();
  if (!beginShapeWindow("Contours", &view.open, 450, documents.empty(),
                        "The view file names no contour (contour: or curve:).")) {
    return;
  }
  view.document = std::min(view.document, documents.size() - 1);
  if (chooseDocument("contour", documents, view.document)) state.selected = state.dragging = -1;
  CurveDocument& shown = documents[view.document];
  const CurveFile& file = shown.history.current();
  const CurveFileBlock block = file.blocks()[0];  // a copy: an edit replaces `file`
  const std::vector<CurveFileRow>& rows = block.rows;
  if (state.selected >= static_cast<int>(rows.size())) state.selected = -1;

  const ContourCurve curve = file.contour();
  std::vector<glm::dvec2> ring;
  try {
    ContourLibrary library;
    library.add(1, contourOfCurve(curve, file.fileName()));
    const ContourSamples& samples = library.samples(1, workbench.contourSides());
    // A closed contour's samples are turned to start on +x (contour.cpp); turned back here so
    // that they lie on the curve drawn.
    double angle = 0;
    if (samples.closed) {
      const std::array<double, 3> first = curve.point(0.0);
      angle = std::atan2(first[1], first[0]);
    }
    for (const glm::dvec2& p : samples.points) {
      ring.emplace_back(std::cos(angle) * p.x - std::sin(angle) * p.y,
                        std::sin(angle) * p.x + std::cos(angle) * p.y);
    }
    if (samples.closed && !ring.empty()) ring.push_back(ring.front());
  } catch (const DiagnosticError& error) {
    ImGui::TextWrapped("%s", error.diagnostic().text().c_str());
  }

  // The plane: the points' extent, square, held still while a point is dragged.
  if (state.dragging < 0) {
    float low[2] = {0, 0}, high[2] = {0, 0};
    for (const CurveFileRow& row : rows) {
      for (int k = 0; k < 2; ++k) {
        low[k] = std::min(low[k], static_cast<float>(row.point[k]));
        high[k] = std::max(high[k], static_cast<float>(row.point[k]));
      }
    }
    const float margin = 0.12f * std::max(high[0] - low[0], high[1] - low[1]) + 1e-3f;
    for (int k = 0; k < 2; ++k) {
      state.low[k] = low[k] - margin;
      state.high[k] = high[k] + margin;
    }
  }
  const PlotCanvas canvas = beginCanvas("##contour", 280, state.low, state.high, true);
  const bool active = ImGui::IsItemActive();
  const bool hovered = ImGui::IsItemHovered();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->PushClipRect(canvas.origin,
                     ImVec2(canvas.origin.x + canvas.size.x, canvas.origin.y + canvas.size.y),
                     true);
  for (std::size_t i = 0; i + 1 < rows.size() + (block.closed ? 1 : 0); ++i) {
    const CurveFileRow& a = rows[i];
    const CurveFileRow& b = rows[(i + 1) % rows.size()];
    draw->AddLine(canvas.toScreen(a.point[0], a.point[1]), canvas.toScreen(b.point[0], b.point[1]),
                  kPolygonColour);
  }
  std::vector<ImVec2> line;
  for (int i = 0; i <= kCurveSamples; ++i) {
    const std::array<double, 3> p = curve.point(static_cast<double>(i) / kCurveSamples);
    line.push_back(canvas.toScreen(static_cast<float>(p[0]), static_cast<float>(p[1])));
  }
  draw->AddPolyline(line.data(), static_cast<int>(line.size()), kCurveColour, ImDrawFlags_None,
                    2.0f);
  std::vector<ImVec2> ringOnScreen;
  for (const glm::dvec2& p : ring) {
    ringOnScreen.push_back(canvas.toScreen(static_cast<float>(p.x), static_cast<float>(p.y)));
  }
  draw->AddPolyline(ringOnScreen.data(), static_cast<int>(ringOnScreen.size()), kRingColour,
                    ImDrawFlags_None, 1.0f);
  for (const ImVec2& p : ringOnScreen) draw->AddCircleFilled(p, 2.5f, kRingColour);
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
    // After the nearest point (cuspy inserts on the nearest edge of the control polygon).
    std::size_t nearest = 0;
    double best = INFINITY;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double d = std::hypot(rows[i].point[0] - mouseX, rows[i].point[1] - mouseY);
      if (d < best) {
        best = d;
        nearest = i;
      }
    }
    const std::size_t at = std::min(nearest + 1, rows.size());
    const std::array<double, 3> point{roundToMicro(mouseX), roundToMicro(mouseY),
                                      rows[nearest].point[2]};
    state.message = workbench.edit(
        shown, [&](CurveFile& f) { return f.insertPoint(0, at, point); }, true);
    if (state.message.empty()) state.selected = static_cast<int>(at);
  }
  if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) {
    const int under = pointUnderMouse(static_cast<int>(rows.size()), screenOf);
    if (under >= 0) {
      state.message = workbench.edit(
          shown, [&](CurveFile& f) { return f.removePoint(0, static_cast<std::size_t>(under)); },
          true);
      state.selected = -1;
    }
  }
  if (state.dragging >= 0 && active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 1.0f)) {
    const std::size_t i = static_cast<std::size_t>(state.dragging);
    const std::array<double, 3> point{roundToMicro(mouseX), roundToMicro(mouseY), rows[i].point[2]};
    const Clock::time_point now = Clock::now();
    const bool write = now - state.lastWrite >= kDragWriteInterval;
    state.message = workbench.edit(
        shown, [&](CurveFile& f) { return f.setPoint(0, i, point); }, !state.moved, write);
    state.moved = true;
    if (write) state.lastWrite = now;
  }
  if (state.dragging >= 0 && !active) {
    state.dragging = -1;
    if (state.moved) state.message = workbench.save(shown);
  }

  if (state.selected >= 0) {
    const CurveFileRow& row = rows[static_cast<std::size_t>(state.selected)];
    float values[3] = {static_cast<float>(row.point[0]), static_cast<float>(row.point[1]),
                       static_cast<float>(row.point[2])};
    ImGui::SetNextItemWidth(260);
    if (ImGui::InputFloat3(("point " + std::to_string(state.selected + 1)).c_str(), values, "%.6f",
                           ImGuiInputTextFlags_EnterReturnsTrue)) {
      const std::array<double, 3> point{roundToMicro(values[0]), roundToMicro(values[1]),
                                        roundToMicro(values[2])};
      const std::size_t i = static_cast<std::size_t>(state.selected);
      state.message = workbench.edit(
          shown, [&](CurveFile& f) { return f.setPoint(0, i, point); }, true);
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
  ImGui::TextDisabled("%s, %s, %zu points; green: %d sides", block.closed ? "closed" : "open",
                      shown.path.filename().string().c_str(), rows.size(),
                      workbench.contourSides());
  if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
  ImGui::End();
}

}  // namespace hirsute
