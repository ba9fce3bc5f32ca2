// The random numbers and the warps of the path tracer (trace/path_tracer.h): a small counter-based
// generator, so that a pixel's samples depend on the seed, the pixel and the pass alone and a
// picture is the same on any number of threads; and the maps from the unit square to the
// directions the lights and materials sample.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace hirsute::trace {

inline constexpr float kPi = 3.14159265358979323846f;

// PCG32 (O'Neill 2014): 64-bit state, 32-bit output, one stream per (pixel, pass).
class Random {
 public:
  Random(std::uint64_t seed, std::uint64_t stream);
  std::uint32_t next();
  float uniform();  // in [0, 1)
  glm::vec2 uniform2() {
    const float a = uniform();
    return {a, uniform()};
  }

 private:
  std::uint64_t state_ = 0, increment_ = 1;
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
