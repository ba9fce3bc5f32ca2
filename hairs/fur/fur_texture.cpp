#include "hirsute/hairs/fur/fur_texture.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace hirsute::fur {
namespace {

// A uniform integer in [0, n) from the generator's raw output (std::uniform_int_distribution is
// not the same on every standard library).
std::uint32_t below(std::mt19937& random, std::uint32_t n) {
  const std::uint64_t wide = static_cast<std::uint64_t>(random()) * n;
  return static_cast<std::uint32_t>(wide >> 32);
}

}  // namespace

FurTexture makeFurTexture(int size, std::uint32_t seed, float density) {
  FurTexture texture;
  texture.size = size;
  texture.density = density;
  const auto texels = static_cast<std::uint32_t>(size) * static_cast<std::uint32_t>(size);
  texture.lengths.assign(texels, 0);
  const auto strands = static_cast<std::uint32_t>(
      std::lround(std::clamp(density, 0.0f, 1.0f) * static_cast<float>(texels)));
  std::mt19937 random(seed);
  // The first `strands` of a partial Fisher-Yates shuffle.
  std::vector<std::uint32_t> order(texels);
  std::iota(order.begin(), order.end(), 0u);
  for (std::uint32_t i = 0; i < strands; ++i) {
    std::swap(order[i], order[i + below(random, texels - i)]);
    const float fraction = kShortestStrand + (1 - kShortestStrand) * (random() / 4294967296.0f);
    texture.lengths[order[i]] = static_cast<std::uint8_t>(std::max(1L, std::lround(255 * fraction)));
  }
  return texture;
}

std::size_t strandCount(const FurTexture& texture) {
  return static_cast<std::size_t>(std::count_if(texture.lengths.begin(), texture.lengths.end(),
                                                [](std::uint8_t l) { return l != 0; }));
}

}  // namespace hirsute::fur
