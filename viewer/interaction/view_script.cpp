#include "hirsute/viewer/interaction/view_script.h"

#include <cctype>
#include <cstdlib>
#include <map>
#include <memory>

namespace hirsute {
namespace {

using Kind = ViewCommand::Kind;

// What each command takes: its kind, and its arguments as a pattern: 'n' a number, 'w' a word,
// lower case required, upper case optional (optional ones come last).
struct Signature {
  Kind kind;
  const char* arguments;
};

const std::map<std::string, Signature>& signatures() {
  static const std::map<std::string, Signature> table = {
      {"rotate", {Kind::Rotate, "nN"}},
      {"roll", {Kind::Roll, "n"}},
      {"zoom", {Kind::Zoom, "n"}},
      {"pan", {Kind::Pan, "nn"}},
      {"reset", {Kind::Reset, ""}},
      {"step", {Kind::Step, "N"}},
      {"back", {Kind::Back, "N"}},
      {"goto", {Kind::Goto, "n"}},
      {"animate", {Kind::Animate, ""}},
      {"hairs", {Kind::Hairs, "w"}},
      {"feathers", {Kind::Feathers, "w"}},
      {"fur", {Kind::Fur, "w"}},
      {"droplets", {Kind::Droplets, "n"}},
      {"dynamics", {Kind::Dynamics, "w"}},
      {"wireframe", {Kind::Wireframe, "w"}},
      {"define", {Kind::Define, "ww"}},
      {"help", {Kind::Help, "w"}},
      {"panel", {Kind::Panel, "w"}},
      {"save", {Kind::Save, ""}},
      {"wait-reload", {Kind::WaitReload, "N"}},
      {"sleep", {Kind::Sleep, "n"}},
      {"measure", {Kind::Measure, "N"}},
      {"screenshot", {Kind::Screenshot, "wW"}},
      {"quit", {Kind::Quit, ""}},
  };
  return table;
}

struct Token {
  std::string text;
  int line, column;
};

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
    const std::string pattern = found->second.arguments;
    ViewCommand command{found->second.kind, {}, {}, where};
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
        command.words.push_back(t.text);
      }
    }
    if ((command.kind == Kind::Hairs || command.kind == Kind::Feathers || command.kind == Kind::Fur ||
         command.kind == Kind::Dynamics ||
         command.kind == Kind::Wireframe || command.kind == Kind::Help ||
         command.kind == Kind::Panel) &&
        command.words[0] != "on" && command.words[0] != "off") {
      throw DiagnosticError(SourceLocation{name, tokens[1].line, tokens[1].column},
                            "expected on or off, found '" + command.words[0] + "'");
    }
    if (command.kind == Kind::Screenshot && command.words.size() == 2 && command.words[1] != "ui") {
      throw DiagnosticError(SourceLocation{name, tokens[2].line, tokens[2].column},
                            "expected 'ui' or nothing after the file name");
    }
    script.push_back(std::move(command));
  }
  return script;
}

}  // namespace hirsute
