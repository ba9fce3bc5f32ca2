// Stems of particles: construction from a Scene feather, strain limiting under a strong pull,
// gold springs bringing a displaced stem back to rest, at any step.
#include "hirsute/hairs/dynamics/feather_stem.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "hirsute/hairs/dynamics/feather_coat_simulation.h"
#include "hirsute/hairs/feathers/feather_part.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// A straight stem of `segments` segments of `length` from `root` along +x, the front up (+z).
FeatherStem straightStem(const Vector3d& root, int segments, double length,
                         const StemParameters& parameters) {
  std::vector<Vector3d> points;
  for (int i = 0; i <= segments; ++i) points.push_back(root + Vector3d(i * length, 0, 0));
  StemFrame anchor;
  anchor.origin = root;
  anchor.axes.col(0) = Vector3d::UnitZ();
  anchor.axes.col(1) = Vector3d::UnitX().cross(Vector3d::UnitZ());
  anchor.axes.col(2) = Vector3d::UnitX();
  return buildStemFromPoints(points, anchor, parameters);
}

TEST(FeatherStem, FollowsTheFeathersRachisInWorldSpace) {
  Scene scene;
  FeatherType type;
  type.calamusLength = 0.1f;
  type.rachisLength = 1.0f;
  scene.organ<FeatherPart>().types.push_back(type);
  Feather feather;
  feather.position = glm::vec3(1, 2, 3);
  feather.heading = glm::vec3(0, 0, 1);
  feather.up = glm::vec3(1, 0, 0);
  feather.size = 2;
  const FeatherStem stem = buildFeatherStem(scene, feather, 5);
  ASSERT_EQ(stem.nodeCount(), 6u);
  EXPECT_TRUE(stem.positions[0].isApprox(Vector3d(1, 2, 3)));
  // The calamus is the first segment, the rachis the other four.
  EXPECT_TRUE(stem.positions[1].isApprox(Vector3d(1, 2, 3.2), 1e-6));
  EXPECT_TRUE(stem.positions[5].isApprox(Vector3d(1, 2, 5.2), 1e-6));
  double total = 0;
  for (double l : stem.restLengths) total += l;
  EXPECT_NEAR(total, 2.2, 1e-5);
  // Frames: tangent along the rachis, binormal the feather's front.
  for (const StemFrame& frame : stem.frames) {
    EXPECT_TRUE(frame.axes.col(2).isApprox(Vector3d::UnitZ(), 1e-6));
    EXPECT_TRUE(frame.axes.col(0).isApprox(Vector3d::UnitX(), 1e-6));
  }
}

TEST(FeatherStem, GoldPositionsAreTheRestShapeInTheParentsFrame) {
  std::vector<Vector3d> points{{0, 0, 0}, {0.1, 0, 0}, {0.2, 0.05, 0}, {0.25, 0.15, 0.02}};
  StemFrame anchor;
  anchor.axes.col(0) = Vector3d::UnitZ();
  anchor.axes.col(1) = Vector3d::UnitY();
  anchor.axes.col(2) = Vector3d::UnitX();
  anchor.axes.col(1) = anchor.axes.col(2).cross(anchor.axes.col(0));
  FeatherStem stem = buildStemFromPoints(points, anchor);
  for (std::size_t i = 1; i < points.size(); ++i)
    EXPECT_TRUE(worldGoldPosition(stem, i).isApprox(points[i], 1e-12));
  // Rotating the whole stem with its anchor carries the gold positions along.
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (Vector3d& p : stem.positions) p = turn * p;
  StemFrame turned = anchor;
  turned.axes = turn * anchor.axes;
  rebuildFrames(stem, turned);
  for (std::size_t i = 1; i < points.size(); ++i)
    EXPECT_TRUE(worldGoldPosition(stem, i).isApprox(turn * points[i], 1e-12));
}

// A stem whose anchor is jerked upwards each step while a gravity two hundred times Earth's pulls
// it down.
double largestStrainUnderPull(double strainLimit) {
  StemParameters parameters;
  parameters.goldStiffness = 10;
  parameters.strainLimit = strainLimit;
  SimulationParameters simulation;
  simulation.stem = parameters;
  simulation.gravity = Vector3d(0, 0, -2000);
  FeatherCoatSimulation sim({straightStem(Vector3d::Zero(), 8, 0.1, parameters)}, {}, simulation);
  double largest = 0;
  std::vector<StemFrame> anchors = sim.anchors();
  for (int step = 0; step < 60; ++step) {
    anchors[0].origin += Vector3d(0, 0.01, 0.05);
    sim.step(1.0 / 240, anchors);
    largest = std::max(largest, largestStrain(sim.stems()[0]));
  }
  return largest;
}

