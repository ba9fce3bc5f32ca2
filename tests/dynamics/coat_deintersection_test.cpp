// A coat laid in layer order (docs/feathers.md, "Shingling"): a feather groomed through the one
// beneath it is laid on it, its root where it was and its segments as long, and the simulator's
// own exact checks find nothing left; the same stems give the same result bit for bit.
#include "hirsute/hairs/dynamics/coat_deintersection.h"

#include <gtest/gtest.h>

#include <cmath>

#include "hirsute/hairs/dynamics/feather_coat_simulation.h"
#include "hirsute/hairs/dynamics/stem_vane.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// A straight stem along `heading` from `root`, its front towards `up`, its vane `halfWidth`
// either side on every node but the anchor.
FeatherStem vanedStem(const Vector3d& root, const Vector3d& heading, const Vector3d& up,
                      int segments, double length, double halfWidth, StemFrame& anchor) {
  std::vector<Vector3d> points;
  for (int i = 0; i <= segments; ++i) points.push_back(root + i * length * heading);
  anchor.origin = root;
  anchor.axes.col(0) = up;
  anchor.axes.col(1) = heading.cross(up);
  anchor.axes.col(2) = heading;
  FeatherStem stem = buildStemFromPoints(points, anchor);
  stem.vaneWidths.assign(points.size(), {halfWidth, halfWidth});
  stem.vaneWidths[0] = {0, 0};
  stem.vaneCorners = vaneCornersOf(stem);
  return stem;
}

// Two feathers on a floor: the lower along x, the upper along y and groomed in the same plane,
// straight through the lower one's vane; both lying a little above the floor (two triangles at
// z = -0.01), rising from it by 3 degrees.
struct CrossingPair {
  std::vector<FeatherStem> stems;
  std::vector<StemFrame> anchors{2};
  BodyMesh floor;

  CrossingPair() {
    const double rise = 3 * std::acos(-1.0) / 180;
    const Vector3d up(0, 0, 1);
    const Vector3d alongX(std::cos(rise), 0, std::sin(rise));
    const Vector3d alongY(0, std::cos(rise), std::sin(rise));
    stems.push_back(vanedStem({-0.5, 0, 0}, alongX, (up - up.dot(alongX) * alongX).normalized(), 10,
                              0.1, 0.1, anchors[0]));
    stems.push_back(vanedStem({0, -0.5, 0}, alongY, (up - up.dot(alongY) * alongY).normalized(), 10,
                              0.1, 0.1, anchors[1]));
    floor.vertices = {{-2, -2, -0.01}, {2, -2, -0.01}, {2, 2, -0.01}, {-2, 2, -0.01}};
    floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  }
};

std::size_t intersections(const std::vector<FeatherStem>& stems, const BodyMesh& body) {
  return countPenetrations(stems, body, 0) + countVaneIntersections(stems, 0);
}

TEST(CoatDeintersection, AStackedCrossingPairIsLaidClearItsRootsAndLengthsKept) {
  CrossingPair pair;
  ASSERT_GT(intersections(pair.stems, pair.floor), 0u);  // the groom passes through
  const std::vector<FeatherStem> grown = pair.stems;
  const DeintersectionReport report =
      deintersectStems(pair.stems, pair.anchors, pair.floor, LayingParameters{});
  EXPECT_EQ(report.stems, 2u);
  EXPECT_EQ(report.moved, 1u);  // the bottom one stays as it grew
  EXPECT_EQ(report.intersections, 0u);
  EXPECT_EQ(report.leftAsGrown, 0u);
  // The simulator's own exact checks agree.
  EXPECT_EQ(intersections(pair.stems, pair.floor), 0u);
  EXPECT_EQ(pair.stems[0].positions, grown[0].positions);
  const FeatherStem& upper = pair.stems[1];
  EXPECT_EQ(upper.positions[0], grown[1].positions[0]);  // the root stays on the body
  for (std::size_t k = 0; k + 1 < upper.nodeCount(); ++k) {
    const double length = (upper.positions[k + 1] - upper.positions[k]).norm();
    EXPECT_NEAR(length, upper.restLengths[k], 1e-12 * upper.restLengths[k]);
  }
  EXPECT_LT(largestStrain(upper), 1e-9);
  // It lies over the lower one where it crosses it, and beyond it bends back towards its groom:
  // its tip lower than the straight line from its root through its lift would put it.
  const Vector3d crossing = upper.positions[5];
  EXPECT_GT(crossing.z(), grown[1].positions[5].z());
  const Vector3d lifted = upper.positions[5] - upper.positions[0];
  const Vector3d tip = upper.positions[10] - upper.positions[0];
  EXPECT_LT(tip.z() / tip.norm(), lifted.z() / lifted.norm());
  // Only as much as it needs: the lift is a few degrees, not a feather standing up.
  EXPECT_LT(report.largestLift, 0.5);
}

TEST(CoatDeintersection, TheSameStemsAreLaidTheSameBitForBit) {
  CrossingPair a, b;
  deintersectStems(a.stems, a.anchors, a.floor, LayingParameters{});
  deintersectStems(b.stems, b.anchors, b.floor, LayingParameters{});
  for (std::size_t s = 0; s < a.stems.size(); ++s) {
    EXPECT_EQ(a.stems[s].positions, b.stems[s].positions);
    EXPECT_EQ(a.stems[s].vaneCorners, b.stems[s].vaneCorners);
  }
}

TEST(CoatDeintersection, PastThePairTestLimitTheFeathersAboveAreLeftAsGrown) {
  CrossingPair pair;
  // A third feather beside the upper one, through the lower one too.
  FeatherStem third = pair.stems[1];
  for (Vector3d& p : third.positions) p.x() += 0.05;
  third.vaneCorners = vaneCornersOf(third);
  StemFrame anchor = pair.anchors[1];
  anchor.origin.x() += 0.05;
  pair.stems.push_back(third);
  pair.anchors.push_back(anchor);
  const std::vector<FeatherStem> grown = pair.stems;
  LayingParameters parameters;
  parameters.maxPairTests = 0;  // the first pair tested ends the pass
  const DeintersectionReport report =
      deintersectStems(pair.stems, pair.anchors, pair.floor, parameters);
  EXPECT_EQ(report.stems, 2u);
  EXPECT_EQ(report.leftAsGrown, 1u);
  EXPECT_EQ(pair.stems[2].positions, grown[2].positions);
  EXPECT_GT(intersections(pair.stems, pair.floor), 0u);
}

TEST(CoatDeintersection, AStemThatMeetsNothingIsLeftAsGroomed) {
  CrossingPair pair;
  pair.stems.pop_back();
  pair.anchors.pop_back();
  const std::vector<FeatherStem> grown = pair.stems;
  const DeintersectionReport report =
      deintersectStems(pair.stems, pair.anchors, pair.floor, LayingParameters{});
  EXPECT_EQ(report.moved, 0u);
  EXPECT_EQ(report.intersections, 0u);
  EXPECT_EQ(pair.stems[0].positions, grown[0].positions);
}

}  // namespace
}  // namespace hirsute::dynamics
