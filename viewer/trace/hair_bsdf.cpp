#include "hirsute/viewer/trace/hair_bsdf.h"

#include <algorithm>
#include <cmath>

#include "hirsute/viewer/trace/sampling.h"

namespace hirsute::trace {
namespace {

// The modified Bessel function of the first kind, order 0, by its power series.
double besselI0(double x) {
  double sum = 0, term = 1, x2 = x * x / 4;
  for (int i = 1; i < 64; ++i) {
    sum += term;
    term *= x2 / (static_cast<double>(i) * i);
    if (term < sum * 1e-16) break;
  }
  return sum;
}

double logBesselI0(double x) {
  if (x <= 12) return std::log(besselI0(x));
  // The asymptotic expansion, exact to float precision beyond 12.
  return x + 0.5 * (-std::log(2.0 * kPi) + std::log(1.0 / x) + 1.0 / (8.0 * x));
}

float sinOf(float cosine) { return std::sqrt(std::max(0.0f, 1.0f - cosine * cosine)); }

}  // namespace

float longitudinalLobe(float sinThetaI, float cosThetaI, float sinThetaO, float cosThetaO,
                       float variance) {
  const double v = variance;
  const double a = static_cast<double>(cosThetaI) * cosThetaO / v;
  const double b = static_cast<double>(sinThetaI) * sinThetaO / v;
  // For narrow lobes sinh(1/v) and I0(a) overflow; their logarithms do not.
  if (v <= 0.1) {
    return static_cast<float>(std::exp(logBesselI0(a) - b - 1.0 / v + std::log(2.0) +
                                       std::log(1.0 / (2.0 * v))));
  }
  return static_cast<float>(std::exp(-b) * besselI0(a) / (std::sinh(1.0 / v) * 2.0 * v));
}

HairBsdf::HairBsdf(const HairMaterial& material, const glm::vec3& tangent)
    : tangent_(tangent),
      variance_(std::max(1e-3f, material.roughness * material.roughness)) {
  glm::vec3 diffuse = glm::max(material.diffuse, glm::vec3(0.0f));
  glm::vec3 specular = glm::max(material.specular, glm::vec3(0.0f));
  for (int c = 0; c < 3; ++c) {
    const float total = diffuse[c] + specular[c];
    if (total > 1) {
      diffuse[c] /= total;
      specular[c] /= total;
    }
  }
  const float back = std::clamp(material.backscatter, 0.0f, 1.0f);
  weights_[0] = diffuse * back;
  weights_[1] = diffuse * (1 - back);
  weights_[2] = specular * back;
  weights_[3] = specular * (1 - back);
  float sum = 0;
  for (int k = 0; k < 4; ++k) sum += choice_[k] = luminance(weights_[k]) + 1e-6f * (k < 2);
  for (float& p : choice_) p /= sum;
}

void HairBsdf::densities(const glm::vec3& wo, const glm::vec3& wi, float out[4]) const {
  const float sinO = std::clamp(glm::dot(wo, tangent_), -1.0f, 1.0f);
  const float sinI = std::clamp(glm::dot(wi, tangent_), -1.0f, 1.0f);
  const float cosO = sinOf(sinO), cosI = sinOf(sinI);
  // The azimuth between the two directions' projections across the hair.
  const glm::vec3 acrossO = wo - sinO * tangent_, acrossI = wi - sinI * tangent_;
  const float lengths = cosO * cosI;
  const float cosPhi =
      lengths > 1e-8f ? std::clamp(glm::dot(acrossO, acrossI) / lengths, -1.0f, 1.0f) : 0.0f;
  const float back = (1 + cosPhi) / (2 * kPi), through = (1 - cosPhi) / (2 * kPi);
  const float diffuse = 2 / kPi * cosI;
  const float specular = longitudinalLobe(sinI, cosI, sinO, cosO, variance_);
  out[0] = diffuse * back;
  out[1] = diffuse * through;
  out[2] = specular * back;
  out[3] = specular * through;
}

glm::vec3 HairBsdf::value(const glm::vec3& wo, const glm::vec3& wi) const {
  float d[4];
  densities(wo, wi, d);
  return weights_[0] * d[0] + weights_[1] * d[1] + weights_[2] * d[2] + weights_[3] * d[3];
}

float HairBsdf::pdf(const glm::vec3& wo, const glm::vec3& wi) const {
  float d[4];
  densities(wo, wi, d);
  return choice_[0] * d[0] + choice_[1] * d[1] + choice_[2] * d[2] + choice_[3] * d[3];
}

HairSample HairBsdf::sample(const glm::vec3& wo, const glm::vec4& u) const {
  int lobe = 0;
  float below = 0;
  while (lobe < 3 && u.x >= below + choice_[lobe]) below += choice_[lobe++];
  const float sinO = std::clamp(glm::dot(wo, tangent_), -1.0f, 1.0f);
  const float cosO = sinOf(sinO);
  // The frame across the hair: a towards the eye's side, b = T × a.
  glm::vec3 a = wo - sinO * tangent_;
  a = cosO > 1e-6f ? a / cosO : Frame::around(tangent_).x;
  const glm::vec3 b = glm::cross(tangent_, a);

  float sinI, cosI;
  if (lobe < 2) {
    const float theta = sampleCosSquared(u.y);
    sinI = std::sin(theta);
    cosI = std::cos(theta);
  } else {
    // d'Eon et al. 2011: the lobe about −θo, sampled exactly.
    const double v = variance_;
    const double y = std::max(static_cast<double>(u.y), 1e-5);
    const double cosTheta = 1 + v * std::log(y + (1 - y) * std::exp(-2 / v));
    const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    const double cosTurn = std::cos(2 * kPi * static_cast<double>(u.z));
    sinI = static_cast<float>(std::clamp(-cosTheta * sinO + sinTheta * cosTurn * cosO, -1.0, 1.0));
    cosI = sinOf(sinI);
  }
  // The azimuth: (1 + cos φ)/2π about the eye's side for the back lobes, about the far side
  // for the through lobes.
  float phi = 2 * sampleCosSquared(u.w);
  if (lobe == 1 || lobe == 3) phi += kPi;
  HairSample s;
  s.direction = sinI * tangent_ + cosI * (std::cos(phi) * a + std::sin(phi) * b);
  s.direction = glm::normalize(s.direction);
  s.value = value(wo, s.direction);
  s.pdf = pdf(wo, s.direction);
  return s;
}

}  // namespace hirsute::trace
