// The feather-coat step: a feather comes to rest on a surface without passing through it, two
// stems driven into each other at high speed never cross, the same seed gives the same frames,
// and the final check finds planted intersections (a calamus left out).
#include "hirsute/hairs/dynamics/feather_coat_simulation.h"

#include <gtest/gtest.h>

#include <map>

#include "hirsute/hairs/dynamics/exact_predicates.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

FeatherStem straightStem(const Vector3d& root, const Vector3d& direction, int segments,
                         double length, const StemParameters& parameters) {
  std::vector<Vector3d> points;
  for (int i = 0; i <= segments; ++i) points.push_back(root + i * length * direction);
  StemFrame anchor;
  anchor.origin = root;
  anchor.axes.col(2) = direction;
  anchor.axes.col(0) = direction.unitOrthogonal();
  anchor.axes.col(1) = direction.cross(anchor.axes.col(0));
  return buildStemFromPoints(points, anchor, parameters);
}

// The square [-1, 1]^2 at height z, two triangles.
BodyMesh ground(double z) {
  BodyMesh body;
  body.vertices = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
  body.triangles = {{0, 1, 2}, {0, 2, 3}};
  return body;
}

TEST(FeatherCoatSimulation, AFeatherFallsOntoASurfaceAndRestsOnItWithoutPassingThrough) {
  SimulationParameters parameters;
  parameters.stem.goldStiffness = 2;
  parameters.stem.goldDamping = 2;
  parameters.dragCoefficient = 1;
  const BodyMesh body = ground(0);
  FeatherCoatSimulation sim(
      {straightStem({-0.3, 0, 0.12}, Vector3d::UnitX(), 6, 0.1, parameters.stem)}, body,
      parameters);
  for (int step = 0; step < 360; ++step) {
    sim.step(1.0 / 120);
    for (const Vector3d& p : sim.stems()[0].positions) ASSERT_GT(p.z(), 0) << "step " << step;
    ASSERT_EQ(countPenetrations(sim.stems(), body, 0), 0u) << "step " << step;
  }
  // It came down onto the surface (the tip started 0.12 above it) and lies still there.
  const std::vector<Vector3d> settled = sim.stems()[0].positions;
  EXPECT_LT(settled.back().z(), 2 * parameters.thickness);
  for (int step = 0; step < 12; ++step) sim.step(1.0 / 120);
  double moved = 0;
  for (std::size_t i = 0; i < settled.size(); ++i)
    moved = std::max(moved, (sim.stems()[0].positions[i] - settled[i]).norm());
  EXPECT_LT(moved, 2e-3);
  EXPECT_GT(sim.counters().repulsions + sim.counters().impulses + sim.counters().restingMoves, 0u);
}

// For pairs of segments (one of each stem) whose shadows on the xy plane cross: which passes over
// the other there, as the sign of the volume they span. A pair whose shadows cross before and
// after a step changes sides only by passing through the other.
std::map<std::pair<int, int>, int> sidesWhereShadowsCross(const std::vector<Vector3d>& a,
                                                          const std::vector<Vector3d>& b) {
  std::map<std::pair<int, int>, int> sides;
  for (int i = 0; i + 1 < static_cast<int>(a.size()); ++i)
    for (int j = 0; j + 1 < static_cast<int>(b.size()); ++j) {
      const Eigen::Vector2d p = a[i].head<2>(), r = a[i + 1].head<2>() - p;
      const Eigen::Vector2d q = b[j].head<2>(), s = b[j + 1].head<2>() - q;
      const double d = r.x() * s.y() - r.y() * s.x();
      if (std::abs(d) < 1e-12) continue;
      const Eigen::Vector2d qp = q - p;
      const double t = (qp.x() * s.y() - qp.y() * s.x()) / d;
      const double u = (qp.x() * r.y() - qp.y() * r.x()) / d;
      if (t < 0 || t > 1 || u < 0 || u > 1) continue;
      sides[{i, j}] = orient3d(a[i], a[i + 1], b[j], b[j + 1]);
    }
  return sides;
}

// Pairs whose shadows cross before and after a step and that swapped sides.
int sideChanges(const std::map<std::pair<int, int>, int>& before,
                const std::map<std::pair<int, int>, int>& after) {
  int changes = 0;
  for (const auto& [pair, side] : after) {
    const auto it = before.find(pair);
    if (it != before.end() && it->second != side) ++changes;
  }
  return changes;
}

