// Generalized cylinders: the geometry of tubes built from control-point turtle states
// (cpfg-generalized-cylinders.md §1–§4), and cpfg's own triangles for its GeneralizedCylinder
// model.
#include "hirsute/interpreter/generalized_cylinder.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtx/rotate_vector.hpp>
#include <iterator>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"

namespace hirsute {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTolerance = 1e-5;

double radians(double degrees) {
  return degrees * kPi / 180.0;
}

// Turtle rotations as cpfg applies them (cpfg-features.md (d)), written here independently of
// the turtle so that the builder is tested alone.
void turnLeft(TurtleState& s, double degrees) {  // `+`: about U, H toward L
  const double c = std::cos(radians(degrees)), n = std::sin(radians(degrees));
  const glm::dvec3 h = s.heading, l = s.left;
  s.heading = h * c + l * n;
  s.left = l * c - h * n;
}

void pitchDown(TurtleState& s, double degrees) {  // `&`: about L, H toward U
  const double c = std::cos(radians(degrees)), n = std::sin(radians(degrees));
  const glm::dvec3 h = s.heading, u = s.up;
  s.heading = h * c + u * n;
  s.up = u * c - h * n;
}

void rollRight(TurtleState& s, double degrees) {  // `/`: about H, L toward U
  const double c = std::cos(radians(degrees)), n = std::sin(radians(degrees));
  const glm::dvec3 l = s.left, u = s.up;
  s.left = l * c + u * n;
  s.up = u * c - l * n;
}

void move(TurtleState& s, double length) {
  s.position += s.heading * length;
}

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected,
                double tolerance = kTolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

glm::dvec3 d(const glm::vec3& v) {
  return glm::dvec3(v);
}

class GeneralizedCylinderTest : public ::testing::Test {
 protected:
  GeneralizedCylinderTest() { resources.view.lineStyle = LineStyle::Cylinder; }

  TurtleState turtle(double width = 1, int sides = 8) const {
    TurtleState s;
    s.lineWidth = width;
    s.cylinderSides = sides;
    return s;
  }

  // The mesh index of vertex j of ring k of a segment.
  std::uint32_t vertexIndex(const CylinderSegment& segment, int k, int j) const {
    return segment.firstVertex + static_cast<std::uint32_t>(k * (segment.sides + 1) + j);
  }

  glm::dvec3 vertex(const CylinderSegment& segment, int k, int j) const {
    const TriangleMesh& mesh = scene.meshes.at(static_cast<std::size_t>(segment.mesh));
    return d(mesh.positions.at(vertexIndex(segment, k, j)));
  }

  // A closed square-ish and an open contour, as B-spline control polygons with the end points
  // tripled (cpfg-generalized-cylinders.md §3).
  void addContours() {
    Contour square;
    square.closed = true;
    square.controlPoints = {{1.2, 0, 0},  {1.2, 1.2, 0},   {0, 1.2, 0},  {-1.2, 1.2, 0},
                            {-1.2, 0, 0}, {-1.2, -1.2, 0}, {0, -1.2, 0}, {1.2, -1.2, 0}};
    resources.contours.add(1, square);
    Contour open;
    open.closed = false;
    open.controlPoints = {{-1, 0, 0}, {-1, 0, 0}, {-1, 0, 0}, {0, 0.5, 0},
                          {1, 0, 0},  {1, 0, 0},  {1, 0, 0}};
    resources.contours.add(2, open);
  }

  ModelResources resources;
  Scene scene;
};

TEST_F(GeneralizedCylinderTest, StraightTubeHasRingsOfTheRadiusAndTwoTrianglesPerSidePerStrip) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(2.0, 8);
  s.tangentParameter = {1.0, 1.0};  // @Gt(1): tangents as long as the chord space rings evenly
  builder.start(s);
  move(s, 3.0);
  builder.end(s, 4);

  ASSERT_EQ(scene.cylinderSegments.size(), 1u);
  const CylinderSegment& segment = scene.cylinderSegments[0];
  EXPECT_EQ(segment.strips, 4);
  ASSERT_EQ(segment.rings.size(), 5u);
  EXPECT_EQ(segment.indexCount, 4u * 2u * 8u * 3u);
  EXPECT_EQ(scene.triangleCount(), 4u * 2u * 8u);
  EXPECT_EQ(segment.vertexCount, 5u * 9u);
  for (int k = 0; k <= 4; ++k) {
    EXPECT_NEAR(segment.rings[static_cast<std::size_t>(k)].radius, 1.0, kTolerance);
    for (int j = 0; j <= 8; ++j) {
      const glm::dvec3 v = vertex(segment, k, j);
      // Axis along +y; the ring lies in the plane y = 0.75·k at distance 1 from the axis.
      EXPECT_NEAR(v.y, 0.75 * k, kTolerance);
      EXPECT_NEAR(std::hypot(v.x, v.z), 1.0, kTolerance);
    }
  }
  // Sample 0 (the seam) lies along the turtle's up vector, and the contour's +y along -L.
  expectNear(vertex(segment, 0, 0), glm::dvec3(0, 0, -1));
  expectNear(vertex(segment, 0, 2), glm::dvec3(1, 0, 0));
  EXPECT_FALSE(builder.active());
}

