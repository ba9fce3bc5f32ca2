#pragma once

#include <string_view>

namespace hirsute {

// Whether `c` is one of the characters of `set`. Unlike strchr, a NUL byte of the input is in no
// set: strchr finds every string's terminator, so a format scanner built on it reads `%` then
// NUL as a complete conversion and hands printf a broken one.
constexpr bool isOneOf(char c, std::string_view set) {
  return set.find(c) != std::string_view::npos;
}

}  // namespace hirsute
