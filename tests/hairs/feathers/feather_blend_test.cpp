// Blending feather types (Streit & Heidrich 2002, Sec. 4.2.3) and growth (Sec. 4.2.4), measured
// on the parameters and on the geometry built from them.
#include "hirsute/hairs/feathers/feather_file.h"
#include "hirsute/hairs/feathers/feather_blend.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <glm/geometric.hpp>

#include "hirsute/hairs/feathers/barb_interpolation.h"
#include "hirsute/hairs/feathers/default_barbs.h"
#include "hirsute/hairs/feathers/feather_geometry.h"
#include "hirsute/hairs/feathers/silhouette.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
const fs::path kFixtures = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "feathers";

FeatherType load(const std::string& name) {
  Diagnostics diagnostics;
  return loadFeatherType(kFixtures / name, diagnostics);
}

KeyBarb keyBarb(BarbSide side, float position, std::vector<glm::vec3> vertices) {
  KeyBarb key;
  key.side = side;
  key.position = position;
  key.vertices = std::move(vertices);
  return key;
}

void expectSameGeometry(const FeatherGeometry& a, const FeatherGeometry& b) {
  EXPECT_EQ(a.shaft.positions, b.shaft.positions);
  EXPECT_EQ(a.shaft.normals, b.shaft.normals);
  EXPECT_EQ(a.vertices.positions, b.vertices.positions);
  EXPECT_EQ(a.vertices.vaneUv, b.vertices.vaneUv);
  EXPECT_EQ(a.vertices.growthUv, b.vertices.growthUv);
  EXPECT_EQ(a.vertices.stripSides, b.vertices.stripSides);
  ASSERT_EQ(a.afterfeathers.size(), b.afterfeathers.size());
  for (std::size_t i = 0; i < a.afterfeathers.size(); ++i) {
    expectSameGeometry(a.afterfeathers[i], b.afterfeathers[i]);
  }
}

// The largest distance between corresponding barb vertices of two feathers of equal barb count.
float largestBarbDistance(const FeatherGeometry& a, const FeatherGeometry& b) {
  EXPECT_EQ(a.vertices.positions.size(), b.vertices.positions.size());
  float worst = 0;
  for (std::size_t i = 0; i < std::min(a.vertices.positions.size(), b.vertices.positions.size());
       ++i) {
    worst = std::max(worst, glm::length(a.vertices.positions[i] - b.vertices.positions[i]));
  }
  return worst;
}

TEST(FeatherBlend, BlendAtZeroAndOneGivesTheTwoTypesExactly) {
  const FeatherType contour = load("contour.fea");
  const FeatherType down = load("down.fea");
  const FeatherDetail detail{10, 6, 5};
  expectSameGeometry(buildFeatherGeometry(blendFeatherTypes(contour, down, 0), detail),
                     buildFeatherGeometry(contour, detail));
  expectSameGeometry(buildFeatherGeometry(blendFeatherTypes(contour, down, 1), detail),
                     buildFeatherGeometry(down, detail));
  // Outside [0, 1] is clamped.
  expectSameGeometry(buildFeatherGeometry(blendFeatherTypes(contour, down, -2), detail),
                     buildFeatherGeometry(contour, detail));
}

TEST(FeatherBlend, ParametersInterpolateLinearly) {
  const FeatherType a = load("contour.fea");
  const FeatherType b = load("down.fea");
  const FeatherType half = blendFeatherTypes(a, b, 0.25f);
  EXPECT_FLOAT_EQ(half.rachisLength, 0.75f * 1.2f + 0.25f * 0.3f);
  EXPECT_FLOAT_EQ(half.calamusLength, 0.75f * 0.15f + 0.25f * 0.05f);
  EXPECT_FLOAT_EQ(half.rachisWidth, 0.75f * 0.03f + 0.25f * 0.01f);
  EXPECT_FLOAT_EQ(half.rachisSideCurvature, 0.75f * 0.1f);
  EXPECT_FLOAT_EQ(half.barbSpacingTip, 0.75f * 0.01f + 0.25f * 0.01f);
  EXPECT_FLOAT_EQ(half.left.baseAngle, 0.75f * 110 + 0.25f * 120);
  EXPECT_FLOAT_EQ(half.right.tipAngle, 0.75f * 150 + 0.25f * 150);
  // The left silhouette against down's constant 0.25: the blend of the two lengths everywhere.
  for (float p : {0.0f, 0.1f, 0.3f, 0.55f, 0.8f, 0.95f, 1.0f}) {
    EXPECT_NEAR(vaneBarbLength(half.left, p),
                0.75f * vaneBarbLength(a.left, p) + 0.25f * vaneBarbLength(b.left, p), 1e-6f);
  }
  EXPECT_FLOAT_EQ(half.right.barbLength, 0.75f * 0.35f + 0.25f * 0.25f);
  // The afterfeather only a has shrinks towards b.
  ASSERT_TRUE(half.afterfeather);
  EXPECT_FLOAT_EQ(half.afterfeatherSize, 0.75f * 0.4f);
  EXPECT_EQ(half.seed, a.seed);
}