TEST(FeatherCoatSimulation, TwoStemsDrivenIntoEachOtherAtHighSpeedNeverCross) {
  SimulationParameters parameters;
  parameters.gravity = Vector3d::Zero();
  parameters.stem.goldStiffness = 1;
  parameters.stem.goldDamping = 0.1;
  FeatherCoatSimulation sim(
      {straightStem({-0.66, 0, 0.05}, Vector3d::UnitX(), 8, 0.12, parameters.stem),
       straightStem({0, -0.66, -0.05}, Vector3d::UnitY(), 8, 0.12, parameters.stem)},
      {}, parameters);
  // Both swing about their anchors towards each other, the tips at 60 units a second: at 100
  // steps a second the points where they cross close 0.7 a step, seventy times the thickness.
  const double spin = 60 / 0.96, h = 0.01;
  for (int s = 0; s < 2; ++s) {
    FeatherStem& stem = sim.stem(s);
    for (std::size_t i = 1; i < stem.nodeCount(); ++i) {
      const double r = (stem.positions[i] - stem.positions[0]).norm();
      stem.velocities[i] = Vector3d(0, 0, s == 0 ? -spin * r : spin * r);
    }
  }
  auto sides = [&](const std::vector<FeatherStem>& stems) {
    return sidesWhereShadowsCross(stems[0].positions, stems[1].positions);
  };
  // Unchecked, one step of free flight would carry them through each other.
  std::vector<FeatherStem> free = sim.stems();
  for (FeatherStem& stem : free)
    for (std::size_t i = 0; i < stem.nodeCount(); ++i) stem.positions[i] += h * stem.velocities[i];
  ASSERT_GT(sideChanges(sides(sim.stems()), sides(free)), 0);

  for (int step = 0; step < 40; ++step) {
    const auto before = sides(sim.stems());
    sim.step(h);
    ASSERT_EQ(sideChanges(before, sides(sim.stems())), 0) << "the stems crossed at step " << step;
    ASSERT_EQ(countPenetrations(sim.stems(), {}, 0), 0u) << "step " << step;
  }
  EXPECT_GT(sim.counters().contacts, 0u);  // they did meet
}

// A stem swung up through another's calamus (its first segment, x from 0 to 0.12, whose root
// the body holds), with no impulse passes to stop it: the zones leave calami to the impulses, so
// the step in which the calamus meets the stem is tried again in halves.
FeatherCoatSimulation swungThroughACalamus(int maxHalvings) {
  SimulationParameters parameters;
  parameters.gravity = Vector3d::Zero();
  parameters.impulsePasses = 0;
  parameters.maxHalvings = maxHalvings;
  parameters.stem.goldStiffness = 1;
  parameters.stem.goldDamping = 0.1;
  FeatherCoatSimulation sim(
      {straightStem({0, 0, 0.05}, Vector3d::UnitX(), 8, 0.12, parameters.stem),
       straightStem({0.06, -0.66, -0.05}, Vector3d::UnitY(), 8, 0.12, parameters.stem)},
      {}, parameters);
  FeatherStem& swung = sim.stem(1);
  for (std::size_t i = 1; i < swung.nodeCount(); ++i)
    swung.velocities[i] = Vector3d(0, 0, 60 * (swung.positions[i] - swung.positions[0]).norm());
  return sim;
}

TEST(FeatherCoatSimulation, AStepInWhichACalamusMeetsAStemIsRetriedInHalves) {
  FeatherCoatSimulation sim = swungThroughACalamus(3);
  sim.step(0.01);
  // The whole step and its first half met the calamus; the quarters, slower, let the repulsion
  // lift the calamus's free end over the stem.
  EXPECT_GE(sim.counters().calamiCrossed, 1u);
  EXPECT_GE(sim.counters().retries, 1u);
  EXPECT_EQ(sim.counters().calamiZoned, 0u);
  EXPECT_GT(sim.stems()[0].positions[1].z(), 0.1);
}

// At the smallest step the crossing pair goes into an impact zone with the calamus's root: the
// stem keeps its side of the calamus, and the step is accepted with no crossing.
TEST(FeatherCoatSimulation, ACalamusMeetingAStemAtTheSmallestStepIsZonedNeverCrossed) {
  FeatherCoatSimulation sim = swungThroughACalamus(0);
  // Unchecked, the step would carry the stem through the calamus.
  std::vector<FeatherStem> free = sim.stems();
  for (FeatherStem& stem : free)
    for (std::size_t i = 0; i < stem.nodeCount(); ++i)
      stem.positions[i] += 0.01 * stem.velocities[i];
  const auto before = sidesWhereShadowsCross(sim.stems()[0].positions, sim.stems()[1].positions);
  ASSERT_GT(sideChanges(before, sidesWhereShadowsCross(free[0].positions, free[1].positions)), 0);
  sim.step(0.01);
  EXPECT_EQ(sim.counters().retries, 0u);
  EXPECT_GE(sim.counters().calamiZoned, 1u);
  EXPECT_EQ(sim.counters().calamiCrossed, sim.counters().calamiZoned);
  EXPECT_EQ(sideChanges(before,
                        sidesWhereShadowsCross(sim.stems()[0].positions, sim.stems()[1].positions)),
            0)
      << "the stem passed through the calamus";
  EXPECT_EQ(countPenetrations(sim.stems(), {}, 0), 0u);
}

