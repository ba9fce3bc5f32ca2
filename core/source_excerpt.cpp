#include "hirsute/core/source_excerpt.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

#include "hirsute/core/nearest_name.h"

namespace hirsute {
namespace {

constexpr std::size_t kMaxScannedBytes = std::size_t{64} << 20;  // a line deeper is not shown
constexpr std::size_t kShownAround = 60;  // bytes of a long line shown each side of the column

// The name relative to the folder, as ModelFolder takes it: a location names its file as the
// user finds it, the folder joined with the name (ModelFolder::pathOf).
std::string nameInFolder(const std::string& shown, const ModelFolder& folder) {
  const std::string prefix = folder.path().string();
  if (prefix == "." || prefix.empty()) return shown;
  const std::string joined = prefix.back() == '/' ? prefix : prefix + "/";
  if (shown.compare(0, joined.size(), joined) == 0) return shown.substr(joined.size());
  return shown;  // absolute or elsewhere: ModelFolder refuses it
}

// Line `number` (1-based) of the open file, without its newline; false when the file is shorter.
bool readLine(int fd, int number, std::string& line) {
  std::string buffer(1 << 16, '\0');
  std::size_t scanned = 0;
  int current = 1;
  line.clear();
  for (;;) {
    const ssize_t got = ::read(fd, buffer.data(), buffer.size());
    if (got <= 0) return current == number && !line.empty();
    scanned += static_cast<std::size_t>(got);
    for (ssize_t i = 0; i < got; ++i) {
      const char c = buffer[static_cast<std::size_t>(i)];
      if (c == '\n') {
        if (current == number) return true;
        ++current;
      } else if (current == number) {
        line += c;
        if (line.size() > kMaxScannedBytes) return true;
      }
    }
    if (scanned > kMaxScannedBytes && current < number) return false;
  }
}

bool isNameStart(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// The lines of the open file, at most kMaxScannedBytes of it.
std::vector<std::string> readLines(int fd) {
  std::vector<std::string> lines(1);
  std::string buffer(1 << 16, '\0');
  std::size_t scanned = 0;
  for (;;) {
    const ssize_t got = ::read(fd, buffer.data(), buffer.size());
    if (got <= 0) break;
    for (ssize_t i = 0; i < got; ++i) {
      const char c = buffer[static_cast<std::size_t>(i)];
      if (c == '\n')
        lines.emplace_back();
      else
        lines.back() += c;
    }
    scanned += static_cast<std::size_t>(got);
    if (scanned > kMaxScannedBytes) break;
  }
  return lines;
}

// The name a `#define NAME …` line defines and its column (1-based); none for other lines.
std::optional<std::pair<std::string, int>> definedName(const std::string& line) {
  std::size_t i = 0;
  const auto skipBlanks = [&] {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  };
  skipBlanks();
  if (i >= line.size() || line[i] != '#') return std::nullopt;
  ++i;
  skipBlanks();
  if (line.compare(i, 6, "define") != 0) return std::nullopt;
  i += 6;
  const std::size_t afterKeyword = i;
  skipBlanks();
  if (i == afterKeyword || i >= line.size() || !isNameStart(line[i])) return std::nullopt;
  const std::size_t start = i;
  while (i < line.size() && isNameChar(line[i])) ++i;
  return std::pair{line.substr(start, i - start), static_cast<int>(start) + 1};
}

}  // namespace

std::string macroNotes(const SourceLocation& where, const std::string& message,
                       const ModelFolder& folder) {
  if (where.line <= 0 || !where.file || where.file->empty()) return {};
  ConfinedFile file = folder.open(nameInFolder(*where.file, folder), FileAccess::Read);
  if (!file) return {};
  const std::vector<std::string> lines = readLines(file.fd.get());
  if (static_cast<std::size_t>(where.line) > lines.size()) return {};
  std::map<std::string, std::pair<int, int>> macros;  // name: line and column of its #define
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (const auto defined = definedName(lines[k]))
      macros.emplace(defined->first, std::pair{static_cast<int>(k) + 1, defined->second});
  }
  if (macros.empty()) return {};