TEST_F(GeneralizedCylinderTest, TrianglesFaceAlongTheirNormals) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(1.0, 12);
  builder.start(s);
  move(s, 2.0);
  turnLeft(s, 30);
  builder.point(s, 3);
  move(s, 1.0);
  builder.end(s, 2);
  const TriangleMesh& mesh = scene.meshes.at(0);
  ASSERT_EQ(mesh.triangleCount(), (3u + 2u) * 2u * 12u);
  // Circle normals point from the ring centre to the vertex.
  for (const CylinderSegment& segment : scene.cylinderSegments) {
    for (int k = 0; k <= segment.strips; ++k) {
      const glm::dvec3 centre = d(segment.rings[static_cast<std::size_t>(k)].frame.position);
      for (int j = 0; j <= segment.sides; ++j) {
        const std::uint32_t index = vertexIndex(segment, k, j);
        expectNear(d(mesh.normals[index]), glm::normalize(d(mesh.positions[index]) - centre));
      }
    }
  }
  // Counter-clockwise seen from outside.
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    const glm::dvec3 a = d(mesh.positions[mesh.indices[i]]);
    const glm::dvec3 b = d(mesh.positions[mesh.indices[i + 1]]);
    const glm::dvec3 c = d(mesh.positions[mesh.indices[i + 2]]);
    const glm::dvec3 faceNormal = glm::cross(b - a, c - a);
    EXPECT_GT(glm::dot(faceNormal, d(mesh.normals[mesh.indices[i]])), 0.0) << "triangle " << i / 3;
  }
}

TEST_F(GeneralizedCylinderTest, NormalsTurnWhereTheRadiusProfileDipsBelowZero) {
  // FernLeaf's idiom: zero widths at both ends and a steep @Gr start tangent (-90°, 1), so the
  // radius r(s) = −s(1 − s)² runs negative and the contour is turned half around. The normals
  // follow (cpfg scales them by r·dX/ds), still facing the way the triangles face.
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(0.0, 8);
  s.tangentParameter = {1.0, 1.0};
  s.radiusTangent = {glm::dvec2(1, 0), glm::dvec2(0, -1)};
  builder.start(s);
  move(s, 1.0);
  builder.end(s, 4);
  const CylinderSegment& segment = scene.cylinderSegments.at(0);
  const TriangleMesh& mesh = scene.meshes.at(0);
  const CylinderRing& middle = segment.rings[2];
  ASSERT_LT(middle.radius, 0.0);
  for (int j = 0; j <= 8; ++j) {
    const std::uint32_t index = vertexIndex(segment, 2, j);
    // The vertex lies at r·c_j, on the far side; the normal points away from the axis there.
    const glm::dvec3 outward = d(mesh.positions[index]) - d(middle.frame.position);
    expectNear(d(mesh.normals[index]), glm::normalize(outward));
  }
  for (std::uint32_t i = segment.firstIndex + 3 * 16; i < segment.firstIndex + 3 * 48; i += 3) {
    const glm::dvec3 a = d(mesh.positions[mesh.indices[i]]);
    const glm::dvec3 b = d(mesh.positions[mesh.indices[i + 1]]);
    const glm::dvec3 c = d(mesh.positions[mesh.indices[i + 2]]);
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), d(mesh.normals[mesh.indices[i]])), 0.0);
  }
}

TEST_F(GeneralizedCylinderTest, RadiusIsLinearByDefault) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(2.0);
  builder.start(s);
  move(s, 4.0);
  s.lineWidth = 4.0;
  builder.end(s, 4);

  const CylinderSegment& segment = scene.cylinderSegments.at(0);
  for (int k = 0; k <= 4; ++k) {
    const CylinderRing& ring = segment.rings[static_cast<std::size_t>(k)];
    EXPECT_NEAR(ring.radius, 1.0 + 0.25 * k, kTolerance);
    EXPECT_NEAR(ring.axisParameter, 0.25 * k, kTolerance);
    // Straight axis with the default tangents 1.2·len: P(t) = 4·(1.2t − 0.6t² + 0.4t³).
    const double t = 0.25 * k;
    EXPECT_NEAR(ring.frame.position.y, 4.0 * (1.2 * t - 0.6 * t * t + 0.4 * t * t * t), kTolerance);
    const glm::dvec3 v = vertex(segment, k, 3);
    EXPECT_NEAR(std::hypot(v.x, v.z), 1.0 + 0.25 * k, kTolerance);
  }
}

TEST_F(GeneralizedCylinderTest, RadiusFollowsGrTangents) {
  // @Gr(0,1) at both ends: flat tangents (1, 0), so the radius eases in and out:
  // Y(s) = r1 + Δr(3s² − 2s³), X(s) = s.
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(2.0);
  s.radiusTangent = {glm::dvec2(1, 0), glm::dvec2(1, 0)};
  builder.start(s);
  move(s, 4.0);
  s.lineWidth = 6.0;
  builder.end(s, 4);
  const CylinderSegment& eased = scene.cylinderSegments.at(0);
  for (int k = 0; k <= 4; ++k) {
    const double u = 0.25 * k;
    EXPECT_NEAR(eased.rings[static_cast<std::size_t>(k)].radius,
                1.0 + 2.0 * (3 * u * u - 2 * u * u * u), kTolerance);
    EXPECT_NEAR(eased.rings[static_cast<std::size_t>(k)].axisParameter, u, kTolerance);
  }
  EXPECT_NEAR(eased.rings[1].radius, 1.3125, kTolerance);

  // A start tangent (2, 0): X(s) = 2s − 2s² + s³ moves the rings along the axis parameter.
  scene.clear();
  TurtleState t = turtle(2.0);
  t.radiusTangent = {glm::dvec2(0.0), glm::dvec2(2, 0)};
  builder.start(t);
  move(t, 4.0);
  builder.end(t, 2);
  const CylinderSegment& shifted = scene.cylinderSegments.at(0);
  EXPECT_NEAR(shifted.rings[1].axisParameter, 0.625, kTolerance);
  // Straight axis with tangents 1.2·len·H: P(t) = 4·(1.2t + (3 − 3.6)t² + (−2 + 2.4)t³) along y.
  const double tm = 0.625;
  EXPECT_NEAR(shifted.rings[1].frame.position.y,
              4 * (1.2 * tm - 0.6 * tm * tm + 0.4 * tm * tm * tm), kTolerance);

  // The scale flag (@Gr(1)) on the second point multiplies the r-components by the length:
  // start tangent (1, 0.5) on a segment of length 2 becomes (1, 1), end tangent (1, 0) stays.
  // Y(½) = r1 + Δr/2 + T0y/8.
  scene.clear();
  TurtleState w = turtle(2.0);
  w.radiusTangent = {glm::dvec2(1, 0), glm::dvec2(1, 0.5)};
  builder.start(w);
  move(w, 2.0);
  w.lineWidth = 4.0;  // Δr = 1
  w.scaleRadiusTangents = true;
  builder.end(w, 2);
  const CylinderSegment& scaled = scene.cylinderSegments.at(0);
  EXPECT_NEAR(scaled.rings[1].radius, 1.625, kTolerance);

  scene.clear();
  w.position = glm::dvec3(0.0);
  w.lineWidth = 2.0;
  w.scaleRadiusTangents = false;
  builder.start(w);
  move(w, 2.0);
  w.lineWidth = 4.0;
  builder.end(w, 2);
  EXPECT_NEAR(scene.cylinderSegments.at(0).rings[1].radius, 1.5625, kTolerance);
}

