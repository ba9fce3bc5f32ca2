// A hair as a rough dielectric cylinder that absorbs inside (docs/trace.md, "Hairs"): the fibre
// scattering model of Chiang, Bitterli, Tappan and Burley 2016 ("A Practical and Controllable
// Hair and Fur Model for Production Path Tracing"), after Marschner et al. 2003 and d'Eon et al.
// 2011.
//
// Light that meets the fibre at offset h across it (−1 to 1) leaves by p internal paths: R
// (reflected at the cuticle), TT (refracted in and out: the forward scattering that makes a
// backlit fuzz glow), TRT (one reflection inside), and a residual for the longer paths. Each
// lobe is Mp(θi, θo) · Ap · Np(φ):
//   Mp  d'Eon et al.'s longitudinal lobe about −θo, turned by the cuticle's scales' tilt α
//       (−2α for R, α for TT, 4α for TRT), of variance v_p from the longitudinal roughness βm
//       (Chiang et al., Sec. 4.1; v_TT = v/4, v_TRT = v_res = 4v);
//   Ap  the share of the light on that path: Fresnel's reflectance at the cuticle (index η)
//       and the absorption σa along the chord 2 cos γt / cos θt inside (in units of the radius);
//       with σa = 0 the shares sum to 1, so the fibre returns all the light it receives;
//   Np  a logistic in the azimuth about the path's deflection Φ = 2pγt − 2γo + pπ, trimmed to
//       (−π, π), of scale s from the azimuthal roughness βn (Sec. 4.1); the residual is uniform.
// The value f·|cos| = Σ Mp·Ap·Np integrates over the sphere to Σ Ap. Sampling follows Sec. 4.3:
// a lobe in proportion to its Ap, then θ from Mp exactly and φ from the trimmed logistic.
//
// θ is measured from the plane across the fibre (sin θ = ω·T), φ about T; directions point away
// from the hit (ωo towards the eye, ωi towards the light), as in hair_bsdf.h.
#pragma once

#include <glm/glm.hpp>

#include "hirsute/viewer/trace/hair_bsdf.h"

namespace hirsute::trace {

struct FibreMaterial {
  glm::vec3 absorption{0.0f};  // σa a unit of the fibre's radius (absorptionFromColour, …)
  float longitudinalRoughness = 0.3f;  // βm, 0–1
  float azimuthalRoughness = 0.3f;     // βn, 0–1
  float tilt = 0.035f;                 // α, the cuticle scales' tilt in radians (2°)
  float eta = 1.55f;                   // the index of refraction (keratin, cellulose walls)
};

class FibreBsdf {
 public:
  // `tangent`: unit, along the fibre; `offset`: h, where the ray met the fibre across its width.
  FibreBsdf(const FibreMaterial& material, const glm::vec3& tangent, const glm::vec3& wo,
            float offset);

  glm::vec3 value(const glm::vec3& wo, const glm::vec3& wi) const;  // f·|cos θi|
  float pdf(const glm::vec3& wo, const glm::vec3& wi) const;
  // `u`: four uniform numbers in [0, 1): the lobe, θ, the turn about the cone, φ.
  HairSample sample(const glm::vec3& wo, const glm::vec4& u) const;

  // The shares of R, TT, TRT and the residual (Ap) for this ωo and h.
  const glm::vec3* shares() const { return shares_; }

 private:
  static constexpr int kLobes = 4;
  // ωo's angles, turned by each lobe's tilt.
  void tilted(int p, float& sinThetaO, float& cosThetaO) const;
  float azimuthal(int p, float phi) const;  // Np
  float azimuthOf(const glm::vec3& w) const;

  glm::vec3 tangent_, across_, third_;  // a right-handed frame: across_ × third_ = tangent_
  float sinThetaO_, cosThetaO_, phiO_;
  float gammaO_, gammaT_;
  float variance_[kLobes];
  float scale_;  // s of the logistic
  float sin2kAlpha_[3], cos2kAlpha_[3];
  glm::vec3 shares_[kLobes];
  float choice_[kLobes];  // the probability of sampling each lobe
};

// σa that gives a fibre of azimuthal roughness βn the colour `colour` (linear, 0–1) after many
// scattering events: Chiang et al. 2016, Sec. 4.2, their fit of the colour against σa.
glm::vec3 absorptionFromColour(const glm::vec3& colour, float azimuthalRoughness);
// σa from the concentrations of eumelanin (brown-black) and pheomelanin (red-yellow), each
// from 0 (none: white hair) to about 8 (black): d'Eon et al. 2011's absorption spectra as RGB.
glm::vec3 absorptionFromMelanin(float eumelanin, float pheomelanin);

// h for a ray towards the eye `wo` that met a round fibre along `tangent` where its surface's
// normal is `normal`: the sine of the azimuth from the normal to ωo about the tangent, so that
// the R lobe leaves about the mirror direction of ωo in that normal.
float fibreOffset(const glm::vec3& tangent, const glm::vec3& normal, const glm::vec3& wo);

// The trimmed logistic of scale s over (a, b), its integral over (a, b) 1, and a sample of it
// from a uniform u: the azimuthal term and its sampling.
float trimmedLogistic(float x, float s, float a, float b);
float sampleTrimmedLogistic(float u, float s, float a, float b);

}  // namespace hirsute::trace
