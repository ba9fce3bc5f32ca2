// The lines of the text formats, read one way: numbered from 1, blank lines skipped, each split
// into words at blanks, read front to back with errors at their line in the file. The function
// and contour files (funcedit, cuspy), the surface files (.s) and the view file's words read
// through it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

// The blanks between words: space, tab, and the carriage return of a file written on Windows.
inline bool isWordBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// How a line splits into words: at blanks only, or also after a colon inside a word, as surface
// files write labels (`X:0.5` is the words `X:` and `0.5`).
enum class WordSplit { AtBlanks, AfterColons };

std::vector<std::string_view> splitWords(std::string_view text,
                                         WordSplit split = WordSplit::AtBlanks);

// The whole word as a number, nothing when any of it is not (no blanks, no leading '+').
std::optional<double> wordAsNumber(std::string_view word);
std::optional<int> wordAsInteger(std::string_view word);

// Calls `visit(number, line)` for each line of `text`, numbered from 1, without its '\n'.
template <class Visit>
void forEachLine(std::string_view text, Visit&& visit) {
  int number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    visit(++number, text.substr(start, end - start));
    start = end + 1;
  }
}

// One non-blank line. The views point into the text the reader was given.
struct TextLine {
  int number = 0;                       // 1-based line in the file
  std::string_view text;                // the line without blanks at either end
  std::vector<std::string_view> words;  // never empty
};

// The non-blank lines of one file, read front to back.
class LineReader {
 public:
  // `text` must outlive the reader; `file` names it in errors.
  LineReader(std::string_view text, const std::string& file,
             WordSplit split = WordSplit::AtBlanks);

  bool atEnd() const { return next_ >= lines_.size(); }
  const TextLine& peek() const { return lines_[next_]; }
  // The next line; an error at the file's last line, saying `expected` was, when it ends.
  const TextLine& take(const std::string& expected);

  // Throws DiagnosticError at `line` of the file (column 0: the whole line).
  [[noreturn]] void fail(int line, const std::string& message) const;

 private:
  std::shared_ptr<const std::string> file_;
  std::vector<TextLine> lines_;
  std::size_t next_ = 0;
  int lastNumber_ = 0;
};

}  // namespace hirsute
