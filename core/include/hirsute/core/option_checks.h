// Checks of command-line values that every command and every organ's options share.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

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

}  // namespace hirsute
