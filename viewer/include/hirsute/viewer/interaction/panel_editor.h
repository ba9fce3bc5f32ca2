// The control panels' session (docs/viewer.md, "Editors"): every vlab panel (.pnl,
// control_panel.h) in the model's folder, each with its undo history (edit_history.h) of the
// edits made to it (a slider's range or default, a slider added for a constant or removed, a
// panel made from the constants) and the state of its controls; what a control asks of the
// model (a #define's new value); and the saving, under a temporary name in the model's folder
// renamed over the file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hirsute/viewer/interaction/control_panel.h"
#include "hirsute/viewer/interaction/define_editor.h"
#include "hirsute/viewer/interaction/edit_history.h"

namespace hirsute {

class PanelEditor {
 public:
  struct Panel {
    std::filesystem::path path;
    EditHistory<ControlPanel> history{ControlPanel{}};
    std::string error;  // why it cannot be shown (file:line); empty when it can
    // The controls as the user left them, by item index: a slider's value, a button's 0 or 1.
    std::map<std::size_t, int> state;
  };

  // `modelFolder`: the .l's folder, where panels are read and written; `lsystemStem` names the
  // panel made from the constants (`STEM.pnl`).
  PanelEditor(std::filesystem::path modelFolder, std::string lsystemStem);

  // Reads the .pnl files of the model's folder again (regular files beneath it); a panel with
  // unsaved edits keeps them.
  void reload();
  const std::vector<Panel>& panels() const { return panels_; }

  // The value a control shows: a slider bound to a constant shows the constant's value (times
  // its scale), others what the user set, or the file's `value:`.
  int shownValue(std::size_t panel, std::size_t item, const std::vector<DefineConstant>& constants,
                 const std::map<std::string, std::string>& changed) const;

  // The user set control `item` to `value` (a slider's value, a button 1 on or 0 off; a group's
  // other buttons go off): the #define it sets and its new text, or none when its message sets
  // none (vlab's line/word messages edit other files than the .l).
  std::optional<std::pair<std::string, std::string>> activate(
      std::size_t panel, std::size_t item, int value, const std::vector<DefineConstant>& constants);

  // Edits of a panel file: a new step of its history.
  bool edit(std::size_t panel, ControlPanel next);
  bool undo(std::size_t panel);
  bool redo(std::size_t panel);
  std::optional<std::size_t> lastEdited() const { return lastEdited_; }
  bool modified() const;
  // Writes the panel; returns the message (empty on success).
  std::string save(std::size_t panel);
  // Writes STEM.pnl, a panel of the constants (makeControlPanel), and shows it; its index in
  // `created`. Returns the message (empty on success); a file of that name is not replaced.
  std::string create(const std::vector<DefineConstant>& constants, std::size_t* created = nullptr);

 private:
  std::filesystem::path folder_;
  std::string stem_;
  std::vector<Panel> panels_;
  std::optional<std::size_t> lastEdited_;
};

}  // namespace hirsute
