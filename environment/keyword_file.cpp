#include "hirsute/environment/keyword_file.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>

namespace hirsute {

std::vector<KeywordToken> KeywordLine::tokens(const char* separators) const {
  std::vector<KeywordToken> out;
  std::size_t i = rest;
  while (i < text.size()) {
    while (i < text.size() && std::strchr(separators, text[i]) != nullptr) ++i;
    const std::size_t from = i;
    while (i < text.size() && std::strchr(separators, text[i]) == nullptr) ++i;
    if (i > from)
      out.push_back(KeywordToken{text.substr(from, i - from), static_cast<int>(from) + 1});
  }
  return out;
}

std::vector<KeywordLine> readKeywordLines(const std::filesystem::path& file,
                                          std::size_t maxLength) {
  auto name = std::make_shared<const std::string>(file.string());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw DiagnosticError(SourceLocation{name, 0, 0}, "cannot read the file");
  std::vector<KeywordLine> lines;
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    ++number;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.size() > maxLength) {
      throw DiagnosticError(SourceLocation{name, number, static_cast<int>(maxLength) + 1},
                            "the line is longer than " + std::to_string(maxLength) + " characters");
    }
    KeywordLine line;
    line.file = name;
    line.line = number;
    line.text = text;
    const std::size_t end = text.find_first_of(":\t");
    line.keyword = text.substr(0, end);
    line.rest = end == std::string::npos ? text.size() : end + 1;
    lines.push_back(std::move(line));
  }
  if (in.bad()) throw DiagnosticError(SourceLocation{name, number, 0}, "cannot read the file");
  return lines;
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
