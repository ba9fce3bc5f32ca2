// Feather geometry (Streit & Heidrich 2002, Sec. 4.3) in the local frame of feather_geometry.h:
// barb count and angles, silhouettes, the rachis Bézier and shaft tube, level of detail, strips,
// texture coordinates, the afterfeather and the seed, all measured.
#include "hirsute/hairs/feathers/feather_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <numbers>

#include "hirsute/hairs/feathers/feather_file.h"
#include "hirsute/hairs/feathers/silhouette.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
const fs::path kFixtures = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "feathers";

// A straight rachis (no curvature), so the vane plane is exactly the z–y plane.
FeatherType straightFeather() {
  FeatherType type;
  type.calamusLength = 0.1f;
  type.rachisLength = 1.0f;
  type.rachisWidth = 0.02f;
  type.barbSpacingBase = type.barbSpacingTip = 0.05f;
  return type;
}

KeyBarb straightKeyBarb(BarbSide side, float position) {
  KeyBarb key;
  key.side = side;
  key.position = position;
  key.vertices = {{0, 0, 0}, {1, 0, 0}};
  return key;
}

glm::vec3 first(const FeatherGeometry& g, const Barb& b) {
  return g.vertices.positions[b.firstVertex];
}
glm::vec3 last(const FeatherGeometry& g, const Barb& b) {
  return g.vertices.positions[b.firstVertex + b.vertexCount - 1];
}

std::size_t countSide(const FeatherGeometry& g, BarbSide side) {
  std::size_t n = 0;
  for (const Barb& b : g.barbs) n += b.side == side ? 1 : 0;
  return n;
}

TEST(FeatherGeometry, BarbCountFollowsRachisLengthAndSpacing) {
  FeatherType type = straightFeather();
  for (const auto& [rl, sp] :
       {std::pair{1.0f, 0.05f}, {1.0f, 0.03f}, {2.5f, 0.1f}, {0.3f, 0.01f}}) {
    type.rachisLength = rl;
    type.barbSpacingBase = type.barbSpacingTip = sp;
    const FeatherGeometry g = buildFeatherGeometry(type, {});
    const std::size_t expected = static_cast<std::size_t>(std::floor(rl / sp + 1e-6)) + 1;
    EXPECT_EQ(countSide(g, BarbSide::Left), expected) << rl << " / " << sp;
    EXPECT_EQ(countSide(g, BarbSide::Right), expected) << rl << " / " << sp;
  }
  // Spacing growing from spb to spt: about rl ∫ dr / sp(r) = rl ln(spt/spb) / (spt - spb) gaps.
  type.rachisLength = 1;
  type.barbSpacingBase = 0.01f;
  type.barbSpacingTip = 0.04f;
  const double gaps = std::log(0.04 / 0.01) / (0.04 - 0.01);
  const std::vector<float> positions = barbPositions(type);
  EXPECT_NEAR(static_cast<double>(positions.size()), gaps + 1, 1.5);
  // Neighbouring barbs are the spacing at the lower one apart.
  for (std::size_t k = 1; k < positions.size(); ++k) {
    const float rp = positions[k - 1];
    EXPECT_NEAR(positions[k] - rp, 0.01f + rp * 0.03f, 1e-5f);
  }
  type.rachisLength = 0;
  EXPECT_TRUE(buildFeatherGeometry(type, {}).barbs.empty());
}

// The angle of a barb's chord to the rachis direction towards the base (-z), in degrees.
double chordAngle(const FeatherGeometry& g, const Barb& b) {
  const glm::dvec3 chord = glm::normalize(glm::dvec3(last(g, b) - first(g, b)));
  return std::acos(glm::dot(chord, glm::dvec3(0, 0, -1))) * 180 / std::numbers::pi;
}