TEST(FeatherStem, StrainLimitingKeepsEverySegmentWithinOnePercentUnderAStrongPull) {
  EXPECT_LE(largestStrainUnderPull(0.01), 0.01);
  // The same pull without the limit stretches the stem far beyond it.
  EXPECT_GT(largestStrainUnderPull(1e9), 0.05);
}

TEST(FeatherStem, StrainLimitingAddsItsCorrectionsToTheVelocities) {
  StemParameters parameters;
  FeatherStem stem = straightStem(Vector3d::Zero(), 4, 0.1, parameters);
  stem.positions[3] += Vector3d(0.02, 0.01, 0);
  stem.positions[4] += Vector3d(0.06, -0.02, 0.01);
  const std::vector<Vector3d> before = stem.positions;
  const double h = 0.01;
  limitStrain(stem, h);
  EXPECT_LE(largestStrain(stem), 0.01);
  EXPECT_TRUE(stem.positions[0].isApprox(before[0]));  // the anchor never moves
  double moved = 0;
  for (std::size_t i = 0; i < stem.nodeCount(); ++i) {
    EXPECT_TRUE((stem.velocities[i] * h).isApprox(stem.positions[i] - before[i], 1e-9) ||
                (stem.positions[i] - before[i]).norm() < 1e-15);
    moved = std::max(moved, (stem.positions[i] - before[i]).norm());
  }
  EXPECT_GT(moved, 0.01);
}

TEST(FeatherStem, GoldSpringsReturnADisplacedFeatherToRest) {
  StemParameters parameters;
  parameters.goldStiffness = 200;
  parameters.goldDamping = 20;
  SimulationParameters simulation;
  simulation.stem = parameters;
  simulation.gravity = Vector3d::Zero();
  const FeatherStem rest = straightStem(Vector3d::Zero(), 6, 0.1, parameters);
  FeatherCoatSimulation sim({rest}, {}, simulation);
  // Released bent: the stem turned 40 degrees about its anchor, and curled further.
  FeatherStem& stem = sim.stem(0);
  for (std::size_t i = 1; i < stem.nodeCount(); ++i) {
    const double angle = 0.7 + 0.05 * i;
    stem.positions[i] = Eigen::AngleAxisd(angle, Vector3d::UnitZ()) * rest.positions[i];
  }
  double displaced = 0;
  for (std::size_t i = 1; i < stem.nodeCount(); ++i)
    displaced = std::max(displaced, (stem.positions[i] - rest.positions[i]).norm());
  ASSERT_GT(displaced, 0.3);
  for (int step = 0; step < 360; ++step) sim.step(1.0 / 120);
  double remaining = 0;
  for (std::size_t i = 1; i < stem.nodeCount(); ++i)
    remaining = std::max(remaining, (sim.stems()[0].positions[i] - rest.positions[i]).norm());
  EXPECT_LT(remaining, 1e-3);
}

// A stem curled in the plane z = 0 from the origin along +x: `segments` segments of `length`,
// each turned by `bend` from the one before; the front up (+z).
FeatherStem curledStem(int segments, double length, double bend, const StemParameters& parameters) {
  std::vector<Vector3d> points{Vector3d::Zero()};
  for (int i = 0; i < segments; ++i)
    points.push_back(points.back() + length * Vector3d(std::cos(i * bend), std::sin(i * bend), 0));
  StemFrame anchor;
  anchor.axes.col(0) = Vector3d::UnitZ();
  anchor.axes.col(1) = Vector3d::UnitY();
  anchor.axes.col(2) = Vector3d::UnitX();
  return buildStemFromPoints(points, anchor, parameters);
}

// The coat's springs (models/coat-bending), or ones `stiffness` times as stiff.
StemParameters coatSprings(double stiffness = 1) {
  StemParameters parameters;
  parameters.goldStiffness = 20000 * stiffness;
  parameters.goldDamping = 100;
  return parameters;
}

// The curled stem after a second in `steps` steps, from rest under gravity along -y.
FeatherStem settledUnderGravity(int steps) {
  SimulationParameters simulation;
  simulation.stem = coatSprings();
  simulation.gravity = Vector3d(0, -9.81, 0);
  FeatherCoatSimulation sim({curledStem(8, 0.1, 0.1, simulation.stem)}, {}, simulation);
  for (int step = 0; step < steps; ++step) sim.step(1.0 / steps);
  return sim.stems()[0];
}