TEST_F(GeneralizedCylinderTest, HermiteAxisPassesThroughControlPointsWithTheirTangents) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(0.2, 6);
  s.tangentParameter = {9.0, 0.5};  // the outgoing 0.5 counts at the first point
  builder.start(s);
  const glm::dvec3 p1 = s.position, h1 = s.heading;
  s.position = glm::dvec3(2, 1, 0.5);
  turnLeft(s, -70);
  pitchDown(s, 20);
  s.tangentParameter = {2.0, 7.0};  // the incoming 2.0 counts at the second point
  const glm::dvec3 p2 = s.position, h2 = s.heading;
  builder.end(s, 8);

  const CylinderSegment& segment = scene.cylinderSegments.at(0);
  const double len = glm::length(p2 - p1);
  const glm::dvec3 r1 = h1 * (0.5 * len), r2 = h2 * (2.0 * len);
  ASSERT_EQ(segment.rings.size(), 9u);
  expectNear(d(segment.rings.front().frame.position), p1);
  expectNear(d(segment.rings.back().frame.position), p2);
  for (int k = 0; k <= 8; ++k) {
    // Cubic Hermite basis: P = h00 P1 + h10 R1 + h01 P2 + h11 R2.
    const double t = k / 8.0;
    const double h00 = 2 * t * t * t - 3 * t * t + 1, h10 = t * t * t - 2 * t * t + t;
    const double h01 = -2 * t * t * t + 3 * t * t, h11 = t * t * t - t * t;
    const glm::dvec3 p = h00 * p1 + h10 * r1 + h01 * p2 + h11 * r2;
    const glm::dvec3 dp = (6 * t * t - 6 * t) * p1 + (3 * t * t - 4 * t + 1) * r1 +
                          (-6 * t * t + 6 * t) * p2 + (3 * t * t - 2 * t) * r2;
    const CylinderRing& ring = segment.rings[static_cast<std::size_t>(k)];
    expectNear(d(ring.frame.position), p);
    expectNear(d(ring.frame.heading), glm::normalize(dp));
    // Rings within 90° of the start heading are perpendicular to the axis there.
    if (glm::dot(h1, d(ring.frame.heading)) > 0.0) {
      EXPECT_NEAR(glm::dot(d(ring.frame.up), d(ring.frame.heading)), 0.0, 1e-5);
    }
  }
}

TEST_F(GeneralizedCylinderTest, OneStripIgnoresTheCurve) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(1.0);
  builder.start(s);
  move(s, 1.0);
  turnLeft(s, 60);
  move(s, 1.0);
  builder.end(s, 1);
  const CylinderSegment& segment = scene.cylinderSegments.at(0);
  ASSERT_EQ(segment.rings.size(), 2u);
  EXPECT_NEAR(segment.axisLength, glm::length(s.position), kTolerance);
  EXPECT_EQ(segment.indexCount, 2u * 8u * 3u);
}

TEST_F(GeneralizedCylinderTest, TwistOffIgnoresRollsBetweenControlPoints) {
  auto build = [&](double roll) {
    Scene result;
    GeneralizedCylinderBuilder builder(resources, &result);
    TurtleState s = turtle(1.0, 8);
    builder.start(s);
    move(s, 1.0);
    turnLeft(s, 40);
    move(s, 1.0);
    rollRight(s, roll);
    builder.point(s, 4);
    rollRight(s, roll);
    move(s, 1.0);
    builder.end(s, 4);
    return result;
  };
  const Scene plain = build(0.0);
  const Scene rolled = build(65.0);
  ASSERT_EQ(plain.meshes.size(), 1u);
  ASSERT_EQ(rolled.meshes.size(), 1u);
  ASSERT_EQ(plain.meshes[0].positions.size(), rolled.meshes[0].positions.size());
  for (std::size_t i = 0; i < plain.meshes[0].positions.size(); ++i) {
    expectNear(d(rolled.meshes[0].positions[i]), d(plain.meshes[0].positions[i]));
  }
  // The frame at the second point is the first one carried along: U stays (0, 0, −1) for turns
  // about U, whatever the turtle's own up vector.
  expectNear(d(rolled.cylinderSegments.at(0).end.up), glm::dvec3(0, 0, -1));
  expectNear(d(rolled.cylinderSegments.at(1).start.up), glm::dvec3(0, 0, -1));
  expectNear(d(rolled.cylinderSegments.at(1).end.up), glm::dvec3(0, 0, -1));
}

