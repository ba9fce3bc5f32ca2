// Checks of a parsed `.l` file for mistakes that the language accepts but that are almost never
// meant: a production whose predecessor's parameter count the string never holds, unbalanced
// brackets in a successor, a multi-letter name read as several one-letter modules, an unknown
// `@` module, a production that can never apply. Each is a named warning (`-W no-NAME`).
#pragma once

#include <array>
#include <functional>
#include <string_view>

#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/ast.h"

namespace hirsute {

// The warnings' names, as `-W no-NAME` takes them.
inline constexpr std::string_view kParameterCountWarning = "parameter-count";
inline constexpr std::string_view kUnbalancedBracketsWarning = "unbalanced-brackets";
inline constexpr std::string_view kMultiLetterNameWarning = "multi-letter-name";
inline constexpr std::string_view kUnknownAtModuleWarning = "unknown-at-module";
inline constexpr std::string_view kUnusedProductionWarning = "unused-production";
inline constexpr std::array<std::string_view, 5> kModelWarnings{
    kParameterCountWarning, kUnbalancedBracketsWarning, kMultiLetterNameWarning,
    kUnknownAtModuleWarning, kUnusedProductionWarning};

// What the interpreter makes of modules (the L-system library knows no turtle): given by the
// turtle itself (interpreter/turtle.h, turtleModuleMeanings).
struct ModuleMeanings {
  // The turtle interprets `symbol` on its own (F, +, [, …).
  std::function<bool(char symbol)> interpreted;
  // `@` `first` without parameters is the first letter of a two-letter module (@Gs, @Tf, @Hd).
  std::function<bool(char first)> atFamily;
  // `@` `first` `second` (second 0: `@` `first` alone) is a module the turtle knows.
  std::function<bool(char first, char second)> atModule;
};

// Warns, through `diagnostics`, of each mistake above found in `file`, once, at its place.
void checkModel(const ast::File& file, const ModuleMeanings& meanings, Diagnostics& diagnostics);

}  // namespace hirsute
