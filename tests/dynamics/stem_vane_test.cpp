// Vanes as collision geometry (docs/dynamics.md, "Vanes"; issue 26, item 2): a feather type's
// vane widths follow its drawn barbs, the final check counts vanes that meet, and two feathers
// driven so that their vanes (not their rachises) would cross do not with vanes colliding and
// do without.
#include "hirsute/hairs/dynamics/stem_vane.h"

#include <gtest/gtest.h>

#include <cmath>

#include "hirsute/hairs/dynamics/feather_coat_simulation.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// A straight stem along `heading` from `root`, its front towards `up`, its vane `halfWidth`
// either side on every node but the anchor.
FeatherStem vanedStem(const Vector3d& root, const Vector3d& heading, const Vector3d& up,
                      int segments, double length, double halfWidth,
                      const StemParameters& parameters) {
  std::vector<Vector3d> points;
  for (int i = 0; i <= segments; ++i) points.push_back(root + i * length * heading);
  StemFrame anchor;
  anchor.origin = root;
  anchor.axes.col(0) = up;
  anchor.axes.col(1) = heading.cross(up);
  anchor.axes.col(2) = heading;
  FeatherStem stem = buildStemFromPoints(points, anchor, parameters);
  stem.vaneWidths.assign(points.size(), {halfWidth, halfWidth});
  stem.vaneWidths[0] = {0, 0};
  stem.vaneCorners = vaneCornersOf(stem);
  return stem;
}

FeatherType straightBarbedType(float angle) {
  FeatherType type;
  type.calamusLength = 0.1f;
  type.rachisLength = 1.0f;
  type.left.baseAngle = type.left.tipAngle = angle;
  type.right = type.left;
  type.left.barbLength = type.right.barbLength = 0.3f;
  for (float position : {0.0f, 1.0f}) {
    KeyBarb barb;
    barb.position = position;
    barb.vertices = {glm::vec3(0), glm::vec3(1, 0, 0)};
    type.keyBarbs.push_back(barb);
  }
  return type;
}

TEST(StemVane, TheVanesWidthIsTheDrawnBarbsExtentAcrossTheRachis) {
  std::vector<Vector3d> nodes;
  for (int i = 0; i <= 5; ++i) nodes.emplace_back(0, 0, 0.1 + 0.2 * i);
  nodes.insert(nodes.begin(), Vector3d(0, 0, 0));  // the calamus base: no vane
  for (const float angle : {90.0f, 120.0f}) {
    const auto widths = vaneHalfWidths(straightBarbedType(angle), nodes);
    ASSERT_EQ(widths.size(), nodes.size());
    EXPECT_EQ(widths[0][0], 0);
    EXPECT_EQ(widths[0][1], 0);
    // Straight barbs 0.3 long at the angle: 0.3 sin(angle) across the rachis along the vane.
    const double across = 0.3 * std::sin(angle * M_PI / 180);
    for (std::size_t i = 2; i + 1 < nodes.size(); ++i)
      for (int side = 0; side < 2; ++side)
        EXPECT_NEAR(widths[i][side], across, 0.01 * across) << angle << " node " << i;
  }
  // A rachis curved to the left: the widths are measured from the node, so the left one is
  // narrower by the node's offset where the barbs cross it.
  FeatherType curved = straightBarbedType(90);
  std::vector<Vector3d> offset = nodes;
  for (std::size_t i = 1; i < offset.size(); ++i) offset[i].y() = 0.05;
  const auto shifted = vaneHalfWidths(curved, offset);
  EXPECT_NEAR(shifted[3][0], 0.25, 0.005);
  EXPECT_NEAR(shifted[3][1], 0.35, 0.005);
}

