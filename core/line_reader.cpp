#include "hirsute/core/line_reader.h"

#include <algorithm>
#include <charconv>
#include <system_error>

namespace hirsute {

std::vector<std::string_view> splitWords(std::string_view text, WordSplit split) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isWordBlank(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !isWordBlank(text[i])) ++i;
    if (i == start) continue;
    const std::string_view word = text.substr(start, i - start);
    const std::size_t colon = split == WordSplit::AfterColons ? word.find(':') : word.npos;
    if (colon != std::string_view::npos && colon + 1 < word.size()) {
      words.push_back(word.substr(0, colon + 1));
      words.push_back(word.substr(colon + 1));
    } else {
      words.push_back(word);
    }
  }
  return words;
}

namespace {

template <class T>
std::optional<T> wordAs(std::string_view word) {
  T value{};
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size()) return std::nullopt;
  return value;
}

}  // namespace

std::optional<double> wordAsNumber(std::string_view word) {
  return wordAs<double>(word);
}

std::optional<int> wordAsInteger(std::string_view word) {
  return wordAs<int>(word);
}

LineReader::LineReader(std::string_view text, const std::string& file, WordSplit split)
    : file_(std::make_shared<const std::string>(file)) {
  forEachLine(text, [&](int number, std::string_view line) {
    lastNumber_ = number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return;
    line = line.substr(first, line.find_last_not_of(" \t\r") + 1 - first);
    lines_.push_back(TextLine{number, line, splitWords(line, split)});
  });
}

const TextLine& LineReader::take(const std::string& expected) {
  if (atEnd()) fail(std::max(1, lastNumber_), "the file ends where " + expected + " was expected");
  return lines_[next_++];
}

void LineReader::fail(int line, const std::string& message) const {
  throw DiagnosticError(SourceLocation{file_, line, 0}, message);
}

}  // namespace hirsute
