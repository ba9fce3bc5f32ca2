#include "hirsute/hairs/feathers/feather_live.h"

#include <algorithm>
#include <exception>
#include <string>

#include <fmt/format.h>

#include "hirsute/interpreter/feather_part.h"
#include "hirsute/interpreter/feather_settings.h"

namespace hirsute {
namespace {

const LiveAction kActions[] = {
    {"dynamics", "o", 'D',
     "start / pause the feathers' dynamics (wind, gravity, collisions; docs/dynamics.md)"},
};

// The most simulated time one frame takes: a slow frame slows the motion down rather than
// taking a step the collisions would have to halve.
constexpr double kMaxFrameSeconds = 1.0 / 30;

}  // namespace

void LiveFeathers::take(const Scene& scene, const ViewSettings& view) {
  scene_ = &scene;
  view_ = &view;
  if (!coat_) return;
  bodyMoved_ = true;
  coatScene_.organ<FeatherPart>().types = scene.organ<FeatherPart>().types;
  coatScene_.materials = scene.materials;
  host_.redraw(coatScene_);
}

void LiveFeathers::filesChanged() {
  coat_.reset();
  simulating_ = false;
}

void LiveFeathers::act(std::size_t /*index*/, const LiveActionCall& call) {
  if (call.byKey || (call.words.front() == "on") != simulating_) toggleDynamics();
}

void LiveFeathers::toggleDynamics() {
  if (simulating_) {
    simulating_ = false;
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
    coatScene_.organ<FeatherPart>().types = scene_->organ<FeatherPart>().types;
    coatScene_.materials = scene_->materials;
    bodyMoved_ = false;
  }
  simulating_ = true;
  lastStep_ = host_.now();
}

void LiveFeathers::stop(const std::string& why) {
  simulating_ = false;
  coat_.reset();
  host_.fail(why);
  if (scene_ != nullptr) host_.redraw(*scene_);
}

bool LiveFeathers::step() {
  if (!simulating_ || !coat_ || scene_ == nullptr) return false;
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
  return fmt::format("dynamics {}: {:.1f} s simulated, {:.0f} frames/s, {} steps retried",
                     simulating_ ? "running" : "paused (D)", coat_->simulation().time(),
                     simulatedFps_, coat_->simulation().counters().retries);
}

const LiveOrganType& featherLive() {
  static const LiveOrganTypeOf<LiveFeathers> type("feathers", 'E', kActions);
  return type;
}

}  // namespace hirsute
