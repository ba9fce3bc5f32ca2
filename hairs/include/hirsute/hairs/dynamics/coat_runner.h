// A CoatMotion stepped on a thread of its own against the steady clock (docs/dynamics.md, "In the
// viewer"; issue 26, item 3): the simulated time keeps pace with the wall clock however long the
// display takes to draw a frame, and the display takes the latest complete state without waiting
// for a step. The single-threaded path (CoatMotion::advance a frame at a time) stays what tests
// drive on a clock moved by hand; this runs it in real time.
//
// Pacing: the runner simulates what the wall clock has run ahead of the simulation, in chunks of
// at most kMaxChunkSeconds (each split into steps as `substeps` asks), publishing a state after
// each chunk. It never runs ahead of the wall clock; a machine that cannot keep up drops what
// lags more than kMaxLagSeconds rather than spending ever longer catching up, and says so in the
// ratio of simulated to wall time.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hirsute/hairs/dynamics/coat_motion.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::dynamics {

// One complete state of the coat as the runner publishes it; never changed once published.
struct CoatSnapshot {
  std::uint64_t generation = 0;    // one more for each state published
  std::vector<FeatherPose> poses;  // one per feather, as CoatMotion::pose gives them
  double time = 0;                 // the simulation's time (FeatherCoatSimulation::time)
  std::uint64_t retries = 0;       // steps retried so far (SimulationCounters::retries)
  // Simulated seconds per wall-clock second over the last half second or so (since the start
  // before that): 1 when the runner keeps up.
  double ratio = 0;
};

class CoatRunner {
 public:
  using Clock = std::chrono::steady_clock;

  // The most simulated time one chunk takes before a state is published.
  static constexpr double kMaxChunkSeconds = 1.0 / 30;
  // The least: a runner ahead of the clock waits for this much wall time to pass (no display
  // shows more states a second).
  static constexpr double kMinChunkSeconds = 1.0 / 120;
  // How far the simulation may lag behind the wall clock before the rest is dropped.
  static constexpr double kMaxLagSeconds = 2 * kMaxChunkSeconds;
  // The wall time over which the ratio is measured.
  static constexpr double kRatioWindowSeconds = 0.5;

  // Starts stepping `coat` at once, in steps no longer than a kMaxChunkSeconds frame split in
  // `substeps` (the view file's `dynamics substeps:`). `posing` gives the feather types the poses
  // are built with (a Scene of the coat's types, as CoatMotion::pose takes it). When `target` is
  // given, the first chunk, a full kMaxChunkSeconds long, moves the body and the roots to it (a
  // new frame of the animation). The states' generations follow `after` (a
  // runner started again after a pause carries on the count). Until stop() or destruction nothing
  // else may touch `coat`.
  CoatRunner(CoatMotion& coat, Scene posing, int substeps,
             std::optional<CoatTarget> target = std::nullopt, std::uint64_t after = 0);
  ~CoatRunner();
  CoatRunner(const CoatRunner&) = delete;
  CoatRunner& operator=(const CoatRunner&) = delete;

  // Stops stepping and joins the thread (the chunk under way finishes first). Idempotent.
  void stop();
  // The latest state published; null before the first chunk has finished.
  std::shared_ptr<const CoatSnapshot> latest() const;
  // Why the runner stopped on its own (a step that could not be resolved); empty while it runs.
  std::string failure() const;
  // Simulated and wall-clock seconds since the start (the wall time while it ran).
  double simulatedSeconds() const;
  double wallSeconds() const;

 private:
  void run();

  CoatMotion& coat_;
  Scene posing_;
  int substeps_;
  std::optional<CoatTarget> target_;

  mutable std::mutex mutex_;  // guards what follows
  std::condition_variable wake_;
  std::shared_ptr<const CoatSnapshot> latest_;
  std::string failure_;
  double simulated_ = 0, wall_ = 0;
  std::uint64_t generation_ = 0;
  bool stopping_ = false;

  std::thread thread_;  // last: started once everything above is made
};

}  // namespace hirsute::dynamics