TEST_F(GeneralizedCylinderTest, TwistOffCarriesTheFrameWithCpfgsArcsine) {
  // A pitch of 120° between two control points: cpfg rotates the previous frame by
  // asin(|H1 × H2|) = 60°, not 120°, about H1 × H2.
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(1.0);
  builder.start(s);
  const TurtleState first = s;
  move(s, 1.0);
  pitchDown(s, 120);
  move(s, 1.0);
  builder.end(s, 3);
  const glm::dvec3 axis = glm::normalize(glm::cross(first.heading, s.heading));
  const glm::dvec3 up = glm::rotate(first.up, radians(60), axis);
  const CylinderSegment& segment = scene.cylinderSegments.at(0);
  expectNear(d(segment.end.up), up);
  expectNear(d(segment.end.left), glm::cross(s.heading, up));
  expectNear(d(segment.end.heading), s.heading);

  // Up to 90° the carried frame is the turtle's own frame for a plain pitch.
  scene.clear();
  TurtleState t = turtle(1.0);
  builder.start(t);
  move(t, 1.0);
  pitchDown(t, 80);
  move(t, 1.0);
  builder.end(t, 3);
  expectNear(d(scene.cylinderSegments.at(0).end.up), t.up);
  expectNear(d(scene.cylinderSegments.at(0).end.left), t.left);
}

TEST_F(GeneralizedCylinderTest, TwistOnDistributesTheRollLinearly) {
  resources.view.twistOfCylinders = true;
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(2.0, 8);
  // A radius start tangent (2, 0) puts ring k at the axis parameter t = 2u − 2u² + u³, u = k/4.
  s.radiusTangent = {glm::dvec2(0.0), glm::dvec2(2, 0)};
  builder.start(s);
  const glm::dvec3 up0 = s.up;
  move(s, 2.0);
  rollRight(s, 80);
  builder.end(s, 4);
  const CylinderSegment& segment = scene.cylinderSegments.at(0);
  for (int k = 0; k <= 4; ++k) {
    // `/` turns U toward −L; about H that is a rotation by −80°·t.
    const double u = k / 4.0;
    const double t = 2 * u - 2 * u * u + u * u * u;
    const glm::dvec3 expected = glm::rotate(up0, radians(-80.0 * t), glm::dvec3(0, 1, 0));
    expectNear(d(segment.rings[static_cast<std::size_t>(k)].frame.up), expected);
    expectNear(vertex(segment, k, 0),
               d(segment.rings[static_cast<std::size_t>(k)].frame.position) + expected);
  }
  expectNear(d(segment.end.up), s.up);
}

TEST_F(GeneralizedCylinderTest, ContoursBlendAlongTheAxis) {
  addContours();
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(2.0, 16);
  s.contour = 0;
  builder.start(s);
  move(s, 2.0);
  s.contour = 1;
  builder.end(s, 4);
  const ContourSamples& circle = resources.contours.samples(0, 16);
  const ContourSamples& square = resources.contours.samples(1, 16);
  const CylinderSegment& segment = scene.cylinderSegments.at(0);
  EXPECT_TRUE(segment.closed);
  ASSERT_EQ(segment.contourStart.size(), 16u);
  ASSERT_EQ(segment.contourEnd.size(), 16u);
  for (int k = 0; k <= 4; ++k) {
    const CylinderRing& ring = segment.rings[static_cast<std::size_t>(k)];
    for (int j = 0; j <= 16; ++j) {
      const std::size_t i = static_cast<std::size_t>(j % 16);
      const double t = ring.axisParameter;
      const glm::dvec2 q =
          double(ring.radius) * ((1.0 - t) * circle.points[i] + t * square.points[i]);
      const glm::dvec3 expected =
          d(ring.frame.position) + q.x * d(ring.frame.up) - q.y * d(ring.frame.left);
      expectNear(vertex(segment, k, j), expected);
    }
  }
  for (std::size_t i = 0; i < 16; ++i) {
    EXPECT_NEAR(segment.contourEnd[i].x, square.points[i].x, 1e-6);
    EXPECT_NEAR(segment.contourEnd[i].y, square.points[i].y, 1e-6);
  }
  EXPECT_NEAR(segment.girthEnd, square.length, 1e-5);
}

TEST_F(GeneralizedCylinderTest, ContourDepthShiftsVerticesAlongTheHeading) {
  // §2: a contour's z moves its ring vertices by radius·z·H/len.
  Contour raised;
  raised.closed = true;
  raised.controlPoints = {{1, 0, 0.5}, {0, 1, 0.5}, {-1, 0, 0.5}, {0, -1, 0.5}};
  resources.contours.add(3, raised);
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(2.0, 8);
  s.contour = 3;
  builder.start(s);
  move(s, 4.0);
  builder.end(s, 2);
  const ContourSamples& samples = resources.contours.samples(3, 8);
  const CylinderSegment& segment = scene.cylinderSegments.at(0);
  for (int j = 0; j < 8; ++j) {
    const glm::dvec2 q = samples.points[static_cast<std::size_t>(j)];
    const glm::dvec3 flat = q.x * s.up - q.y * s.left;
    expectNear(vertex(segment, 0, j), flat + glm::dvec3(0, 0.5 / 4.0, 0));
  }
}

