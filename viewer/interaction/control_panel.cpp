#include "hirsute/viewer/interaction/control_panel.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>
#include <sstream>

namespace hirsute {
namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

std::string trim(std::string_view s) {
  std::size_t begin = 0, end = s.size();
  while (begin < end && (s[begin] == ' ' || s[begin] == '\t' || s[begin] == '\r')) ++begin;
  while (end > begin && (s[end - 1] == ' ' || s[end - 1] == '\t' || s[end - 1] == '\r')) --end;
  return std::string(s.substr(begin, end - begin));
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

bool wholeNumber(const std::string& word, int& value) {
  const char* end = word.data() + word.size();
  auto [ptr, error] = std::from_chars(word.data(), end, value);
  return error == std::errc() && ptr == end;
}

// The name as vlab shows it: a `%…` suffix only makes names unique in the file.
std::string shownName(const std::string& name) {
  const std::size_t percent = name.find('%');
  return percent == std::string::npos ? name : name.substr(0, percent);
}

std::optional<PanelItem::Type> itemType(const std::string& word) {
  if (word == "PAGE") return PanelItem::Type::Page;
  if (word == "SLIDER") return PanelItem::Type::Slider;
  if (word == "BUTTON") return PanelItem::Type::Button;
  if (word == "GROUP") return PanelItem::Type::Group;
  if (word == "LABEL") return PanelItem::Type::Label;
  if (word == "MENU") return PanelItem::Type::Menu;
  return std::nullopt;
}

// Replaces what follows `keyword:` on a line, keeping the keyword, the spacing after the colon
// and a '\r' at the end as they were.
std::string withValue(const std::string& line, const std::string& value) {
  const std::size_t colon = line.find(':');
  std::size_t start = colon + 1;
  while (start < line.size() && (line[start] == ' ' || line[start] == '\t')) ++start;
  if (start == colon + 1)
    return line.substr(0, colon + 1) + " " + value +
           (!line.empty() && line.back() == '\r' ? "\r" : "");
  return line.substr(0, start) + value + (!line.empty() && line.back() == '\r' ? "\r" : "");
}

void reparse(ControlPanel& panel, const std::string& fileName) {
  ControlPanel parsed = parseControlPanel(controlPanelText(panel), fileName);
  panel = std::move(parsed);
}

}  // namespace

ControlPanel parseControlPanel(const std::string& text, const std::string& fileName) {
  auto name = std::make_shared<const std::string>(fileName);
  auto fail = [&](std::size_t index, const std::string& message) {
    throw DiagnosticError(SourceLocation{name, static_cast<int>(index + 1), 1}, message);
  };
  if (text.size() > kMaxPanelBytes) {
    throw DiagnosticError(SourceLocation{name, 1, 1},
                          "a panel file may be " + std::to_string(kMaxPanelBytes) +
                              " bytes long, this one has " + std::to_string(text.size()));
  }
  ControlPanel panel;
  panel.finalNewline = text.empty() || text.back() == '\n';
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    panel.lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  if (text.find('\0') != std::string::npos)
    fail(0, "a panel file is text; this one holds a NUL byte");

  PanelItem* item = nullptr;
  bool inGroup = false;
  for (std::size_t i = 0; i < panel.lines.size(); ++i) {
    const std::string line = trim(panel.lines[i]);
    if (line.empty()) continue;
    if (inGroup) {
      if (line == "ENDGROUP") {
        inGroup = false;
        item->endLine = i + 1;
        continue;
      }
      const std::size_t colon = line.find(':');
      const std::string key = colon == std::string::npos ? "" : trim(line.substr(0, colon));
      if (key != "color" && key != "origin") {
        // A button of the group, by the name it was defined with (checked below).
        item->buttons.push_back(line);
        item->endLine = i + 1;
        continue;
      }
    }
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) {
      fail(i, "expected 'keyword: value' in a panel file, found '" + line + "'");
    }
    const std::string key = trim(line.substr(0, colon));
    const std::string value = trim(line.substr(colon + 1));
    if (key == "type") {
      const auto type = itemType(value);
      if (!type) {
        fail(i, "unknown panel item type '" + value +
                    "' (expected PAGE, SLIDER, BUTTON, GROUP, LABEL or MENU)");
      }
      panel.items.emplace_back();
      item = &panel.items.back();
      item->type = *type;
      item->line = static_cast<int>(i + 1);
      item->valueLine = kNone;
      item->minMaxLine = kNone;
      item->endLine = i + 1;
      if (*type == PanelItem::Type::Group) inGroup = true;
      continue;
    }
    if (!item) {
      // The panel's header (§2.4.1).
      if (key == "target") {
        panel.target = value;
      } else if (key == "panel name") {
        panel.title = value;
      } else if (key != "background" && key != "size" && key != "font") {
        fail(i, "unknown panel header keyword '" + key +
                    "' (expected target, panel name, background, size or font)");
      }
      continue;
    }
    item->endLine = i + 1;
    if (key == "name") {
      item->name = shownName(value);
    } else if (key == "message") {
      item->message = value;
    } else if (key == "min/max") {
      const std::vector<std::string> range = words(value);
      if (range.size() != 2 || !wholeNumber(range[0], item->minimum) ||
          !wholeNumber(range[1], item->maximum)) {
        fail(i, "'min/max:' takes two whole numbers, found '" + value + "'");
      }
      item->minMaxLine = i;
    } else if (key == "value") {
      if (!wholeNumber(value, item->value))
        fail(i, "'value:' takes a whole number, found '" + value + "'");
      item->valueLine = i;
    } else if (key != "colors" && key != "color" && key != "tricolor" && key != "origin") {
      fail(i, "unknown panel keyword '" + key + "'");
    }
  }
  if (inGroup) fail(panel.lines.empty() ? 0 : panel.lines.size() - 1, "a GROUP without ENDGROUP");

