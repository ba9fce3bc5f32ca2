// The subcommands of the `hirsute` program. Each registers its options with CLI11 and, when the
// user picked it, leaves the action to run in `action`.
#pragma once

#include <cmath>
#include <cstdlib>
#include <functional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hirsute/core/progress.h"

namespace hirsute::cli {

using Action = std::function<int()>;

// Exit codes: 0 success, 1 an I/O failure, 2 bad input (a diagnostic was printed).
inline constexpr int kExitOk = 0;
inline constexpr int kExitIoError = 1;
inline constexpr int kExitBadInput = 2;

// What a run that ran out of memory says: the stage that was running, and the limits that
// bound what a model can make.
inline std::string outOfMemoryMessage() {
  const std::string stage = Progress::lastStage();
  return "hirsute: error: out of memory" + (stage.empty() ? std::string() : " while " + stage) +
         ": the model made more than this machine holds; lower its size or the limits "
         "(--max-modules, --max-vertices, --max-hairs, --max-feathers)";
}

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

void registerDeriveCommand(CLI::App& app, Action& action);
void registerRenderCommand(CLI::App& app, Action& action);
void registerExportCommand(CLI::App& app, Action& action);
void registerViewCommand(CLI::App& app, Action& action);
void registerBenchCommand(CLI::App& app, Action& action);
void registerSimulateCommand(CLI::App& app, Action& action);

}  // namespace hirsute::cli
