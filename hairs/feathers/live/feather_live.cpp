#include "hirsute/hairs/feathers/feather_live.h"

#include <algorithm>
#include <exception>
#include <string>

#include <fmt/format.h>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_settings.h"

namespace hirsute {
namespace {

const LiveAction kActions[] = {
    {"dynamics", "o", 'D',
     "start / pause the feathers' dynamics (wind, gravity, collisions; docs/dynamics.md)"},
};

// On a clock moved by hand, the most simulated time one frame takes: a slow frame slows the
// motion down rather than taking a step the collisions would have to halve. (On the wall clock
// the runner's chunks are as long at most, dynamics::CoatRunner::kMaxChunkSeconds, and it
// catches up with more of them.)
constexpr double kMaxFrameSeconds = dynamics::CoatRunner::kMaxChunkSeconds;

}  // namespace

void LiveFeathers::take(const Scene& scene, const ViewSettings& view) {
  // The thread stops before the coat's next frame is read from the new build; it never reads
  // a build itself, so the one replaced may already be gone.
  const bool running = runner_ != nullptr;
  stopRunner();
  scene_ = &scene;
  view_ = &view;
  if (!coat_) return;
  bodyMoved_ = true;
  coatScene_.organ<FeatherPart>().types = scene.organ<FeatherPart>().types;
  coatScene_.materials = scene.materials;
  host_.redraw(coatScene_);
  if (running) startRunner();
}

void LiveFeathers::filesChanged() {
  stopRunner();
  coat_.reset();
  simulating_ = false;
}

void LiveFeathers::act(std::size_t /*index*/, const LiveActionCall& call) {
  if (call.byKey || (call.words.front() == "on") != simulating_) toggleDynamics();
}

void LiveFeathers::toggleDynamics() {
  if (simulating_) {
    simulating_ = false;
    stopRunner();
    return;
  }
  if (scene_ == nullptr || scene_->organ<FeatherPart>().feathers.empty()) return;
  if (!coat_) {
    try {
      coat_.emplace(*scene_, dynamics::simulationParametersOf(view_->organ<FeatherSettings>().dynamics));
    } catch (const std::exception& e) {
      stop(std::string("cannot simulate the feathers: ") + e.what());
      return;
    }
    if (coat_->penetrations() > 0) {
      stop("the feathers' stems already meet before the first step (docs/dynamics.md)");
      return;
    }
    coatScene_ = Scene{};
    FeatherPart& part = coatScene_.organ<FeatherPart>();
    part.types = scene_->organ<FeatherPart>().types;
    // The coat's feathers are the first build's (CoatMotion::pose), bent as the states come.
    part.feathers = scene_->organ<FeatherPart>().feathers;
    part.bounds = scene_->organ<FeatherPart>().bounds;
    coatScene_.materials = scene_->materials;
    bodyMoved_ = false;
    ratio_ = 0;
  }
  simulating_ = true;
  lastStep_ = host_.now();
  if (host_.realTime()) startRunner();
}

void LiveFeathers::startRunner() {
  std::optional<dynamics::CoatTarget> target;
  if (bodyMoved_) {
    try {
      target = coat_->targetOf(*scene_);
    } catch (const std::exception& e) {
      stop(std::string("the feathers' dynamics stopped: ") + e.what());
      return;
    }
    bodyMoved_ = false;
  }
  // The runner poses the feathers in a Scene of its own, of the coat's types.
  Scene posing;
  posing.organ<FeatherPart>().types = coatScene_.organ<FeatherPart>().types;
  runner_ = std::make_unique<dynamics::CoatRunner>(
      *coat_, std::move(posing), view_->organ<FeatherSettings>().dynamics.substeps,
      std::move(target), shownGeneration_);
}

void LiveFeathers::stopRunner() {
  if (!runner_) return;
  runner_->stop();
  // The state the coat was left in is the last one published: drawn, so that the picture and
  // the coat agree while it pauses.
  stepThreaded();
  runner_.reset();
}

void LiveFeathers::stop(const std::string& why) {
  simulating_ = false;
  if (runner_) {
    runner_->stop();
    runner_.reset();
  }
  coat_.reset();
  host_.fail(why);
  if (scene_ != nullptr) host_.redraw(*scene_);
}

bool LiveFeathers::stepThreaded() {
  const std::string failure = runner_->failure();
  if (!failure.empty()) {
    stop("the feathers' dynamics stopped: " + failure);
    return true;
  }
  // The latest complete state, taken without waiting for the step under way.
  const std::shared_ptr<const dynamics::CoatSnapshot> state = runner_->latest();
  if (!state || state->generation == shownGeneration_) return false;
  shownGeneration_ = state->generation;
  shownTime_ = state->time;
  shownRetries_ = state->retries;
  ratio_ = state->ratio;
  coatScene_.organ<FeatherPart>().poses = state->poses;
  host_.redraw(coatScene_);
  return true;
}

bool LiveFeathers::step() {
  if (!simulating_ || !coat_ || scene_ == nullptr) return false;
  if (runner_) return stepThreaded();
  // A clock moved by hand: one frame's step here.
  const auto now = host_.now();
  const double seconds =
      std::min(std::chrono::duration<double>(now - lastStep_).count(), kMaxFrameSeconds);
  lastStep_ = now;
  if (!(seconds > 0)) return false;
  try {
    coat_->advance(seconds, view_->organ<FeatherSettings>().dynamics.substeps, bodyMoved_ ? scene_ : nullptr);
  } catch (const std::exception& e) {
    stop(std::string("the feathers' dynamics stopped: ") + e.what());
    return true;
  }
  bodyMoved_ = false;
  coat_->pose(coatScene_);
  host_.redraw(coatScene_);
  const double took = std::chrono::duration<double>(host_.now() - now).count();
  simulatedFps_ = took > 0 ? 1 / took : 0;
  return true;
}

std::string LiveFeathers::status() const {
  if (!coat_) return {};
  const char* state = simulating_ ? "running" : "paused (D)";
  if (host_.realTime()) {
    // While the thread runs the coat is its: the figures of the state drawn last.
    const double time = runner_ ? shownTime_ : coat_->simulation().time();
    const std::uint64_t retries = runner_ ? shownRetries_ : coat_->simulation().counters().retries;
    return fmt::format("dynamics {}: {:.1f} s simulated, {:.2f}x real time, {} steps retried",
                       state, time, ratio_, retries);
  }
  return fmt::format("dynamics {}: {:.1f} s simulated, {:.0f} frames/s, {} steps retried", state,
                     coat_->simulation().time(), simulatedFps_,
                     coat_->simulation().counters().retries);
}

const LiveOrganType& featherLive() {
  static const LiveOrganTypeOf<LiveFeathers> type("feathers", 'E', kActions);
  return type;
}

}  // namespace hirsute
