// The options of `hirsute simulate` (docs/dynamics.md, "hirsute simulate"), apart from the run:
// registered with CLI11 and checked before any model file is read, so that the option vector
// alone can be tested and fuzzed (fuzz/simulate_options_fuzzer.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model_pipeline.h"

namespace hirsute::cli {

struct SimulateOptions {
  ModelOptions model;
  std::string animation;
  std::string output;
  std::optional<int> frames;
  double fps = 24;
  bool obj = false;
  bool noFrames = false;  // only the table: for measuring the simulation alone
  int width = 800, height = 600;
  // Overrides of the view file's `dynamics …:` lines.
  std::vector<double> gravity, wind;
  std::optional<double> gusts, gustScale, gustPeriod, drag;
  std::optional<unsigned> gustSeed;
  std::optional<int> substeps, segments;
  std::string animate;  // NAME=FROM:TO: a #define of the .l moved over the frames
};

// Adds the model's arguments and simulate's own options to `command`.
void addSimulateOptions(CLI::App& command, SimulateOptions& options);

// `--animate NAME=FROM:TO`, read.
struct AnimatedDefine {
  std::string name;
  double from = 0, to = 0;
  bool integer = false;  // the .l writes it as an integer: frames round it
};

// NAME=FROM:TO with NAME one of the #define constants of the .l file `lsystem` and FROM and TO
// finite numbers; nothing when the text is not that.
std::optional<AnimatedDefine> animatedDefine(const std::string& text,
                                             const std::filesystem::path& lsystem);

}  // namespace hirsute::cli
