#include "hirsute/hairs/feathers/default_barbs.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace hirsute {
namespace {

// SplitMix64 (Steele, Lea & Flood 2014): a small generator whose sequence is the same on every
// platform, unlike the standard distributions.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [low, high).
  float uniform(float low, float high) {
    const double unit = static_cast<double>(next() >> 11) * 0x1.0p-53;
    return static_cast<float>(low + (high - low) * unit);
  }

 private:
  std::uint64_t state_;
};

}  // namespace

PlumulaceousBarbTable::PlumulaceousBarbTable(std::uint64_t seed) {
  SplitMix64 random(seed);
  vertices_.reserve(kEntries * kVertices);
  for (std::size_t entry = 0; entry < kEntries; ++entry) {
    // A loose, wavy barb: the inner vertices wander off the chord in the vane plane and out of
    // it; the end point lies roughly ahead, so the chord, once rotated into the vane plane, keeps
    // the vane's barb angle. Chords shorter than 1 make the fuzzy, ragged edge of down (the
    // non-linear scaling of Sec. 4.2.1).
    const glm::vec3 cv0(0);
    const glm::vec3 cv1(random.uniform(0.15f, 0.45f), random.uniform(-0.3f, 0.3f),
                        random.uniform(-0.3f, 0.3f));
    const glm::vec3 cv2(random.uniform(0.45f, 0.8f), random.uniform(-0.3f, 0.3f),
                        random.uniform(-0.3f, 0.3f));
    glm::vec3 cv3(1, random.uniform(-0.15f, 0.15f), random.uniform(-0.15f, 0.15f));
    cv3 *= random.uniform(0.7f, 1.0f) / glm::length(cv3);
    vertices_.insert(vertices_.end(), {cv0, cv1, cv2, cv3});
  }
}

PlumulaceousBarbTable::PlumulaceousBarbTable(
    const std::vector<std::pair<std::uint64_t, float>>& seeds)
    : vertices_(kEntries * kVertices, glm::vec3(0.0f)) {
  float total = 0;
  for (const auto& [seed, weight] : seeds) total += std::max(weight, 0.0f);
  if (!(total > 0)) {
    *this = PlumulaceousBarbTable(seeds.empty() ? 1 : seeds.front().first);
    return;
  }
  for (const auto& [seed, weight] : seeds) {
    if (!(weight > 0)) continue;
    const PlumulaceousBarbTable one(seed);
    for (std::size_t k = 0; k < vertices_.size(); ++k) vertices_[k] += (weight / total) * one.vertices_[k];
  }
}

std::span<const glm::vec3> PlumulaceousBarbTable::barb(std::size_t index, BarbSide side) const {
  // Neighbouring barbs and the two vanes read different entries; the table repeats only every
  // kEntries / 2 barbs, further than a vane's random shapes let the eye follow.
  const std::size_t entry = (2 * index + (side == BarbSide::Right ? 1 : 0)) % kEntries;
  return std::span<const glm::vec3>(vertices_).subspan(entry * kVertices, kVertices);
}

std::span<const glm::vec3> pennaceousDefaultBarb() {
  static const std::array<glm::vec3, 4> kBarb = {glm::vec3(0, 0, 0), glm::vec3(1.0f / 3, 0, -0.05f),
                                                 glm::vec3(2.0f / 3, 0, -0.05f),
                                                 glm::vec3(1, 0, 0)};
  return kBarb;
}

}  // namespace hirsute