TEST(FeatherGeometry, BarbAnglesAtBaseAndTip) {
  FeatherType type = straightFeather();
  type.left.baseAngle = 100;
  type.left.tipAngle = 160;
  type.right.baseAngle = 120;
  type.right.tipAngle = 140;
  // Down (random Bdf1 barbs, chords out of the vane plane) and a pennaceous feather.
  for (bool withKeyBarbs : {false, true}) {
    if (withKeyBarbs) {
      KeyBarb curved;
      curved.side = BarbSide::Both;
      curved.position = 0.5f;
      curved.vertices = {{0, 0, 0}, {0.3f, 0.2f, 0.1f}, {0.7f, 0.3f, -0.1f}, {0.9f, 0.3f, 0.2f}};
      type.keyBarbs = {curved};
    }
    const FeatherGeometry g = buildFeatherGeometry(type, {});
    for (const Barb& b : g.barbs) {
      const glm::vec3 chord = last(g, b) - first(g, b);
      EXPECT_NEAR(chord.x, 0, 1e-5f);                               // in the vane plane
      EXPECT_GT(b.side == BarbSide::Left ? chord.y : -chord.y, 0);  // on its own side
      const Vane& vane = type.vane(b.side);
      const double expected = (1 - b.position) * vane.baseAngle + b.position * vane.tipAngle;
      EXPECT_NEAR(chordAngle(g, b), expected, 0.1) << b.position;
    }
    const Barb& leftBase = g.barbs.front();
    const Barb& leftTip = g.barbs[countSide(g, BarbSide::Left) - 1];
    EXPECT_EQ(leftBase.position, 0);
    EXPECT_EQ(leftTip.position, 1);
    EXPECT_NEAR(chordAngle(g, leftBase), 100, 0.1);
    EXPECT_NEAR(chordAngle(g, leftTip), 160, 0.1);
    EXPECT_NEAR(chordAngle(g, g.barbs[countSide(g, BarbSide::Left)]), 120, 0.1);
    EXPECT_NEAR(chordAngle(g, g.barbs.back()), 140, 0.1);
  }
}

TEST(FeatherGeometry, BarbsHangFromTheRachis) {
  FeatherType type = straightFeather();
  type.rachisSideCurvature = 0.3f;
  type.rachisFrontCurvature = 0.2f;
  const FeatherGeometry g = buildFeatherGeometry(type, {});
  for (const Barb& b : g.barbs) {
    // On the rachis Bézier of Sec. 4.3.1 at parameter rp: z = cl + rl·rp, x and y 3t(1-t)·c·rl.
    const float t = b.position;
    const glm::vec3 attach = first(g, b);
    EXPECT_NEAR(attach.z, 0.1f + t, 1e-5f);
    EXPECT_NEAR(attach.x, 3 * t * (1 - t) * 0.2f, 1e-5f);
    EXPECT_NEAR(attach.y, 3 * t * (1 - t) * 0.3f, 1e-5f);
  }
}

TEST(FeatherGeometry, RachisIsTheBezierOfSection431) {
  FeatherType type = straightFeather();
  type.calamusLength = 0.2f;
  type.rachisLength = 1.5f;
  type.rachisSideCurvature = 0.2f;
  type.rachisFrontCurvature = -0.1f;
  const FeatherGeometry g = buildFeatherGeometry(type, FeatherDetail{4, 3, 3});
  ASSERT_EQ(g.shaftAxis.size(), 6u);  // the calamus base, then 5 rachis rings
  EXPECT_EQ(g.shaftAxis[0], glm::vec3(0, 0, 0));
  EXPECT_NEAR(glm::length(g.shaftAxis[1] - glm::vec3(0, 0, 0.2f)), 0, 1e-6f);
  EXPECT_NEAR(glm::length(g.shaftAxis[5] - glm::vec3(0, 0, 1.7f)), 0, 1e-6f);
  // The middle: (cv0 + 3cv1 + 3cv2 + cv3) / 8 = (0.75 rvdc rl, 0.75 rlc rl, cl + rl/2).
  const glm::vec3 middle = g.shaftAxis[3];
  EXPECT_NEAR(middle.x, 0.75f * -0.1f * 1.5f, 1e-6f);
  EXPECT_NEAR(middle.y, 0.75f * 0.2f * 1.5f, 1e-6f);
  EXPECT_NEAR(middle.z, 0.2f + 0.75f, 1e-6f);
}

