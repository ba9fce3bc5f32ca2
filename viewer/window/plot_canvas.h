// The plot the shape editors draw on (shape_panels.h): a rectangle of the panel mapped to a
// range of the plane, with the grab radius and the colours they share.
#pragma once

#include <imgui.h>

#include <algorithm>
#include <cmath>

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

}  // namespace hirsute
