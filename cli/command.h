// The subcommands of the `hirsute` program. Each registers its options with CLI11 and, when the
// user picked it, leaves the action to run in `action`.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace hirsute::cli {

using Action = std::function<int()>;

// Exit codes: 0 success, 1 an I/O failure, 2 bad input (a diagnostic was printed).
inline constexpr int kExitOk = 0;
inline constexpr int kExitIoError = 1;
inline constexpr int kExitBadInput = 2;

void registerDeriveCommand(CLI::App& app, Action& action);
void registerRenderCommand(CLI::App& app, Action& action);
void registerExportCommand(CLI::App& app, Action& action);
void registerViewCommand(CLI::App& app, Action& action);
void registerBenchCommand(CLI::App& app, Action& action);
void registerSimulateCommand(CLI::App& app, Action& action);

}  // namespace hirsute::cli