TEST_F(GeneralizedCylinderTest, OpenContoursGiveOpenStrips) {
  addContours();
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(3.0, 6);
  s.contour = 2;
  builder.start(s);
  move(s, 2.0);
  builder.end(s, 2);
  const ContourSamples& open = resources.contours.samples(2, 6);
  ASSERT_FALSE(open.closed);
  ASSERT_EQ(open.points.size(), 7u);
  const CylinderSegment& segment = scene.cylinderSegments.at(0);
  EXPECT_FALSE(segment.closed);
  ASSERT_EQ(segment.contourStart.size(), 7u);
  EXPECT_EQ(segment.indexCount, 2u * 2u * 6u * 3u);
  for (int j = 0; j <= 6; ++j) {
    const glm::dvec2 q = 1.5 * open.points[static_cast<std::size_t>(j)];
    expectNear(vertex(segment, 0, j), glm::dvec3(0, 0, 0) + q.x * s.up - q.y * s.left);
    EXPECT_NEAR(segment.contourStart[static_cast<std::size_t>(j)].x, q.x, 1e-6);
    EXPECT_NEAR(segment.contourStart[static_cast<std::size_t>(j)].y, q.y, 1e-6);
  }
  // The two edges stay apart: the last sample is the far edge, not the first one again.
  EXPECT_GT(glm::length(vertex(segment, 0, 6) - vertex(segment, 0, 0)), 2.0);
  EXPECT_NEAR(segment.girthStart, open.length * 1.5, 1e-5);
}

TEST_F(GeneralizedCylinderTest, SegmentDataIsExact) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(2.0, 10);
  move(s, 0.5);
  builder.start(s);
  const TurtleState first = s;
  move(s, 3.0);
  s.lineWidth = 1.0;
  builder.point(s, 3);
  const TurtleState second = s;
  move(s, 2.0);
  builder.end(s, 5);

  ASSERT_EQ(scene.cylinderSegments.size(), 2u);
  const CylinderSegment& a = scene.cylinderSegments[0];
  const CylinderSegment& b = scene.cylinderSegments[1];
  expectNear(d(a.start.position), first.position);
  expectNear(d(a.start.heading), first.heading);
  expectNear(d(a.start.left), first.left);
  expectNear(d(a.start.up), first.up);
  expectNear(d(a.end.position), second.position);
  expectNear(d(b.start.position), second.position);
  expectNear(d(b.end.position), s.position);
  EXPECT_FLOAT_EQ(a.radiusStart, 1.0f);
  EXPECT_FLOAT_EQ(a.radiusEnd, 0.5f);
  EXPECT_FLOAT_EQ(b.radiusStart, 0.5f);
  const double girth = resources.contours.samples(0, 10).length;
  EXPECT_NEAR(a.girthStart, girth * 1.0, 1e-5);
  EXPECT_NEAR(a.girthEnd, girth * 0.5, 1e-5);
  EXPECT_NEAR(b.girthEnd, girth * 0.5, 1e-5);
  // Arc length from @Gs, continued across segments.
  EXPECT_NEAR(a.axisStart, 0.0, kTolerance);
  EXPECT_NEAR(a.axisLength, 3.0, kTolerance);
  EXPECT_NEAR(b.axisStart, 3.0, kTolerance);
  EXPECT_NEAR(b.axisLength, 2.0, kTolerance);
  EXPECT_NEAR(b.rings.back().axisDistance, 5.0, kTolerance);
  EXPECT_EQ(a.tube, b.tube);
  EXPECT_EQ(a.strips, 3);
  EXPECT_EQ(b.strips, 5);
  ASSERT_EQ(a.contourStart.size(), 10u);
  EXPECT_NEAR(a.contourStart[0].x, 1.0, 1e-6);  // sample 0 on +x (along U)
  EXPECT_NEAR(a.contourEnd[0].x, 0.5, 1e-6);
  // Each segment's index range holds its own triangles, built from its own vertices.
  const TriangleMesh& mesh = scene.meshes.at(static_cast<std::size_t>(a.mesh));
  EXPECT_EQ(a.mesh, b.mesh);
  EXPECT_EQ(b.firstIndex, a.firstIndex + a.indexCount);
  EXPECT_EQ(a.indexCount, 3u * 2u * 10u * 3u);
  EXPECT_EQ(b.indexCount, 5u * 2u * 10u * 3u);
  for (const CylinderSegment* segment : {&a, &b}) {
    for (std::uint32_t i = segment->firstIndex; i < segment->firstIndex + segment->indexCount;
         ++i) {
      EXPECT_GE(mesh.indices[i], segment->firstVertex);
      EXPECT_LT(mesh.indices[i], segment->firstVertex + segment->vertexCount);
    }
  }
}

TEST_F(GeneralizedCylinderTest, BranchesForkATube) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(1.0);
  builder.start(s);
  move(s, 2.0);
  builder.point(s, 2);  // fork point at (0, 2, 0)
  const auto saved = builder.save();
  TurtleState branch = s;
  turnLeft(branch, 45);
  move(branch, 1.0);
  builder.point(branch, 2);
  builder.end(branch, 2);  // a branch may end the tube...
  EXPECT_FALSE(builder.active());
  builder.restore(saved);  // ...the parent continues from its own last point
  EXPECT_TRUE(builder.active());
  move(s, 1.5);
  builder.end(s, 2);

  ASSERT_EQ(scene.cylinderSegments.size(), 3u);
  const CylinderSegment& stem = scene.cylinderSegments[0];
  const CylinderSegment& side = scene.cylinderSegments[1];
  const CylinderSegment& top = scene.cylinderSegments[2];
  expectNear(d(side.start.position), glm::dvec3(0, 2, 0));
  expectNear(d(top.start.position), glm::dvec3(0, 2, 0));
  expectNear(d(top.end.position), glm::dvec3(0, 3.5, 0));
  EXPECT_EQ(stem.tube, side.tube);
  EXPECT_EQ(stem.tube, top.tube);
  EXPECT_NEAR(side.axisStart, 2.0, kTolerance);
  EXPECT_NEAR(top.axisStart, 2.0, kTolerance);
  EXPECT_NEAR(top.axisLength, 1.5, kTolerance);
}

