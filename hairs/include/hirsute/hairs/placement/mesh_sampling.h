// Points over a mesh surface's area (docs/design.md, "Meshes"): a mesh from another tool
// has a texture atlas whose islands are cut, stretched and scaled at will, so a tile laid over
// its (u, v) would seam at the cuts and crowd where the atlas shrinks. Its points are chosen on
// the surface itself instead, by weighted sample elimination (Yuksel 2015): uniform candidates,
// five for each point wanted, from which the point with the most crowded neighbourhood in world
// distance is removed until the count is reached. The count is exact and the pattern even: the
// relative radius ρ is about 0.7 (tests/hairs/mesh_sampling_test.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "hirsute/hairs/placement/patch_unfolding.h"

namespace hirsute {

// At most this many points on one side of one mesh: each costs about 650 bytes while they are
// chosen (five candidates with their neighbours), so ten million take some 6.5 GB.
inline constexpr std::size_t kMaxMeshPoints = 10'000'000;

// Thrown for more points than kMaxMeshPoints; the organ reports it at the model.
struct SamplingLimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A point on triangle `triangle` of the unfolding: corner 0 + b1·(corner 1 − corner 0) +
// b2·(corner 2 − corner 0).
struct SurfaceSample {
  std::uint32_t triangle = 0;
  float b1 = 0, b2 = 0;
};

// `count` points over the surface's triangles, the same for the same key.
std::vector<SurfaceSample> sampleSurfaceArea(const PatchUnfolding& unfolding, std::size_t count,
                                             std::uint64_t key);

}  // namespace hirsute
