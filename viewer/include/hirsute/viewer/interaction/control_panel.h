// vlab's control panels (.pnl; vlab tools manual §2.4, "The panel specification file"): sliders,
// buttons, button groups, labels, pages and menu items, each a block of `keyword: value` lines,
// and what they do here: a message `d NAME %d SCALE` (the parameter editor awkped's, §11.2.1)
// sets the `#define NAME` of the model's .l to the control's value divided by SCALE, as the
// constants panel sets it (define_editor.h). The file is kept as its lines, so that it is written
// back byte for byte as it was read, with only the lines an edit changed.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/viewer/interaction/define_editor.h"

namespace hirsute {

struct PanelItem {
  enum class Type { Page, Slider, Button, Group, Label, Menu };
  Type type = Type::Label;
  std::string name;     // shown without a `%…` suffix (vlab makes names unique with %Copy1)
  std::string message;  // with %d where the value goes
  int minimum = 0, maximum = 0;
  int value = 0;                     // a slider's; a button's 0 off, 1 on, 2 monostable
  std::vector<std::string> buttons;  // a group's, by name
  int line = 0;                      // of its `type:` line, 1-based
  std::size_t valueLine = 0;         // the index in ControlPanel::lines of `value:`, or npos
  std::size_t minMaxLine = 0;        // of `min/max:`, or npos
  std::size_t endLine = 0;           // one past the block's last line (blank lines excluded)
};

struct ControlPanel {
  std::vector<std::string> lines;  // as read, each without its '\n' (a '\r' stays)
  bool finalNewline = true;
  std::string title;   // `panel name:`
  std::string target;  // `target:`, for information only (vlab)
  std::vector<PanelItem> items;
  bool operator==(const ControlPanel& other) const {
    return lines == other.lines && finalNewline == other.finalNewline;
  }
};

// The most bytes of a .pnl read: a panel is a page of text.
inline constexpr std::size_t kMaxPanelBytes = std::size_t{1} << 20;

// Parses a .pnl; `fileName` names it in messages. Throws DiagnosticError at the line of what
// it cannot hold (an unknown keyword, a value that is no number, a group's unknown button).
ControlPanel parseControlPanel(const std::string& text, const std::string& fileName);
// The file's text: what parseControlPanel read, with the edits made since.
std::string controlPanelText(const ControlPanel& panel);

// The item named `name` (its name as shown, or the #define its message sets) of `type`.
std::optional<std::size_t> findPanelItem(const ControlPanel& panel, PanelItem::Type type,
                                         std::string_view name);

// A message that sets a #define: `d NAME %d [SCALE]`.
struct DefineMessage {
  std::string name;
  double scale = 1;
};
std::optional<DefineMessage> defineMessage(const std::string& message);
// The #define's value for the control's value, as it is written into the .l: value / scale,
// an integer when the scale is 1 and the constant is one.
std::string defineValueFor(const DefineMessage& message, int value, bool integerConstant);

// Edits, each rewriting the item's lines (and parsing the panel again).
void setPanelValue(ControlPanel& panel, std::size_t item, int value, const std::string& fileName);
void setPanelRange(ControlPanel& panel, std::size_t item, int minimum, int maximum,
                   const std::string& fileName);
void removePanelItem(ControlPanel& panel, std::size_t item, const std::string& fileName);
// A slider for the constant, added at the end of the panel.
void addConstantSlider(ControlPanel& panel, const DefineConstant& constant,
                       const std::string& fileName);

// A panel with a slider for each constant (vlab's default colours, one under another), bound to
// it by a `d NAME %d SCALE` message whose scale keeps the value's decimals (at most three).
ControlPanel makeControlPanel(const std::vector<DefineConstant>& constants,
                              const std::string& title, const std::string& target);

}  // namespace hirsute
