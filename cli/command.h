// The subcommands of the `hirsute` program. Each registers its options with CLI11 and, when the
// user picked it, leaves the action to run in `action`.
#pragma once

#include <cmath>
#include <cstdlib>
#include <functional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hirsute/core/option_checks.h"
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

void registerCheckCommand(CLI::App& app, Action& action);
void registerDeriveCommand(CLI::App& app, Action& action);
void registerRenderCommand(CLI::App& app, Action& action);
void registerExportCommand(CLI::App& app, Action& action);
void registerViewCommand(CLI::App& app, Action& action);
void registerBenchCommand(CLI::App& app, Action& action);
void registerSimulateCommand(CLI::App& app, Action& action);
void registerFeatherScanCommand(CLI::App& app, Action& action);
void registerRenderFramesCommand(CLI::App& app, Action& action);

}  // namespace hirsute::cli
