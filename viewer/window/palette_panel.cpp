#include "hirsute/viewer/window/palette_panel.h"

#include <imgui.h>

#include <algorithm>
#include <string>

namespace hirsute {
namespace {

constexpr int kGridSide = 16;

ImVec4 colorOf(const std::array<std::uint8_t, 3>& c) {
  return ImVec4(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1.0f);
}

glm::vec3 vecOf(const std::array<std::uint8_t, 3>& c) {
  return glm::vec3(c[0], c[1], c[2]) / 255.0f;
}

// The grid of 256 colours, numbered down the columns as vlab's palette numbers them (the
// first column 0–15); the selected one is outlined.
void drawGrid(const PaletteDocument& document, PaletteUiState& state) {
  const float cell = 13.0f;
  ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(1, 1));
  ImGui::PushStyleVar(ImGuiStyleVar_FrameBorderSize, 0.0f);
  for (int row = 0; row < kGridSide; ++row) {
    for (int column = 0; column < kGridSide; ++column) {
      const int index = column * kGridSide + row;
      if (column > 0) ImGui::SameLine();
      ImGui::PushID(index);
      const bool selected = index == state.selected;
      const std::string label = "colour " + std::to_string(index);
      if (ImGui::ColorButton(label.c_str(), colorOf(colorAt(document, index)),
                             ImGuiColorEditFlags_NoAlpha | ImGuiColorEditFlags_NoDragDrop,
                             ImVec2(cell, cell)))
        state.selected = index;
      if (selected) {
        // Outlined in white, as vlab's palette outlines the selected colour.
        const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
        ImGui::GetWindowDrawList()->AddRect(ImVec2(low.x - 1, low.y - 1),
                                            ImVec2(high.x + 1, high.y + 1),
                                            IM_COL32(255, 255, 255, 255), 0, 0, 2);
      }
      ImGui::PopID();
    }
  }
  ImGui::PopStyleVar(2);
}

}  // namespace

void drawPalettePanel(LiveModel& live, PaletteUiState& state, bool* open) {
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 8, 40), ImGuiCond_FirstUseEver,
                          ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.85f);
  const PaletteEditor& palette = live.palette();
  if (!ImGui::Begin("Colours and materials", open,
                    ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::End();
    return;
  }
  if (palette.empty()) {
    ImGui::TextWrapped("The model has no colour file: it is drawn with the default palette.");
    if (ImGui::Button("Create a colour map (.map)")) live.createEditorFile("colors");
    if (ImGui::Button("Create a material file (.mat)")) live.createEditorFile("materials");
    ImGui::End();
    return;
  }
  // The entry a script edited is the one shown.
  if (live.scriptedEntry() >= 0 && live.scriptedEntry() != state.scripted) {
    state.scripted = live.scriptedEntry();
    state.selected = state.scripted % 256;
    if (const auto file = palette.fileOf(state.scripted)) state.file = *file;
  }
  state.file = std::min(state.file, palette.files().size() - 1);
  if (palette.files().size() > 1) {
    const auto label = [&](std::size_t f) {
      return "bank " + std::to_string(palette.files()[f].bank) + ": " +
             palette.files()[f].path.filename().string();
    };
    if (ImGui::BeginCombo("file", label(state.file).c_str())) {
      for (std::size_t f = 0; f < palette.files().size(); ++f) {
        if (ImGui::Selectable(label(f).c_str(), f == state.file)) state.file = f;
      }
      ImGui::EndCombo();
    }
  }
  const PaletteEditor::File& file = palette.files()[state.file];
  ImGui::TextDisabled("%s%s", file.path.filename().string().c_str(),
                      file.history.modified() ? " (modified)" : "");
  if (!file.error.empty()) {
    ImGui::PushTextWrapPos(360);
    ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", file.error.c_str());
    ImGui::PopTextWrapPos();
    ImGui::End();
    return;
  }
  const PaletteDocument& document = file.history.current();
  drawGrid(document, state);

  const int index = state.selected;
  ImGui::Text("%s %d", document.kind == PaletteDocument::Kind::ColorMap ? "colour" : "material",
              index + (file.bank - 1) * 256);
  PaletteDocument next = document;
  bool edited = false;
  if (document.kind == PaletteDocument::Kind::ColorMap) {
    glm::vec3 rgb = vecOf(document.colors[index]);
    if (ImGui::ColorEdit3("colour", &rgb.x, ImGuiColorEditFlags_Uint8)) {
      setColor(next, index, rgb);
      edited = true;
    }
  } else {
    const MaterialRecord record = materialAt(document, index);
    struct ColorRow {
      const char* name;
      MaterialField field;
      std::array<std::uint8_t, 3> value;
    };
    for (const ColorRow& row : {ColorRow{"ambient", MaterialField::Ambient, record.ambient},
                                ColorRow{"diffuse", MaterialField::Diffuse, record.diffuse},
                                ColorRow{"specular", MaterialField::Specular, record.specular},
                                ColorRow{"emission", MaterialField::Emission, record.emission}}) {
      glm::vec3 rgb = vecOf(row.value);
      if (ImGui::ColorEdit3(row.name, &rgb.x, ImGuiColorEditFlags_Uint8)) {
        setMaterialField(next, index, row.field, rgb);
        edited = true;
      }
    }
    int shininess = record.shininess;
    if (ImGui::SliderInt("shininess", &shininess, 0, 128)) {
      setMaterialField(next, index, MaterialField::Shininess,
                       glm::vec3(static_cast<float>(shininess)));
      edited = true;
    }
    float transparency = record.transparency / 255.0f;
    if (ImGui::SliderFloat("transparency", &transparency, 0, 1, "%.3f")) {
      setMaterialField(next, index, MaterialField::Transparency, glm::vec3(transparency));
      edited = true;
    }
  }
  if (edited) {
    live.editPalette(state.file, std::move(next), state.editing);
    state.editing = true;
  }
  if (!ImGui::IsAnyItemActive()) state.editing = false;

  // Undo and redo act on the file edited last (the one shown, unless the bank was changed).
  ImGui::BeginDisabled(!file.history.canUndo());
  if (ImGui::Button("Undo")) live.undoEdit("colors");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!file.history.canRedo());
  if (ImGui::Button("Redo")) live.undoEdit("colors", true);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!file.history.modified());
  if (ImGui::Button("Save")) live.saveEditor("colors");
  ImGui::EndDisabled();
  ImGui::End();
}

}  // namespace hirsute
