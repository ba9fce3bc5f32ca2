// The resting stage of the coat's step (resting_contacts.h): a stacked pair is held at the
// resting distance and the continuous collision detection is asked nothing about it; a pair
// slides along another held so; a step retried in halves starts them from the contact set it
// had before; one thread and two give the same steps bit for bit; and with the stage off the
// repulsion and the collisions alone still leave no intersection.
#include "hirsute/hairs/dynamics/resting_contacts.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "hirsute/hairs/dynamics/feather_coat_simulation.h"

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

// The square [x0, x1] x [-1, 1] at height z, two triangles.
BodyMesh ground(double z, double x0 = -1, double x1 = 1) {
  BodyMesh body;
  body.vertices = {{x0, -1, z}, {x1, -1, z}, {x1, 1, z}, {x0, 1, z}};
  body.triangles = {{0, 1, 2}, {0, 2, 3}};
  return body;
}

SimulationParameters softStems() {
  SimulationParameters parameters;
  parameters.stem.goldStiffness = 2;
  parameters.stem.goldDamping = 2;
  parameters.dragCoefficient = 1;
  return parameters;
}

// Whether a resting contact joins stem vertices of [first, last) and of [last, end).
bool holdsBetween(const RestingContacts& set, int first, int last, int end) {
  return std::any_of(set.contacts().begin(), set.contacts().end(), [&](const RestingContact& c) {
    bool lower = false, upper = false;
    for (int v : c.vertices) {
      lower |= v >= first && v < last;
      upper |= v >= last && v < end;
    }
    return lower && upper;
  });
}

// Two stems crossed on the ground, the upper one lying across the lower under gravity: once
// settled, each step holds them at the resting distance without one query of the CCD.
TEST(RestingContacts, AStackedPairIsHeldAtRestWithoutCcdQueries) {
  const SimulationParameters parameters = softStems();
  const double rest = parameters.restDistance();
  const BodyMesh body = ground(0);
  FeatherCoatSimulation sim(
      {straightStem({-0.3, 0, rest}, Vector3d::UnitX(), 6, 0.1, parameters.stem),
       straightStem({0.05, -0.3, 2 * rest}, Vector3d::UnitY(), 6, 0.1, parameters.stem)},
      body, parameters);
  for (int step = 0; step < 120; ++step) sim.step(1.0 / 120);
  ASSERT_EQ(countPenetrations(sim.stems(), body, sim.nearestAllowed()), 0u);
  const std::uint64_t queries = sim.counters().ccdQueries;
  const std::vector<FeatherStem> settled = sim.stems();
  for (int step = 0; step < 30; ++step) {
    sim.step(1.0 / 120);
    ASSERT_EQ(countPenetrations(sim.stems(), body, sim.nearestAllowed()), 0u) << "step " << step;
  }
  EXPECT_EQ(sim.counters().ccdQueries, queries) << "a held pair reached the CCD";
  EXPECT_EQ(sim.counters().retries, 0u);
  // Stem 0's nodes are vertices 0 to 6, stem 1's 7 to 13: the pair is held, and the upper stem
  // lies on the lower one at the resting distance where they cross.
  EXPECT_TRUE(holdsBetween(sim.restingContacts(), 0, 7, 14));
  const Vector3d crossing = sim.stems()[1].positions[3];
  EXPECT_NEAR(crossing.z() - sim.stems()[0].positions[3].z(), rest, 0.1 * rest);
  for (std::size_t s = 0; s < 2; ++s)
    for (std::size_t i = 1; i < settled[s].nodeCount(); ++i) {
      EXPECT_LT((sim.stems()[s].positions[i] - settled[s].positions[i]).norm(), 1e-3);
      EXPECT_GT(sim.stems()[s].positions[i].z(), 0.9 * rest);  // on the ground, at rest distance
    }
  EXPECT_EQ(sim.counters().repulsions, 0u);  // the stage took the repulsion's place
}

