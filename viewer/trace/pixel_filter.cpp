#include "hirsute/viewer/trace/pixel_filter.h"

#include <algorithm>
#include <cmath>

namespace hirsute::trace {

std::optional<PixelFilterKind> pixelFilterNamed(std::string_view name) {
  if (name == "box") return PixelFilterKind::Box;
  if (name == "gaussian") return PixelFilterKind::Gaussian;
  if (name == "mitchell") return PixelFilterKind::Mitchell;
  return std::nullopt;
}

namespace {

constexpr float kGaussianRadius = 1.5f, kGaussianSigma = 0.5f;
constexpr float kMitchellRadius = 2, kMitchellB = 1.0f / 3, kMitchellC = 1.0f / 3;

float gaussian(float x) {
  return std::exp(-x * x / (2 * kGaussianSigma * kGaussianSigma));
}

// Mitchell and Netravali 1988, eq. 8: the cubic of B and C over |x| < 2.
float mitchell(float x) {
  const float a = std::abs(x), b = kMitchellB, c = kMitchellC;
  if (a >= 2) return 0;
  if (a < 1) {
    return ((12 - 9 * b - 6 * c) * a * a * a + (-18 + 12 * b + 6 * c) * a * a + (6 - 2 * b)) / 6;
  }
  return ((-b - 6 * c) * a * a * a + (6 * b + 30 * c) * a * a + (-12 * b - 48 * c) * a +
          (8 * b + 24 * c)) /
         6;
}

}  // namespace

PixelFilter::PixelFilter(PixelFilterKind kind) : kind_(kind) {
  if (kind_ == PixelFilterKind::Box) return;
  radius_ = kind_ == PixelFilterKind::Gaussian ? kGaussianRadius : kMitchellRadius;
  value_.resize(kBins);
  cdf_.assign(kBins + 1, 0.0f);
  double magnitude = 0, integral = 0;
  for (int i = 0; i < kBins; ++i) {
    const float x = -radius_ + (2 * radius_) * (static_cast<float>(i) + 0.5f) / kBins;
    value_[i] = evaluate(x);
    magnitude += std::abs(value_[i]);
    integral += value_[i];
    cdf_[i + 1] = static_cast<float>(magnitude);
  }
  for (float& c : cdf_) c = static_cast<float>(c / magnitude);
  cdf_[kBins] = 1;
  magnitudeOverIntegral_ = static_cast<float>(magnitude / integral);
}

float PixelFilter::evaluate(float x) const {
  switch (kind_) {
    case PixelFilterKind::Box:
      return std::abs(x) <= 0.5f ? 1.0f : 0.0f;
    case PixelFilterKind::Gaussian:
      // Less its value at the radius, so that it falls to 0 there (pbrt's GaussianFilter).
      return std::abs(x) >= kGaussianRadius ? 0.0f : gaussian(x) - gaussian(kGaussianRadius);
    case PixelFilterKind::Mitchell:
      return mitchell(x);
  }
  return 0;
}

PixelFilter::Axis PixelFilter::sampleAxis(float u) const {
  // The bin whose share of the magnitude holds u, then uniformly within it.
  const auto upper = std::upper_bound(cdf_.begin() + 1, cdf_.end() - 1, u);
  const auto bin = static_cast<int>(upper - cdf_.begin()) - 1;
  const float low = cdf_[bin], high = cdf_[bin + 1];
  const float within = high > low ? std::clamp((u - low) / (high - low), 0.0f, 1.0f) : 0.5f;
  Axis axis;
  axis.offset = -radius_ + (2 * radius_) * (static_cast<float>(bin) + within) / kBins;
  axis.weight = value_[bin] < 0 ? -magnitudeOverIntegral_ : magnitudeOverIntegral_;
  return axis;
}

PixelFilter::Sample PixelFilter::sample(const glm::vec2& u) const {
  Sample s;
  if (kind_ == PixelFilterKind::Box) {
    s.offset = u - 0.5f;
    return s;
  }
  const Axis x = sampleAxis(u.x), y = sampleAxis(u.y);
  s.offset = {x.offset, y.offset};
  s.weight = x.weight * y.weight;
  return s;
}

}  // namespace hirsute::trace
