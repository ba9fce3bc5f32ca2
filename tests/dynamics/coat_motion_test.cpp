// Feathers on a moving body: roots bound by barycentric coordinates follow a turning body
// exactly, a body that rises lifts the stem lying on it without passing through it, and a pose
// draws a feather at rest as its frame does and a bent one along its stem.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <glm/matrix.hpp>

#include "hirsute/hairs/dynamics/coat_motion.h"
#include "hirsute/hairs/dynamics/feather_poses.h"
#include "hirsute/hairs/feathers/feather_instances.h"
#include "hirsute/hairs/feathers/feather_part.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// A square of two triangles in the plane z = 0, [-1, 1]^2.
BodyMesh square() {
  BodyMesh body;
  body.vertices = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  body.triangles = {{0, 1, 2}, {0, 2, 3}};
  return body;
}

StemFrame frameAt(const Vector3d& origin, const Vector3d& heading) {
  StemFrame f;
  f.origin = origin;
  f.axes.col(2) = heading.normalized();
  f.axes.col(0) = f.axes.col(2).unitOrthogonal();
  f.axes.col(1) = f.axes.col(2).cross(f.axes.col(0));
  return f;
}

TEST(BodyAnchors, ARootBoundToATriangleTurnsAndMovesWithTheBody) {
  const BodyMesh body = square();
  const StemFrame root = frameAt({0.3, -0.2, 0.01}, {0.2, 0.1, 1});
  const std::vector<BodyAnchor> bound = bindAnchors(body, {root}, 0.05);
  ASSERT_EQ(bound.size(), 1u);
  ASSERT_GE(bound[0].triangle, 0);
  // The body turned about an axis and shifted: the root goes with it.
  const Matrix3d turn = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 0.5).normalized()).matrix();
  const Vector3d shift(0.4, -1, 2);
  BodyMesh moved = body;
  for (Vector3d& v : moved.vertices) v = turn * v + shift;
  const StemFrame on = anchorOnBody(moved, vertexNormals(moved), bound[0]);
  EXPECT_LT((on.origin - (turn * root.origin + shift)).norm(), 1e-12);
  EXPECT_LT((on.axes - turn * root.axes).norm(), 1e-12);
}

TEST(BodyAnchors, ARootFarFromTheBodyIsNotBound) {
  const std::vector<BodyAnchor> bound =
      bindAnchors(square(), {frameAt({0, 0, 0.5}, {0, 0, 1})}, 0.05);
  EXPECT_EQ(bound[0].triangle, -1);
}

TEST(MovingBody, ARisingBodyLiftsAStemLyingOnItWithoutPassingThroughIt) {
  SimulationParameters parameters;
  parameters.gravity = {0, 0, -9.81};
  std::vector<Vector3d> points;
  for (int i = 0; i <= 6; ++i) points.push_back({-0.3 + 0.1 * i, 0, 0.02});
  StemFrame anchor = frameAt(points.front(), {1, 0, 0});
  // The stem lies along the square, its root held 0.02 above it.
  FeatherCoatSimulation sim({buildStemFromPoints(points, anchor, parameters.stem)}, square(),
                            parameters);
  // The square rises 0.5 in half a second while the root rises with it: the stem must be
  // carried, never crossing the body.
  const int steps = 120;
  for (int k = 1; k <= steps; ++k) {
    const double lift = 0.5 * k / steps;
    BodyMesh body = square();
    for (Vector3d& v : body.vertices) v.z() += lift;
    StemFrame a = anchor;
    a.origin.z() += lift;
    sim.step(0.5 / steps, {a}, body.vertices);
    ASSERT_EQ(countPenetrations(sim.stems(), body, 0), 0u) << "step " << k;
    for (const Vector3d& p : sim.stems()[0].positions) ASSERT_GT(p.z(), lift) << "step " << k;
  }
}