  // Checks that need the whole file: a slider has its range and value, a group names buttons
  // defined before it (vlab §2.4.5).
  for (const PanelItem& it : panel.items) {
    const std::size_t at = static_cast<std::size_t>(it.line - 1);
    if (it.type == PanelItem::Type::Slider) {
      if (it.minMaxLine == kNone) fail(at, "the slider '" + it.name + "' has no 'min/max:' line");
      if (it.minimum >= it.maximum)
        fail(it.minMaxLine, "the slider '" + it.name + "' has min/max " +
                                std::to_string(it.minimum) + " " + std::to_string(it.maximum) +
                                ": the minimum must be below the maximum");
    }
    if (it.type == PanelItem::Type::Group) {
      for (const std::string& button : it.buttons) {
        const bool defined =
            std::any_of(panel.items.begin(), panel.items.end(), [&](const PanelItem& b) {
              return b.type == PanelItem::Type::Button && b.line < it.line &&
                     b.name == shownName(button);
            });
        if (!defined)
          fail(at,
               "the group names the button '" + button + "', which no BUTTON before it defines");
      }
    }
  }
  return panel;
}

std::string controlPanelText(const ControlPanel& panel) {
  std::string text;
  for (std::size_t i = 0; i < panel.lines.size(); ++i) {
    text += panel.lines[i];
    if (i + 1 < panel.lines.size() || panel.finalNewline) text += '\n';
  }
  return text;
}

std::optional<std::size_t> findPanelItem(const ControlPanel& panel, PanelItem::Type type,
                                         std::string_view name) {
  for (std::size_t i = 0; i < panel.items.size(); ++i) {
    const PanelItem& item = panel.items[i];
    if (item.type != type) continue;
    if (item.name == name) return i;
    const auto define = defineMessage(item.message);
    if (define && define->name == name) return i;
  }
  return std::nullopt;
}

std::optional<DefineMessage> defineMessage(const std::string& message) {
  const std::vector<std::string> w = words(message);
  if (w.size() < 3 || w.size() > 4 || w[0] != "d" || w[2] != "%d") return std::nullopt;
  DefineMessage m;
  m.name = w[1];
  if (w.size() == 4) {
    char* end = nullptr;
    m.scale = std::strtod(w[3].c_str(), &end);
    if (end != w[3].c_str() + w[3].size() || !std::isfinite(m.scale) || m.scale == 0)
      return std::nullopt;
  }
  return m;
}

std::string defineValueFor(const DefineMessage& message, int value, bool integerConstant) {
  if (message.scale == 1) return formatDefineValue(value, integerConstant);
  // value / scale written as short as it reads back (46 / 10 is 4.6, not 4.6000000000000005).
  const double v = value / message.scale;
  char buffer[32];
  auto result = std::to_chars(buffer, buffer + sizeof buffer - 1, static_cast<float>(v));
  *result.ptr = '\0';
  return formatDefineValue(std::strtod(buffer, nullptr), false);
}

