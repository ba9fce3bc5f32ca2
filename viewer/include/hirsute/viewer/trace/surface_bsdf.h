// How a surface scatters light in the path tracer: Lambert's diffuse reflection, diffuse
// transmission for leaves and petals (papers/002_0e0bce38b72f21dc.txt, Sec. 5: "diffuse
// transmission is used to simulate the translucency in the leaves"), and the energy-conserving
// Phong lobe (Lafortune and Willems 1994) for a material's specular colour and shininess.
// Each is a lobe whose albedo is its weight; the weights are scaled to sum to at most 1 a
// channel, so a surface never returns more light than it receives, and all of it when they
// sum to 1.
#pragma once

#include <glm/glm.hpp>

namespace hirsute::trace {

struct SurfaceMaterial {
  glm::vec3 reflectance{0.8f};    // Lambertian, on the side the light comes from
  glm::vec3 transmittance{0.0f};  // Lambertian, to the other side
  glm::vec3 specular{0.0f};       // the Phong lobe's albedo
  float exponent = 0;             // the Phong lobe's exponent (cpfg's shininess)
};

struct SurfaceSample {
  glm::vec3 direction{0.0f};  // ωi
  glm::vec3 value{0.0f};      // f·|cos θi|
  float pdf = 0;              // in solid angle
};

class SurfaceBsdf {
 public:
  // `normal`: unit, the side the eye sees (the integrator faces it to ωo).
  SurfaceBsdf(const SurfaceMaterial& material, const glm::vec3& normal);

  glm::vec3 value(const glm::vec3& wo, const glm::vec3& wi) const;  // f·|cos θi|
  float pdf(const glm::vec3& wo, const glm::vec3& wi) const;
  // `u`: three uniform numbers in [0, 1): the lobe, then the direction.
  SurfaceSample sample(const glm::vec3& wo, const glm::vec3& u) const;

 private:
  void densities(const glm::vec3& wo, const glm::vec3& wi, float out[3], float& cosine) const;

  glm::vec3 normal_;
  glm::vec3 weights_[3];  // reflected, transmitted, specular
  float choice_[3];
  float exponent_;
};

}  // namespace hirsute::trace
