// Checks of command-line values that every command and every organ's options share.
#pragma once

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <system_error>

namespace hirsute {

// A number from min to max. Unlike CLI::Range, which lets NaN through, NaN and infinities are
// refused: a bad option ends the run with exit code 2 before anything is written.
inline CLI::Validator finiteRange(double min, double max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size())
          return "'" + text + "' is not a number";
        if (!std::isfinite(value) || value < min || value > max)
          return fmt::format("'{}' is not a finite number from {:g} to {:g}", text, min, max);
        return {};
      },
      fmt::format("FINITE in [{:g} - {:g}]", min, max));
}

// An integer from min to max, in decimal digits with an optional '-'. CLI11's own conversion
// reads `1e3` as a number out of range and clamps what an integer type cannot hold (`--seed -1`
// read as 0 and 2^64 as 2^64 - 1, without a word): each is refused with what it is.
inline CLI::Validator integerRange(std::int64_t min, std::uint64_t max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        const bool negative = !text.empty() && text[0] == '-';
        const char* first = text.data() + (negative ? 1 : 0);
        const char* last = text.data() + text.size();
        std::uint64_t magnitude = 0;
        const auto [end, error] = std::from_chars(first, last, magnitude);
        if (first == last || end != last ||
            (error != std::errc() && error != std::errc::result_out_of_range))
          return "'" + text + "' is not an integer";
        const bool inRange =
            error == std::errc() &&
            (negative
                 ? min < 0 && magnitude <= static_cast<std::uint64_t>(-(min + 1)) + 1
                 : magnitude <= max && (min <= 0 || magnitude >= static_cast<std::uint64_t>(min)));
        if (!inRange) return fmt::format("'{}' is not an integer from {} to {}", text, min, max);
        return {};
      },
      fmt::format("INT in [{} - {}]", min, max));
}

}  // namespace hirsute
