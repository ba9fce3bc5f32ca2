#include "hirsute/viewer/interaction/view_script.h"

#include <cctype>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "hirsute/viewer/interaction/live_organ.h"
#include "hirsute/viewer/interaction/shape_workbench.h"

namespace hirsute {
namespace {

using Kind = ViewCommand::Kind;

// What each command takes: its kind, and its arguments as a pattern: 'n' a number, 'w' a word,
// 'o' on or off, lower case required, upper case optional (optional ones come last); an organ's
// command names the organ and its action (-1: showing or hiding it).
struct Signature {
  Kind kind;
  std::string_view arguments;
  std::size_t organ = 0;
  int action = -1;
};

// The viewer's own commands, then each organ's (live_organ.h): `NAME on|off` and its actions'.
std::map<std::string, Signature, std::less<>> makeSignatures() {
  std::map<std::string, Signature, std::less<>> table = {
      {"rotate", {Kind::Rotate, "nN"}},
      {"roll", {Kind::Roll, "n"}},
      {"zoom", {Kind::Zoom, "n"}},
      {"pan", {Kind::Pan, "nn"}},
      {"reset", {Kind::Reset, ""}},
      {"step", {Kind::Step, "N"}},
      {"back", {Kind::Back, "N"}},
      {"goto", {Kind::Goto, "n"}},
      {"animate", {Kind::Animate, ""}},
      {"wireframe", {Kind::Wireframe, "o"}},
      {"define", {Kind::Define, "ww"}},
      {"help", {Kind::Help, "o"}},
      {"panel", {Kind::Panel, "wWWW"}},
      {"save", {Kind::Save, "W"}},
      {"wait-reload", {Kind::WaitReload, "N"}},
      {"sleep", {Kind::Sleep, "n"}},
      {"measure", {Kind::Measure, "N"}},
      {"screenshot", {Kind::Screenshot, "wW"}},
      {"quit", {Kind::Quit, ""}},
      {"color", {Kind::Color, "nnnn"}},
      {"material", {Kind::Material, "nwnNN"}},
      {"undo", {Kind::Undo, "W"}},
      {"redo", {Kind::Redo, "W"}},
      {"create", {Kind::Create, "w"}},
      {"colors", {Kind::Colors, "o"}},
      {"controls", {Kind::Controls, "o"}},
      {"function", {Kind::Shape, "wwNNNN"}},
      {"contour", {Kind::Shape, "wwNNNN"}},
      {"surface", {Kind::Shape, "wwNNNN"}},
  };
  const auto organs = liveOrgans();
  auto add = [&table](std::string_view name, const Signature& signature) {
    if (!table.emplace(std::string(name), signature).second)
      throw std::logic_error("two viewer commands are named " + std::string(name));
  };
  for (std::size_t k = 0; k < organs.size(); ++k) {
    add(organs[k]->name(), {Kind::Organ, "o", k, -1});
    const auto actions = organs[k]->actions();
    for (std::size_t a = 0; a < actions.size(); ++a) {
      if (!actions[a].command.empty())
        add(actions[a].command, {Kind::Organ, actions[a].arguments, k, static_cast<int>(a)});
    }
  }
  return table;
}

const std::map<std::string, Signature, std::less<>>& signatures() {
  static const std::map<std::string, Signature, std::less<>> table = makeSignatures();
  return table;
}

struct Token {
  std::string text;
  int line, column;
};

// The editors' commands' arguments beyond their pattern (docs/viewer.md, "Editors"); throws at
// the token that is wrong.
void checkEditorCommand(const ViewCommand& command, const std::vector<Token>& tokens,
                        const std::shared_ptr<const std::string>& name) {
  auto at = [&](std::size_t token) {
    return SourceLocation{name, tokens[token].line, tokens[token].column};
  };
  auto oneOf = [&](std::size_t token, std::initializer_list<std::string_view> allowed) {
    for (std::string_view a : allowed) {
      if (tokens[token].text == a) return;
    }
    std::string list;
    for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    throw DiagnosticError(at(token),
                          "expected one of " + list + ", found '" + tokens[token].text + "'");
  };
  // Colour indices of cpfg's twelve banks of 256.
  auto colorIndex = [&](double index) {
    if (index < 0 || index >= 12 * 256 || index != static_cast<int>(index))
      throw DiagnosticError(at(1), "a colour index is a whole number from 0 to 3071");
  };
  switch (command.kind) {
    case Kind::Color:
      colorIndex(command.numbers[0]);
      break;
    case Kind::Material: {
      colorIndex(command.numbers[0]);
      oneOf(2, {"ambient", "diffuse", "specular", "emission", "shininess", "transparency"});
      const bool color = command.words[0] != "shininess" && command.words[0] != "transparency";
      if (command.numbers.size() != (color ? 4u : 2u)) {
        throw DiagnosticError(at(2), "'" + command.words[0] + "' takes " +
                                         (color ? "three values (R G B)" : "one value"));
      }
      break;
    }
    case Kind::Undo:
    case Kind::Redo:
      if (tokens.size() > 1) oneOf(1, {"colors", "materials", "panel"});
      break;
    case Kind::Save:
      if (tokens.size() > 1) oneOf(1, {"constants", "colors", "materials", "panel"});
      break;
    case Kind::Create:
      oneOf(1, {"colors", "materials", "panel"});
      break;
    case Kind::Panel: {
      oneOf(1, {"on", "off", "slider", "button", "range"});
      const std::string& what = command.words[0];
      const std::size_t wanted = what == "on" || what == "off" ? 1 : what == "range" ? 4 : 3;
      if (tokens.size() - 1 != wanted) {
        throw DiagnosticError(at(1), "'panel " + what + "' takes " + std::to_string(wanted - 1) +
                                         " argument" + (wanted == 2 ? "" : "s"));
      }
      if (what == "button") oneOf(3, {"on", "off"});
      for (std::size_t t = 3; what != "button" && t < tokens.size(); ++t) {
        int value = 0;
        const char* end = tokens[t].text.data() + tokens[t].text.size();
        auto [ptr, error] = std::from_chars(tokens[t].text.data(), end, value);
        if (error != std::errc() || ptr != end)
          throw DiagnosticError(
              at(t), "expected a whole number (a slider's value), found '" + tokens[t].text + "'");
      }
      break;
    }
    default:
      break;
  }
}

}  // namespace

std::vector<ViewCommand> parseViewScript(const std::string& text, const std::string& fileName) {
  auto name = std::make_shared<const std::string>(fileName);
  // Split into commands (lists of tokens with their positions).
  std::vector<std::vector<Token>> commands(1);
  int line = 1, column = 1;
  for (std::size_t i = 0; i < text.size();) {
    char c = text[i];
    if (c == '\n' || c == ';') {
      commands.emplace_back();
      if (c == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      ++column;
    } else {
      Token token{"", line, column};
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) &&
             text[i] != ';' && text[i] != '#') {
        token.text += text[i++];
        ++column;
      }
      commands.back().push_back(token);
    }
  }

