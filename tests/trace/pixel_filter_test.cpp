// The pixel filters: each one's samples weigh 1 on average (the filter normalised), their
// weighted density is the filter's, and the box keeps a pixel's samples inside it.
#include "hirsute/viewer/trace/pixel_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace hirsute::trace {
namespace {

// The mean weight and the weighted share of the offsets in [a, b) along x, over n uniform points
// along x with y at the centre, whose own weight (the root of the centre's) is divided out:
// the filters are separable, so this is the x axis's alone.
struct Moments {
  double meanWeight = 0, share = 0;
  float farthest = 0;
};
Moments moments(const PixelFilter& filter, float a, float b, int n = 1 << 16) {
  Moments m;
  const float centre = std::sqrt(filter.sample(glm::vec2(0.5f)).weight);
  for (int i = 0; i < n; ++i) {
    const PixelFilter::Sample s =
        filter.sample(glm::vec2((static_cast<float>(i) + 0.5f) / n, 0.5f));
    const double weight = s.weight / centre;
    m.meanWeight += weight;
    if (s.offset.x >= a && s.offset.x < b) m.share += weight;
    m.farthest = std::max({m.farthest, std::abs(s.offset.x), std::abs(s.offset.y)});
  }
  m.meanWeight /= n;
  m.share /= n;
  return m;
}

// The filter's integral over [a, b) against its whole, by the midpoint rule.
double filterShare(const PixelFilter& filter, float a, float b) {
  double part = 0, whole = 0;
  const int steps = 20000;
  for (int i = 0; i < steps; ++i) {
    const float x = -filter.radius() + 2 * filter.radius() * (i + 0.5f) / steps;
    const double f = filter.evaluate(x);
    whole += f;
    if (x >= a && x < b) part += f;
  }
  return part / whole;
}

TEST(PixelFilters, WeightsAverageOneAndFollowTheFilter) {
  for (const PixelFilterKind kind :
       {PixelFilterKind::Box, PixelFilterKind::Gaussian, PixelFilterKind::Mitchell}) {
    const PixelFilter filter(kind);
    EXPECT_NEAR(moments(filter, -10, 10).meanWeight, 1.0, 1e-3);
    EXPECT_NEAR(filter.sample(glm::vec2(0.5f)).weight,
                kind == PixelFilterKind::Mitchell ? 1.1 : 1.0, 0.1);
    EXPECT_LE(moments(filter, -10, 10).farthest, filter.radius());
    // The weighted share of the samples in each quarter of the footprint is the filter's.
    for (int q = 0; q < 4; ++q) {
      const float a = filter.radius() * (-1 + 0.5f * q), b = a + 0.5f * filter.radius();
      EXPECT_NEAR(moments(filter, a, b).share, filterShare(filter, a, b), 0.01) << q;
    }
  }
}

TEST(PixelFilters, TheirShapesAreTheirNames) {
  const PixelFilter box(PixelFilterKind::Box), gaussian(PixelFilterKind::Gaussian),
      mitchell(PixelFilterKind::Mitchell);
  EXPECT_EQ(box.radius(), 0.5f);
  EXPECT_EQ(gaussian.radius(), 1.5f);
  EXPECT_EQ(mitchell.radius(), 2.0f);
  EXPECT_EQ(gaussian.evaluate(1.5f), 0.0f);
  EXPECT_GT(gaussian.evaluate(0), gaussian.evaluate(0.5f));
  // Mitchell-Netravali with B = C = 1/3: 8/9 at the centre, a negative lobe past 1.
  EXPECT_NEAR(mitchell.evaluate(0), 8.0f / 9, 1e-6f);
  EXPECT_LT(mitchell.evaluate(1.5f), 0.0f);
  EXPECT_EQ(mitchell.evaluate(2), 0.0f);
  // Its negative lobe gives negative weights, a few.
  EXPECT_LT(mitchell.sample(glm::vec2(0.01f, 0.5f)).weight, 0.0f);
  EXPECT_GT(mitchell.sample(glm::vec2(0.5f, 0.5f)).weight, 0.0f);
  // The box places the sample where the uniform point is, weight 1.
  const PixelFilter::Sample s = box.sample(glm::vec2(0.25f, 0.75f));
  EXPECT_EQ(s.offset, glm::vec2(-0.25f, 0.25f));
  EXPECT_EQ(s.weight, 1.0f);
}

TEST(PixelFilters, AreNamed) {
  EXPECT_EQ(pixelFilterNamed("box"), PixelFilterKind::Box);
  EXPECT_EQ(pixelFilterNamed("gaussian"), PixelFilterKind::Gaussian);
  EXPECT_EQ(pixelFilterNamed("mitchell"), PixelFilterKind::Mitchell);
  EXPECT_FALSE(pixelFilterNamed("lanczos").has_value());
}

}  // namespace
}  // namespace hirsute::trace