TEST_F(GeneralizedCylinderTest, TubeStartedInABranchEndsAtItsEnd) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(1.0);
  const auto saved = builder.save();
  builder.start(s);
  move(s, 1.0);
  builder.point(s, 2);
  builder.restore(saved);
  EXPECT_FALSE(builder.active());
  move(s, 1.0);
  builder.point(s, 2);  // starts a new tube: nothing drawn from the branch's points
  EXPECT_EQ(scene.cylinderSegments.size(), 1u);
  move(s, 1.0);
  builder.end(s, 2);
  ASSERT_EQ(scene.cylinderSegments.size(), 2u);
  EXPECT_NE(scene.cylinderSegments[0].tube, scene.cylinderSegments[1].tube);
  expectNear(d(scene.cylinderSegments[1].start.position), glm::dvec3(0, 2, 0));
  EXPECT_NEAR(scene.cylinderSegments[1].axisStart, 0.0, kTolerance);
}

TEST_F(GeneralizedCylinderTest, ZeroLengthSegmentsAreSkipped) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(1.0);
  builder.start(s);
  builder.point(s, 4);  // @Gs@Gc: nothing to draw
  EXPECT_TRUE(scene.cylinderSegments.empty());
  EXPECT_EQ(scene.triangleCount(), 0u);
  s.position += glm::dvec3(0, 5e-6, 0);
  builder.point(s, 4);  // still shorter than cpfg's 1e-5
  EXPECT_TRUE(scene.cylinderSegments.empty());
  move(s, 1.0);
  builder.end(s, 4);
  ASSERT_EQ(scene.cylinderSegments.size(), 1u);
  expectNear(d(scene.cylinderSegments[0].start.position), glm::dvec3(0, 5e-6, 0), 1e-9);
  EXPECT_EQ(scene.triangleCount(), 4u * 2u * 8u);
}

TEST_F(GeneralizedCylinderTest, GcWithoutGsStartsATubeThatTakesPointsFromMoves) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(1.0);
  EXPECT_FALSE(builder.active());
  builder.point(s, 4);
  EXPECT_TRUE(builder.active());
  EXPECT_TRUE(builder.addsPointsOnMoves());
  EXPECT_TRUE(scene.cylinderSegments.empty());
  move(s, 1.0);
  builder.end(s, 4);
  EXPECT_EQ(scene.cylinderSegments.size(), 1u);
  EXPECT_FALSE(builder.addsPointsOnMoves());

  builder.start(s);
  EXPECT_FALSE(builder.addsPointsOnMoves());
  builder.end(s, 4);

  // An unmatched @Ge starts and ends at once, drawing nothing.
  builder.end(s, 4);
  EXPECT_FALSE(builder.active());
  EXPECT_EQ(scene.cylinderSegments.size(), 1u);
}

TEST_F(GeneralizedCylinderTest, StripsTakeTheFirstControlPointsColour) {
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(1.0);
  s.color = 5;
  builder.start(s);
  move(s, 1.0);
  s.color = 7;
  builder.point(s, 2);
  move(s, 1.0);
  builder.end(s, 2);
  ASSERT_EQ(scene.cylinderSegments.size(), 2u);
  EXPECT_EQ(scene.meshes.at(static_cast<std::size_t>(scene.cylinderSegments[0].mesh)).material, 5);
  EXPECT_EQ(scene.meshes.at(static_cast<std::size_t>(scene.cylinderSegments[1].mesh)).material, 7);
  EXPECT_EQ(scene.meshes.at(static_cast<std::size_t>(scene.cylinderSegments[0].mesh)).texture, -1);
  EXPECT_TRUE(scene.meshes[0].texcoords.empty());
}

TEST_F(GeneralizedCylinderTest, TextureTAdvancesByChordOverCircumferenceInImageAspect) {
  // A 300×100 image is clamped to 256×64 (W/H = 4); R = 0.5 stretches it along the axis.
  Texture image;
  image.width = 300;
  image.height = 100;
  resources.textures.push_back(image);
  TextureDeclaration declaration;
  declaration.ratio = 0.5f;
  resources.view.textures.push_back(declaration);

  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(2.0, 8);
  s.texture = 1;
  s.texCoordT = 0.25;
  builder.start(s);
  move(s, 3.0);
  builder.point(s, 1);
  move(s, 1.0);
  s.lineWidth = 4.0;
  builder.end(s, 2);

  const double perUnit = 1.0 / (kPi * 2.0) * 4.0 / 0.5;
  ASSERT_EQ(scene.cylinderSegments.size(), 2u);
  const CylinderSegment& a = scene.cylinderSegments[0];
  const CylinderSegment& b = scene.cylinderSegments[1];
  const TriangleMesh& mesh = scene.meshes.at(static_cast<std::size_t>(a.mesh));
  EXPECT_EQ(mesh.texture, 0);
  ASSERT_EQ(mesh.texcoords.size(), mesh.positions.size());
  EXPECT_NEAR(a.rings[0].textureT, 0.25, 1e-6);
  EXPECT_NEAR(a.rings[1].textureT, 0.25 + 3.0 * perUnit, 1e-5);
  // Rings of the second segment: diameters 3 and 4 (linear), chords 0.5 each.
  const double mid = 0.25 + 3.0 * perUnit + 0.5 / (kPi * 3.0) * 8.0;
  EXPECT_NEAR(b.rings[0].textureT, 0.25 + 3.0 * perUnit, 1e-5);
  EXPECT_NEAR(b.rings[1].textureT, mid, 1e-5);
  EXPECT_NEAR(b.rings[2].textureT, mid + 0.5 / (kPi * 4.0) * 8.0, 1e-5);
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j <= 8; ++j) {
      const glm::vec2 st = mesh.texcoords[vertexIndex(a, k, j)];
      EXPECT_NEAR(st.x, 1.0 - j / 8.0, 1e-6);
      EXPECT_NEAR(st.y, a.rings[static_cast<std::size_t>(k)].textureT, 1e-6);
    }
  }
}

