#include "hirsute/viewer/trace/tone_curve.h"

#include <algorithm>
#include <cmath>

namespace hirsute::trace {

std::optional<ToneCurve> toneCurveNamed(std::string_view name) {
  if (name == "none") return ToneCurve::None;
  if (name == "filmic") return ToneCurve::Filmic;
  return std::nullopt;
}

float toneMap(float linear, ToneCurve tone) {
  const float x = linear > 0 ? linear : 0.0f;  // NaN and negative values as black
  if (tone == ToneCurve::None) return std::min(x, 1.0f);
  // Narkowicz 2015: f(x) = x (a x + b) / (x (c x + d) + e), a rational fit of the ACES RRT and
  // ODT. f(0) = 0, it rises monotonically, gives 0.80 for 1 and reaches white only near 7.2, so
  // highlights up to seven times white keep their gradations.
  constexpr float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  if (!std::isfinite(x)) return 1.0f;
  return std::clamp(x * (a * x + b) / (x * (c * x + d) + e), 0.0f, 1.0f);
}

namespace {

float inverseToneMap(float light, ToneCurve tone) {
  const float y = std::clamp(light, 0.0f, 1.0f);
  if (tone == ToneCurve::None) return y;
  // y (c x² + d x + e) = a x² + b x, a quadratic in x whose roots multiply to y e / (y c - a)
  // <= 0 (y c < a for y <= 1): the non-negative root.
  constexpr float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  const double qa = y * c - a, qb = y * d - b, qc = y * e;
  return static_cast<float>((-qb - std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa));
}

}  // namespace

glm::vec3 radianceShownAs(const glm::vec3& light, const DisplayTransform& transform) {
  const float scale = std::exp2(-transform.exposure);
  return glm::vec3(inverseToneMap(light.r, transform.tone), inverseToneMap(light.g, transform.tone),
                   inverseToneMap(light.b, transform.tone)) *
         scale;
}

glm::vec3 displayLight(const glm::vec3& radiance, const DisplayTransform& transform) {
  const float scale = std::exp2(transform.exposure);
  return {toneMap(radiance.r * scale, transform.tone), toneMap(radiance.g * scale, transform.tone),
          toneMap(radiance.b * scale, transform.tone)};
}

}  // namespace hirsute::trace