  std::vector<ViewCommand> script;
  for (const std::vector<Token>& tokens : commands) {
    if (tokens.empty()) continue;
    const Token& head = tokens.front();
    SourceLocation where{name, head.line, head.column};
    auto found = signatures().find(head.text);
    if (found == signatures().end()) {
      throw DiagnosticError(where, "unknown viewer command '" + head.text + "'");
    }
    const std::string pattern(found->second.arguments);
    ViewCommand command{found->second.kind, {}, {}, where};
    command.organ = found->second.organ;
    command.action = found->second.action;
    std::size_t required = 0;
    for (char p : pattern) required += std::islower(static_cast<unsigned char>(p)) ? 1 : 0;
    std::size_t given = tokens.size() - 1;
    if (given < required || given > pattern.size()) {
      SourceLocation at = given > pattern.size()
                              ? SourceLocation{name, tokens[pattern.size() + 1].line,
                                               tokens[pattern.size() + 1].column}
                              : where;
      throw DiagnosticError(
          at, "'" + head.text + "' takes " +
                  (required == pattern.size()
                       ? std::to_string(required)
                       : std::to_string(required) + " to " + std::to_string(pattern.size())) +
                  " argument" + (pattern.size() == 1 ? "" : "s"));
    }
    for (std::size_t a = 0; a < given; ++a) {
      const Token& t = tokens[a + 1];
      if (std::tolower(static_cast<unsigned char>(pattern[a])) == 'n') {
        char* end = nullptr;
        double value = std::strtod(t.text.c_str(), &end);
        if (end == t.text.c_str() || *end != '\0') {
          throw DiagnosticError(SourceLocation{name, t.line, t.column},
                                "expected a number, found '" + t.text + "'");
        }
        command.numbers.push_back(value);
      } else {
        if (std::tolower(static_cast<unsigned char>(pattern[a])) == 'o' && t.text != "on" &&
            t.text != "off") {
          throw DiagnosticError(SourceLocation{name, t.line, t.column},
                                "expected on or off, found '" + t.text + "'");
        }
        command.words.push_back(t.text);
      }
    }
    checkEditorCommand(command, tokens, name);
    if (command.kind == Kind::Screenshot) {
      // The picture's format is its name's extension's, as for `hirsute render -o`.
      std::string extension = std::filesystem::path(command.words[0]).extension().string();
      for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (extension != ".png" && extension != ".jpg" && extension != ".jpeg") {
        throw DiagnosticError(SourceLocation{name, tokens[1].line, tokens[1].column},
                              "'" + command.words[0] +
                                  "': the picture's format is chosen by its extension: .png, "
                                  ".jpg, .jpeg");
      }
    }
    if (command.kind == Kind::Screenshot && command.words.size() == 2 && command.words[1] != "ui" &&
        command.words[1] != "shown") {
      throw DiagnosticError(SourceLocation{name, tokens[2].line, tokens[2].column},
                            "expected 'ui', 'shown' or nothing after the file name");
    }
    if (command.kind == Kind::Shape) {
      command.words.insert(command.words.begin(), head.text);
      checkShapeCommand(command);
    }
    script.push_back(std::move(command));
  }
  return script;
}

}  // namespace hirsute
