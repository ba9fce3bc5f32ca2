// How a hair scatters light in the path tracer (papers/002_0e0bce38b72f21dc.txt, Sec. 5: "a
// slightly modified Kajiya model that accounts for backscattering, similar to Goldman's").
//
// Kajiya and Kay's hair has a diffuse term proportional to sin(T, L) and a specular cone about
// the mirror angle −θo. Goldman's fake fur weights every term by where the light lies around the
// hair seen from the eye: (1 + κ)/2 for light scattered back towards the side it came from and
// (1 − κ)/2 for light passed through, κ the cosine of the azimuth Δφ between the light and the
// eye in the plane across the hair. Here the four terms are four lobes, each a density over the
// sphere of directions:
//   diffuse back, diffuse through:  (2/π) cos θi · (1 ± cos Δφ) / 2π
//   specular back, specular through: M_v(θi, θo) · (1 ± cos Δφ) / 2π
// M_v is d'Eon et al.'s (2011) longitudinal lobe about −θo, of variance v, which has an exact
// sampling method. The hair's value f·|cos θi| = Σ wₖ·lobeₖ(ωi), so a hair whose weights sum to 1
// returns all the light it receives and one whose weights sum to less absorbs the rest; each lobe
// is sampled exactly, in proportion to its weight.
//
// θ is measured from the plane across the hair (sin θ = ω·T), directions point away from the hair
// (ωo towards the eye, ωi towards the light).
#pragma once

#include <glm/glm.hpp>

namespace hirsute::trace {

struct HairMaterial {
  glm::vec3 diffuse{0.6f};    // the diffuse lobes' albedo (the hair's colour)
  glm::vec3 specular{0.1f};   // the specular lobes' albedo; diffuse + specular ≤ 1 a channel
  float backscatter = 0.4f;   // share of each term scattered back (κ = 1); the rest goes through
  float roughness = 0.25f;    // the specular cone's angular spread, radians (v = roughness²)
};

struct HairSample {
  glm::vec3 direction{0.0f};  // ωi
  glm::vec3 value{0.0f};      // f·|cos θi|
  float pdf = 0;              // in solid angle
};

class HairBsdf {
 public:
  // `tangent`: unit, along the hair. Diffuse + specular is scaled down where it passes 1.
  HairBsdf(const HairMaterial& material, const glm::vec3& tangent);

  glm::vec3 value(const glm::vec3& wo, const glm::vec3& wi) const;  // f·|cos θi|
  float pdf(const glm::vec3& wo, const glm::vec3& wi) const;
  // `u`: four uniform numbers in [0, 1): the lobe, θ, the turn about the cone, φ.
  HairSample sample(const glm::vec3& wo, const glm::vec4& u) const;

  // The lobes' weights, diffuse back, diffuse through, specular back, specular through.
  const glm::vec3* weights() const { return weights_; }

 private:
  void densities(const glm::vec3& wo, const glm::vec3& wi, float out[4]) const;

  glm::vec3 tangent_;
  glm::vec3 weights_[4];
  float choice_[4];  // the probability of sampling each lobe
  float variance_;
};

// d'Eon et al. 2011's longitudinal scattering function, normalised so that
// ∫ M cos θi dθi = 1 over [−π/2, π/2], peaked at θi = −θo.
float longitudinalLobe(float sinThetaI, float cosThetaI, float sinThetaO, float cosThetaO,
                       float variance);

}  // namespace hirsute::trace
