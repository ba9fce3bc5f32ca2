// The fur geometry texture (Silva et al. 2010, Sec. 4, after Papaioannou 2002): strands seeded
// at random texels of a size² tile, each with a length of its own, so that the layers thin out
// towards the tips. The tile repeats over a fur surface (FurSurface::texcoords).
#pragma once

#include <cstdint>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::fur {

// The shortest strand, as a fraction of the fur length (the longest is 1).
inline constexpr float kShortestStrand = 0.7f;

// round(density · size²) distinct texels, chosen by `seed` alone (the same on every machine),
// each with a length uniform in [kShortestStrand, 1].
FurTexture makeFurTexture(int size, std::uint32_t seed, float density);

// Strands of the texture (texels with a length).
std::size_t strandCount(const FurTexture& texture);

}  // namespace hirsute::fur
