// A CoatMotion stepped on its own thread in real time (coat_runner.h).
#include "hirsute/hairs/dynamics/coat_runner.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

namespace hirsute::dynamics {
namespace {

using Seconds = std::chrono::duration<double>;

CoatRunner::Clock::duration clockDuration(double seconds) {
  return std::chrono::duration_cast<CoatRunner::Clock::duration>(Seconds(seconds));
}

}  // namespace

CoatRunner::CoatRunner(CoatMotion& coat, Scene posing, int substeps,
                       std::optional<CoatTarget> target, std::uint64_t after)
    : coat_(coat),
      posing_(std::move(posing)),
      substeps_(std::max(substeps, 1)),
      target_(std::move(target)),
      generation_(after),
      thread_([this] { run(); }) {}

CoatRunner::~CoatRunner() {
  stop();
}

void CoatRunner::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

std::shared_ptr<const CoatSnapshot> CoatRunner::latest() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

std::string CoatRunner::failure() const {
  std::lock_guard lock(mutex_);
  return failure_;
}

double CoatRunner::simulatedSeconds() const {
  std::lock_guard lock(mutex_);
  return simulated_;
}

double CoatRunner::wallSeconds() const {
  std::lock_guard lock(mutex_);
  return wall_;
}

void CoatRunner::run() {
  const Clock::time_point start = Clock::now();
  // The wall time at which the simulation's run time 0 was due: it moves on when a lag is
  // dropped, so that the runner never spends its time on a backlog it cannot clear.
  Clock::time_point origin = start;
  double simulated = 0;
  // The ratio over the last window of kRatioWindowSeconds, since the start before the first.
  Clock::time_point windowStart = start;
  double windowSimulated = 0, windowRatio = 0;
  bool windowDone = false;
  for (;;) {
    const Clock::time_point now = Clock::now();
    double due = Seconds(now - origin).count() - simulated;
    if (due > kMaxLagSeconds) {
      origin += clockDuration(due - kMaxLagSeconds);
      due = kMaxLagSeconds;
    }
    {
      std::unique_lock lock(mutex_);
      wall_ = Seconds(now - start).count();
      if (stopping_) return;
      // A body that moves does so over a full chunk, as a frame of the animation would.
      const double least = target_ ? kMaxChunkSeconds : kMinChunkSeconds;
      if (due < least) {
        // Ahead of the clock: wait for a chunk's worth of wall time, or for stop().
        wake_.wait_until(lock, now + clockDuration(least - due), [this] { return stopping_; });
        if (stopping_) return;
        continue;
      }
    }
    const double seconds = std::min(due, kMaxChunkSeconds);
    // The steps are as long as a frame of kMaxChunkSeconds in `substeps` would take: a short
    // chunk takes fewer, not shorter, steps.
    const int steps =
        std::max(1, static_cast<int>(std::ceil(substeps_ * seconds / kMaxChunkSeconds - 1e-9)));
    try {
      if (target_) {
        coat_.advance(seconds, steps, *target_);
        target_.reset();
      } else {
        coat_.advance(seconds, steps);
      }
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      failure_ = e.what();
      return;
    }
    simulated += seconds;

    const Clock::time_point after = Clock::now();
    const double windowWall = Seconds(after - windowStart).count();
    if (windowWall >= kRatioWindowSeconds) {
      windowRatio = (simulated - windowSimulated) / windowWall;
      windowStart = after;
      windowSimulated = simulated;
      windowDone = true;
    }
    const double sinceStart = Seconds(after - start).count();
    const double ratio = windowDone ? windowRatio : sinceStart > 0 ? simulated / sinceStart : 0;

    // The state is made whole before it is published: the display never sees half of it.
    coat_.pose(posing_);
    auto snapshot = std::make_shared<CoatSnapshot>();
    snapshot->poses = std::move(posing_.organ<FeatherPart>().poses);
    snapshot->time = coat_.simulation().time();
    snapshot->retries = coat_.simulation().counters().retries;
    snapshot->ratio = ratio;
    std::lock_guard lock(mutex_);
    snapshot->generation = ++generation_;
    latest_ = std::move(snapshot);
    simulated_ = simulated;
    wall_ = sinceStart;
  }
}

}  // namespace hirsute::dynamics