void setPanelValue(ControlPanel& panel, std::size_t item, int value, const std::string& fileName) {
  PanelItem& it = panel.items.at(item);
  if (it.valueLine == kNone) {
    panel.lines.insert(panel.lines.begin() + static_cast<std::ptrdiff_t>(it.endLine),
                       "value: " + std::to_string(value));
  } else {
    panel.lines[it.valueLine] = withValue(panel.lines[it.valueLine], std::to_string(value));
  }
  reparse(panel, fileName);
}

void setPanelRange(ControlPanel& panel, std::size_t item, int minimum, int maximum,
                   const std::string& fileName) {
  PanelItem& it = panel.items.at(item);
  const std::string range = std::to_string(minimum) + " " + std::to_string(maximum);
  if (it.minMaxLine == kNone) {
    panel.lines.insert(panel.lines.begin() + static_cast<std::ptrdiff_t>(it.endLine),
                       "min/max: " + range);
  } else {
    panel.lines[it.minMaxLine] = withValue(panel.lines[it.minMaxLine], range);
  }
  reparse(panel, fileName);
}

void removePanelItem(ControlPanel& panel, std::size_t item, const std::string& fileName) {
  const PanelItem& it = panel.items.at(item);
  std::size_t begin = static_cast<std::size_t>(it.line - 1), end = it.endLine;
  // The blank line after the block goes with it.
  if (end < panel.lines.size() && trim(panel.lines[end]).empty()) ++end;
  panel.lines.erase(panel.lines.begin() + static_cast<std::ptrdiff_t>(begin),
                    panel.lines.begin() + static_cast<std::ptrdiff_t>(end));
  reparse(panel, fileName);
}

namespace {

// A slider's block for a constant: its value scaled to a whole number (vlab's sliders are
// whole numbers; awkped divides by the scale), the range about the value as the constants
// panel's.
std::vector<std::string> sliderBlock(const DefineConstant& c, int y) {
  int scale = 1;
  if (!c.integer) {
    // At least one decimal for a floating-point constant; more when its value has them.
    scale = 10;
    while (scale < 1000 && std::abs(c.value * scale - std::round(c.value * scale)) > 1e-9)
      scale *= 10;
  }
  const long long value = std::llround(c.value * scale);
  const long long reach = std::max<long long>(10, 2 * std::llabs(value));
  const long long low = value < 0 ? -reach : 0;
  std::string message = "message: d ";
  message += c.name;
  message += " %d";
  if (scale != 1) {
    message += ' ';
    message += std::to_string(scale);
  }
  std::vector<std::string> block = {
      "type: SLIDER",
      "name: " + c.name,
      "colors: 255,255,255 255,0,0",
      "origin: 10 " + std::to_string(y),
      "min/max: " + std::to_string(low) + " " + std::to_string(reach),
      "value: " + std::to_string(value),
      message,
  };
  return block;
}

constexpr int kSliderPitch = 60;

}  // namespace

void addConstantSlider(ControlPanel& panel, const DefineConstant& constant,
                       const std::string& fileName) {
  const int sliders = static_cast<int>(
      std::count_if(panel.items.begin(), panel.items.end(),
                    [](const PanelItem& i) { return i.type == PanelItem::Type::Slider; }));
  if (!panel.lines.empty() && !trim(panel.lines.back()).empty()) panel.lines.emplace_back();
  for (const std::string& line : sliderBlock(constant, 10 + kSliderPitch * sliders))
    panel.lines.push_back(line);
  panel.finalNewline = true;
  reparse(panel, fileName);
}

ControlPanel makeControlPanel(const std::vector<DefineConstant>& constants,
                              const std::string& title, const std::string& target) {
  std::vector<std::string> lines = {
      "target: " + target,
      "panel name: " + title,
      "background: 0,0,0",
      "size: 220 " + std::to_string(20 + kSliderPitch * static_cast<int>(constants.size())),
  };
  int y = 10;
  for (const DefineConstant& c : constants) {
    lines.emplace_back();
    for (const std::string& line : sliderBlock(c, y)) lines.push_back(line);
    y += kSliderPitch;
  }
  ControlPanel panel;
  panel.lines = std::move(lines);
  panel.finalNewline = true;
  reparse(panel, title + ".pnl");
  return panel;
}

}  // namespace hirsute
