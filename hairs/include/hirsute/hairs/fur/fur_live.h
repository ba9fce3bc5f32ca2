// The fur in the interactive viewer (live_organ.h; docs/fur.md, "In the viewer"): a copy of the
// model's fur surfaces whose strands move under the view file's force and the gusts, which dries
// and takes droplets (sprayed with J or the script's `droplets N`, dropped with ctrl + click).
#pragma once

#include <cstdint>

#include "hirsute/hairs/fur/fur_motion.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/interaction/live_organ.h"

namespace hirsute {

class LiveFur final : public LiveOrgan {
 public:
  explicit LiveFur(LiveOrganHost& host);

  void take(const Scene& scene, const ViewSettings& view) override;
  bool step() override;
  bool moving() const override { return moving_; }
  void act(std::size_t index, const LiveActionCall& call) override;
  bool pointAt(glm::vec2 point, glm::ivec2 viewport) override;
  std::string status() const override;

  // The fur as it moves (its part of a Scene of its own).
  const Scene& fur() const { return fur_; }
  bool drying() const { return drying_; }
  void toggleDrying();
  // `count` droplets at random; returns how many landed.
  std::size_t spray(std::size_t count);
  // A gust across the line of sight of `viewport`'s camera, from alternating sides.
  void gust(glm::ivec2 viewport);

 private:
  LiveOrganHost& host_;
  const ViewSettings* view_ = nullptr;
  Scene fur_;
  fur::FurMotion motion_;
  bool drying_ = false, moving_ = false;
  glm::vec3 gust_{0.0f};
  float gustLeft_ = 0;  // seconds
  std::uint32_t spraySeed_ = 1;
  LiveOrganHost::Clock::time_point lastStep_;
};

// The fur's type in the viewer: name "fur", key U; J sprays, Y dries, G blows.
const LiveOrganType& furLive();

}  // namespace hirsute
