// Checks of command-line values that every command and every organ's options share.
#pragma once

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <system_error>
#include <utility>

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

// The largest side, in pixels, of a picture or window any command makes.
inline constexpr int kMaxImageSide = 16384;

// `WIDTHxHEIGHT` (`1024x768`), each side an integer from 1 to kMaxImageSide; none otherwise.
inline std::optional<std::pair<int, int>> parseImageSize(const std::string& text) {
  const std::size_t x = text.find('x');
  if (x == std::string::npos) return std::nullopt;
  int sides[2] = {0, 0};
  const std::pair<std::size_t, std::size_t> parts[2] = {{0, x}, {x + 1, text.size()}};
  for (int k = 0; k < 2; ++k) {
    const char* first = text.data() + parts[k].first;
    const char* last = text.data() + parts[k].second;
    if (first == last || *first == '+' || *first == '-') return std::nullopt;
    const auto [end, error] = std::from_chars(first, last, sides[k]);
    if (error != std::errc() || end != last || sides[k] < 1 || sides[k] > kMaxImageSide)
      return std::nullopt;
  }
  return std::pair{sides[0], sides[1]};
}

// `--size WIDTHxHEIGHT`, as parseImageSize reads it.
inline CLI::Validator imageSizeCheck() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (parseImageSize(text)) return {};
        return fmt::format("'{}' is not WIDTHxHEIGHT (as 1024x768) with each side from 1 to {}",
                           text, kMaxImageSide);
      },
      "WIDTHxHEIGHT");
}

// Registers `--size WIDTHxHEIGHT` on a command that makes pictures, into `width` and `height`
// (int, or std::optional<int> where no size means "as before"). The former spellings `--width N`
// and `--height N` stay as hidden aliases with the same limit.
template <typename Side>
void addImageSizeOption(CLI::App& command, Side& width, Side& height,
                        const std::string& description) {
  CLI::Option* size = command
                          .add_option_function<std::string>(
                              "--size",
                              [&width, &height](const std::string& text) {
                                const auto sides = parseImageSize(text);
                                width = sides->first;
                                height = sides->second;
                              },
                              description)
                          ->check(imageSizeCheck());
  command.add_option("--width", width, "The width alone (as --size)")
      ->check(integerRange(1, kMaxImageSide))
      ->group("")
      ->excludes(size);
  command.add_option("--height", height, "The height alone (as --size)")
      ->check(integerRange(1, kMaxImageSide))
      ->group("")
      ->excludes(size);
}

}  // namespace hirsute
