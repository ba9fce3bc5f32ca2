// The feathers in the interactive viewer (live_organ.h; docs/dynamics.md, "In the viewer"): the
// model's coat simulated while the dynamics run (D, or the script's `dynamics on|off`), the roots
// carried by the body as the animation moves it, the bent feathers drawn over the model's.
#pragma once

#include <optional>

#include "hirsute/hairs/dynamics/coat_motion.h"
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
  const dynamics::CoatMotion* coat() const { return coat_ ? &*coat_ : nullptr; }
  // Simulated frames per second of wall-clock time, at the last step.
  double simulatedFps() const { return simulatedFps_; }

 private:
  void stop(const std::string& why);

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
};

// The feathers' type in the viewer: name "feathers", key E; D runs and pauses the dynamics.
const LiveOrganType& featherLive();

}  // namespace hirsute