TEST(FeatherCoatSimulation, AStepThatCannotBeResolvedIsRetriedThenRefusedNeverAccepted) {
  SimulationParameters parameters;
  parameters.gravity = Vector3d::Zero();
  parameters.maxHalvings = 4;
  // A stem lies between the ground and a plate above it, and the plate is driven down through
  // the ground in one step: the stem's free nodes, caught between the two, can go nowhere.
  BodyMesh body = ground(0);
  const BodyMesh plate = ground(0.1);
  for (const Vector3d& v : plate.vertices) body.vertices.push_back(v);
  for (const auto& t : plate.triangles) body.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  FeatherCoatSimulation sim(
      {straightStem({-1.5, 0, 0.05}, Vector3d::UnitX(), 3, 0.5, parameters.stem)}, body,
      parameters);
  std::vector<Vector3d> moved = body.vertices;
  for (int v = 4; v < 8; ++v) moved[v].z() = -0.1;
  const std::vector<FeatherStem> before = sim.stems();
  EXPECT_THROW(sim.step(0.01, sim.anchors(), moved), StepFailure);
  EXPECT_GE(sim.counters().retries, 4u);
  EXPECT_EQ(sim.time(), 0);
  for (std::size_t s = 0; s < before.size(); ++s)
    for (std::size_t i = 0; i < before[s].nodeCount(); ++i)
      EXPECT_EQ(sim.stems()[s].positions[i], before[s].positions[i]);
  EXPECT_EQ(sim.body().vertices[4].z(), 0.1);
}

// The CCD's separation is a box: a stem lying a fifth farther than the separation from a body
// triangle whose normal is the diagonal (1, 1, 1) is within it on every axis. No zone can open
// that gap, and such a pair, clear of the zones' separation, is left to the impulses: the steps go
// on, and the stem moves off the triangle.
TEST(FeatherCoatSimulation, APairJustBeyondTheSeparationButInsideItsBoxDoesNotStopTheSteps) {
  SimulationParameters parameters;
  parameters.gravity = Vector3d::Zero();
  parameters.thickness = parameters.minimumSeparation;  // no repulsion at that distance
  const double eta = parameters.minimumSeparation;
  BodyMesh body;
  body.vertices = {{1, -1, 0}, {0, 1, -1}, {-1, 0, 1}};  // the plane x + y + z = 0
  body.triangles = {{0, 1, 2}};
  const Vector3d normal = Vector3d(1, 1, 1).normalized();
  const Vector3d along = Vector3d(1, -1, 0).normalized();
  const Vector3d root = 1.2 * eta * normal - 0.15 * along;
  FeatherCoatSimulation sim({straightStem(root, along, 3, 0.1, parameters.stem)}, body, parameters);
  auto height = [&](std::size_t node) { return normal.dot(sim.stems()[0].positions[node]); };
  ASSERT_LT((height(1) * normal).cwiseAbs().maxCoeff(), eta);  // inside the box
  for (int step = 0; step < 20; ++step) {
    ASSERT_NO_THROW(sim.step(0.01)) << "step " << step;
    for (std::size_t i = 1; i < sim.stems()[0].nodeCount(); ++i)
      ASSERT_GT(height(i), 0.5 * eta) << "step " << step << ", node " << i;
  }
  EXPECT_GT(sim.counters().contacts, 0u);
  EXPECT_GT(sim.counters().keptNear, 0u);
  EXPECT_EQ(sim.counters().retries, 0u);
  EXPECT_GT(height(2), 1.2 * eta);  // pushed off by the impulses
}

