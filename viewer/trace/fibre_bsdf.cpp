#include "hirsute/viewer/trace/fibre_bsdf.h"

#include <algorithm>
#include <cmath>

#include "hirsute/viewer/trace/sampling.h"

namespace hirsute::trace {
namespace {

float safeSqrt(float x) {
  return std::sqrt(std::max(0.0f, x));
}

float safeAsin(float x) {
  return std::asin(std::clamp(x, -1.0f, 1.0f));
}

// Fresnel's reflectance of unpolarised light at a dielectric of relative index `eta`, met at
// the cosine `cosI` from outside.
float fresnel(float cosI, float eta) {
  cosI = std::clamp(cosI, 0.0f, 1.0f);
  const float sin2T = (1 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1) return 1;
  const float cosT = safeSqrt(1 - sin2T);
  const float parallel = (eta * cosI - cosT) / (eta * cosI + cosT);
  const float perpendicular = (cosI - eta * cosT) / (cosI + eta * cosT);
  return (parallel * parallel + perpendicular * perpendicular) / 2;
}

float logistic(float x, float s) {
  x = std::abs(x);
  const float e = std::exp(-x / s);
  return e / (s * (1 + e) * (1 + e));
}

float logisticCdf(float x, float s) {
  return 1 / (1 + std::exp(-x / s));
}

// An angle brought into [−π, π].
float wrapped(float phi) {
  phi = std::fmod(phi, 2 * kPi);
  if (phi > kPi) phi -= 2 * kPi;
  if (phi < -kPi) phi += 2 * kPi;
  return phi;
}

// The azimuth a path p leaves at (Chiang et al. 2016, Eq. 7 after Marschner et al.).
float deflection(int p, float gammaO, float gammaT) {
  return 2.0f * static_cast<float>(p) * gammaT - 2.0f * gammaO + static_cast<float>(p) * kPi;
}

}  // namespace

float trimmedLogistic(float x, float s, float a, float b) {
  return logistic(x, s) / (logisticCdf(b, s) - logisticCdf(a, s));
}

float sampleTrimmedLogistic(float u, float s, float a, float b) {
  const float k = logisticCdf(b, s) - logisticCdf(a, s);
  const float y = u * k + logisticCdf(a, s);
  const float x = -s * std::log(1 / std::clamp(y, 1e-7f, 1 - 1e-7f) - 1);
  return std::clamp(x, a, b);
}

float fibreOffset(const glm::vec3& tangent, const glm::vec3& normal, const glm::vec3& wo) {
  glm::vec3 n = normal - glm::dot(normal, tangent) * tangent;
  const glm::vec3 o = wo - glm::dot(wo, tangent) * tangent;
  const float lengths = glm::length(n) * glm::length(o);
  if (!(lengths > 1e-12f)) return 0;
  // The side of the tube the ray met faces the eye.
  if (glm::dot(n, o) < 0) n = -n;
  return std::clamp(glm::dot(glm::cross(n, o), tangent) / lengths, -1.0f, 1.0f);
}

glm::vec3 absorptionFromColour(const glm::vec3& colour, float azimuthalRoughness) {
  const float b = azimuthalRoughness;
  const float fit = 5.969f - 0.215f * b + 2.532f * b * b - 10.73f * b * b * b +
                    5.574f * b * b * b * b + 0.245f * b * b * b * b * b;
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) {
    const float r = std::log(std::clamp(colour[c], 1e-4f, 1.0f)) / fit;
    out[c] = r * r;
  }
  return out;
}

glm::vec3 absorptionFromMelanin(float eumelanin, float pheomelanin) {
  return std::max(0.0f, eumelanin) * glm::vec3(0.419f, 0.697f, 1.37f) +
         std::max(0.0f, pheomelanin) * glm::vec3(0.187f, 0.4f, 1.05f);
}

