// Fur that moves (Silva et al. 2010, Sec. 3.2.1; docs/design.md, "Fur in motion"): the strands'
// particles stepped in time under the view file's force, a gust of wind and the motion of the
// surface they grow on, and the wetness drying off; and the point of a fur surface under a ray,
// where a click drops a droplet. `hirsute view` runs it every frame; it changes only the Scene's
// fur surfaces (their particles and masks), which the renderer then uploads again.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::fur {

class FurMotion {
 public:
  // Damping of the particles per second, and the longest sub-step taken.
  static constexpr float kDamping = 3.0f;
  static constexpr float kMaxStep = 1.0f / 240;

  // Starts from the scene's particles at rest. When `previous` (the fur of the frame before, as
  // stepped) has surfaces of the same vertex counts, each particle keeps its offset from its
  // root and its velocity there, so that a moving plant drags its fur, and each mask its wetness.
  void reset(Scene& fur, const Scene* previous = nullptr);

  // Advances `seconds` under `force` per unit mass (the view file's plus any gust). Returns
  // whether a particle still moves.
  bool step(Scene& fur, float seconds, const glm::vec3& force);

  // The same with a force that varies over the fur (wind and gusts): `forceAt` gives the force
  // per unit mass on the strand rooted at a point, evaluated once per call for each strand.
  // `seconds` is taken whole, in sub-steps of at most kMaxStep.
  bool step(Scene& fur, float seconds, const std::function<glm::vec3(const glm::vec3&)>& forceAt);

  // Whether any particle moves faster than `speed` fur lengths per second.
  bool moving(const Scene& fur, float speed = 1e-3f) const;

  // Each particle's velocity, per surface, per vertex (empty before the first reset or step).
  const std::vector<std::vector<glm::vec3>>& velocities() const { return velocities_; }

 private:
  std::vector<std::vector<glm::vec3>> velocities_;  // per surface, per vertex
};

// How far the fur is from rest and how wet it is, over all its strands and masks.
struct FurMeasures {
  std::size_t strands = 0;  // particles: one per surface vertex
  // Each tip's distance from its rest tip (root + length · normal), in fur lengths.
  double meanBend = 0, largestBend = 0;
  double largestSpeed = 0;  // fur lengths per second (0 before any step)
  std::size_t texels = 0, wetTexels = 0;  // of the masks that exist
  double meanWetness = 0;                 // over the wet texels
};
FurMeasures measureFur(const Scene& fur, const FurMotion* motion = nullptr);

// The wetness falls by `rate` per second: a fur drying over 1 / rate seconds. Returns whether any
// texel is still wet.
bool dryFur(Scene& fur, float rate, float seconds);

// Where the ray from `origin` along `direction` first meets a fur surface's base: the surface's
// index and the (u, v) there.
struct FurHit {
  std::size_t surface = 0;
  glm::vec2 uv{0.0f};
  float distance = 0;
};
std::optional<FurHit> pickFur(const Scene& fur, const glm::vec3& origin, const glm::vec3& direction);

}  // namespace hirsute::fur