TEST(FeatherBlend, SmallerKeyBarbSetIsInflatedByNearestPosition) {
  FeatherType a, b;
  a.keyBarbs = {keyBarb(BarbSide::Both, 0.2f, {{0, 0, 0}, {1, 0, 0}}),
                keyBarb(BarbSide::Both, 0.8f, {{0, 0, 0}, {0.5f, 0.2f, 0}, {1, 0, 0}})};
  b.keyBarbs = {keyBarb(BarbSide::Both, 0.1f, {{0, 0, 0}, {0.9f, 0, 0}}),
                keyBarb(BarbSide::Both, 0.3f, {{0, 0, 0}, {0.8f, 0, 0}}),
                keyBarb(BarbSide::Both, 0.4f, {{0, 0, 0}, {0.7f, 0, 0}}),
                keyBarb(BarbSide::Both, 0.9f, {{0, 0, 0}, {0.6f, 0, 0}})};
  const FeatherType mid = blendFeatherTypes(a, b, 0.5f);
  // Four key barbs a vane; a's 0.2 pairs with b's 0.1, 0.3 and 0.4, a's 0.8 with b's 0.9.
  ASSERT_EQ(mid.keyBarbs.size(), 8u);
  const float expected[] = {0.15f, 0.25f, 0.3f, 0.85f};
  for (int side = 0; side < 2; ++side) {
    for (int k = 0; k < 4; ++k) {
      const KeyBarb& key = mid.keyBarbs[static_cast<std::size_t>(side * 4 + k)];
      EXPECT_EQ(key.side, side == 0 ? BarbSide::Left : BarbSide::Right);
      EXPECT_FLOAT_EQ(key.position, expected[k]);
    }
  }
  // The last pair blends a quadratic with a line elevated to it.
  const KeyBarb& last = mid.keyBarbs[3];
  ASSERT_EQ(last.vertices.size(), 3u);
  EXPECT_FLOAT_EQ(last.vertices[1].y, 0.1f);
  EXPECT_FLOAT_EQ(last.vertices[2].x, 0.8f);
}

TEST(FeatherBlend, DownAgainstKeyBarbsMixesInThePlumulaceousBarb) {
  FeatherType a;  // down: no key barbs
  FeatherType b;
  b.keyBarbs = {keyBarb(BarbSide::Both, 0.5f, {{0, 0, 0}, {1, 0, 0}})};
  const FeatherType mid = blendFeatherTypes(a, b, 0.25f);
  // Per vane: the key barb and Bdf2 at the tip, each paired with a fully plumulaceous copy.
  ASSERT_EQ(mid.keyBarbs.size(), 4u);
  EXPECT_FLOAT_EQ(mid.keyBarbs[0].plumulaceous, 0.75f);
  EXPECT_FLOAT_EQ(mid.keyBarbs[0].position, 0.5f);
  EXPECT_FLOAT_EQ(mid.keyBarbs[1].plumulaceous, 0.75f);
  EXPECT_FLOAT_EQ(mid.keyBarbs[1].position, 1);
}

TEST(FeatherBlend, BlendIsContinuousNearTheEnds) {
  FeatherType a = load("contour.fea");
  FeatherType b = load("down.fea");
  // The same rachis and spacing, so that the barb count is the same throughout.
  b.rachisLength = a.rachisLength;
  b.barbSpacingBase = a.barbSpacingBase;
  b.barbSpacingTip = a.barbSpacingTip;
  b.seed = a.seed;
  const FeatherDetail detail{8, 6, 4};
  const FeatherGeometry atA = buildFeatherGeometry(a, detail);
  const FeatherGeometry atB = buildFeatherGeometry(b, detail);
  EXPECT_LT(largestBarbDistance(buildFeatherGeometry(blendFeatherTypes(a, b, 1e-4f), detail), atA),
            1e-3f);
  EXPECT_LT(
      largestBarbDistance(buildFeatherGeometry(blendFeatherTypes(a, b, 1 - 1e-4f), detail), atB),
      1e-3f);
}

