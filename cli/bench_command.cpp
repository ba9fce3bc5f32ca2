// `hirsute bench`: figures measured on the command line. `bench ccd FILE.csv…` runs the
// continuous collision detection over query files with ground truth (docs/dynamics.md) and
// prints, per file and in total, the queries, false negatives, false positives and the time per
// query. `bench live-coat MODEL.l MODEL.v` runs a model's feather coat as the viewer's dynamics
// do (D) beside a stand-in display that takes a fixed time a frame, stepped a frame at a time
// (each frame's step at most 1/30 s, as the viewer stepped before issue 26, item 3) and on the
// runner's thread (dynamics::CoatRunner), and prints the simulated seconds, the wall seconds
// and their ratio for each.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "command.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/core/progress.h"
#include "hirsute/hairs/dynamics/ccd_query_file.h"
#include "hirsute/hairs/dynamics/coat_motion.h"
#include "hirsute/hairs/dynamics/coat_runner.h"
#include "hirsute/hairs/dynamics/coat_shingling.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_settings.h"
#include "model_pipeline.h"

namespace hirsute::cli {
namespace {

// Each file's queries are run again until this much time has passed, so that the time per query
// of a small file is not the clock's resolution.
constexpr double kMinimumTimedSeconds = 0.05;
constexpr int kMaximumPasses = 10000;

struct BenchCcdOptions {
  std::vector<std::string> files;
  double eta = 0;
  double tolerance = dynamics::CcdOptions{}.relativeTolerance;
};

struct Tally {
  std::size_t queries = 0, falseNegatives = 0, falsePositives = 0;
  double seconds = 0;  // for all the queries once
};

void printTally(const std::string& name, const Tally& tally) {
  const double microseconds =
      tally.queries == 0 ? 0.0 : tally.seconds * 1e6 / static_cast<double>(tally.queries);
  std::printf("%s: %zu queries, %zu false negatives, %zu false positives, %.2f us/query\n",
              name.c_str(), tally.queries, tally.falseNegatives, tally.falsePositives,
              microseconds);
}

Tally measure(const dynamics::CcdQueryFile& file, const dynamics::CcdOptions& options) {
  using Clock = std::chrono::steady_clock;
  Tally tally;
  tally.queries = file.queries.size();
  for (const dynamics::CcdQuery& query : file.queries) {
    const bool contact = dynamics::runCcdQuery(file.kind, query, options).contact;
    tally.falseNegatives += query.collides && !contact;
    tally.falsePositives += !query.collides && contact;
  }
  if (file.queries.empty()) return tally;
  int passes = 0;
  const auto start = Clock::now();
  double elapsed = 0;
  do {
    for (const dynamics::CcdQuery& query : file.queries) {
      // A call into another library, with its allocations: never optimised away.
      dynamics::runCcdQuery(file.kind, query, options);
    }
    ++passes;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < kMinimumTimedSeconds && passes < kMaximumPasses);
  tally.seconds = elapsed / passes;
  return tally;
}

int runBenchCcd(const BenchCcdOptions& o) {
  // Every file is read before any is run: bad input prints its error and no figures.
  std::vector<dynamics::CcdQueryFile> files;
  try {
    for (const std::string& name : o.files) files.push_back(dynamics::readCcdQueryFile(name));
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    return kExitBadInput;
  }
  dynamics::CcdOptions options;
  options.minimumSeparation = o.eta;
  options.relativeTolerance = o.tolerance;
  Tally total;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const Tally tally = measure(files[i], options);
    printTally(o.files[i], tally);
    total.queries += tally.queries;
    total.falseNegatives += tally.falseNegatives;
    total.falsePositives += tally.falsePositives;
    total.seconds += tally.seconds;
  }
  printTally("total", total);
  return kExitOk;
}

struct BenchLiveCoatOptions {
  ModelOptions model;
  double seconds = 5;   // wall-clock seconds each way runs
  double frameMs = 60;  // what the stand-in display takes a frame (a slow llvmpipe frame)
};

struct LiveCoatRun {
  double simulated = 0, wall = 0;
  long frames = 0;  // frames the stand-in display showed
  std::uint64_t retries = 0;
};

void printRun(const char* name, const LiveCoatRun& run) {
  std::printf(
      "%s: %.2f s simulated in %.2f s wall, %.2fx real time, %ld frames shown (%.1f/s), "
      "%llu steps retried\n",
      name, run.simulated, run.wall, run.wall > 0 ? run.simulated / run.wall : 0.0, run.frames,
      run.wall > 0 ? static_cast<double>(run.frames) / run.wall : 0.0,
      static_cast<unsigned long long>(run.retries));
}

// The viewer's stepping before issue 26, item 3: each displayed frame advances the coat by the
// wall time since the frame before, at most 1/30 s, then poses it and takes the display's time.
LiveCoatRun runCapped(const Scene& scene, const dynamics::SimulationParameters& parameters,
                      int substeps, const BenchLiveCoatOptions& o) {
  using Clock = std::chrono::steady_clock;
  dynamics::CoatMotion coat(scene, parameters);
  Scene drawn;
  drawn.organ<FeatherPart>().types = scene.organ<FeatherPart>().types;
  const auto frame = std::chrono::duration<double, std::milli>(o.frameMs);
  LiveCoatRun run;
  const auto start = Clock::now();
  auto last = start;
  while (std::chrono::duration<double>(Clock::now() - start).count() < o.seconds) {
    const auto now = Clock::now();
    const double step = std::min(std::chrono::duration<double>(now - last).count(),
                                 dynamics::CoatRunner::kMaxChunkSeconds);
    last = now;
    if (step > 0) {
      coat.advance(step, substeps);
      run.simulated += step;
    }
    coat.pose(drawn);
    std::this_thread::sleep_for(frame);
    ++run.frames;
  }
  run.wall = std::chrono::duration<double>(Clock::now() - start).count();
  run.retries = coat.simulation().counters().retries;
  return run;
}

// The viewer's stepping now: the coat on the runner's thread, the display taking the latest
// state each frame.
LiveCoatRun runThreaded(const Scene& scene, const dynamics::SimulationParameters& parameters,
                        int substeps, const BenchLiveCoatOptions& o) {
  using Clock = std::chrono::steady_clock;
  dynamics::CoatMotion coat(scene, parameters);
  Scene posing, drawn;
  posing.organ<FeatherPart>().types = scene.organ<FeatherPart>().types;
  drawn.organ<FeatherPart>().types = scene.organ<FeatherPart>().types;
  const auto frame = std::chrono::duration<double, std::milli>(o.frameMs);
  LiveCoatRun run;
  dynamics::CoatRunner runner(coat, std::move(posing), substeps);
  const auto start = Clock::now();
  std::uint64_t shown = 0;
  while (std::chrono::duration<double>(Clock::now() - start).count() < o.seconds) {
    if (auto state = runner.latest(); state && state->generation != shown) {
      shown = state->generation;
      drawn.organ<FeatherPart>().poses = state->poses;
    }
    std::this_thread::sleep_for(frame);
    ++run.frames;
  }
  runner.stop();
  const std::string failure = runner.failure();
  if (!failure.empty()) throw dynamics::StepFailure(failure);
  run.simulated = runner.simulatedSeconds();
  run.wall = runner.wallSeconds();
  run.retries = coat.simulation().counters().retries;
  return run;
}

int runBenchLiveCoat(BenchLiveCoatOptions o) {
  Progress progress = Progress::onTerminal(stderr);
  o.model.terminalProgress = &progress;
  // The simulation starts from the coat as it grew and settles it by its own collisions.
  leaveStageOut(o.model, dynamics::coatShinglingStage());
  Diagnostics diagnostics(&std::cerr);
  std::optional<BuiltScene> built = buildSceneOrSay(o.model, diagnostics, progress);
  if (!built) return kExitBadInput;
  const Scene& scene = built->scene;
  const std::size_t feathers = scene.organ<FeatherPart>().feathers.size();
  if (feathers == 0) {
    std::cerr << "hirsute: error: " << o.model.lsystemFile << " grows no feathers to simulate\n";
    return kExitBadInput;
  }
  const FeatherDynamicsSettings& view = built->resources.view.organ<FeatherSettings>().dynamics;
  try {
    const dynamics::SimulationParameters parameters = dynamics::simulationParametersOf(view);
    std::printf("%zu feathers, a display frame of %.0f ms, %.1f s each way, on %u cores\n",
                feathers, o.frameMs, o.seconds, std::thread::hardware_concurrency());
    printRun("capped frame steps (at most 1/30 s a frame)",
             runCapped(scene, parameters, view.substeps, o));
    printRun("threaded runner", runThreaded(scene, parameters, view.substeps, o));
  } catch (const std::exception& e) {
    std::cerr << "hirsute: error: the feathers' dynamics stopped: " << e.what() << '\n';
    return kExitBadInput;
  }
  return kExitOk;
}

// A finite number >= 0, said in words.
const CLI::Validator kNonNegative(
    [](std::string& text) -> std::string {
      double value = 0;
      std::size_t used = 0;
      try {
        value = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || !std::isfinite(value) || value < 0) {
        return "expected a number >= 0, found \"" + text + "\"";
      }
      return {};
    },
    "NUMBER >= 0");

}  // namespace