// The upper stem's root is carried along the lower stem: it slides along it, held at the resting
// distance, and the CCD is asked nothing about the pair.
TEST(RestingContacts, APairSlidesAlongAnotherHeldAtRest) {
  const SimulationParameters parameters = softStems();
  const double rest = parameters.restDistance();
  const BodyMesh body = ground(0);
  FeatherCoatSimulation sim(
      {straightStem({-0.5, 0, rest}, Vector3d::UnitX(), 8, 0.12, parameters.stem),
       straightStem({-0.2, -0.3, 2 * rest}, Vector3d::UnitY(), 6, 0.1, parameters.stem)},
      body, parameters);
  for (int step = 0; step < 60; ++step) sim.step(1.0 / 120);
  const std::uint64_t queries = sim.counters().ccdQueries;
  const double startX = sim.stems()[1].positions[3].x();
  std::vector<StemFrame> anchors = sim.anchors();
  for (int step = 0; step < 60; ++step) {
    anchors[1].origin.x() += 0.5 / 120;  // half a unit a second along the lower stem
    sim.step(1.0 / 120, anchors);
    ASSERT_EQ(countPenetrations(sim.stems(), body, sim.nearestAllowed()), 0u) << "step " << step;
    const Vector3d& over = sim.stems()[1].positions[3];
    ASSERT_GT(over.z(), 1.5 * rest) << "step " << step;  // still over the lower stem
  }
  EXPECT_GT(sim.stems()[1].positions[3].x() - startX, 0.05);  // a soft stem, lagging its root
  EXPECT_TRUE(holdsBetween(sim.restingContacts(), 0, 9, 16));
  EXPECT_EQ(sim.counters().ccdQueries, queries) << "a held pair reached the CCD";
}

// A stem resting on the ground under gravity, and a stem swung through another's calamus (which
// the zones leave to the impulses, none here): the step is retried in halves. The halves start
// from the contact set of before the step, as two steps of half the length do.
FeatherCoatSimulation restingBesideASwing() {
  SimulationParameters parameters;
  parameters.impulsePasses = 0;
  parameters.stem.goldStiffness = 1;
  parameters.stem.goldDamping = 0.1;
  const double rest = parameters.restDistance();
  return FeatherCoatSimulation(
      {straightStem({0, 0, 0.05}, Vector3d::UnitX(), 8, 0.12, parameters.stem),
       straightStem({0.06, -0.66, -0.05}, Vector3d::UnitY(), 8, 0.12, parameters.stem),
       straightStem({2, 0, -0.3 + rest}, Vector3d::UnitX(), 6, 0.1, parameters.stem)},
      ground(-0.3, 1.5, 3.5), parameters);
}

void swing(FeatherCoatSimulation& sim) {
  FeatherStem& swung = sim.stem(1);
  for (std::size_t i = 1; i < swung.nodeCount(); ++i)
    swung.velocities[i] = Vector3d(0, 0, 60 * (swung.positions[i] - swung.positions[0]).norm());
}

TEST(RestingContacts, AStepRetriedInHalvesRestoresTheContactSet) {
  FeatherCoatSimulation halved = restingBesideASwing(), byHand = restingBesideASwing();
  for (FeatherCoatSimulation* sim : {&halved, &byHand}) {
    for (int step = 0; step < 3; ++step) sim->step(0.01);
    ASSERT_GT(sim->restingContacts().size(), 0u);
    swing(*sim);
  }
  ASSERT_EQ(halved.counters().retries, 0u);
  halved.step(0.01);
  ASSERT_GE(halved.counters().retries, 1u);
  // The same two halves by hand, the anchors' middle as the retry makes it.
  std::vector<StemFrame> middle = byHand.anchors();
  for (StemFrame& frame : middle)
    frame.axes = Eigen::Quaterniond(frame.axes)
                     .slerp(0.5, Eigen::Quaterniond(frame.axes))
                     .normalized()
                     .toRotationMatrix();
  const std::vector<StemFrame> end = byHand.anchors();
  byHand.step(0.005, middle);
  byHand.step(0.005, end);
  const auto& a = halved.restingContacts().contacts();
  const auto& b = byHand.restingContacts().contacts();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 0u);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].primitives, b[k].primitives);
    EXPECT_EQ(a[k].steps, b[k].steps) << "held over a step thrown away";
    EXPECT_EQ(a[k].multiplier, b[k].multiplier);
  }
  for (std::size_t s = 0; s < halved.stems().size(); ++s)
    for (std::size_t i = 0; i < halved.stems()[s].nodeCount(); ++i)
      EXPECT_EQ(halved.stems()[s].positions[i], byHand.stems()[s].positions[i]) << s << ", " << i;
}