// Bdf1 blends with the shape: across a row of blends of two down types that differ only in
// their seed, neighbouring feathers differ by as little on either side of the middle as
// elsewhere (the nearer type's seed made the barbs jump at t = 0.5).
TEST(FeatherBlend, DefaultBarbsBlendWithoutAJumpInTheMiddle) {
  FeatherType a = load("down.fea");
  FeatherType b = a;
  b.seed = a.seed + 77;
  const FeatherDetail detail{8, 6, 4};
  float largestStep = 0, middleStep = 0;
  constexpr int kSteps = 20;
  FeatherGeometry previous = buildFeatherGeometry(a, detail);
  for (int i = 1; i <= kSteps; ++i) {
    const float t = static_cast<float>(i) / kSteps;
    const FeatherGeometry next = buildFeatherGeometry(blendFeatherTypes(a, b, t), detail);
    const float step = largestBarbDistance(next, previous);
    // The two steps about t = 0.5, and the others.
    const bool middle = i == kSteps / 2 || i == kSteps / 2 + 1;
    (middle ? middleStep : largestStep) = std::max(middle ? middleStep : largestStep, step);
    previous = next;
  }
  // The two types differ: the ends are far apart.
  const float apart = largestBarbDistance(buildFeatherGeometry(a, detail), buildFeatherGeometry(b, detail));
  EXPECT_GT(apart, 4 * largestStep);
  EXPECT_LT(middleStep, 1.5f * largestStep) << "a jump in the middle of the row";
}

TEST(FeatherGrowth, GrowthAtAgeOneGivesTheGrownFeather) {
  const FeatherType contour = load("contour.fea");
  const FeatherDetail detail{10, 6, 5};
  expectSameGeometry(buildFeatherGeometry(grownFeatherType(contour, 1), detail),
                     buildFeatherGeometry(contour, detail));
  expectSameGeometry(buildFeatherGeometry(grownFeatherType(contour, 7), detail),
                     buildFeatherGeometry(contour, detail));
}

TEST(FeatherGrowth, RachisLengthIsMonotoneInAge) {
  const FeatherType contour = load("contour.fea");
  float previousLength = -1;
  float previousTip = -1;
  for (int i = 0; i <= 100; ++i) {
    const float age = i / 100.0f;
    const FeatherType young = grownFeatherType(contour, age);
    EXPECT_GE(young.rachisLength, previousLength) << age;
    previousLength = young.rachisLength;
    const float tip = buildFeatherGeometry(young, {}).shaftAxis.back().z;
    EXPECT_GE(tip, previousTip - 1e-6f) << age;
    previousTip = tip;
  }
  // The shaft is grown at 30%, and nothing grows before it.
  EXPECT_FLOAT_EQ(grownFeatherType(contour, 0.3f).rachisLength, contour.rachisLength);
  EXPECT_FLOAT_EQ(grownFeatherType(contour, 0.3f).rachisWidth, contour.rachisWidth);
  EXPECT_EQ(grownFeatherType(contour, 0).rachisLength, 0);
}

TEST(FeatherGrowth, ScheduleOfSection424) {
  const FeatherType contour = load("contour.fea");
  // Barbs lengthen between 30% and 50%.
  EXPECT_EQ(grownFeatherType(contour, 0.3f).right.barbLength, 0);
  EXPECT_FLOAT_EQ(grownFeatherType(contour, 0.4f).right.barbLength, 0.5f * 0.35f);
  EXPECT_FLOAT_EQ(grownFeatherType(contour, 0.5f).right.barbLength, 0.35f);
  // Until 80% the barbs lie in the sheath and the rachis is straight; curvature rises after.
  const FeatherType sheathed = grownFeatherType(contour, 0.6f);
  EXPECT_EQ(sheathed.left.baseAngle, 180);
  EXPECT_EQ(sheathed.rachisSideCurvature, 0);
  const FeatherType rising = grownFeatherType(contour, 0.9f);
  EXPECT_FLOAT_EQ(rising.rachisSideCurvature, 0.5f * 0.1f);
  EXPECT_FLOAT_EQ(rising.left.baseAngle, 0.5f * 180 + 0.5f * 110);
  // Four extra key barbs a vane; the migrating one from the tip (50%) to the base (80%), the
  // sheath's edge just below it.
  const auto migrating = [](const FeatherType& type) { return type.keyBarbs[2].position; };
  EXPECT_EQ(grownFeatherType(contour, 0.5f).keyBarbs.size(), 4u * 2 + 1 + 2);
  EXPECT_FLOAT_EQ(migrating(grownFeatherType(contour, 0.5f)), 1);
  EXPECT_FLOAT_EQ(migrating(grownFeatherType(contour, 0.65f)), 0.5f);
  EXPECT_FLOAT_EQ(migrating(grownFeatherType(contour, 0.8f)), 0);
  // Its angle is the grown vane's where it stands; the tip, which it has passed, is open at the
  // grown vane's angle; the base and the sheath's edge are closed at 180°.
  const FeatherType opening = grownFeatherType(contour, 0.65f);
  EXPECT_FLOAT_EQ(*opening.keyBarbs[2].angle, 0.5f * 110 + 0.5f * 155);
  EXPECT_EQ(*opening.keyBarbs[0].angle, 180);
  EXPECT_FLOAT_EQ(*opening.keyBarbs[1].angle, 155);
  EXPECT_EQ(*opening.keyBarbs[3].angle, 180);
  EXPECT_LT(opening.keyBarbs[3].position, 0.5f);
  // The feather's own key barbs are straight in the sheath.
  const KeyBarb& own = opening.keyBarbs[4];
  ASSERT_EQ(own.vertices.size(), 4u);
  EXPECT_NEAR(own.vertices[1].y, 0, 1e-7f);
  EXPECT_NEAR(own.vertices[1].z, 0, 1e-7f);
  // The barb count stays the grown feather's.
  EXPECT_EQ(barbPositions(grownFeatherType(contour, 0.2f)).size(), barbPositions(contour).size());
}

