#include "hirsute/viewer/window/control_panel_window.h"

#include <imgui.h>

#include <algorithm>
#include <string>

namespace hirsute {
namespace {

bool inGroup(const ControlPanel& panel, const PanelItem& button) {
  return std::any_of(panel.items.begin(), panel.items.end(), [&](const PanelItem& g) {
    return g.type == PanelItem::Type::Group &&
           std::find(g.buttons.begin(), g.buttons.end(), button.name) != g.buttons.end();
  });
}

// The controls, as the panel manager's execute mode shows them (vlab §2.1).
void drawControls(LiveModel& live, std::size_t p) {
  const PanelEditor& editor = live.panels();
  const ControlPanel& panel = editor.panels()[p].history.current();
  for (std::size_t i = 0; i < panel.items.size(); ++i) {
    const PanelItem& item = panel.items[i];
    ImGui::PushID(static_cast<int>(i));
    const bool bound = defineMessage(item.message).has_value();
    const int value = editor.shownValue(p, i, live.constants(), live.changedDefines());
    switch (item.type) {
      case PanelItem::Type::Page:
        ImGui::Separator();
        ImGui::TextUnformatted(item.name.c_str());
        break;
      case PanelItem::Type::Label:
        ImGui::TextUnformatted(item.name.c_str());
        break;
      case PanelItem::Type::Slider: {
        int v = value;
        if (ImGui::SliderInt(item.name.c_str(), &v, item.minimum, item.maximum))
          live.activatePanelItem(p, i, v);
        break;
      }
      case PanelItem::Type::Button:
        if (item.value == 2) {
          // Monostable: 1 as it is pressed, 0 as it is let go.
          if (ImGui::Button(item.name.c_str())) {
            live.activatePanelItem(p, i, 1);
            live.activatePanelItem(p, i, 0);
          }
        } else if (inGroup(panel, item)) {
          if (ImGui::RadioButton(item.name.c_str(), value == 1)) live.activatePanelItem(p, i, 1);
        } else {
          bool on = value == 1;
          if (ImGui::Checkbox(item.name.c_str(), &on)) live.activatePanelItem(p, i, on ? 1 : 0);
        }
        break;
      case PanelItem::Type::Menu:
        if (ImGui::SmallButton(item.name.c_str())) live.activatePanelItem(p, i, 0);
        break;
      case PanelItem::Type::Group:
        break;
    }
    if (!bound && !item.message.empty() && ImGui::IsItemHovered()) {
      ImGui::SetTooltip("'%s' sets no #define of the .l (only 'd NAME %%d SCALE' does)",
                        item.message.c_str());
    }
    ImGui::PopID();
  }
}

// The panel's editor (vlab §2.2, the parts a panel of #defines needs).
void drawEditor(LiveModel& live, std::size_t p) {
  PanelEditor& editor = live.panels();
  const PanelEditor::Panel& entry = editor.panels()[p];
  const ControlPanel& panel = entry.history.current();
  const std::string file = entry.path.string();
  for (std::size_t i = 0; i < panel.items.size(); ++i) {
    const PanelItem& item = panel.items[i];
    if (item.type != PanelItem::Type::Slider) continue;
    ImGui::PushID(static_cast<int>(i));
    int range[2] = {item.minimum, item.maximum};
    ImGui::SetNextItemWidth(120);
    // The range is taken when the field is left, so that typing is one edit.
    ImGui::InputInt2(("min/max " + item.name).c_str(), range);
    if (ImGui::IsItemDeactivatedAfterEdit() && range[0] < range[1]) {
      ControlPanel next = panel;
      setPanelRange(next, i, range[0], range[1], file);
      live.editPanel(p, std::move(next));
      ImGui::PopID();
      return;  // `panel` was the history's present state, which has moved on
    }
    ImGui::SameLine();
    if (ImGui::SmallButton("remove")) {
      ControlPanel next = panel;
      removePanelItem(next, i, file);
      live.editPanel(p, std::move(next));
      ImGui::PopID();
      return;  // the items changed
    }
    ImGui::PopID();
  }
  // A slider for a constant no slider sets yet.
  if (ImGui::BeginCombo("add slider", "for a constant")) {
    for (const DefineConstant& c : live.constants()) {
      if (findPanelItem(panel, PanelItem::Type::Slider, c.name)) continue;
      if (ImGui::Selectable(c.name.c_str())) {
        ControlPanel next = panel;
        addConstantSlider(next, c, file);
        live.editPanel(p, std::move(next));
        ImGui::EndCombo();
        return;  // the panel has moved on
      }
    }
    ImGui::EndCombo();
  }
  ImGui::BeginDisabled(!entry.history.canUndo());
  if (ImGui::Button("Undo")) live.undoEdit("panel");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!entry.history.canRedo());
  if (ImGui::Button("Redo")) live.undoEdit("panel", true);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!entry.history.modified());
  if (ImGui::Button("Save")) live.saveEditor("panel");
  ImGui::EndDisabled();
}

}  // namespace

void drawControlPanels(LiveModel& live) {
  const float right = ImGui::GetIO().DisplaySize.x;
  for (std::size_t p = 0; p < live.panels().panels().size(); ++p) {
    const PanelEditor::Panel& entry = live.panels().panels()[p];
    const std::string fileName = entry.path.filename().string();
    const std::string& title = entry.history.current().title;
    const std::string windowName =
        (title.empty() ? fileName : title + " (" + fileName + ")") + "###panel" + fileName;
    ImGui::SetNextWindowPos(ImVec2(right - 8, 40 + 30.0f * static_cast<float>(p)),
                            ImGuiCond_FirstUseEver, ImVec2(1, 0));
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (ImGui::Begin(windowName.c_str(), nullptr,
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize)) {
      // Sliders of a fixed width, the window as wide as their names need.
      ImGui::PushItemWidth(180);
      if (!entry.error.empty()) {
        ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 360);
        ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", entry.error.c_str());
        ImGui::PopTextWrapPos();
      } else {
        drawControls(live, p);
        if (ImGui::CollapsingHeader(entry.history.modified() ? "Edit the panel (modified)###edit"
                                                             : "Edit the panel###edit"))
          drawEditor(live, p);
      }
      ImGui::PopItemWidth();
    }
    ImGui::End();
  }
}

}  // namespace hirsute
