// Barbs between key barbs (Streit & Heidrich 2002, Sec. 4.2.1): the blend of the key barbs below
// and above, the defaults Bdf1 and Bdf2 where one is missing, and the Bdf1 table's seed.
#include "hirsute/hairs/feathers/barb_interpolation.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <vector>

#include "hirsute/hairs/feathers/bezier_curve.h"
#include "hirsute/hairs/feathers/default_barbs.h"

namespace hirsute {
namespace {

KeyBarb keyBarb(BarbSide side, float position, std::vector<glm::vec3> vertices) {
  KeyBarb key;
  key.side = side;
  key.position = position;
  key.vertices = std::move(vertices);
  return key;
}

// A quadratic key barb at 0.25 and a quartic one at 0.75, on both vanes.
FeatherType twoKeyBarbs() {
  FeatherType type;
  type.keyBarbs.push_back(keyBarb(BarbSide::Both, 0.25f, {{0, 0, 0}, {0.5f, 0.3f, 0}, {1, 0, 0}}));
  type.keyBarbs.push_back(
      keyBarb(BarbSide::Both, 0.75f,
              {{0, 0, 0}, {0.2f, -0.1f, 0.1f}, {0.5f, 0.2f, 0.2f}, {0.8f, 0, 0.1f}, {0.9f, 0, 0}}));
  return type;
}

TEST(BarbInterpolation, InterpolatedBarbsEqualTheKeyBarbsAtTheirPositions) {
  const FeatherType type = twoKeyBarbs();
  const PlumulaceousBarbTable table(type.seed);
  const VaneKeyBarbs left(type, BarbSide::Left);
  EXPECT_EQ(left.barbAt(0.25f, 3, table).vertices, type.keyBarbs[0].vertices);
  EXPECT_EQ(left.barbAt(0.75f, 9, table).vertices, type.keyBarbs[1].vertices);
}

TEST(BarbInterpolation, InterpolatedBarbsLieBetweenTheKeyBarbs) {
  const FeatherType type = twoKeyBarbs();
  const PlumulaceousBarbTable table(type.seed);
  const VaneKeyBarbs right(type, BarbSide::Right);
  const std::vector<glm::vec3>& below = type.keyBarbs[0].vertices;
  const std::vector<glm::vec3>& above = type.keyBarbs[1].vertices;
  for (float position : {0.3f, 0.5f, 0.7f}) {
    const float t = (position - 0.25f) / 0.5f;
    const BarbCurve barb = right.barbAt(position, 5, table);
    ASSERT_EQ(barb.vertices.size(), above.size());  // the quadratic was elevated to a quartic
    for (int i = 0; i <= 200; ++i) {
      const double u = i / 200.0;
      const glm::dvec3 a = bezierPoint(below, u);
      const glm::dvec3 b = bezierPoint(above, u);
      const glm::dvec3 p = bezierPoint(barb.vertices, u);
      // On the segment between the two key curves' points, at t of the way.
      EXPECT_LT(glm::length(p - ((1.0 - t) * a + double(t) * b)), 1e-6) << position << " " << u;
      for (int c = 0; c < 3; ++c) {
        EXPECT_GE(p[c], std::min(a[c], b[c]) - 1e-6);
        EXPECT_LE(p[c], std::max(a[c], b[c]) + 1e-6);
      }
    }
  }
}

TEST(BarbInterpolation, DefaultBarbsStandBelowAndAboveTheKeyBarbs) {
  const FeatherType type = twoKeyBarbs();
  const PlumulaceousBarbTable table(type.seed);
  const VaneKeyBarbs left(type, BarbSide::Left);
  // At the base, Bdf1 of that barb; at the tip, Bdf2.
  const std::span<const glm::vec3> bdf1 = table.barb(0, BarbSide::Left);
  EXPECT_EQ(left.barbAt(0, 0, table).vertices, std::vector<glm::vec3>(bdf1.begin(), bdf1.end()));
  const std::vector<glm::vec3> tip = left.barbAt(1, 40, table).vertices;
  const std::vector<glm::vec3> bdf2 = elevateBezierTo(pennaceousDefaultBarb(), tip.size());
  ASSERT_EQ(tip.size(), bdf2.size());
  for (std::size_t i = 0; i < tip.size(); ++i) EXPECT_LT(glm::length(tip[i] - bdf2[i]), 1e-6f);
}

TEST(BarbInterpolation, WithoutKeyBarbsEveryBarbIsPlumulaceous) {
  const FeatherType type;  // no key barbs: down
  const PlumulaceousBarbTable table(type.seed);
  const VaneKeyBarbs left(type, BarbSide::Left);
  for (std::size_t k = 0; k < 10; ++k) {
    const std::span<const glm::vec3> bdf1 = table.barb(k, BarbSide::Left);
    EXPECT_EQ(left.barbAt(k / 10.0f, k, table).vertices,
              std::vector<glm::vec3>(bdf1.begin(), bdf1.end()));
  }
}

TEST(BarbInterpolation, KeyBarbsApplyToTheirSideOnly) {
  FeatherType type;
  type.keyBarbs.push_back(keyBarb(BarbSide::Right, 0.5f, {{0, 0, 0}, {1, 0, 0}}));
  EXPECT_TRUE(VaneKeyBarbs(type, BarbSide::Left).keys().empty());
  EXPECT_EQ(VaneKeyBarbs(type, BarbSide::Right).keys().size(), 1u);
}

TEST(BarbInterpolation, AngleIsInterpolatedFromBaseToTip) {
  FeatherType type;
  type.left.baseAngle = 100;
  type.left.tipAngle = 160;
  const PlumulaceousBarbTable table(type.seed);
  const VaneKeyBarbs left(type, BarbSide::Left);
  EXPECT_FLOAT_EQ(left.barbAt(0, 0, table).angle, 100);
  EXPECT_FLOAT_EQ(left.barbAt(0.5f, 0, table).angle, 130);
  EXPECT_FLOAT_EQ(left.barbAt(1, 0, table).angle, 160);
}

TEST(BarbInterpolation, SameSeedSameTableDifferentSeedDifferentBdf1) {
  const PlumulaceousBarbTable a(3), b(3), c(4);
  bool differs = false;
  for (std::size_t k = 0; k < 20; ++k) {
    const auto va = a.barb(k, BarbSide::Left);
    const auto vb = b.barb(k, BarbSide::Left);
    const auto vc = c.barb(k, BarbSide::Left);
    for (std::size_t i = 0; i < va.size(); ++i) {
      EXPECT_EQ(va[i], vb[i]);
      differs = differs || va[i] != vc[i];
    }
    // Every Bdf1 keeps |cv0 cvn| in [0.7, 1] (Sec. 4.1 clamps it to [0, 1]).
    const float chord = glm::length(va.back() - va.front());
    EXPECT_GE(chord, 0.7f - 1e-6f);
    EXPECT_LE(chord, 1.0f + 1e-6f);
  }
  EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace hirsute