TEST(StemVane, TheFinalCheckCountsVanesThatMeet) {
  StemParameters parameters;
  // A: along x, its vane in the x-y plane at z = 0, 0.2 either side.
  const FeatherStem a =
      vanedStem({0, 0, 0}, Vector3d::UnitX(), Vector3d::UnitZ(), 4, 0.25, 0.2, parameters);
  ASSERT_EQ(vaneTrianglesOf(a).size(), 3u * 2 * 2);  // the calamus segment has no vane
  // B: along y above A, its vane in the y-z plane, crossing A's vane at height h.
  const auto b = [&](double height, double x) {
    return vanedStem({x, -0.5, height}, Vector3d::UnitY(), Vector3d::UnitX(), 4, 0.25, 0.2,
                     parameters);
  };
  // B's vane reaches 0.2 down from its rachis: through A's vane, touching it, near, apart.
  EXPECT_GT(countVaneIntersections({a, b(0.1, 0.6)}, 0.001), 0u);
  EXPECT_GT(countVaneIntersections({a, b(0.2, 0.6)}, 0.001), 0u);
  EXPECT_GT(countVaneIntersections({a, b(0.2005, 0.6)}, 0.001), 0u);
  EXPECT_EQ(countVaneIntersections({a, b(0.21, 0.6)}, 0.001), 0u);
  // Vanes off the stems' check: the rachises are 0.1 apart, only the vanes meet.
  EXPECT_EQ(countPenetrations({a, b(0.1, 0.6)}, {}, 0.001), 0u);
  // B's rachis through A's vane (B's vane lying beside it): a vane and another stem.
  const FeatherStem pierce =
      vanedStem({0.6, 0.1, -0.5}, Vector3d::UnitZ(), Vector3d::UnitY(), 4, 0.25, 0.001, parameters);
  EXPECT_GT(countVaneIntersections({a, pierce}, 0.0001), 0u);
  // Over A's calamus (x from 0 to 0.25), where A has no vane, nothing meets A's vane.
  EXPECT_EQ(countVaneIntersections({a, b(0.1, 0.1)}, 0.001), 0u);
  // One stem's own vane is not tested against itself.
  EXPECT_EQ(countVaneIntersections({a}, 0.001), 0u);
  // With a kept list (a slack of 0.01, B lowered 0.0025 a check, a list made anew every few
  // checks), the counts are those of a fresh search, down through A's vane and out of it.
  BoxTree tree;
  std::size_t met = 0;
  for (int k = 0; k < 80; ++k) {
    const std::vector<FeatherStem> pair{a, b(0.3 - 0.0025 * k, 0.6)};
    const std::size_t count = countVaneIntersections(pair, 0.001, tree, nullptr, nullptr, 0.01);
    EXPECT_EQ(count, countVaneIntersections(pair, 0.001)) << "check " << k;
    met += count > 0;
  }
  EXPECT_GT(met, 10u);
  EXPECT_LT(met, 70u);
  EXPECT_GT(tree.listFilters(), tree.listSearches());
}

// Two feathers side by side, their rachises 0.2 apart in x and never nearer: A stands along z
// with its vane across y (0.4 either side, in the plane x = 0), B stands 1 away in y with its
// vane across x (from x = -0.2 to 0.6) and is carried towards A along -y, its root moved 0.08 a
// step for 10 steps and its nodes moving with it, so that B's vane would cut 0.2 into A's.
// With `behind`, a third feather C like A stands 0.05 behind it (at y = -0.05), where B's push
// brings A's vane against C's.
FeatherCoatSimulation across(bool vanes, int threads = 0, double slack = 0.01, bool keep = true,
                             bool behind = false) {
  SimulationParameters parameters;
  parameters.keepAnswers = keep;
  parameters.gravity = Vector3d::Zero();
  parameters.vaneCollisions = vanes;
  parameters.threads = threads;
  parameters.candidateSlack = slack;
  std::vector<FeatherStem> stems{
      vanedStem({0, 0, 0}, Vector3d::UnitZ(), Vector3d::UnitX(), 4, 0.25, 0.4, parameters.stem),
      vanedStem({0.2, 1, 0}, Vector3d::UnitZ(), Vector3d::UnitY(), 4, 0.25, 0.4, parameters.stem)};
  if (behind)
    stems.push_back(vanedStem({0, -0.05, 0}, Vector3d::UnitZ(), Vector3d::UnitX(), 4, 0.25, 0.4,
                              parameters.stem));
  FeatherCoatSimulation sim(std::move(stems), {}, parameters);
  FeatherStem& b = sim.stem(1);
  for (std::size_t i = 1; i < b.nodeCount(); ++i) b.velocities[i] = Vector3d(0, -8, 0);
  return sim;
}

void carryB(FeatherCoatSimulation& sim, int step) {
  std::vector<StemFrame> anchors = sim.anchors();
  if (step < 10) anchors[1].origin.y() -= 0.08;
  sim.step(0.01, anchors);
}