TEST(FeatherStem, AStemSettlesUnderGravityToTheSameShapeWhateverTheStep) {
  const FeatherStem fine = settledUnderGravity(960);
  const FeatherStem coarse = settledUnderGravity(24);
  const FeatherStem rest = curledStem(8, 0.1, 0.1, coatSprings());
  // Gravity bends it away from its rest shape ...
  EXPECT_GT((fine.positions.back() - rest.positions.back()).norm(), 0.005);
  // ... to the equilibrium, which does not depend on the step: one step a frame at 24 frames a
  // second, 21 times longer than a turn followed explicitly allowed, gives the same shape.
  for (std::size_t i = 1; i < fine.nodeCount(); ++i) {
    EXPECT_LT(fine.velocities[i].norm(), 1e-6);
    EXPECT_LT(coarse.velocities[i].norm(), 1e-6);
    EXPECT_LT((coarse.positions[i] - fine.positions[i]).norm(), 1e-6) << "node " << i;
  }
}

// The energy of the gold springs and of the motion.
double stemEnergy(FeatherStem stem, const StemFrame& anchor) {
  rebuildFrames(stem, anchor);
  double energy = 0;
  for (std::size_t i = 1; i < stem.nodeCount(); ++i) {
    energy += 0.5 * stem.masses[i] * stem.velocities[i].squaredNorm();
    energy += 0.5 * stem.parameters.goldStiffness *
              (stem.positions[i] - worldGoldPosition(stem, i)).squaredNorm();
  }
  return energy;
}

// The largest angle between two successive segments.
double sharpestTurn(const FeatherStem& stem) {
  double sharpest = 0;
  for (std::size_t i = 2; i < stem.nodeCount(); ++i) {
    const Vector3d a = stem.positions[i - 1] - stem.positions[i - 2];
    const Vector3d b = stem.positions[i] - stem.positions[i - 1];
    sharpest = std::max(sharpest, std::atan2(a.cross(b).norm(), a.dot(b)));
  }
  return sharpest;
}

// What a curled stem does when released curled twice as far, without gravity, in `steps` steps a
// second for half a second: the most energy it had, its sharpest turn, and how far from
// rest it ends.
struct Release {
  double mostEnergy = 0, sharpestTurn = 0, endsFromRest = 0;
};

Release releaseBentStem(const StemParameters& parameters, int steps) {
  SimulationParameters simulation;
  simulation.stem = parameters;
  simulation.gravity = Vector3d::Zero();
  const FeatherStem rest = curledStem(8, 0.1, 0.1, parameters);
  FeatherCoatSimulation sim({rest}, {}, simulation);
  sim.stem(0).positions = curledStem(8, 0.1, 0.2, parameters).positions;
  Release release;
  for (int step = 0; step <= steps / 2; ++step) {
    if (step > 0) sim.step(1.0 / steps);
    const FeatherStem& stem = sim.stems()[0];
    release.mostEnergy = std::max(release.mostEnergy, stemEnergy(stem, sim.anchors()[0]));
    release.sharpestTurn = std::max(release.sharpestTurn, sharpestTurn(stem));
  }
  for (std::size_t i = 1; i < rest.nodeCount(); ++i)
    release.endsFromRest =
        std::max(release.endsFromRest, (sim.stems()[0].positions[i] - rest.positions[i]).norm());
  return release;
}

TEST(FeatherStem, AStemReleasedBentGainsNoEnergyAndNeverFolds) {
  // The coat's springs, then fifty times stiffer ones (k = 10^6, which folded at four steps a
  // frame while the turn was explicit), at the coat's four steps a frame of 24 frames a second
  // and at one; against the same stem stepped finely (the springs are not conservative: the
  // turn of a frame is not reacted, so the energy may rise a little above the released one).
  for (const double stiffness : {1.0, 50.0}) {
    const Release fine = releaseBentStem(coatSprings(stiffness), 9600);
    for (const int steps : {96, 24}) {
      const Release coarse = releaseBentStem(coatSprings(stiffness), steps);
      EXPECT_LE(coarse.mostEnergy, fine.mostEnergy) << stiffness << ", " << steps;
      EXPECT_LE(coarse.sharpestTurn, fine.sharpestTurn) << stiffness << ", " << steps;
      EXPECT_LT(coarse.endsFromRest, 1e-3) << stiffness << ", " << steps;
    }
  }
}

}  // namespace
}  // namespace hirsute::dynamics