// A body that folds is not a rigid motion: two stems lying one on the other over a hinge, the
// flap beyond it turned up a degree a step, are pressed by it and by each other (impact zones
// that hold the moving flap). They go up with the flap, never through it or each other.
TEST(FeatherCoatSimulation, StemsPressedByAFoldingBodyRideUpWithItNeverThroughIt) {
  SimulationParameters parameters;
  parameters.gravity = Vector3d::Zero();
  parameters.impulsePasses = 0;                         // the zones answer every contact,
  parameters.thickness = parameters.minimumSeparation;  // and no repulsion keeps them off
  BodyMesh body;
  body.vertices = {{-1, -1, 0}, {-1, 1, 0}, {0, -1, 0}, {0, 1, 0}, {1, -1, 0}, {1, 1, 0}};
  body.triangles = {{0, 2, 3}, {0, 3, 1}, {2, 4, 5}, {2, 5, 3}};
  FeatherCoatSimulation sim(
      {straightStem({-0.5, 0, 0.004}, Vector3d::UnitX(), 6, 0.15, parameters.stem),
       straightStem({-0.5, 0.003, 0.009}, Vector3d::UnitX(), 6, 0.15, parameters.stem)},
      body, parameters);
  const double degree = 5 * M_PI / 180;
  for (int step = 1; step <= 10; ++step) {
    std::vector<Vector3d> folded = sim.body().vertices;
    for (int v : {4, 5})
      folded[v] = Vector3d(std::cos(step * degree), folded[v].y(), std::sin(step * degree));
    ASSERT_NO_THROW(sim.step(0.01, sim.anchors(), folded)) << "step " << step;
    const BodyMesh now{folded, body.triangles};
    ASSERT_EQ(countPenetrations(sim.stems(), now, sim.nearestAllowed()), 0u) << "step " << step;
    // Every node on the flap's side lies above it, the upper stem's above the lower one's.
    const Vector3d flapNormal(-std::sin(step * degree), 0, std::cos(step * degree));
    for (const FeatherStem& stem : sim.stems())
      for (const Vector3d& p : stem.positions)
        if (p.x() > 0) {
          ASSERT_GT(flapNormal.dot(p), 0) << "step " << step;
        }
  }
  EXPECT_GT(sim.counters().impactZones, 0u);
  // The tips rode up: the flap stands at 50 degrees.
  EXPECT_GT(sim.stems()[0].positions.back().z(), 0.2);
}

// A bump rising under a stem: the body's centre goes up while its rim stays, no rigid motion.
// The impact zones that hold the stem and the rising triangles (no impulse passes and no
// repulsion here, so that the zones answer every contact) lift it with them, never through.
TEST(FeatherCoatSimulation, AStemOnABumpRisingUnderItIsLiftedNeverPassedThrough) {
  SimulationParameters parameters;
  parameters.gravity = Vector3d::Zero();
  parameters.impulsePasses = 0;
  parameters.thickness = parameters.minimumSeparation;
  BodyMesh body;
  body.vertices.push_back({0, 0, 0});
  for (int k = 0; k < 6; ++k)
    body.vertices.push_back({std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0});
  for (int k = 0; k < 6; ++k) body.triangles.push_back({0, 1 + k, 1 + (k + 1) % 6});
  FeatherCoatSimulation sim(
      {straightStem({-0.6, 0.05, 0.003}, Vector3d::UnitX(), 8, 0.15, parameters.stem)}, body,
      parameters);
  for (int step = 1; step <= 20; ++step) {
    std::vector<Vector3d> raised = sim.body().vertices;
    raised[0].z() = 0.01 * step;
    ASSERT_NO_THROW(sim.step(0.01, sim.anchors(), raised)) << "step " << step;
    ASSERT_EQ(countPenetrations(sim.stems(), {raised, body.triangles}, 0), 0u) << "step " << step;
  }
  EXPECT_GT(sim.counters().impactZones, 0u);
  // A zone moved only by the rigid motion fitted to the triangles' vertices keeps meeting the
  // centre, which outruns that fit, and its steps were retried; lifted off, none is.
  EXPECT_EQ(sim.counters().retries, 0u);
  // The node nearest the top went up with it.
  double highest = 0;
  for (const Vector3d& p : sim.stems()[0].positions) highest = std::max(highest, p.z());
  EXPECT_GT(highest, 0.15);
}

// Two roots the body drives through each other: their first segments are the body's to place,
// and the step goes on.
TEST(FeatherCoatSimulation, RootsTheBodyBringsTogetherDoNotStopTheStep) {
  SimulationParameters parameters;
  parameters.gravity = Vector3d::Zero();
  FeatherCoatSimulation sim({straightStem({0, 0, 0}, Vector3d::UnitX(), 3, 0.1, parameters.stem),
                             straightStem({0, 0.1, 0}, Vector3d::UnitZ(), 3, 0.1, parameters.stem)},
                            {}, parameters);
  std::vector<StemFrame> anchors = sim.anchors();
  anchors[1].origin += Vector3d(0, -0.2, 0);
  sim.step(0.01, anchors);
  EXPECT_EQ(sim.anchors()[1].origin, anchors[1].origin);
  EXPECT_EQ(countPenetrations(sim.stems(), {}, sim.nearestAllowed()), 0u);
}