  // "'STEPZ' is no constant": a name no #define gave a value, most often a misspelt one.
  constexpr std::string_view kNoConstant = "' is no constant";
  if (message.size() > 1 && message[0] == '\'') {
    const std::size_t end = message.find(kNoConstant);
    if (end != std::string::npos) {
      const std::string name = message.substr(1, end - 1);
      std::vector<std::string> names;
      for (const auto& [defined, place] : macros) names.push_back(defined);
      const std::string meant = nearestName(name, names, typoDistance(name.size()));
      if (meant.empty() || meant == name) return {};
      const auto& [line, column] = macros.at(meant);
      const SourceLocation definition{where.file, line, column};
      return definition.text() + ": note: did you mean '" + meant + "'? It is defined here\n" +
             sourceExcerpt(definition, folder);
    }
  }

  const std::string& line = lines[static_cast<std::size_t>(where.line) - 1];
  const std::size_t from = where.column > 0 ? static_cast<std::size_t>(where.column - 1) : 0;
  if (const std::size_t found = message.rfind("found '"); found != std::string::npos) {
    const std::size_t start = found + 7, end = message.find('\'', start);
    if (end != std::string::npos && end > start &&
        line.compare(from, end - start, message, start, end - start) == 0)
      return {};
  }
  std::string notes;
  std::set<std::string> noted;
  for (std::size_t i = 0; i < line.size() && noted.size() < 3;) {
    if (!isNameStart(line[i]) || (i > 0 && isNameChar(line[i - 1]))) {
      ++i;
      continue;
    }
    const std::size_t start = i;
    while (i < line.size() && isNameChar(line[i])) ++i;
    if (i <= from) continue;  // ends before the column
    const std::string name = line.substr(start, i - start);
    const auto macro = macros.find(name);
    if (macro == macros.end() || macro->second.first == where.line || !noted.insert(name).second)
      continue;
    const SourceLocation definition{where.file, macro->second.first, macro->second.second};
    notes += definition.text() + ": note: '" + name + "' is a macro, defined here\n" +
             sourceExcerpt(definition, folder);
  }
  return notes;
}

std::string sourceExcerpt(const SourceLocation& where, const ModelFolder& folder) {
  if (where.line <= 0 || !where.file || where.file->empty()) return {};
  ConfinedFile file = folder.open(nameInFolder(*where.file, folder), FileAccess::Read);
  if (!file) return {};
  std::string line;
  if (!readLine(file.fd.get(), where.line, line)) return {};
  if (!line.empty() && line.back() == '\r') line.pop_back();

  // The column is a byte's (1-based); past the end it points just after the line.
  std::size_t caret = where.column > 0 ? static_cast<std::size_t>(where.column - 1) : 0;
  caret = std::min(caret, line.size());
  std::string lead;
  if (line.size() > 2 * kShownAround + 20) {
    const std::size_t from = caret > kShownAround ? caret - kShownAround : 0;
    const std::size_t to = std::min(line.size(), caret + kShownAround);
    line = (from > 0 ? "..." : "") + line.substr(from, to - from) + (to < line.size() ? "..." : "");
    caret = caret - from + (from > 0 ? 3 : 0);
  }
  // A control byte shows as \xHH: the part before the caret is shown on its own, so that the
  // caret stays under the character it points at.
  const std::string shownBefore = printableText(line.substr(0, caret));
  line = shownBefore + printableText(line.substr(caret));
  caret = shownBefore.size();

  std::string pad;
  for (std::size_t i = 0; i < caret && i < line.size(); ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    if ((c & 0xc0) == 0x80) continue;  // a UTF-8 continuation byte: the character has its space
    pad += c == '\t' ? '\t' : ' ';
  }
  const std::string number = std::to_string(where.line);
  const std::string gutter(number.size(), ' ');
  return " " + number + " | " + line + "\n " + gutter + " | " + pad + "^\n";
}

}  // namespace hirsute
