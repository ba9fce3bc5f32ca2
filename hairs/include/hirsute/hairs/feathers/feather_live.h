// The feathers in the interactive viewer (live_organ.h; docs/dynamics.md, "In the viewer"): the
// model's coat simulated while the dynamics run (D, or the script's `dynamics on|off`), the roots
// carried by the body as the animation moves it, the bent feathers drawn over the model's.
//
// On the wall clock (LiveOrganHost::realTime) the coat steps on a thread of its own
// (dynamics::CoatRunner) and step() draws its latest state: the simulated time keeps pace with
// the wall clock whatever a frame costs to draw (issue 26, item 3). On a clock moved by hand,
// step() advances the coat by the time since the turn before, at most kMaxFrameSeconds.
// Pausing, a new build (the animation's next frame) and edited files stop and join the thread
// before they touch the coat or let the build it came from go.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "hirsute/hairs/dynamics/coat_motion.h"
#include "hirsute/hairs/dynamics/coat_runner.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/interaction/live_organ.h"

namespace hirsute {

class LiveFeathers final : public LiveOrgan {
 public:
  explicit LiveFeathers(LiveOrganHost& host) : host_(host) {}

  void take(const Scene& scene, const ViewSettings& view) override;
  bool step() override;
  void filesChanged() override;
  bool moving() const override { return simulating_; }
  void act(std::size_t index, const LiveActionCall& call) override;
  std::string status() const override;

  // Starts the dynamics (a simulation of the model shown, made on first use) or pauses them.
  void toggleDynamics();
  bool simulating() const { return simulating_; }
  // The simulation, while no thread steps it (on a clock moved by hand, or paused).
  const dynamics::CoatMotion* coat() const { return coat_ && !runner_ ? &*coat_ : nullptr; }
  // Simulated frames per second of wall-clock time, at the last step.
  double simulatedFps() const { return simulatedFps_; }
  // Running on its own thread: simulated seconds per wall-clock second (the runner's, as last
  // drawn; 0 before the first state), and the generation of the state drawn last.
  bool threaded() const { return runner_ != nullptr; }
  double realTimeRatio() const { return ratio_; }
  std::uint64_t shownGeneration() const { return shownGeneration_; }

 private:
  void stop(const std::string& why);
  // Starts the thread that steps the coat (realTime()), the body moving first when a build
  // moved it; joins it.
  void startRunner();
  void stopRunner();
  bool stepThreaded();

  LiveOrganHost& host_;
  const Scene* scene_ = nullptr;
  const ViewSettings* view_ = nullptr;
  // The simulation, the feathers it bends, whether it runs, whether a new build moved the body,
  // and the rate it keeps.
  std::optional<dynamics::CoatMotion> coat_;
  Scene coatScene_;
  bool simulating_ = false, bodyMoved_ = false;
  LiveOrganHost::Clock::time_point lastStep_;
  double simulatedFps_ = 0;
  // On the wall clock: the thread that steps coat_ (declared after it, so joined before the coat
  // goes), the state drawn last, its time and retries, and the ratio it keeps.
  std::unique_ptr<dynamics::CoatRunner> runner_;
  std::uint64_t shownGeneration_ = 0;
  double shownTime_ = 0, ratio_ = 0;
  std::uint64_t shownRetries_ = 0;
};

// The feathers' type in the viewer: name "feathers", key E; D runs and pauses the dynamics.
const LiveOrganType& featherLive();

}  // namespace hirsute