// Three stems over the ground in gusty wind, `steps` steps: every node's position.
std::vector<Vector3d> gustyCoat(int seed, int steps) {
  SimulationParameters parameters;
  parameters.stem.goldStiffness = 20;
  parameters.dragCoefficient = 0.5;
  parameters.wind.velocity = Vector3d(1, 0, 0);
  parameters.wind.gustStrength = 3;
  parameters.wind.gustScale = 0.5;
  parameters.wind.seed = seed;
  std::vector<FeatherStem> stems;
  for (int s = 0; s < 3; ++s)
    stems.push_back(straightStem({-0.3, 0.03 * s, 0.02 + 0.02 * s},
                                 Vector3d(1, 0, 0.2).normalized(), 6, 0.08, parameters.stem));
  FeatherCoatSimulation sim(std::move(stems), ground(0), parameters);
  for (int step = 0; step < steps; ++step) sim.step(1.0 / 60);
  std::vector<Vector3d> out;
  for (const FeatherStem& stem : sim.stems())
    for (const Vector3d& p : stem.positions) out.push_back(p);
  return out;
}

TEST(FeatherCoatSimulation, TheSameSeedGivesTheSameFramesBitForBit) {
  const auto first = gustyCoat(7, 30), second = gustyCoat(7, 30);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(first[i][k], second[i][k]);
  // The seed matters: another gives other frames.
  const auto other = gustyCoat(8, 30);
  double difference = 0;
  for (std::size_t i = 0; i < first.size(); ++i)
    difference = std::max(difference, (first[i] - other[i]).norm());
  EXPECT_GT(difference, 1e-3);
}

TEST(FeatherCoatSimulation, TheFinalCheckFindsPlantedIntersections) {
  StemParameters parameters;
  const BodyMesh body = ground(0);
  // A stem standing on the ground: its first segment touches it at the root, as anchored stems do.
  const FeatherStem standing = straightStem({0, 0, 0}, Vector3d::UnitZ(), 3, 0.1, parameters);
  EXPECT_EQ(countPenetrations({standing}, body, 0.001), 0u);
  // A stem through the ground.
  FeatherStem through = straightStem({0.3, 0.1, 0.15}, Vector3d(0, 0, -1), 3, 0.1, parameters);
  EXPECT_EQ(countPenetrations({through}, body, 0.001), 1u);
  // One touching it exactly at its tip counts too.
  FeatherStem touching = straightStem({0.3, 0.1, 0.3}, Vector3d(0, 0, -1), 3, 0.1, parameters);
  EXPECT_EQ(countPenetrations({touching}, body, 0.001), 1u);
  // Two stems crossing, then the same 0.0005 apart (nearer than the minimum), then 0.01 apart.
  const FeatherStem a = straightStem({-0.5, 0, 0.5}, Vector3d::UnitX(), 5, 0.2, parameters);
  for (const auto& [offset, expected] :
       {std::pair{0.0, 1u}, std::pair{0.0005, 1u}, std::pair{0.01, 0u}}) {
    const FeatherStem b =
        straightStem({0, -0.5, 0.5 + offset}, Vector3d::UnitY(), 5, 0.2, parameters);
    EXPECT_EQ(countPenetrations({a, b}, {}, 0.001), expected) << "offset " << offset;
  }
  // A stem through another's calamus (its first segment, from x = -0.5 to -0.3) is left out;
  // through the next segment it counts.
  for (const auto& [x, expected] : {std::pair{-0.4, 0u}, std::pair{-0.2, 1u}}) {
    const FeatherStem b = straightStem({x, -0.5, 0.5}, Vector3d::UnitY(), 5, 0.2, parameters);
    EXPECT_EQ(countPenetrations({a, b}, {}, 0.001), expected) << "at x = " << x;
  }
  // A stem folded back onto itself crosses its own segments.
  FeatherStem folded = straightStem({0, 0, 1}, Vector3d::UnitX(), 4, 0.1, parameters);
  folded.positions = {{0, 0, 1}, {0.1, 0, 1}, {0.2, 0, 1}, {0.2, 0.1, 1}, {0.05, -0.1, 1}};
  folded.restLengths.assign(4, 0.1);
  EXPECT_GE(countPenetrations({folded}, {}, 0.001), 1u);
}

}  // namespace
}  // namespace hirsute::dynamics
