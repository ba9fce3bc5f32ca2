#include "hirsute/viewer/window/define_panel.h"

#include <imgui.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace hirsute {

DefinePanel drawDefinePanel(const std::vector<DefineConstant>& constants,
                            const std::map<std::string, std::string>& changed, bool saveAtOnce,
                            bool* open) {
  DefinePanel panel;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(300, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.75f);
  if (ImGui::Begin("Constants", open, ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::TextDisabled("#define values; ctrl+click to type");
    for (const DefineConstant& c : constants) {
      auto found = changed.find(c.name);
      double value = found != changed.end() ? std::strtod(found->second.c_str(), nullptr) : c.value;
      // The range follows the file's value, not the current one, so that it holds still while
      // the slider is dragged.
      bool edited = false;
      std::string text;
      if (c.integer) {
        int v = static_cast<int>(std::llround(value));
        int base = static_cast<int>(std::llround(c.value));
        int low = std::min(0, 2 * base), high = std::max(10, 2 * std::abs(base));
        edited = ImGui::SliderInt(c.name.c_str(), &v, low, high);
        text = formatDefineValue(v, true);
      } else {
        float v = static_cast<float>(value);
        float range = std::max(1.0f, 2.0f * std::abs(static_cast<float>(c.value)));
        float low = c.value < 0 ? -range : 0.0f;
        edited = ImGui::SliderFloat(c.name.c_str(), &v, low, range, "%.4g");
        // The slider's float, written as short as a float allows (not 0.100000001).
        char shortest[32];
        *std::to_chars(shortest, shortest + sizeof shortest - 1, v).ptr = '\0';
        text = formatDefineValue(std::strtod(shortest, nullptr), false);
      }
      bool finished = ImGui::IsItemDeactivatedAfterEdit();
      if (edited || finished) panel.edits.push_back({c.name, text, finished});
    }
    if (!saveAtOnce) {
      ImGui::BeginDisabled(changed.empty());
      panel.save = ImGui::Button("Save into the .l");
      ImGui::SameLine();
      panel.revert = ImGui::Button("Revert");
      ImGui::EndDisabled();
      ImGui::SameLine();
    }
    panel.makePanel = ImGui::Button("Make a .pnl");
  }
  ImGui::End();
  return panel;
}

}  // namespace hirsute