// The share of a vane's barbs that have left the sheath (their angle below 170°, 180° lying
// along the rachis), over 400 positions, and whether they are all above the closed ones.
struct Opening {
  float fraction = 0;
  bool tipFirst = true;
};
Opening openingOf(const FeatherType& type, BarbSide side) {
  const VaneKeyBarbs vane(type, side);
  const PlumulaceousBarbTable table(type.seed);
  Opening out;
  bool sawOpen = false;
  int open = 0;
  constexpr int kPositions = 400;
  for (int i = 0; i < kPositions; ++i) {
    const float position = (static_cast<float>(i) + 0.5f) / kPositions;
    const bool isOpen = vane.barbAt(position, static_cast<std::size_t>(i), table).angle < 170;
    if (sawOpen && !isOpen) out.tipFirst = false;  // a closed barb above an open one
    sawOpen = sawOpen || isOpen;
    open += isOpen ? 1 : 0;
  }
  out.fraction = static_cast<float>(open) / kPositions;
  return out;
}

// Sec. 4.2.4, Figs. 6–7: the sheath opens from the tip; a barb that has broken out stays open,
// so the open share of each vane grows with age, from none before 50% to all at 80%, and the
// open barbs are always those nearest the tip.
TEST(FeatherGrowth, TheVaneOpensFromTheTipAndStaysOpen) {
  const FeatherType contour = load("contour.fea");
  for (BarbSide side : {BarbSide::Left, BarbSide::Right}) {
    float previous = 0;
    for (int i = 0; i <= 40; ++i) {
      const float age = static_cast<float>(i) / 40;
      const Opening opening = openingOf(grownFeatherType(contour, age), side);
      EXPECT_TRUE(opening.tipFirst) << "age " << age;
      EXPECT_GE(opening.fraction, previous - 1e-6f) << "age " << age;
      previous = opening.fraction;
      if (age <= 0.5f) {
        EXPECT_EQ(opening.fraction, 0) << "age " << age;
      }
      if (age >= 0.8f) {
        EXPECT_EQ(opening.fraction, 1) << "age " << age;
      }
      // Between, the front stands at 1 − (age − 0.5)/0.3 of the vane, and the barbs are
      // open above it and on part of the sheath's short edge below it.
      if (age > 0.55f && age < 0.75f) {
        const float above = (age - 0.5f) / 0.3f;
        EXPECT_GE(opening.fraction, above - 0.01f) << "age " << age;
        EXPECT_LE(opening.fraction, above + 0.07f) << "age " << age;
      }
    }
  }
}

TEST(FeatherGrowth, GrowthIsContinuousUpToTheGrownFeather) {
  FeatherType contour = load("contour.fea");
  contour.barbSpacingTip = contour.barbSpacingBase;  // a count that rounding cannot change
  const FeatherDetail detail{8, 6, 4};
  const FeatherGeometry grown = buildFeatherGeometry(contour, detail);
  const FeatherGeometry almost = buildFeatherGeometry(grownFeatherType(contour, 0.9999f), detail);
  EXPECT_LT(largestBarbDistance(almost, grown), 1e-3f);
}

}  // namespace
}  // namespace hirsute