TEST(FeatherGeometry, ShaftTapersToAPointAndMeetsTheCalamus) {
  FeatherType type = straightFeather();
  type.calamusWidthRatio = 0.5f;
  const int sides = 5;
  const FeatherGeometry g = buildFeatherGeometry(type, FeatherDetail{4, 3, sides});
  const FeatherMesh& mesh = g.shaft;
  // Rings: calamus base, calamus top, then 5 rachis rings.
  ASSERT_EQ(mesh.positions.size(), static_cast<std::size_t>(7 * sides));
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  EXPECT_EQ(mesh.indices.size(), static_cast<std::size_t>(5 * sides * 6));
  const auto radiusOfRing = [&](int ring) {
    const glm::vec3 p = mesh.positions[static_cast<std::size_t>(ring * sides)];
    return std::hypot(p.x, p.y);
  };
  EXPECT_NEAR(radiusOfRing(0), 0.5f * 0.01f, 1e-7f);  // cwr · rw/2 at the calamus base
  EXPECT_NEAR(radiusOfRing(1), 0.01f, 1e-7f);         // rw/2 at the calamus top...
  EXPECT_NEAR(radiusOfRing(2), 0.01f, 1e-7f);         // ...and at the rachis base
  EXPECT_NEAR(radiusOfRing(4), 0.005f, 1e-7f);        // half way
  EXPECT_NEAR(radiusOfRing(6), 0, 1e-7f);             // a point at the tip
  for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
    EXPECT_NEAR(glm::length(mesh.normals[i]), 1, 1e-5f);
    const glm::vec3 radial(mesh.positions[i].x, mesh.positions[i].y, 0);
    if (glm::length(radial) > 1e-6f) {  // outward
      EXPECT_GT(glm::dot(mesh.normals[i], radial), 0);
    }
  }
  // Counter-clockwise from outside: every triangle's normal points away from the axis.
  for (std::size_t i = 0; i + 2 < 2 * sides * 6; i += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[i]];
    const glm::vec3 b = mesh.positions[mesh.indices[i + 1]];
    const glm::vec3 c = mesh.positions[mesh.indices[i + 2]];
    const glm::vec3 centre = (a + b + c) / 3.0f;
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), glm::vec3(centre.x, centre.y, 0)), 0);
  }
}

TEST(FeatherGeometry, LevelOfDetailSetsTheTessellation) {
  const FeatherType type = straightFeather();
  for (const FeatherDetail detail : {FeatherDetail{3, 3, 3}, FeatherDetail{20, 12, 9}}) {
    const FeatherGeometry g = buildFeatherGeometry(type, detail);
    for (const Barb& b : g.barbs) {
      EXPECT_EQ(b.vertexCount, static_cast<std::uint32_t>(detail.barbSegments + 1));
    }
    EXPECT_EQ(g.shaft.positions.size(),
              static_cast<std::size_t>((detail.rachisSegments + 3) * detail.shaftSides));
  }
  // A triangle at the least; detail grows with the projected size.
  EXPECT_EQ(buildFeatherGeometry(type, FeatherDetail{1, 1, 1}).shaft.positions.size(), 12u);
  const FeatherDetail small = featherDetailForProjectedLength(4);
  EXPECT_EQ(small.rachisSegments, 3);
  EXPECT_EQ(small.barbSegments, 3);
  EXPECT_EQ(small.shaftSides, 3);
  const FeatherDetail large = featherDetailForProjectedLength(800);
  EXPECT_GT(large.rachisSegments, small.rachisSegments);
  EXPECT_GT(large.barbSegments, small.barbSegments);
  EXPECT_GT(large.shaftSides, small.shaftSides);
}