FibreBsdf::FibreBsdf(const FibreMaterial& material, const glm::vec3& tangent, const glm::vec3& wo,
                     float offset)
    : tangent_(tangent) {
  const Frame frame = Frame::around(tangent_);
  across_ = frame.x;
  third_ = frame.y;
  sinThetaO_ = std::clamp(glm::dot(wo, tangent_), -1.0f, 1.0f);
  cosThetaO_ = safeSqrt(1 - sinThetaO_ * sinThetaO_);
  phiO_ = azimuthOf(wo);
  const float h = std::clamp(offset, -1.0f, 1.0f);
  gammaO_ = safeAsin(h);

  // Chiang et al. 2016, Sec. 4.1: the roughnesses as the lobes' variance and the logistic's
  // scale, fitted so that βm and βn look alike over their range.
  const float bm = std::clamp(material.longitudinalRoughness, 0.01f, 1.0f);
  const float bn = std::clamp(material.azimuthalRoughness, 0.01f, 1.0f);
  const float v = 0.726f * bm + 0.812f * bm * bm + 3.7f * std::pow(bm, 20.0f);
  variance_[0] = std::max(1e-4f, v * v);
  variance_[1] = variance_[0] / 4;
  variance_[2] = variance_[3] = 4 * variance_[0];
  scale_ = std::sqrt(kPi / 8) * (0.265f * bn + 1.194f * bn * bn + 5.372f * std::pow(bn, 22.0f));
  // The cuticle's tilt, doubled for each lobe's turn (−2α for R, α for TT, 4α for TRT).
  sin2kAlpha_[0] = std::sin(material.tilt);
  cos2kAlpha_[0] = safeSqrt(1 - sin2kAlpha_[0] * sin2kAlpha_[0]);
  for (int k = 1; k < 3; ++k) {
    sin2kAlpha_[k] = 2 * cos2kAlpha_[k - 1] * sin2kAlpha_[k - 1];
    cos2kAlpha_[k] =
        cos2kAlpha_[k - 1] * cos2kAlpha_[k - 1] - sin2kAlpha_[k - 1] * sin2kAlpha_[k - 1];
  }

  // The refracted ray inside: Bravais's index for the projection across the fibre.
  const float eta = material.eta;
  const float sinThetaT = sinThetaO_ / eta;
  const float cosThetaT = safeSqrt(1 - sinThetaT * sinThetaT);
  const float etaAcross =
      safeSqrt(eta * eta - sinThetaO_ * sinThetaO_) / std::max(cosThetaO_, 1e-4f);
  const float sinGammaT = h / etaAcross;
  const float cosGammaT = safeSqrt(1 - sinGammaT * sinGammaT);
  gammaT_ = safeAsin(sinGammaT);
  const float chord = 2 * cosGammaT / std::max(cosThetaT, 1e-4f);
  const glm::vec3 inside = glm::exp(-glm::max(material.absorption, glm::vec3(0.0f)) * chord);

  // Ap: the cuticle's reflectance f at the cosine cos θo cos γo, and what passes.
  const float f = fresnel(cosThetaO_ * std::cos(gammaO_), eta);
  shares_[0] = glm::vec3(f);
  shares_[1] = (1 - f) * (1 - f) * inside;
  shares_[2] = shares_[1] * f * inside;
  // The residual: the geometric series of the paths beyond TRT.
  const glm::vec3 more = f * inside;
  shares_[3] = shares_[2] * more / glm::max(glm::vec3(1.0f) - more, glm::vec3(1e-6f));

  float sum = 0;
  for (int p = 0; p < kLobes; ++p)
    sum += choice_[p] = (shares_[p].x + shares_[p].y + shares_[p].z) / 3;
  if (sum > 0) {
    for (float& c : choice_) c /= sum;
  } else {
    for (float& c : choice_) c = 1.0f / kLobes;
  }
}

float FibreBsdf::azimuthOf(const glm::vec3& w) const {
  return std::atan2(glm::dot(w, third_), glm::dot(w, across_));
}