// A step that cannot be resolved leaves the contact set as it was: a stem resting on the ground
// under a plate that is driven down through the ground in one step.
TEST(RestingContacts, AStepRefusedLeavesTheContactSet) {
  SimulationParameters parameters = softStems();
  parameters.maxHalvings = 3;
  BodyMesh body = ground(0);
  const BodyMesh plate = ground(0.1);
  for (const Vector3d& v : plate.vertices) body.vertices.push_back(v);
  for (const auto& t : plate.triangles) body.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  FeatherCoatSimulation sim({straightStem({-0.5, 0, parameters.restDistance()}, Vector3d::UnitX(),
                                          4, 0.25, parameters.stem)},
                            body, parameters);
  for (int step = 0; step < 3; ++step) sim.step(0.01);
  const std::vector<RestingContact> before = sim.restingContacts().contacts();
  ASSERT_GT(before.size(), 0u);
  std::vector<Vector3d> moved = body.vertices;
  for (int v = 4; v < 8; ++v) moved[v].z() = -0.1;
  EXPECT_THROW(sim.step(0.01, sim.anchors(), moved), StepFailure);
  EXPECT_GE(sim.counters().retries, 3u);
  const auto& after = sim.restingContacts().contacts();
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t k = 0; k < before.size(); ++k) {
    EXPECT_EQ(after[k].primitives, before[k].primitives);
    EXPECT_EQ(after[k].steps, before[k].steps);
    EXPECT_EQ(after[k].multiplier, before[k].multiplier);
  }
}

// A small coat pressed together in gusts: three stems lying over each other on the ground.
FeatherCoatSimulation gustyPile(int threads, bool resting) {
  SimulationParameters parameters = softStems();
  parameters.threads = threads;
  parameters.restingContacts = resting;
  parameters.wind.gustStrength = 2;
  parameters.wind.seed = 7;
  std::vector<FeatherStem> stems;
  for (int s = 0; s < 4; ++s)
    stems.push_back(straightStem({-0.3, 0.02 * s, 0.008 + 0.008 * s},
                                 Vector3d(1, 0.1 * s, 0.02).normalized(), 6, 0.08,
                                 parameters.stem));
  return FeatherCoatSimulation(std::move(stems), ground(0), parameters);
}

TEST(RestingContacts, OneThreadAndTwoGiveTheSameStepsBitForBit) {
  FeatherCoatSimulation one = gustyPile(1, true), two = gustyPile(2, true);
  for (int step = 0; step < 40; ++step) {
    one.step(1.0 / 60);
    two.step(1.0 / 60);
  }
  EXPECT_GT(one.counters().restingContacts, 0u);
  EXPECT_EQ(one.counters().restingContacts, two.counters().restingContacts);
  EXPECT_EQ(one.counters().ccdQueries, two.counters().ccdQueries);
  for (std::size_t s = 0; s < one.stems().size(); ++s)
    for (std::size_t i = 0; i < one.stems()[s].nodeCount(); ++i)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(one.stems()[s].positions[i][k], two.stems()[s].positions[i][k]) << s << ", " << i;
  ASSERT_EQ(one.restingContacts().size(), two.restingContacts().size());
  for (std::size_t k = 0; k < one.restingContacts().size(); ++k)
    EXPECT_EQ(one.restingContacts().contacts()[k].multiplier,
              two.restingContacts().contacts()[k].multiplier);
}

TEST(RestingContacts, WithTheStageOffTheCollisionsAloneLeaveNoIntersection) {
  FeatherCoatSimulation sim = gustyPile(2, false);
  for (int step = 0; step < 40; ++step) {
    sim.step(1.0 / 60);
    ASSERT_EQ(countPenetrations(sim.stems(), sim.body(), sim.nearestAllowed()), 0u)
        << "step " << step;
  }
  EXPECT_EQ(sim.counters().restingContacts, 0u);
  EXPECT_EQ(sim.restingContacts().size(), 0u);
  EXPECT_GT(sim.counters().repulsions, 0u);
  EXPECT_GT(sim.counters().ccdQueries, 0u);
}

}  // namespace
}  // namespace hirsute::dynamics