TEST(FeatherGeometry, SilhouetteLengthsTouchTheSilhouetteBoundary) {
  FeatherType type = straightFeather();
  type.barbSpacingBase = type.barbSpacingTip = 0.01f;
  // Straight key barbs of chord 1 everywhere, so a barb's tip is its length from the rachis.
  type.keyBarbs = {straightKeyBarb(BarbSide::Both, 0), straightKeyBarb(BarbSide::Both, 1)};
  // A square-shouldered left vane with a step at 0.5 (two points at one position).
  type.left.silhouette = {{0, 0.1f}, {0.3f, 0.4f}, {0.5f, 0.4f}, {0.5f, 0.15f}, {1, 0.05f}};
  type.right.barbLength = 0.25f;
  const FeatherGeometry g = buildFeatherGeometry(type, {});
  std::size_t checked = 0;
  for (const Barb& b : g.barbs) {
    const float reach = glm::length(last(g, b) - first(g, b));
    if (b.side == BarbSide::Right) {
      EXPECT_NEAR(reach, 0.25f, 1e-5f);
      continue;
    }
    // The tip on the boundary polyline through the points (position, length).
    EXPECT_NEAR(reach, silhouetteLength(type.left.silhouette, b.position), 1e-5f) << b.position;
    for (const SilhouettePoint& p : type.left.silhouette) {
      if (std::abs(b.position - p.position) < 1e-6f && p.position != 0.5f) {
        EXPECT_NEAR(reach, p.length, 1e-5f);
        ++checked;
      }
    }
    if (b.position > 0.305f && b.position < 0.495f) {
      EXPECT_NEAR(reach, 0.4f, 1e-5f);
    }
    if (std::abs(b.position - 0.5f) < 1e-6f) {  // after the step
      EXPECT_NEAR(reach, 0.15f, 1e-5f);
    }
    if (b.position > 0.45f && b.position < 0.495f) {  // before it
      EXPECT_GT(reach, 0.39f);
    }
  }
  EXPECT_EQ(checked, 3u);  // the barbs at 0, 0.3 and 1
}

TEST(FeatherGeometry, ChordShorterThanOneScalesTheBarbNonLinearly) {
  // Sec. 4.2.1: a key barb's chord below 1 makes its barbs shorter than the barb length.
  FeatherType type = straightFeather();
  KeyBarb shortBarb = straightKeyBarb(BarbSide::Both, 0);
  shortBarb.vertices.back() = {0.5f, 0, 0};
  type.keyBarbs = {shortBarb, straightKeyBarb(BarbSide::Both, 1)};
  type.left.barbLength = 0.4f;
  const FeatherGeometry g = buildFeatherGeometry(type, {});
  const Barb& base = g.barbs.front();
  EXPECT_NEAR(glm::length(last(g, base) - first(g, base)), 0.2f, 1e-5f);
}

TEST(FeatherGeometry, StripsGiveASideVectorInTheVanePlane) {
  FeatherType type = straightFeather();
  type.appearance.drawing = BarbStyle::Strips;
  type.appearance.stripWidth = 0.003f;
  const FeatherGeometry g = buildFeatherGeometry(type, {});
  const BarbVertices& v = g.vertices;
  ASSERT_EQ(v.stripSides.size(), v.positions.size());
  EXPECT_EQ(g.appearance.stripWidth, 0.003f);
  for (const Barb& b : g.barbs) {
    const std::uint32_t end = b.firstVertex + b.vertexCount;
    for (std::uint32_t i = b.firstVertex; i < end; ++i) {
      const glm::vec3 side = v.stripSides[i];
      EXPECT_NEAR(glm::length(side), 1, 1e-5f);
      EXPECT_NEAR(side.x, 0, 1e-5f);  // in the vane plane (its normal is x here)
      // Across the barb: perpendicular to its direction there (the central difference).
      const glm::vec3 along =
          v.positions[std::min(i + 1, end - 1)] - v.positions[std::max(i, b.firstVertex + 1) - 1];
      EXPECT_NEAR(glm::dot(side, along), 0, 1e-5f);
    }
  }
  // Lines carry no strip sides.
  EXPECT_TRUE(buildFeatherGeometry(straightFeather(), {}).vertices.stripSides.empty());
}

