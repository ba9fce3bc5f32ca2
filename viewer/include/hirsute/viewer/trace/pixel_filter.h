// The pixel filter of `hirsute render --trace`: how the samples of a pixel spread over the
// picture. `Box` takes each pixel's samples inside the pixel, all of equal weight (the picture as
// the tracer has always made it); `Gaussian` (radius 1.5 pixels, σ 0.5) and `Mitchell`
// (Mitchell and Netravali 1988, B = C = 1/3, radius 2) reach into the neighbours.
//
// By filter importance sampling (Ernst et al. 2006; pbrt-v4's FilterSampler): a pixel's sample
// is placed about its centre with the density of the filter's magnitude and weighted by its sign
// times the ratio of the magnitude's integral to the filter's, so that a pixel's estimate stays
// the mean of its own samples: adaptive sampling and the determinism over threads hold as with
// the box, and no sample is shared between pixels. The filters are separable, f(x) f(y), and
// sampled from a table of each axis's magnitude, piecewise constant over kBins bins.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace hirsute::trace {

enum class PixelFilterKind { Box, Gaussian, Mitchell };

// The filter a name (`box`, `gaussian`, `mitchell`) gives, or nothing for another name.
std::optional<PixelFilterKind> pixelFilterNamed(std::string_view name);

class PixelFilter {
 public:
  explicit PixelFilter(PixelFilterKind kind = PixelFilterKind::Box);

  PixelFilterKind kind() const { return kind_; }
  float radius() const { return radius_; }
  // The filter along one axis at `x` pixels from the centre (not normalised).
  float evaluate(float x) const;

  struct Sample {
    glm::vec2 offset{0.0f};  // from the pixel's centre, in pixels
    float weight = 1;        // its estimate's weight: 1 on average over the pixel's samples
  };
  // The sample `u` (uniform over [0, 1)²) places.
  Sample sample(const glm::vec2& u) const;

  static constexpr int kBins = 64;

 private:
  struct Axis {
    float offset = 0, weight = 1;
  };
  Axis sampleAxis(float u) const;

  PixelFilterKind kind_;
  float radius_ = 0.5f;
  std::vector<float> value_;  // the filter at each bin's middle
  std::vector<float> cdf_;    // of the magnitude, kBins + 1 from 0 to 1
  float magnitudeOverIntegral_ = 1;
};

}  // namespace hirsute::trace