// The side of B's vane that A's vane edge is on, the most towards B's front over A's corners:
// each corner against the plane of B's vane at the node of B nearest it in height (through the
// node, across B's front). Negative while A's vane stays on its side of B's; positive once B's
// vane has cut past A's edge.
double sideOfBsVane(const FeatherCoatSimulation& sim) {
  const FeatherStem &a = sim.stems()[0], &b = sim.stems()[1];
  double most = -1e9;
  for (std::size_t i = 1; i < a.nodeCount(); ++i) {
    const Vector3d& corner = a.vaneCorners[i][0];
    std::size_t nearest = 1;
    for (std::size_t j = 2; j < b.nodeCount(); ++j)
      if (std::abs(b.positions[j].z() - corner.z()) <
          std::abs(b.positions[nearest].z() - corner.z()))
        nearest = j;
    most = std::max(most, (corner - b.positions[nearest]).dot(b.frames[nearest].axes.col(0)));
  }
  return most;
}

TEST(StemVane, VanesDrivenIntoEachOtherDoNotPassThroughWhenTheyCollide) {
  FeatherCoatSimulation sim = across(true);
  for (int step = 0; step < 20; ++step) {
    carryB(sim, step);
    ASSERT_EQ(countVaneIntersections(sim.stems(), sim.nearestAllowed()), 0u) << "step " << step;
    ASSERT_LT(sideOfBsVane(sim), 0) << "step " << step;
  }
  EXPECT_GT(sim.counters().vaneContacts, 0u);                       // they met
  EXPECT_EQ(sim.counters().contacts, sim.counters().vaneContacts);  // and only their vanes
  // Without vane collisions B's vane goes through A's (and so the test above can fail).
  FeatherCoatSimulation free = across(false);
  std::size_t met = 0;
  for (int step = 0; step < 20; ++step) {
    carryB(free, step);
    met += countVaneIntersections(free.stems(), free.nearestAllowed());
  }
  EXPECT_GT(met, 0u);
  EXPECT_GT(sideOfBsVane(free), 0.1);
  EXPECT_EQ(free.counters().vaneCandidates, 0u);
}

// The threads of the step's loops, the slack of the candidates' list and the answers kept from
// search to search change the work, never the result: the same states bit for bit, the same
// contacts, impulses and zones.
TEST(StemVane, TheThreadsTheCandidatesSlackAndKeptAnswersChangeNothing) {
  const auto run = [](int threads, double slack, bool keep) {
    FeatherCoatSimulation sim = across(true, threads, slack, keep, true);
    for (int step = 0; step < 20; ++step) carryB(sim, step);
    return sim;
  };
  const FeatherCoatSimulation reference = run(1, 0.01, true);
  ASSERT_GT(reference.counters().vaneContacts, 0u);
  EXPECT_GT(reference.counters().keptAnswers, 0u);
  struct Variant {
    int threads;
    double slack;
    bool keep;
  };
  for (const auto& [threads, slack, keep] :
       {Variant{3, 0.001, true}, Variant{2, 0.2, true}, Variant{1, 0.01, false}}) {
    const FeatherCoatSimulation other = run(threads, slack, keep);
    if (!keep) {
      EXPECT_EQ(other.counters().keptAnswers, 0u);
    }
    for (std::size_t s = 0; s < reference.stems().size(); ++s) {
      const FeatherStem &a = reference.stems()[s], &b = other.stems()[s];
      for (std::size_t i = 0; i < a.nodeCount(); ++i) {
        EXPECT_EQ(a.positions[i], b.positions[i]) << threads << " threads, stem " << s;
        EXPECT_EQ(a.velocities[i], b.velocities[i]) << threads << " threads, stem " << s;
        for (int side = 0; side < 2; ++side)
          EXPECT_EQ(a.vaneCorners[i][side], b.vaneCorners[i][side]) << threads << " threads";
      }
    }
    EXPECT_EQ(reference.counters().contacts, other.counters().contacts);
    EXPECT_EQ(reference.counters().impulses, other.counters().impulses);
    EXPECT_EQ(reference.counters().repulsions, other.counters().repulsions);
    EXPECT_EQ(reference.counters().impactZones, other.counters().impactZones);
  }
}

}  // namespace
}  // namespace hirsute::dynamics
