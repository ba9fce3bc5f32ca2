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

float Random::uniform() {
  // 24 random bits, so that the result stays below 1 in float.
  return static_cast<float>(next() >> 8u) * 0x1p-24f;
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