TEST_F(GeneralizedCylinderTest, OtherLineStylesDrawTheAxisAsLines) {
  resources.view.lineStyle = LineStyle::Pixel;
  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(2.0);
  builder.start(s);
  move(s, 2.0);
  s.lineWidth = 4.0;
  builder.end(s, 4);
  EXPECT_EQ(scene.triangleCount(), 0u);
  ASSERT_EQ(scene.lines.size(), 4u);
  EXPECT_NEAR(scene.lines[0].widthFrom, 2.0, 1e-6);
  EXPECT_NEAR(scene.lines[3].widthTo, 4.0, 1e-6);
  expectNear(d(scene.lines[3].to), glm::dvec3(0, 2, 0));
  ASSERT_EQ(scene.cylinderSegments.size(), 1u);
  EXPECT_EQ(scene.cylinderSegments[0].mesh, -1);
}

TEST_F(GeneralizedCylinderTest, QueryPassWithoutSceneTracksTheTube) {
  GeneralizedCylinderBuilder builder(resources, nullptr);
  TurtleState s = turtle(1.0);
  builder.start(s);
  move(s, 1.0);
  builder.point(s, 4);
  EXPECT_TRUE(builder.active());
  builder.end(s, 4);
  EXPECT_FALSE(builder.active());
}

// cpfg's own triangles (its rayshade output) for the GeneralizedCylinder model of vlab's
// library: #(0.8) @!(50) @Gt(1.2,1.5) @Gs, then @Gc(10) with + - f between (45°), twist off.
std::vector<std::array<glm::dvec3, 6>> readRayTriangles(const std::filesystem::path& file) {
  std::vector<std::array<glm::dvec3, 6>> triangles;
  gzFile in = gzopen(file.c_str(), "rb");
  if (in == nullptr) return triangles;
  std::string text;
  char buffer[65536];
  int n = 0;
  while ((n = gzread(in, buffer, sizeof buffer)) > 0)
    text.append(buffer, static_cast<std::size_t>(n));
  gzclose(in);
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line != "triangle") continue;
    std::array<glm::dvec3, 6> t;
    for (int v = 0; v < 3; ++v) {
      lines >> t[v * 2].x >> t[v * 2].y >> t[v * 2].z >> t[v * 2 + 1].x >> t[v * 2 + 1].y >>
          t[v * 2 + 1].z;
    }
    triangles.push_back(t);
  }
  return triangles;
}

TEST_F(GeneralizedCylinderTest, MatchesCpfgTrianglesOfItsGeneralizedCylinderModel) {
  const std::filesystem::path folder =
      std::filesystem::path(HIRSUTE_SOURCE_DIR) / "../shared/conformance/cpfg-GeneralizedCylinder";
  if (!std::filesystem::exists(folder / "expected.ray.gz")) GTEST_SKIP() << "no " << folder;
  const auto expected = readRayTriangles(folder / "expected.ray.gz");
  ASSERT_EQ(expected.size(), 32000u);

  std::ifstream homo(folder / "expected.homo.str");
  std::string text((std::istreambuf_iterator<char>(homo)), std::istreambuf_iterator<char>());
  std::erase(text, '\n');
  const std::string prefix = "#(0.8)@!(50)@Gt(1.2,1.5)@Tx(2)@Gs";
  ASSERT_EQ(text.substr(0, prefix.size()), prefix);

  GeneralizedCylinderBuilder builder(resources, &scene);
  TurtleState s = turtle(0.8, 50);
  s.color = 1;
  s.tangentParameter = {1.2, 1.5};
  s.texture = 2;  // no textures loaded here: drawn untextured
  builder.start(s);
  for (std::size_t i = prefix.size(); i < text.size();) {
    if (text.compare(i, 7, "@Gc(10)") == 0 || text.compare(i, 7, "@Ge(10)") == 0) {
      if (text[i + 2] == 'c')
        builder.point(s, 10);
      else
        builder.end(s, 10);
      i += 7;
      continue;
    }
    if (text[i] == '+')
      turnLeft(s, 45);
    else if (text[i] == '-')
      turnLeft(s, -45);
    else if (text[i] == 'f')
      move(s, 1.0);
    else
      FAIL() << "unexpected module at " << i << ": " << text.substr(i, 10);
    ++i;
  }
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.triangleCount(), expected.size());
  // cpfg's rayshade writer turns each triangle's normals to the side its vertex order faces.
  // They differ from the vertex normals only where a hairpin bend (`--f--`, 180° between two
  // control points) folds the tube over itself; nowhere in the first segment.
  int mismatches = 0;
  std::size_t folded = 0;
  for (std::size_t t = 0; t < expected.size() && mismatches < 10; ++t) {
    std::array<std::uint32_t, 3> index{};
    for (int v = 0; v < 3; ++v) index[v] = mesh.indices[t * 3 + static_cast<std::size_t>(v)];
    const glm::dvec3 face = glm::cross(d(mesh.positions[index[1]]) - d(mesh.positions[index[0]]),
                                       d(mesh.positions[index[2]]) - d(mesh.positions[index[0]]));
    for (int v = 0; v < 3; ++v) {
      const glm::dvec3 p = d(mesh.positions[index[v]]);
      glm::dvec3 n = d(mesh.normals[index[v]]);
      if (glm::dot(face, n) < 0.0) {
        n = -n;
        ++folded;
      }
      if (glm::length(p - expected[t][v * 2]) > 2e-4 ||
          glm::length(n - expected[t][v * 2 + 1]) > 2e-4) {
        ADD_FAILURE() << "triangle " << t << " vertex " << v << ": (" << p.x << ' ' << p.y << ' '
                      << p.z << ") n (" << n.x << ' ' << n.y << ' ' << n.z << "), cpfg ("
                      << expected[t][v * 2].x << ' ' << expected[t][v * 2].y << ' '
                      << expected[t][v * 2].z << ") n (" << expected[t][v * 2 + 1].x << ' '
                      << expected[t][v * 2 + 1].y << ' ' << expected[t][v * 2 + 1].z << ')';
        ++mismatches;
      }
    }
    if (t == 999) {
      EXPECT_EQ(folded, 0u);
    }
  }
  EXPECT_GT(folded, 0u);
  EXPECT_LT(folded, expected.size() * 3 / 10);
  EXPECT_EQ(mismatches, 0);
}

