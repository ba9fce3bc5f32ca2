// Counter-based randomness for placement (docs/design.md, "Placement"): every number an instance
// draws is a hash of the seed and where the instance is, so placement is reproducible and
// independent of the order segments are visited in.
#pragma once

#include <cstdint>

namespace hirsute {

// SplitMix64's finaliser.
inline std::uint64_t mixBits(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// A key from two: the seed and a place, or a key and a finer place.
inline std::uint64_t placementKey(std::uint64_t a, std::uint64_t b) {
  return mixBits(a ^ mixBits(b));
}

// The numbers one attachment point draws, from its key.
class PlacementRandom {
 public:
  explicit PlacementRandom(std::uint64_t key) : state_(mixBits(key)) {}
  // Uniform in [0, 1).
  float uniform() {
    state_ = mixBits(state_);
    return static_cast<float>(state_ >> 40) * (1.0f / 16777216.0f);
  }
  // Uniform in [-1, 1).
  float symmetric() { return 2.0f * uniform() - 1.0f; }

 private:
  std::uint64_t state_;
};

}  // namespace hirsute
