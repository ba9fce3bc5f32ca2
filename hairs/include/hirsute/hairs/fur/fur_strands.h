// Fur as explicit strands (docs/design.md, "Fur": POV-Ray and OBJ draw no shells): one strand per
// strand texel of the fur texture where the tiled texture covers a fur surface, bent by the
// strands' particles, curled by Eq. 4 and gathered into the wetness mask's clumps by Eq. 5,
// evaluated exactly where the shells evaluate them.
#pragma once

#include <cstddef>
#include <functional>
#include <span>

#include <glm/glm.hpp>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::fur {

// One strand: its points from the root up (h evenly from 0 to `reach`, the strand's own length
// as a fraction of the fur length), the surface's normal and (u, v) at the root (where its
// colour comes from) and its radius (half a texel of the fur texture, in world units).
struct FurStrandView {
  std::span<const glm::vec3> points;
  glm::vec3 normal{0, 0, 1};
  glm::vec2 uv{0.0f};
  float reach = 1;
  float radius = 0;
};

// Calls `emit` for every strand of `surface`, each with `samples` points (at least 2), evenly
// spaced in h from the root to the strand's own length.
void forEachStrand(const Scene& scene, const FurSurface& surface, int samples,
                   const std::function<void(const FurStrandView&)>& emit);

// The strands forEachStrand makes, without making them.
std::size_t countStrands(const Scene& scene, const FurSurface& surface);

// How many points an exported strand takes (POV-Ray, OBJ, the tracer): enough to follow its
// curl, kSamplesPerTurn a turn of @Uc's ω, at least kMinStrandSamples and at most
// kMaxStrandSamples (the fur stage warns when a curl turns more often than that can follow).
inline constexpr int kMinStrandSamples = 7;
inline constexpr int kSamplesPerTurn = 12;
inline constexpr int kMaxStrandSamples = 193;  // 16 turns
int strandSamples(const FurAttributes& attributes);
// Whether strandSamples had to cap the points of a strand of `attributes`.
bool strandSamplesCapped(const FurAttributes& attributes);

// Counts the points of the exported strands against FurPart::maxVertices, surface by surface,
// before they are made: throws GeometryLimitError naming the surface reached.
class StrandBudget {
 public:
  explicit StrandBudget(const FurPart& part) : limit_(part.maxVertices) {}
  // The points a strand of `surface` gets (strandSamples), once its strands are counted.
  int charge(const Scene& scene, const FurSurface& surface, std::size_t index);

 private:
  std::size_t limit_, used_ = 0;
};

// The colour texture `@Ut` names for strands of `attributes` (docs/fur.md), or null when they
// take the surface's colour or the texture has no pixels.
const Texture* colourTexture(const Scene& scene, const FurAttributes& attributes);

}  // namespace hirsute::fur
