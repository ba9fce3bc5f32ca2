// The point-diffusion texture (docs/design.md, "Placement"): spacing measured as Lagae & Dutré's
// relative radius, the point count, seeding, and seams where tiles meet.
#include "hirsute/hairs/placement/point_diffusion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "hirsute/hairs/placement/point_spacing.h"

namespace hirsute {
namespace {

constexpr double kFills[] = {0.02, 0.05, 0.1, 0.2, 0.3};

TEST(PointDiffusionTest, RelativeRadiusIsAtLeastPointSixFiveForEveryFill) {
  for (double fill : kFills) {
    for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
      const PointDiffusionTexture texture = PointDiffusionTexture::generate({100, 100, fill, seed});
      const std::vector<TorusPoint> points = texture.positions();
      EXPECT_GE(relativeRadius(points), 0.65) << "fill " << fill << " seed " << seed;
    }
  }
}

TEST(PointDiffusionTest, CountIsWithinTwoPercentOfFillTimesCells) {
  for (double fill : kFills) {
    for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
      const PointDiffusionTexture texture = PointDiffusionTexture::generate({100, 100, fill, seed});
      const double expected = fill * 100 * 100;
      EXPECT_LE(std::abs(static_cast<double>(texture.points().size()) - expected), 0.02 * expected)
          << "fill " << fill << " seed " << seed << ": " << texture.points().size() << " points";
    }
  }
}

TEST(PointDiffusionTest, PointsLieInTheirCellsAndMatchTau) {
  const PointDiffusionTexture texture = PointDiffusionTexture::generate({80, 120, 0.1, 7});
  std::size_t cellsOn = 0;
  for (int row = 0; row < 120; ++row) {
    for (int column = 0; column < 80; ++column) cellsOn += texture.at(column, row) ? 1 : 0;
  }
  EXPECT_EQ(cellsOn, texture.points().size());
  for (const TexturePoint& p : texture.points()) {
    EXPECT_GE(p.u, p.column / 80.0);
    EXPECT_LT(p.u, (p.column + 1) / 80.0);
    EXPECT_GE(p.v, p.row / 120.0);
    EXPECT_LT(p.v, (p.row + 1) / 120.0);
    EXPECT_TRUE(texture.at(p.u, p.v));
    EXPECT_TRUE(texture.at(p.u + 3.0, p.v - 2.0));  // τ repeats with period 1
  }
}

TEST(PointDiffusionTest, SameSeedGivesSameTexture) {
  const PointDiffusionTexture a = PointDiffusionTexture::generate({100, 100, 0.05, 42});
  const PointDiffusionTexture b = PointDiffusionTexture::generate({100, 100, 0.05, 42});
  ASSERT_EQ(a.points().size(), b.points().size());
  for (std::size_t i = 0; i < a.points().size(); ++i) {
    EXPECT_EQ(a.points()[i].u, b.points()[i].u);
    EXPECT_EQ(a.points()[i].v, b.points()[i].v);
  }
}

TEST(PointDiffusionTest, DifferentSeedsGiveDifferentTextures) {
  const PointDiffusionTexture a = PointDiffusionTexture::generate({100, 100, 0.05, 1});
  const PointDiffusionTexture b = PointDiffusionTexture::generate({100, 100, 0.05, 2});
  std::size_t shared = 0;
  for (const TexturePoint& p : a.points()) shared += b.at(p.column, p.row) ? 1 : 0;
  // Independent patterns share about fill·count cells; far fewer than half.
  EXPECT_LT(shared, a.points().size() / 2);
}

TEST(PointDiffusionTest, RejectsBadSettings) {
  EXPECT_THROW(PointDiffusionTexture::generate({100, 100, 0.0, 1}), std::invalid_argument);
  EXPECT_THROW(PointDiffusionTexture::generate({100, 100, 0.8, 1}), std::invalid_argument);
  EXPECT_THROW(PointDiffusionTexture::generate({2, 100, 0.1, 1}), std::invalid_argument);
}

// Two-sample Kolmogorov–Smirnov statistic: the largest gap between the empirical distributions.
double ksStatistic(std::vector<double> a, std::vector<double> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  double largest = 0;
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] <= x) ++i;
    while (j < b.size() && b[j] <= x) ++j;
    largest = std::max(
        largest, std::abs(static_cast<double>(i) / a.size() - static_cast<double>(j) / b.size()));
  }
  return largest;
}

// Nearest-neighbour distances of the points whose nearest neighbour lies across the line
// coordinate = at (the tile edge at 0, or a line inside the tile), along u (axis 0) or v.
struct SeamSamples {
  std::vector<double> acrossEdge;
  std::vector<double> acrossMiddle;
};

void collectSeamSamples(const std::vector<TorusPoint>& points, int axis, SeamSamples& samples) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    TorusPoint bestOffset;
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (j == i) continue;
      const TorusPoint d = toroidalOffset(points[i], points[j]);
      const double distance = std::hypot(d.u, d.v);
      if (distance < best) {
        best = distance;
        bestOffset = d;
      }
    }
    const double from = axis == 0 ? points[i].u : points[i].v;
    const double to = from + (axis == 0 ? bestOffset.u : bestOffset.v);
    if (to < 0.0 || to >= 1.0) samples.acrossEdge.push_back(best);
    if ((from < 0.5) != (to < 0.5)) samples.acrossMiddle.push_back(best);
  }
}

// No seam: the nearest-neighbour distances of points whose neighbour is across a tile edge are
// distributed as those whose neighbour is across the line through the middle of the tile (the
// same selection, so the same bias toward longer distances, without an edge). Pooled over seeds;
// the bound is the two-sample KS critical value at α = 0.001.
TEST(PointDiffusionTest, NoSeamWhereTilesMeet) {
  for (int axis : {0, 1}) {
    SeamSamples samples;
    for (std::uint64_t seed = 1; seed <= 30; ++seed) {
      const PointDiffusionTexture texture = PointDiffusionTexture::generate({100, 100, 0.1, seed});
      collectSeamSamples(texture.positions(), axis, samples);
    }
    const double n = static_cast<double>(samples.acrossEdge.size());
    const double m = static_cast<double>(samples.acrossMiddle.size());
    ASSERT_GT(n, 200);
    ASSERT_GT(m, 200);
    const double bound = 1.95 * std::sqrt((n + m) / (n * m));
    const double statistic = ksStatistic(samples.acrossEdge, samples.acrossMiddle);
    EXPECT_LT(statistic, bound) << (axis == 0 ? "u" : "v") << " edge: " << n << " vs " << m
                                << " samples";
    // Printed so that the margin is visible in the test log.
    std::printf("seam along %s: KS %.4f, bound %.4f (%g / %g samples)\n", axis == 0 ? "u" : "v",
                statistic, bound, n, m);
  }
}

}  // namespace
}  // namespace hirsute
