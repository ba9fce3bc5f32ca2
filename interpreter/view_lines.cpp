// The view file's reading of text (view_lines.h).
#include "hirsute/interpreter/view_lines.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

namespace hirsute::view_text {

std::string inQuotes(std::string_view text) {
  return "'" + std::string(text) + "'";
}

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// A number at the front of `text` as sscanf's %f reads it: an optional sign, digits, a fraction,
// an exponent. Returns the value and the characters used; nothing when no number starts there.
// Infinite and NaN values are refused: no view setting means them.
std::optional<std::pair<double, std::size_t>> numberAtFront(std::string_view text) {
  std::size_t skip = 0;
  if (!text.empty() && text[0] == '+' && text.size() > 1 && text[1] != '-') skip = 1;
  const char* begin = text.data() + skip;
  const char* end = text.data() + text.size();
  if (begin == end ||
      !(std::isdigit(static_cast<unsigned char>(*begin)) || *begin == '-' || *begin == '.')) {
    return std::nullopt;
  }
  double value = 0.0;
  const auto [stop, error] = std::from_chars(begin, end, value, std::chars_format::general);
  if (error != std::errc() || !std::isfinite(value)) return std::nullopt;
  return std::make_pair(value, static_cast<std::size_t>(stop - text.data()));
}

// An integer at the front of `text`, as %d reads it.
std::optional<std::pair<long, std::size_t>> integerAtFront(std::string_view text) {
  std::size_t skip = 0;
  if (!text.empty() && text[0] == '+' && text.size() > 1 && text[1] != '-') skip = 1;
  long value = 0;
  const char* begin = text.data() + skip;
  const auto [stop, error] = std::from_chars(begin, text.data() + text.size(), value);
  if (error != std::errc() || stop == begin) return std::nullopt;
  return std::make_pair(value, static_cast<std::size_t>(stop - text.data()));
}

// A whole word as a number; used where words are separated first (light, texture, tropism).
std::optional<double> wholeNumber(std::string_view word) {
  const auto number = numberAtFront(word);
  if (!number || number->second != word.size()) return std::nullopt;
  return number->first;
}

}  // namespace hirsute::view_text