// The whole pipeline (derivation, turtle, builder) on the conformance models with tubes: every
// tube triangle we draw is one of cpfg's, in position to cpfg's printed precision, with the
// same normals (turned to the face as cpfg's rayshade writer turns them; cpfg's normals that are
// too short to have been normalised, at FernLeaf's leaf bases, say nothing).
struct TubeModel {
  const char* id;
  const char* lsystem;
  const char* view;
  const char* materials;
  int steps;
};

TEST(GeneralizedCylinderConformance, TubeTrianglesAreCpfgs) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(HIRSUTE_SOURCE_DIR) / "../shared/conformance";
  if (!fs::exists(root)) GTEST_SKIP() << "no " << root;
  const TubeModel models[] = {
      {"cpfg-GeneralizedCylinder", "fractal.l", "fractal.v", "fractal.mat", 2},  // twist off
      {"cpfg-Horneophyton", "plant.l", "plant.v", "plant.mat", 8},               // forks
      {"cpfg-Tropisms", "lsystem.l", "view.v", "materials.mat", 20},             // twist on
      {"tools-FernLeaf", "plant.l", "plant.v", "plant.mat", 1},                  // @Gr, @Gt
      {"tools-LilyLeaf", "plant.l", "plant.v", "plant.mat", 0},                  // open contour
  };
  for (const TubeModel& m : models) {
    SCOPED_TRACE(m.id);
    const fs::path folder = root / m.id;
    Diagnostics diagnostics;
    const std::optional<fs::path> view = folder / m.view;
    Model model = loadModel(folder / m.lsystem, view, diagnostics);
    ColorFiles colors;
    colors.materials.push_back({1, folder / m.materials});
    const ModelResources resources = loadModelResources(view, colors, diagnostics);
    std::ostringstream printed;
    Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
    DerivationOptions options;
    options.steps = m.steps;
    Derivation derivation(model.program, evaluator, diagnostics, options);
    installQueryPass(derivation, resources, diagnostics);
    derivation.run();
    Scene scene;
    Turtle turtle(resources, &scene, diagnostics);
    turtle.setSourceString(&derivation.mutableString());
    derivation.emit(turtle, true);
    turtle.finish();

    const auto expected = readRayTriangles(folder / "expected.ray.gz");
    ASSERT_FALSE(expected.empty());
    // cpfg prints 6 significant digits: a tolerance relative to the model's size.
    const double tolerance = 2e-5 * std::max(1.0, static_cast<double>(scene.bounds().diagonal()));
    std::multimap<double, std::size_t> byX;
    for (std::size_t i = 0; i < expected.size(); ++i) byX.emplace(expected[i][0].x, i);
    std::size_t ours = 0, found = 0, normalMismatches = 0;
    for (const CylinderSegment& segment : scene.cylinderSegments) {
      const TriangleMesh& mesh = scene.meshes.at(static_cast<std::size_t>(segment.mesh));
      for (std::uint32_t i = segment.firstIndex; i < segment.firstIndex + segment.indexCount;
           i += 3) {
        ++ours;
        std::array<glm::dvec3, 3> p, n;
        for (std::uint32_t v = 0; v < 3; ++v) {
          p[v] = d(mesh.positions[mesh.indices[i + v]]);
          n[v] = d(mesh.normals[mesh.indices[i + v]]);
        }
        const glm::dvec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
        for (glm::dvec3& normal : n) {
          if (glm::dot(face, normal) < 0.0) normal = -normal;
        }
        // The nearest of cpfg's triangles: tiny rings (FernLeaf's leaf bases) crowd samples.
        const std::array<glm::dvec3, 6>* nearest = nullptr;
        double nearestDistance = tolerance;
        for (auto it = byX.lower_bound(p[0].x - tolerance);
             it != byX.end() && it->first <= p[0].x + tolerance; ++it) {
          const auto& t = expected[it->second];
          double distance = 0;
          for (int v = 0; v < 3; ++v) distance = std::max(distance, glm::length(p[v] - t[v * 2]));
          if (distance <= nearestDistance) {
            nearest = &t;
            nearestDistance = distance;
          }
        }
        if (nearest == nullptr) continue;
        ++found;
        for (int v = 0; v < 3; ++v) {
          const glm::dvec3& theirs = (*nearest)[v * 2 + 1];
          if (glm::length(theirs) > 0.5 && glm::length(n[v] - theirs) > 5e-3) {
            ++normalMismatches;
            const std::uint32_t vertex =
                mesh.indices[i + static_cast<std::uint32_t>(v)] - segment.firstVertex;
            ADD_FAILURE() << "segment " << (&segment - scene.cylinderSegments.data()) << " ring "
                          << vertex / static_cast<std::uint32_t>(segment.sides + 1) << " sample "
                          << vertex % static_cast<std::uint32_t>(segment.sides + 1) << ": normal ("
                          << n[v].x << ' ' << n[v].y << ' ' << n[v].z << "), cpfg (" << theirs.x
                          << ' ' << theirs.y << ' ' << theirs.z << ')';
          }
        }
      }
    }
    EXPECT_EQ(ours, expected.size());
    EXPECT_EQ(found, ours);
    EXPECT_EQ(normalMismatches, 0u);
  }
}

}  // namespace
}  // namespace hirsute