TEST(FeatherGeometry, TextureCoordinatesOfTheThreeMappings) {
  FeatherType type = straightFeather();
  // Mirror-symmetric vanes: straight key barbs at the base and tip.
  type.keyBarbs = {straightKeyBarb(BarbSide::Both, 0), straightKeyBarb(BarbSide::Both, 1)};
  const FeatherGeometry g = buildFeatherGeometry(type, {});
  const BarbVertices& v = g.vertices;
  ASSERT_EQ(v.barbUv.size(), v.positions.size());
  ASSERT_EQ(v.vaneUv.size(), v.positions.size());
  ASSERT_EQ(v.growthUv.size(), v.positions.size());
  glm::vec2 low(1e9f), high(-1e9f);
  for (const Barb& b : g.barbs) {
    const std::uint32_t end = b.firstVertex + b.vertexCount;
    EXPECT_EQ(v.s[b.firstVertex], 0);
    EXPECT_FLOAT_EQ(v.s[end - 1], 1);
    for (std::uint32_t i = b.firstVertex; i < end; ++i) {
      if (i > b.firstVertex) {
        EXPECT_GT(v.s[i], v.s[i - 1]);
      }
      EXPECT_EQ(v.barbUv[i], glm::vec2(v.s[i], b.position));  // barb: (s, attachment)
      low = glm::min(low, v.vaneUv[i]);
      high = glm::max(high, v.vaneUv[i]);
      // Growth: u from 0.5 at the rachis round to the back; v from 1 at the base to 0.
      const float u = b.side == BarbSide::Left ? 0.5f + 0.5f * v.s[i] : 0.5f - 0.5f * v.s[i];
      EXPECT_FLOAT_EQ(v.growthUv[i].x, u);
      EXPECT_GE(v.growthUv[i].y, 0);
      EXPECT_LE(v.growthUv[i].y, 1);
    }
    // A straight rachis: the vane mapping is the vertex's (y, z) in the feather's bounding box.
  }
  EXPECT_NEAR(low.x, 0, 1e-6f);
  EXPECT_NEAR(low.y, 0, 1e-6f);
  EXPECT_NEAR(high.x, 1, 1e-6f);
  EXPECT_NEAR(high.y, 1, 1e-6f);
  EXPECT_FLOAT_EQ(v.growthUv[g.barbs.front().firstVertex].y, 1);  // formed last
  // The rachis is at the middle of the vane mapping.
  EXPECT_NEAR(v.vaneUv[g.barbs.front().firstVertex].x, 0.5f, 1e-5f);
}

TEST(FeatherGeometry, AfterfeatherHangsAtTheBackOfTheCalamusTip) {
  Diagnostics diagnostics;
  const FeatherType type = loadFeatherType(kFixtures / "contour.fea", diagnostics);
  const FeatherGeometry g = buildFeatherGeometry(type, {});
  ASSERT_EQ(g.afterfeathers.size(), 1u);
  const FeatherGeometry& after = g.afterfeathers[0];
  const glm::vec3 base(-type.rachisWidth / 2, 0, type.calamusLength);
  EXPECT_NEAR(glm::length(after.shaftAxis.front() - base), 0, 1e-6f);
  const FeatherType& down = *type.afterfeather;
  const glm::vec3 tip = base + 0.4f * glm::vec3(0, 0, down.calamusLength + down.rachisLength);
  EXPECT_NEAR(glm::length(after.shaftAxis.back() - tip), 0, 1e-6f);
  EXPECT_EQ(after.barbs.size(), buildFeatherGeometry(down, {}).barbs.size());
  EXPECT_EQ(after.appearance.colourIndex, 3);
  EXPECT_EQ(g.totalBarbCount(), g.barbs.size() + after.barbs.size());
  EXPECT_GT(g.byteSize(), after.byteSize());
}

TEST(FeatherGeometry, SameSeedSameFeatherDifferentSeedDifferentDown) {
  FeatherType type = straightFeather();  // no key barbs: Bdf1 throughout
  type.seed = 21;
  const FeatherGeometry a = buildFeatherGeometry(type, {});
  const FeatherGeometry b = buildFeatherGeometry(type, {});
  EXPECT_EQ(a.vertices.positions, b.vertices.positions);
  EXPECT_EQ(a.shaft.positions, b.shaft.positions);
  type.seed = 22;
  const FeatherGeometry c = buildFeatherGeometry(type, {});
  ASSERT_EQ(c.vertices.positions.size(), a.vertices.positions.size());
  EXPECT_NE(c.vertices.positions, a.vertices.positions);
  EXPECT_EQ(c.shaft.positions, a.shaft.positions);  // the seed changes the barbs only
}

}  // namespace
}  // namespace hirsute
