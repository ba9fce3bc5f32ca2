#include "hirsute/viewer/trace/sampling.h"

#include <algorithm>
#include <cmath>

namespace hirsute::trace {

Random::Random(std::uint64_t seed, std::uint64_t stream) : increment_((stream << 1u) | 1u) {
  next();
  state_ += seed;
  next();
}

std::uint32_t Random::next() {
  const std::uint64_t old = state_;
  state_ = old * 6364136223846793005ULL + increment_;
  const auto shifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
  const auto rotation = static_cast<std::uint32_t>(old >> 59u);
  return (shifted >> rotation) | (shifted << ((32u - rotation) & 31u));
}

namespace {

// splitmix64's finaliser: a 64-bit key to well-mixed bits.
std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 30u;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27u;
  x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31u);
}

std::uint32_t reverseBits(std::uint32_t x) {
  x = ((x >> 1u) & 0x55555555u) | ((x & 0x55555555u) << 1u);
  x = ((x >> 2u) & 0x33333333u) | ((x & 0x33333333u) << 2u);
  x = ((x >> 4u) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4u);
  x = ((x >> 8u) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8u);
  return (x >> 16u) | (x << 16u);
}

// A random permutation of 32-bit words in which bit j of the result depends on bits 0..j of the
// argument alone (Laine and Karras 2011): adding the seed and xoring with products by even
// numbers only ever carry upwards.
std::uint32_t carryUpwards(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Owen's nested uniform scramble of a binary fraction (bit 31 its first digit): each digit is
// flipped by a hash of the digits before it, read as a permutation on the reversed bits. Applied
// to a sample's index it shuffles the order within every aligned block of 2^k indices, and keeps
// any 2^k first shuffled indices one such block.
std::uint32_t nestedScramble(std::uint32_t x, std::uint32_t seed) {
  return reverseBits(carryUpwards(reverseBits(x), seed));
}

// The Sobol sequence's second dimension: the index's bits through the Pascal matrix mod 2, each
// column the one before it xored with itself moved a digit down; a byte of the index at a time.
struct SobolSecond {
  std::uint32_t bytes[4][256];

  SobolSecond() {
    std::uint32_t columns[32];
    columns[0] = 0x80000000u;
    for (int j = 1; j < 32; ++j) columns[j] = columns[j - 1] ^ (columns[j - 1] >> 1u);
    for (int b = 0; b < 4; ++b) {
      for (std::uint32_t value = 0; value < 256; ++value) {
        std::uint32_t out = 0;
        for (int j = 0; j < 8; ++j) {
          if ((value >> j & 1u) != 0) out ^= columns[8 * b + j];
        }
        bytes[b][value] = out;
      }
    }
  }

  std::uint32_t operator()(std::uint32_t index) const {
    return bytes[0][index & 0xffu] ^ bytes[1][index >> 8u & 0xffu] ^
           bytes[2][index >> 16u & 0xffu] ^ bytes[3][index >> 24u];
  }
};

const SobolSecond sobolSecond;

}  // namespace

Random Random::stratified(std::uint64_t seed, std::uint64_t pixel, std::uint32_t index) {
  Random random(seed, pixel ^ (static_cast<std::uint64_t>(index) << 40u));
  random.pixelKey_ = mix(mix(seed) ^ pixel);
  random.index_ = index;
  random.call_ = 0;
  return random;
}

glm::uvec2 Random::stratifiedPoint() {
  const std::uint64_t key = mix(pixelKey_ + static_cast<std::uint64_t>(call_++) * 0x9e3779b97f4a7c15ULL);
  const std::uint32_t shuffled = nestedScramble(index_, static_cast<std::uint32_t>(key));
  // The first dimension is the index's bits reversed (van der Corput in base 2).
  return {nestedScramble(reverseBits(shuffled), static_cast<std::uint32_t>(key >> 32u)),
          nestedScramble(sobolSecond(shuffled), static_cast<std::uint32_t>(mix(key) >> 32u))};
}

Frame Frame::around(const glm::vec3& n) {
  // Duff et al. 2017: a branchless orthonormal basis.
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  return Frame{{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x},
               {b, sign + n.y * n.y * a, -n.y},
               n};
}

glm::vec3 sampleUniformSphere(glm::vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::vec3 sampleUniformHemisphere(glm::vec2 u) {
  const float z = u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::vec3 sampleCosineHemisphere(glm::vec2 u) {
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
}

glm::vec2 sampleUniformDisk(glm::vec2 u) {
  const float r = std::sqrt(u.x);
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi)};
}

glm::vec3 sampleUniformCone(glm::vec2 u, float cosMax) {
  const float z = 1.0f - u.x * (1.0f - cosMax);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

float sampleCosSquared(float u) {
  // With w = 2z the distribution is (w + sin w + π) / 2π: solve w + sin w = c by Newton's
  // method, kept inside a bracket where the derivative 1 + cos w vanishes (w = ±π).
  const double c = 2.0 * kPi * (static_cast<double>(u) - 0.5);
  double lo = -kPi, hi = kPi;
  double w = std::cbrt(6.0 * c) * 0.5 + c * 0.25;  // near both ends: w ≈ c/2 and (6c)^(1/3)
  w = std::clamp(w, lo, hi);
  for (int i = 0; i < 40; ++i) {
    const double g = w + std::sin(w) - c;
    if (std::abs(g) < 1e-9) break;
    if (g > 0) hi = w; else lo = w;
    const double slope = 1.0 + std::cos(w);
    double next = slope > 1e-12 ? w - g / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    w = next;
  }
  return static_cast<float>(0.5 * w);
}

}  // namespace hirsute::trace
