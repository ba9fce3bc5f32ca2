#include "hirsute/environment/keyword_file.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "hirsute/core/characters.h"
#include "hirsute/core/input_file.h"

namespace hirsute {

std::vector<KeywordToken> KeywordLine::tokens(const char* separators) const {
  std::vector<KeywordToken> out;
  std::size_t i = rest;
  while (i < text.size()) {
    while (i < text.size() && isOneOf(text[i], separators)) ++i;
    const std::size_t from = i;
    while (i < text.size() && !isOneOf(text[i], separators)) ++i;
    if (i > from)
      out.push_back(KeywordToken{text.substr(from, i - from), static_cast<int>(from) + 1});
  }
  return out;
}

std::vector<KeywordLine> keywordLines(std::string_view text, const std::filesystem::path& file,
                                      std::size_t maxLength) {
  auto name = std::make_shared<const std::string>(file.string());
  std::vector<KeywordLine> lines;
  int number = 0;
  // Lines as std::getline splits them: a last line without its newline counts, the empty
  // remainder after a final newline does not.
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string line(text.substr(0, end));
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.size() > maxLength) {
      throw DiagnosticError(SourceLocation{name, number, static_cast<int>(maxLength) + 1},
                            "the line is longer than " + std::to_string(maxLength) + " characters");
    }
    KeywordLine keywordLine;
    keywordLine.file = name;
    keywordLine.line = number;
    const std::size_t keywordEnd = line.find_first_of(":\t");
    keywordLine.keyword = line.substr(0, keywordEnd);
    keywordLine.rest = keywordEnd == std::string::npos ? line.size() : keywordEnd + 1;
    keywordLine.text = std::move(line);
    lines.push_back(std::move(keywordLine));
  }
  return lines;
}

std::vector<KeywordLine> readKeywordLines(const std::filesystem::path& file,
                                          std::size_t maxLength) {
  std::string text;
  std::string failure;
  if (!readInputFile(file, text, failure, kMaxKeywordFileBytes)) {
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(file.string()), 0, 0},
                          "cannot read the file: " + failure);
  }
  return keywordLines(text, file, maxLength);
}

float keywordNumber(const KeywordLine& line, const KeywordToken& token) {
  const char* begin = token.text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin) {
    throw DiagnosticError(line.at(token.column), "expected a number, found '" + token.text + "'");
  }
  if (!std::isfinite(value) || std::fabs(value) > std::numeric_limits<float>::max()) {
    throw DiagnosticError(line.at(token.column), "the number '" + token.text + "' is out of range");
  }
  return static_cast<float>(value);
}

int keywordInteger(const KeywordLine& line, const KeywordToken& token) {
  const float value = keywordNumber(line, token);
  if (std::fabs(value) >= 2147483647.0f) {
    throw DiagnosticError(line.at(token.column), "the number '" + token.text + "' is out of range");
  }
  return static_cast<int>(value);
}

void warnUnknownKeyword(const KeywordLine& line, Diagnostics& diagnostics,
                        const std::string& what) {
  diagnostics.warn(line.at(1), line.text.empty()
                                   ? "empty line ignored"
                                   : "unknown " + what + " keyword '" + line.keyword + "' ignored");
}

}  // namespace hirsute