void FibreBsdf::tilted(int p, float& sinThetaO, float& cosThetaO) const {
  // The scales tilt the cuticle, so each lobe's cone turns by its multiple of α.
  if (p == 0) {
    sinThetaO = sinThetaO_ * cos2kAlpha_[1] - cosThetaO_ * sin2kAlpha_[1];
    cosThetaO = cosThetaO_ * cos2kAlpha_[1] + sinThetaO_ * sin2kAlpha_[1];
  } else if (p == 1) {
    sinThetaO = sinThetaO_ * cos2kAlpha_[0] + cosThetaO_ * sin2kAlpha_[0];
    cosThetaO = cosThetaO_ * cos2kAlpha_[0] - sinThetaO_ * sin2kAlpha_[0];
  } else if (p == 2) {
    sinThetaO = sinThetaO_ * cos2kAlpha_[2] + cosThetaO_ * sin2kAlpha_[2];
    cosThetaO = cosThetaO_ * cos2kAlpha_[2] - sinThetaO_ * sin2kAlpha_[2];
  } else {
    sinThetaO = sinThetaO_;
    cosThetaO = cosThetaO_;
  }
  cosThetaO = std::abs(cosThetaO);
}

float FibreBsdf::azimuthal(int p, float phi) const {
  if (p == kLobes - 1) return 1 / (2 * kPi);
  return trimmedLogistic(wrapped(phi - deflection(p, gammaO_, gammaT_)), scale_, -kPi, kPi);
}

glm::vec3 FibreBsdf::value(const glm::vec3& wo, const glm::vec3& wi) const {
  (void)wo;  // its angles are the constructor's
  const float sinThetaI = std::clamp(glm::dot(wi, tangent_), -1.0f, 1.0f);
  const float cosThetaI = safeSqrt(1 - sinThetaI * sinThetaI);
  const float phi = azimuthOf(wi) - phiO_;
  glm::vec3 sum(0.0f);
  for (int p = 0; p < kLobes; ++p) {
    float sinO, cosO;
    tilted(p, sinO, cosO);
    sum += longitudinalLobe(sinThetaI, cosThetaI, sinO, cosO, variance_[p]) * shares_[p] *
           azimuthal(p, phi);
  }
  return sum;
}

float FibreBsdf::pdf(const glm::vec3& wo, const glm::vec3& wi) const {
  (void)wo;
  const float sinThetaI = std::clamp(glm::dot(wi, tangent_), -1.0f, 1.0f);
  const float cosThetaI = safeSqrt(1 - sinThetaI * sinThetaI);
  const float phi = azimuthOf(wi) - phiO_;
  float sum = 0;
  for (int p = 0; p < kLobes; ++p) {
    if (choice_[p] <= 0) continue;
    float sinO, cosO;
    tilted(p, sinO, cosO);
    sum += choice_[p] * longitudinalLobe(sinThetaI, cosThetaI, sinO, cosO, variance_[p]) *
           azimuthal(p, phi);
  }
  return sum;
}

HairSample FibreBsdf::sample(const glm::vec3& wo, const glm::vec4& u) const {
  int p = 0;
  float below = 0;
  while (p < kLobes - 1 && u.x >= below + choice_[p]) below += choice_[p++];
  float sinO, cosO;
  tilted(p, sinO, cosO);
  // d'Eon et al. 2011: θ about the lobe's cone, exactly (as hair_bsdf.cpp samples it).
  const double v = variance_[p];
  const double y = std::max(static_cast<double>(u.y), 1e-5);
  const double cosTheta = 1 + v * std::log(y + (1 - y) * std::exp(-2 / v));
  const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  const double turn = std::cos(2 * static_cast<double>(kPi) * u.z);
  const float sinThetaI =
      static_cast<float>(std::clamp(-cosTheta * sinO + sinTheta * turn * cosO, -1.0, 1.0));
  const float cosThetaI = safeSqrt(1 - sinThetaI * sinThetaI);
  const float dphi = p < kLobes - 1 ? deflection(p, gammaO_, gammaT_) +
                                          sampleTrimmedLogistic(u.w, scale_, -kPi, kPi)
                                    : 2 * kPi * u.w;
  const float phiI = phiO_ + dphi;
  HairSample s;
  s.direction = glm::normalize(sinThetaI * tangent_ +
                               cosThetaI * (std::cos(phiI) * across_ + std::sin(phiI) * third_));
  s.value = value(wo, s.direction);
  s.pdf = pdf(wo, s.direction);
  return s;
}

}  // namespace hirsute::trace
