#include "hirsute/viewer/trace/surface_bsdf.h"

#include <algorithm>
#include <cmath>

#include "hirsute/viewer/trace/sampling.h"

namespace hirsute::trace {

SurfaceBsdf::SurfaceBsdf(const SurfaceMaterial& material, const glm::vec3& normal)
    : normal_(normal), exponent_(std::max(0.0f, material.exponent)) {
  weights_[0] = glm::max(material.reflectance, glm::vec3(0.0f));
  weights_[1] = glm::max(material.transmittance, glm::vec3(0.0f));
  weights_[2] = glm::max(material.specular, glm::vec3(0.0f));
  for (int c = 0; c < 3; ++c) {
    const float total = weights_[0][c] + weights_[1][c] + weights_[2][c];
    if (total > 1) {
      for (glm::vec3& w : weights_) w[c] /= total;
    }
  }
  float sum = 0;
  for (int k = 0; k < 3; ++k) sum += choice_[k] = luminance(weights_[k]) + (k == 0 ? 1e-6f : 0.0f);
  for (float& p : choice_) p /= sum;
}

void SurfaceBsdf::densities(const glm::vec3& wo, const glm::vec3& wi, float out[3],
                            float& cosine) const {
  const float cosO = glm::dot(wo, normal_), cosI = glm::dot(wi, normal_);
  cosine = std::abs(cosI);
  const bool sameSide = cosO * cosI > 0;
  out[0] = sameSide ? cosine / kPi : 0.0f;
  out[1] = sameSide ? 0.0f : cosine / kPi;
  out[2] = 0;
  if (sameSide && exponent_ >= 0) {
    const glm::vec3 mirror = 2 * cosO * normal_ - wo;
    const float cosAlpha = glm::dot(mirror, wi);
    if (cosAlpha > 0) out[2] = (exponent_ + 1) / (2 * kPi) * std::pow(cosAlpha, exponent_);
  }
}

glm::vec3 SurfaceBsdf::value(const glm::vec3& wo, const glm::vec3& wi) const {
  float d[3], cosine;
  densities(wo, wi, d, cosine);
  // The Phong lobe's value is (n + 2)/2π cosⁿα · cos θi; its density (n + 1)/2π cosⁿα.
  const float phong = d[2] * (exponent_ + 2) / (exponent_ + 1) * cosine;
  return weights_[0] * d[0] + weights_[1] * d[1] + weights_[2] * phong;
}

float SurfaceBsdf::pdf(const glm::vec3& wo, const glm::vec3& wi) const {
  float d[3], cosine;
  densities(wo, wi, d, cosine);
  return choice_[0] * d[0] + choice_[1] * d[1] + choice_[2] * d[2];
}

SurfaceSample SurfaceBsdf::sample(const glm::vec3& wo, const glm::vec3& u) const {
  const float side = glm::dot(wo, normal_) >= 0 ? 1.0f : -1.0f;
  glm::vec3 wi;
  if (u.x < choice_[0] + choice_[1]) {
    const float towards = u.x < choice_[0] ? side : -side;
    wi = Frame::around(towards * normal_).toWorld(sampleCosineHemisphere({u.y, u.z}));
  } else {
    const glm::vec3 mirror = 2 * glm::dot(wo, normal_) * normal_ - wo;
    const float cosAlpha = std::pow(u.y, 1.0f / (exponent_ + 1));
    const float sinAlpha = std::sqrt(std::max(0.0f, 1 - cosAlpha * cosAlpha));
    const float phi = 2 * kPi * u.z;
    wi = Frame::around(mirror).toWorld(
        {sinAlpha * std::cos(phi), sinAlpha * std::sin(phi), cosAlpha});
  }
  SurfaceSample s;
  s.direction = glm::normalize(wi);
  s.value = value(wo, s.direction);
  s.pdf = pdf(wo, s.direction);
  return s;
}

}  // namespace hirsute::trace