void registerBenchCommand(CLI::App& app, Action& action) {
  CLI::App* bench = app.add_subcommand("bench", "Measure Hirsute's algorithms and print figures");
  bench->require_subcommand(1);

  auto options = std::make_shared<BenchCcdOptions>();
  CLI::App* ccd = bench->add_subcommand(
      "ccd",
      "Run the continuous collision detection over CCD query files with ground truth (in folders "
      "named edge-edge or vertex-face) and print queries, false negatives, false positives and "
      "microseconds per query, per file and in total");
  ccd->add_option("files", options->files, "Query files (.csv)")->required();
  ccd->add_option("--eta", options->eta,
                  "Minimum separation: a contact is any time the primitives come within it in "
                  "every coordinate (default 0)")
      ->check(kNonNegative);
  ccd->add_option("--tolerance", options->tolerance,
                  "How near a near miss may come and still be reported, relative to the query's "
                  "size (default 1e-6)")
      ->check(kNonNegative);
  ccd->callback([options, &action] { action = [options] { return runBenchCcd(*options); }; });

  auto live = std::make_shared<BenchLiveCoatOptions>();
  CLI::App* liveCoat = bench->add_subcommand(
      "live-coat",
      "Run a model's feather coat as the viewer's dynamics (D) do, beside a stand-in display "
      "that takes --frame-ms a frame: stepped a frame at a time (at most 1/30 s a frame) and on "
      "a thread of its own; print simulated seconds, wall seconds and their ratio for each");
  addModelOptions(*liveCoat, live->model);
  liveCoat->add_option("--seconds", live->seconds, "Wall-clock seconds each way runs (default 5)")
      ->check(CLI::Range(0.1, 3600.0));
  liveCoat
      ->add_option("--frame-ms", live->frameMs,
                   "Milliseconds the stand-in display takes a frame (default 60)")
      ->check(CLI::Range(0.0, 10000.0));
  liveCoat->callback([live, &action] { action = [live] { return runBenchLiveCoat(*live); }; });
}

}  // namespace hirsute::cli
