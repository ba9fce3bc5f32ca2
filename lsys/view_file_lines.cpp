#include "hirsute/lsys/view_file_lines.h"

#include "hirsute/core/line_reader.h"

#include <charconv>
#include <memory>
#include <system_error>

namespace hirsute {

SourceLocation ViewFileLine::at(std::size_t restOffset) const {
  SourceLocation location = where;
  location.column = restColumn + static_cast<int>(restOffset);
  return location;
}

std::optional<std::pair<int, std::string>> lineMarker(std::string_view line) {
  if (line.empty() || line[0] != '#') return std::nullopt;
  std::string_view rest = line.substr(1);
  const std::vector<std::string_view> words = splitWords(rest);
  std::size_t numberWord = 0;
  if (!words.empty() && words[0] == "line") numberWord = 1;
  if (words.size() <= numberWord) return std::nullopt;
  const std::string_view digits = words[numberWord];
  int number = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
  if (error != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  rest = rest.substr(static_cast<std::size_t>(digits.data() - rest.data()));
  std::string file;
  const std::size_t open = rest.find('"');
  const std::size_t close = rest.rfind('"');
  if (open != std::string_view::npos && close > open) {
    file = std::string(rest.substr(open + 1, close - open - 1));
  }
  return std::make_pair(number, file);
}

std::vector<ViewFileLine> viewFileLines(std::string_view text,
                                        const std::filesystem::path& viewFile) {
  std::vector<ViewFileLine> lines;
  std::shared_ptr<const std::string> currentFile =
      std::make_shared<const std::string>(viewFile.string());
  // Numbered by the markers, not by forEachLine: they count the user's file's lines.
  int lineNumber = 0;
  forEachLine(text, [&](int, std::string_view line) {
    if (const auto marker = lineMarker(line)) {
      lineNumber = marker->first - 1;
      // cpp names the view file as it was given; keep the caller's spelling for it. The
      // built-in pseudo-files carry no lines of their own.
      if (!marker->second.empty() && marker->second != *currentFile) {
        currentFile = std::make_shared<const std::string>(marker->second);
      }
      return;
    }
    ++lineNumber;
    // cpfg skips leading spaces only: a tab-indented command is an unknown label.
    const std::size_t first = line.find_first_not_of(' ');
    if (first == std::string_view::npos || line.find_first_not_of(" \t\r") == std::string::npos) {
      return;
    }
    ViewFileLine out;
    out.where = SourceLocation{currentFile, lineNumber, 0};
    const std::size_t colon = line.find(':', first);
    std::size_t restStart = first;
    if (colon != std::string_view::npos) {
      out.label = line.substr(first, colon + 1 - first);
      restStart = colon + 1;
    }
    out.rest = line.substr(restStart);
    out.restColumn = static_cast<int>(restStart) + 1;
    lines.push_back(out);
  });
  return lines;
}

std::vector<ViewWord> viewWords(const ViewFileLine& line) {
  std::vector<ViewWord> words;
  for (std::string_view word : splitWords(line.rest)) {
    words.push_back(
        ViewWord{word, line.restColumn + static_cast<int>(word.data() - line.rest.data())});
  }
  return words;
}

[[noreturn]] void rethrowAtViewLine(const SourceLocation& where, const std::string& kind,
                                    std::string_view fileName, const DiagnosticError& inner) {
  const Diagnostic& d = inner.diagnostic();
  throw DiagnosticError(where, kind + " file '" + std::string(fileName) +
                                   "' is broken: " + d.where.text() + ": " + d.message);
}

}  // namespace hirsute