// For each pair of segments (i of a, j of b) whose shadows on the xy plane cross: whether a's
// lies above b's there. Where the shadows of two segments cross before and after a step, their
// order changes only if one passed through the other.
std::map<std::pair<std::size_t, std::size_t>, bool> aboveWhereShadowsCross(
    const std::vector<Vector3d>& a, const std::vector<Vector3d>& b) {
  std::map<std::pair<std::size_t, std::size_t>, bool> out;
  for (std::size_t i = 0; i + 1 < a.size(); ++i)
    for (std::size_t j = 0; j + 1 < b.size(); ++j) {
      const Eigen::Vector2d p = a[i].head<2>(), r = a[i + 1].head<2>() - p;
      const Eigen::Vector2d q = b[j].head<2>(), d = b[j + 1].head<2>() - q;
      const double cross = r.x() * d.y() - r.y() * d.x();
      if (std::abs(cross) < 1e-12) continue;
      const Eigen::Vector2d qp = q - p;
      const double t = (qp.x() * d.y() - qp.y() * d.x()) / cross;
      const double u = (qp.x() * r.y() - qp.y() * r.x()) / cross;
      if (t < 0 || t > 1 || u < 0 || u > 1) continue;
      out[{i, j}] = a[i].z() + t * (a[i + 1].z() - a[i].z()) >
                    b[j].z() + u * (b[j + 1].z() - b[j].z());
    }
  return out;
}

TEST(MovingBody, AStackOfStemsPressedTogetherStaysInOrder) {
  SimulationParameters parameters;
  parameters.gravity = {0, 0, -9.81};
  parameters.stem.goldStiffness = 2000;
  parameters.stem.goldDamping = 20;
  // Five stems fanned 10 degrees apart over the origin, stacked 0.05 apart there, each anchored
  // at its left end, like the feathers of a coat; a plate over them comes down from 0.4 to 0.07
  // in a second, pressing them onto one another and onto the ground.
  std::vector<FeatherStem> stems;
  for (int s = 0; s < 5; ++s) {
    const double angle = (-20.0 + 10.0 * s) * M_PI / 180;
    const Vector3d along(std::cos(angle), std::sin(angle), 0);
    const Vector3d over(0, 0, 0.05 + 0.05 * s);
    std::vector<Vector3d> points;
    for (int i = 0; i <= 10; ++i) points.push_back(over + (-0.6 + 0.1 * i) * along);
    stems.push_back(buildStemFromPoints(points, frameAt(points.front(), along), parameters.stem));
  }
  BodyMesh body;
  body.vertices = {{-1, -1, 0},      {1, -1, 0},     {1, 1, 0},     {-1, 1, 0},
                   {-0.25, -1, 0.4}, {1, -1, 0.4},   {1, 1, 0.4},   {-0.25, 1, 0.4}};
  body.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}};
  FeatherCoatSimulation sim(stems, body, parameters);
  const std::vector<StemFrame> anchors = sim.anchors();
  // Every pair crosses over the origin, the higher-numbered stem on top.
  auto sides = [&](int a, int b) {
    return aboveWhereShadowsCross(sim.stems()[a].positions, sim.stems()[b].positions);
  };
  for (int a = 0; a < 5; ++a)
    for (int b = a + 1; b < 5; ++b) {
      const auto start = sides(a, b);
      ASSERT_FALSE(start.empty()) << a << " " << b;
      for (const auto& [segments, above] : start) EXPECT_FALSE(above);
    }
  const int steps = 240;
  std::size_t kept = 0;
  for (int k = 1; k <= steps; ++k) {
    std::map<std::pair<int, int>, std::map<std::pair<std::size_t, std::size_t>, bool>> before;
    for (int a = 0; a < 5; ++a)
      for (int b = a + 1; b < 5; ++b) before[{a, b}] = sides(a, b);
    BodyMesh now = body;
    for (int v = 4; v < 8; ++v) now.vertices[v].z() = 0.4 - 0.33 * k / steps;
    sim.step(1.0 / steps, anchors, now.vertices);
    ASSERT_EQ(countPenetrations(sim.stems(), now, 0), 0u) << "step " << k;
    for (auto& [pair, was] : before)
      for (const auto& [segments, above] : sides(pair.first, pair.second)) {
        const auto found = was.find(segments);
        if (found == was.end()) continue;
        ASSERT_EQ(above, found->second)
            << "stems " << pair.first << " and " << pair.second << " changed sides at step " << k;
        ++kept;
      }
  }
  EXPECT_GT(kept, 1000u);
  // Pressed under the plate.
  for (const FeatherStem& stem : sim.stems()) EXPECT_LT(stem.positions.back().z(), 0.07);
}

// A one-feather scene: type 1 of a straight rachis, calamus 0.2, rachis 0.8.
Scene oneFeather() {
  Scene scene;
  FeatherType type;
  type.calamusLength = 0.2f;
  type.rachisLength = 0.8f;
  type.rachisFrontCurvature = 0.1f;
  scene.organ<FeatherPart>().types.push_back(type);
  Feather f;
  f.position = {0.5f, 0.2f, -0.5f};
  f.heading = glm::normalize(glm::vec3(0, 1, 0.3f));
  f.up = glm::normalize(glm::cross(f.heading, glm::vec3(1, 0, 0)));
  f.size = 2;
  scene.organ<FeatherPart>().feathers.push_back(f);
  return scene;
}

