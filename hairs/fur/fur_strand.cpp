#include "hirsute/hairs/fur/fur_strand.h"

#include <algorithm>
#include <cmath>

namespace hirsute::fur {

glm::vec3 constrainTip(const StrandRoot& strand, const glm::vec3& tip) {
  glm::vec3 offset = tip - strand.root;
  const float across = glm::dot(offset, strand.normal);
  if (across < 0) offset -= across * strand.normal;
  const float distance = glm::length(offset);
  if (distance > strand.length) offset *= strand.length / distance;
  return strand.root + offset;
}

glm::vec3 restingTip(const StrandRoot& strand, float stiffness, float mass, const glm::vec3& force) {
  // Without a spring nothing holds the particle but the constraint: it goes as far as the force
  // takes it.
  const float reach = stiffness > 0 ? mass / stiffness : 1e6f * strand.length;
  return constrainTip(strand, strand.restTip() + reach * force);
}

void stepStrand(const StrandRoot& strand, float stiffness, float mass, float damping,
                const glm::vec3& force, float dt, StrandState& state) {
  const glm::vec3 acceleration =
      (stiffness / mass) * (strand.restTip() - state.tip) + force - damping * state.velocity;
  state.velocity += dt * acceleration;
  const glm::vec3 moved = state.tip + dt * state.velocity;
  const glm::vec3 constrained = constrainTip(strand, moved);
  if (dt > 0) state.velocity += (constrained - moved) / dt;
  state.tip = constrained;
}

glm::vec3 bendPoint(const StrandRoot& strand, const glm::vec3& tip, float h) {
  const float a = 1 - h;
  return a * a * strand.root + 2 * a * h * strand.restTip() + h * h * tip;
}

glm::vec3 bendTangent(const StrandRoot& strand, const glm::vec3& tip, float h) {
  return 2 * (1 - h) * (strand.restTip() - strand.root) + 2 * h * (tip - strand.restTip());
}

glm::vec3 curlOffset(float h, float wetness, float curlRadius, float curlFrequency, float length,
                     const glm::vec3& u, const glm::vec3& v) {
  const float alpha = (1 - wetness) * curlRadius * length * h;
  const float angle = curlFrequency * h;
  return alpha * (std::cos(angle) * u + std::sin(angle) * v);
}

glm::vec3 curlTangent(float h, float wetness, float curlRadius, float curlFrequency, float length,
                      const glm::vec3& u, const glm::vec3& v) {
  const float k = (1 - wetness) * curlRadius * length;
  const float angle = curlFrequency * h;
  const float c = std::cos(angle), s = std::sin(angle);
  return k * ((c - curlFrequency * h * s) * u + (s + curlFrequency * h * c) * v);
}

float clumpProfile(float h, float w, int layers) {
  h = std::clamp(h, 0.0f, 1.0f);
  float bent = h;
  if (layers > 1) {
    const float lowest = 1.0f / static_cast<float>(layers);
    bent = h <= lowest ? 0.0f : 1 + std::log(h) / std::log(static_cast<float>(layers));
  }
  return (1 - w) * h + w * bent;
}

float clumpScale(float h, float w, int layers, float wetness, float radius) {
  return clumpProfile(h, w, layers) * wetness * radius * kClumpTexels;
}

glm::vec2 clumpedPosition(const glm::vec2& root, const glm::vec2& centre, float scale) {
  return centre + (root - centre) / (1 + scale);
}

glm::vec3 furShade(const glm::vec3& colour, const glm::vec3& t, const glm::vec3& l,
                   const glm::vec3& e, float specular, float phong, float kShadow, float h) {
  const float tl = glm::dot(t, l), te = glm::dot(t, e);
  const float sl = std::sqrt(std::max(0.0f, 1 - tl * tl)), se = std::sqrt(std::max(0.0f, 1 - te * te));
  const glm::vec3 diffuse = colour * sl;
  const float highlight = specular * std::pow(std::max(0.0f, tl * te + sl * se), phong);
  return shadowFactor(h, kShadow) * (diffuse + glm::vec3(highlight));
}

}  // namespace hirsute::fur
