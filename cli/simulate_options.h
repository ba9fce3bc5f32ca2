// The options of `hirsute simulate` (docs/dynamics.md, "hirsute simulate"), apart from the run:
// registered with CLI11 and checked before any model file is read, so that the option vector
// alone can be tested and fuzzed (fuzz/simulate_options_fuzzer.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model_pipeline.h"

namespace hirsute::cli {

// What the frames of a run may write by default: 16 GiB.
inline constexpr std::uint64_t kDefaultMaxOutputBytes = std::uint64_t{16} << 30;

struct SimulateOptions {
  ModelOptions model;
  std::string animation;
  std::string output;
  std::optional<int> frames;
  double fps = 24;
  bool obj = false;
  std::string pc2;  // a point cache of every frame, over its base mesh (point_cache.h)
  bool noFrames = false;  // only the table: for measuring the simulation alone
  bool vaneCollisions = false;    // the vanes collide (as `dynamics vanes: on`)
  bool noVaneCollisions = false;  // the vanes follow their stems and may pass through
  bool noRestingContacts = false;  // no resting stage: every contact the CCD's
  // Count, with the vanes not colliding, those that meet in every frame's state (they are
  // counted anyway when they collide: the check that none is left).
  bool countVaneIntersections = false;
  int width = 800, height = 600;
  // The bytes the frames' files may take, all together (--max-output-bytes).
  std::uint64_t maxOutputBytes = kDefaultMaxOutputBytes;
  // Overrides of the view file's `dynamics …:` lines.
  std::vector<double> gravity, wind;
  std::optional<double> gusts, gustScale, gustPeriod, drag;
  std::optional<unsigned> gustSeed;
  std::optional<int> substeps, segments;
  std::string animate;  // NAME=FROM:TO: a #define of the .l moved over the frames
  // Fur over time (docs/fur.md, "Fur over time"): droplets at given frames (FRAME:N[:RADIUS
  // [:WETNESS]]), rain (RATE[:RADIUS[:WETNESS]], droplets a second), drying (wetness lost a
  // second, from frame dryFrom), the strands' force per unit mass (the view file's `fur force:`)
  // and how strongly the wind pushes them.
  std::vector<std::string> drops;
  std::string rain;
  std::optional<double> dry;
  int dryFrom = 1;
  std::vector<double> furForce;
  std::optional<double> furDrag;
  std::uint32_t dropSeed = 1;
};

// Droplets falling on the fur: `count` at random at frame `frame` (rain: count a second, frame
// 0), each of `radius` (the fur surface's [0, 1] units) and `wetness`.
struct DropletFall {
  int frame = 0;
  double count = 0;
  float radius = 0.05f;
  float wetness = 1;
};

// `--drop FRAME:N[:RADIUS[:WETNESS]]` (rain: false) or `--rain RATE[:RADIUS[:WETNESS]]` (rain:
// true), read; nothing when the text is not that, or a number is out of its range (frame 1 to
// 1 000 000, N and RATE 0 to 10 000 000, RADIUS 1e-6 to 1, WETNESS 0 to 1).
std::optional<DropletFall> dropletFall(const std::string& text, bool rain);

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
