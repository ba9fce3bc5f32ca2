// The random numbers and the warps of the path tracer (trace/path_tracer.h): a small counter-based
// generator, so that a pixel's samples depend on the seed, the pixel and the pass alone and a
// picture is the same on any number of threads; and the maps from the unit square to the
// directions the lights and materials sample.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace hirsute::trace {

inline constexpr float kPi = 3.14159265358979323846f;

// The numbers of one path. Made with (seed, stream), they are PCG32's (O'Neill 2014: 64-bit
// state, 32-bit output), independent from call to call. Made by `stratified`, for the sample
// `index` of a pixel, the first kStratifiedCalls calls (uniform or uniform2 alike) each take the
// next point of their own 2-D sequence, the Sobol (0,2)-sequence Owen-scrambled and shuffled by
// hashes of the seed, the pixel and the call (Burley 2020): over the pixel's samples each call
// covers its square evenly (any 2^k first samples hit each of 2^k equal strips or squares once),
// the paths stay unbiased and seeds differ as independent pictures do; the calls after those
// are PCG32's. A pixel's edges, its soft shadows and its sky then converge faster than 1/√n.
class Random {
 public:
  Random(std::uint64_t seed, std::uint64_t stream);
  static Random stratified(std::uint64_t seed, std::uint64_t pixel, std::uint32_t index);

  std::uint32_t next();
  float uniform() {  // in [0, 1)
    if (call_ < kStratifiedCalls) return toUnit(stratifiedPoint().x);
    return toUnit(next());
  }
  glm::vec2 uniform2() {
    if (call_ < kStratifiedCalls) {
      const glm::uvec2 p = stratifiedPoint();
      return {toUnit(p.x), toUnit(p.y)};
    }
    const float a = uniform();
    return {a, uniform()};
  }

  static constexpr int kStratifiedCalls = 24;

 private:
  // 24 bits, so that the result stays below 1 in float.
  static float toUnit(std::uint32_t bits) { return static_cast<float>(bits >> 8u) * 0x1p-24f; }
  glm::uvec2 stratifiedPoint();

  std::uint64_t state_ = 0, increment_ = 1;
  std::uint64_t pixelKey_ = 0;
  std::uint32_t index_ = 0;
  int call_ = kStratifiedCalls;  // independent unless made stratified
};

// A right-handed frame whose z is `n` (unit).
struct Frame {
  glm::vec3 x, y, z;
  static Frame around(const glm::vec3& n);
  glm::vec3 toWorld(const glm::vec3& local) const { return local.x * x + local.y * y + local.z * z; }
  glm::vec3 toLocal(const glm::vec3& w) const {
    return {glm::dot(w, x), glm::dot(w, y), glm::dot(w, z)};
  }
};

// Directions about +z, with their densities in solid angle.
glm::vec3 sampleUniformSphere(glm::vec2 u);
inline constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);
glm::vec3 sampleUniformHemisphere(glm::vec2 u);
inline constexpr float kUniformHemispherePdf = 1.0f / (2.0f * kPi);
glm::vec3 sampleCosineHemisphere(glm::vec2 u);  // density cos θ / π
glm::vec2 sampleUniformDisk(glm::vec2 u);       // the unit disc, density 1 / π
// Uniform within the cone of half-angle acos(cosMax); density 1 / (2π (1 − cosMax)).
glm::vec3 sampleUniformCone(glm::vec2 u, float cosMax);

// An angle z in [−π/2, π/2] with density (2/π) cos² z: the longitudinal part of Kajiya's
// diffuse hair lobe, and, doubled, an azimuth with density (1 + cos φ) / 2π.
float sampleCosSquared(float u);

// Veach's power heuristic (β = 2) for a sample of density `a` against one of density `b`.
inline float powerHeuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  return a2 + b2 > 0 ? a2 / (a2 + b2) : 0.0f;
}

inline float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

}  // namespace hirsute::trace