TEST(FeatherPoses, AFeatherAtRestIsDrawnByItsFrame) {
  const Scene scene = oneFeather();
  const FeatherStem rest = buildFeatherStem(scene, scene.organ<FeatherPart>().feathers[0], 8);
  const FeatherPose pose = featherPoseOf(scene.organ<FeatherPart>().feathers[0], rest, rest);
  const FeatherMap posed(pose), rigid(featherToWorld(scene.organ<FeatherPart>().feathers[0]));
  for (const glm::vec3 local : {glm::vec3(0), glm::vec3(0.1f, 0.3f, 0.5f),
                                glm::vec3(-0.2f, -0.4f, 0.95f), glm::vec3(0, 0.1f, 1.2f)}) {
    EXPECT_LT(glm::distance(posed.point(local), rigid.point(local)), 1e-5f);
    EXPECT_LT(glm::distance(posed.normal(local, {1, 0, 0}), rigid.normal(local, {1, 0, 0})),
              1e-5f);
  }
}

TEST(FeatherPoses, ABentFeatherFollowsItsStem) {
  const Scene scene = oneFeather();
  const FeatherStem rest = buildFeatherStem(scene, scene.organ<FeatherPart>().feathers[0], 8);
  // The stem bent: each node turned about the root by an angle growing along it.
  FeatherStem moved = rest;
  const Vector3d root = rest.positions[0];
  for (std::size_t i = 1; i < moved.nodeCount(); ++i) {
    const Matrix3d turn = Eigen::AngleAxisd(0.08 * i, Vector3d::UnitX()).matrix();
    moved.positions[i] = root + turn * (rest.positions[i] - root);
  }
  rebuildFrames(moved, rest.frames[0]);
  const FeatherPose pose = featherPoseOf(scene.organ<FeatherPart>().feathers[0], rest, moved);
  const FeatherMap posed(pose);
  // Every point of the rachis on a node lands on the moved node.
  const glm::mat4 toLocal = glm::inverse(featherToWorld(scene.organ<FeatherPart>().feathers[0]));
  for (std::size_t i = 0; i < rest.nodeCount(); ++i) {
    const Vector3d& r = rest.positions[i];
    const glm::vec3 local(toLocal * glm::vec4(r.x(), r.y(), r.z(), 1));
    const glm::vec3 p = posed.point(local);
    EXPECT_LT((Vector3d(p.x, p.y, p.z) - moved.positions[i]).norm(), 1e-4) << "node " << i;
  }
  // Between nodes the rachis stays near the moved stem's polyline.
  const Vector3d restMid = 0.5 * (rest.positions[4] + rest.positions[5]);
  const glm::vec3 halfway =
      posed.point(glm::vec3(toLocal * glm::vec4(restMid.x(), restMid.y(), restMid.z(), 1)));
  const Vector3d mid = 0.5 * (moved.positions[4] + moved.positions[5]);
  EXPECT_LT((Vector3d(halfway.x, halfway.y, halfway.z) - mid).norm(), 0.01);
}

TEST(CoatMotion, AFrameWithOtherFeathersOrAnotherBodyIsRefused) {
  Scene first = oneFeather();
  TriangleMesh& mesh = first.meshFor(0);
  mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.indices = {0, 1, 2};
  CoatMotion motion(first, SimulationParameters{});
  ASSERT_EQ(motion.boundRoots(), 0u);  // the feather stands off the triangle
  Scene next = first;
  next.organ<FeatherPart>().feathers.push_back(next.organ<FeatherPart>().feathers[0]);
  EXPECT_THROW(motion.advance(0.04, 2, &next), FrameMismatch);
  Scene fewer = first;
  fewer.meshes.clear();
  EXPECT_THROW(motion.advance(0.04, 2, &fewer), FrameMismatch);
  motion.advance(0.04, 2, &first);
  Scene drawn = first;
  drawn.organ<FeatherPart>().feathers.clear();
  motion.pose(drawn);
  ASSERT_EQ(drawn.organ<FeatherPart>().feathers.size(), 1u);
  ASSERT_EQ(drawn.organ<FeatherPart>().poses.size(), 1u);
  EXPECT_EQ(drawn.organ<FeatherPart>().poses[0].heights.size(), 9u);
}

}  // namespace
}  // namespace hirsute::dynamics
