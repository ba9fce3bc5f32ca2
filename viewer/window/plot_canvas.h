// The plot the shape editors draw on (shape_panels.h): a rectangle of the panel mapped to a
// range of the plane, with the grab radius and the colours they share.
#pragma once

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace hirsute {

struct PlotCanvas {
  ImVec2 origin, size;  // in pixels
  float low[2], high[2];

  ImVec2 toScreen(float x, float y) const {
    return ImVec2(origin.x + (x - low[0]) / (high[0] - low[0]) * size.x,
                  origin.y + size.y - (y - low[1]) / (high[1] - low[1]) * size.y);
  }
  void toPlane(ImVec2 p, float& x, float& y) const {
    x = low[0] + (p.x - origin.x) / size.x * (high[0] - low[0]);
    y = low[1] + (origin.y + size.y - p.y) / size.y * (high[1] - low[1]);
  }
};

// The canvas fills the rest of the panel's width, `height` pixels high, as one item that takes
// clicks; the range is widened to keep the plane's units square when `square`.
inline PlotCanvas beginCanvas(const char* id, float height, const float low[2], const float high[2],
                              bool square) {
  PlotCanvas canvas;
  canvas.origin = ImGui::GetCursorScreenPos();
  canvas.size = ImVec2(std::max(ImGui::GetContentRegionAvail().x, 120.0f), height);
  for (int k = 0; k < 2; ++k) {
    canvas.low[k] = low[k];
    canvas.high[k] = high[k] > low[k] ? high[k] : low[k] + 1;
  }
  if (square) {
    const float perPixel = std::max((canvas.high[0] - canvas.low[0]) / canvas.size.x,
                                    (canvas.high[1] - canvas.low[1]) / canvas.size.y);
    for (int k = 0; k < 2; ++k) {
      const float middle = (canvas.low[k] + canvas.high[k]) / 2;
      const float half = perPixel * (k == 0 ? canvas.size.x : canvas.size.y) / 2;
      canvas.low[k] = middle - half;
      canvas.high[k] = middle + half;
    }
  }
  ImGui::InvisibleButton(id, canvas.size,
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(canvas.origin,
                      ImVec2(canvas.origin.x + canvas.size.x, canvas.origin.y + canvas.size.y),
                      IM_COL32(24, 26, 30, 235));
  // The axes through 0, where they are in view.
  const ImU32 axis = IM_COL32(90, 90, 100, 255);
  const ImVec2 zero = canvas.toScreen(0, 0);
  if (zero.y >= canvas.origin.y && zero.y <= canvas.origin.y + canvas.size.y)
    draw->AddLine(ImVec2(canvas.origin.x, zero.y), ImVec2(canvas.origin.x + canvas.size.x, zero.y),
                  axis);
  if (zero.x >= canvas.origin.x && zero.x <= canvas.origin.x + canvas.size.x)
    draw->AddLine(ImVec2(zero.x, canvas.origin.y), ImVec2(zero.x, canvas.origin.y + canvas.size.y),
                  axis);
  return canvas;
}

inline constexpr float kGrabPixels = 7.0f;
inline constexpr ImU32 kCurveColour = IM_COL32(250, 210, 90, 255);
inline constexpr ImU32 kPolygonColour = IM_COL32(130, 160, 220, 200);
inline constexpr ImU32 kPointColour = IM_COL32(235, 235, 240, 255);
inline constexpr ImU32 kSelectedColour = IM_COL32(255, 90, 70, 255);

// The index of the point nearest the mouse within the grab radius, or -1.
template <typename ScreenOf>
int pointUnderMouse(int count, ScreenOf&& screenOf) {
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  int nearest = -1;
  float best = kGrabPixels * kGrabPixels;
  for (int i = 0; i < count; ++i) {
    const ImVec2 p = screenOf(i);
    const float d = (p.x - mouse.x) * (p.x - mouse.x) + (p.y - mouse.y) * (p.y - mouse.y);
    if (d <= best) {
      best = d;
      nearest = i;
    }
  }
  return nearest;
}

// Opens a shape editor's window at the viewer's right, where the plant (in the middle) is least
// covered. False when the window is collapsed, or when the view file names nothing for it
// (`empty`; `nothing` says what it would name): the window is then ended already.
inline bool beginShapeWindow(const char* title, bool* open, float height, bool empty,
                             const char* nothing) {
  ImGui::SetNextWindowPos(ImVec2(std::max(8.0f, ImGui::GetIO().DisplaySize.x - 408), 8),
                          ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(400, height), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.85f);
  if (!ImGui::Begin(title, open, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::End();
    return false;
  }
  if (empty) {
    ImGui::TextWrapped("%s", nothing);
    ImGui::End();
    return false;
  }
  return true;
}

// The chooser of the file shown, by its name; true when another was chosen.
template <typename Document>
bool chooseDocument(const char* label, const std::vector<Document>& documents, std::size_t& shown) {
  bool chosen = false;
  if (ImGui::BeginCombo(label, documents[shown].path.filename().string().c_str())) {
    for (std::size_t d = 0; d < documents.size(); ++d) {
      if (ImGui::Selectable(documents[d].path.filename().string().c_str(), d == shown)) {
        shown = d;
        chosen = true;
      }
    }
    ImGui::EndCombo();
  }
  return chosen;
}

// A curve file's control points on the plot, the selected one marked, each repeated point with
// its multiplicity.
template <typename Row>
void drawControlPoints(ImDrawList* draw, const PlotCanvas& canvas, const std::vector<Row>& rows,
                       int selected) {
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ImVec2 p = canvas.toScreen(rows[i].point[0], rows[i].point[1]);
    draw->AddCircleFilled(p, 4.5f,
                          static_cast<int>(i) == selected ? kSelectedColour : kPointColour);
    if (rows[i].multiplicity > 1) {
      // Built by appending: GCC 12 reports a false -Wrestrict on "x" + std::string.
      std::string times = "x";
      times += std::to_string(rows[i].multiplicity);
      draw->AddText(ImVec2(p.x + 6, p.y - 16), kPointColour, times.c_str());
    }
  }
}

}  // namespace hirsute
