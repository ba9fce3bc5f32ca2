// The exact intersection check of a final state: the orientation predicates against GMP on
// nearly degenerate points, and planted intersections, touching contacts and near misses of one
// unit in the last place for segments and triangles.
#include "hirsute/hairs/dynamics/static_intersection.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "hirsute/hairs/dynamics/exact_predicates.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

int exactSign3(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  auto q = [](double x) { return mpq_class(x); };
  const mpq_class m00 = q(a.x()) - q(d.x()), m01 = q(a.y()) - q(d.y()), m02 = q(a.z()) - q(d.z());
  const mpq_class m10 = q(b.x()) - q(d.x()), m11 = q(b.y()) - q(d.y()), m12 = q(b.z()) - q(d.z());
  const mpq_class m20 = q(c.x()) - q(d.x()), m21 = q(c.y()) - q(d.y()), m22 = q(c.z()) - q(d.z());
  const mpq_class det =
      m00 * (m11 * m22 - m12 * m21) - m01 * (m10 * m22 - m12 * m20) + m02 * (m10 * m21 - m11 * m20);
  return sgn(det);
}

TEST(ExactPredicates, Orient3dAgreesWithRationalsOnNearlyCoplanarPoints) {
  // d is a rounded affine combination of a, b, c: within a few ulps of their plane, where the
  // rounded determinant's sign is noise. Every sign must be the rational one.
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-10, 10), weight(-2, 2);
  int zeros = 0, undecidedByRounding = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vector3d a(coordinate(random), coordinate(random), coordinate(random));
    const Vector3d b(coordinate(random), coordinate(random), coordinate(random));
    const Vector3d c = i % 4 == 0
                           ? Vector3d(a + 0.5 * (b - a))
                           : Vector3d(coordinate(random), coordinate(random), coordinate(random));
    const double s = weight(random), t = weight(random);
    const Vector3d d = a + s * (b - a) + t * (c - a);
    const int expected = exactSign3(a, b, c, d);
    zeros += expected == 0;
    const Vector3d ad = a - d, bd = b - d, cd = c - d;
    const double rounded = ad.dot(bd.cross(cd));
    undecidedByRounding += (rounded > 0) - (rounded < 0) != expected;
    ASSERT_EQ(orient3d(a, b, c, d), expected) << i;
  }
  // The test reaches the cases the filter must hand over: plain rounding gets many wrong.
  std::printf("[   INFO   ] plain rounding got %d of 5000 signs wrong, %d zeros\n",
              undecidedByRounding, zeros);
  EXPECT_GT(undecidedByRounding, 1000);
  EXPECT_GT(zeros, 0);
}

TEST(ExactPredicates, Orient2dSeesOneUlp) {
  const Vector3d a(0, 0, 0), b(1, 1, 0), onLine(0.1, 0.1, 5);
  EXPECT_EQ(orient2d(a, b, onLine, 0, 1), 0);
  EXPECT_EQ(orient2d(a, b, Vector3d(0.1, std::nextafter(0.1, 1.0), 5), 0, 1), 1);
  EXPECT_EQ(orient2d(a, b, Vector3d(0.1, std::nextafter(0.1, 0.0), 5), 0, 1), -1);
  EXPECT_EQ(orient2d(Vector3d(1e-300, 0, 0), Vector3d(0, 1e-300, 0), Vector3d(0, 0, 0), 0, 1), 1);
}

TEST(ExactPredicates, NonFinitePointsAreRefused) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_THROW(orient3d(a, b, c, Vector3d(0, 0, INFINITY)), std::invalid_argument);
  EXPECT_THROW(orient2d(a, b, Vector3d(std::nan(""), 0, 0), 0, 1), std::invalid_argument);
  EXPECT_THROW(trianglesIntersect(a, b, c, a, b, Vector3d(0, 0, INFINITY)), std::invalid_argument);
}

// The triangle of the plane x + y + z = 1 cut by the coordinate axes; (0.25, 0.25, 0.5) lies on
// it exactly.
const Vector3d kA(1, 0, 0), kB(0, 1, 0), kC(0, 0, 1), kOnFace(0.25, 0.25, 0.5);

TEST(SegmentTriangle, CrossingTouchingAndOneUlpAway) {
  EXPECT_TRUE(segmentIntersectsTriangle(Vector3d(0, 0, 0), Vector3d(1, 1, 1), kA, kB, kC));
  EXPECT_TRUE(segmentIntersectsTriangle(kOnFace, Vector3d(-1, -1, -1), kA, kB, kC));
  const Vector3d above(0.25, 0.25, std::nextafter(0.5, 1.0));
  EXPECT_FALSE(segmentIntersectsTriangle(above, Vector3d(1, 1, 1), kA, kB, kC));
  const Vector3d below(0.25, 0.25, std::nextafter(0.5, 0.0));
  EXPECT_TRUE(segmentIntersectsTriangle(above, below, kA, kB, kC));
  // Through a corner, and just past it.
  EXPECT_TRUE(segmentIntersectsTriangle(Vector3d(1, -1, 0), Vector3d(1, 1, 0), kA, kB, kC));
  EXPECT_FALSE(
      segmentIntersectsTriangle(Vector3d(1, -1, 1e-300), Vector3d(1, 1, 1e-300), kA, kB, kC));
  // Crossing the plane outside the triangle.
  EXPECT_FALSE(segmentIntersectsTriangle(Vector3d(2, 2, 2), Vector3d(0.9, 0.9, -1), kA, kB, kC));
}

TEST(SegmentTriangle, CoplanarSegments) {
  const Vector3d a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
  // Inside, crossing an edge, along an edge, outside, and beyond the hypotenuse by one ulp.
  EXPECT_TRUE(segmentIntersectsTriangle(Vector3d(1, 1, 0), Vector3d(2, 1, 0), a, b, c));
  EXPECT_TRUE(segmentIntersectsTriangle(Vector3d(-1, 1, 0), Vector3d(1, 1, 0), a, b, c));
  EXPECT_TRUE(segmentIntersectsTriangle(Vector3d(-1, 0, 0), Vector3d(5, 0, 0), a, b, c));
  EXPECT_FALSE(segmentIntersectsTriangle(Vector3d(-1, -1, 0), Vector3d(5, -1, 0), a, b, c));
  const double past = std::nextafter(2.0, 3.0);
  EXPECT_FALSE(segmentIntersectsTriangle(Vector3d(past, past, 0), Vector3d(3, 3, 0), a, b, c));
  EXPECT_TRUE(segmentIntersectsTriangle(Vector3d(2, 2, 0), Vector3d(3, 3, 0), a, b, c));
  // A point (zero-length segment) on the face, and one a hair above it.
  EXPECT_TRUE(segmentIntersectsTriangle(Vector3d(1, 1, 0), Vector3d(1, 1, 0), a, b, c));
  EXPECT_FALSE(segmentIntersectsTriangle(Vector3d(1, 1, 1e-300), Vector3d(1, 1, 1e-300), a, b, c));
}

TEST(SegmentTriangle, DegenerateTriangles) {
  // Collinear corners: the triangle is the segment from (0,0,0) to (2,0,0).
  const Vector3d a(0, 0, 0), b(2, 0, 0), c(1, 0, 0);
  EXPECT_TRUE(segmentIntersectsTriangle(Vector3d(1.5, -1, 0), Vector3d(1.5, 1, 0), a, b, c));
  EXPECT_FALSE(segmentIntersectsTriangle(Vector3d(1.5, -1, 1), Vector3d(1.5, 1, 1e-300), a, b, c));
  EXPECT_FALSE(segmentIntersectsTriangle(Vector3d(2.5, -1, 0), Vector3d(2.5, 1, 0), a, b, c));
  // All three corners at one point.
  EXPECT_TRUE(segmentIntersectsTriangle(Vector3d(-1, -1, -1), Vector3d(1, 1, 1), a, a, a));
  EXPECT_FALSE(segmentIntersectsTriangle(Vector3d(-1, -1, -1), Vector3d(1, 1, 1.5), a, a, a));
}

TEST(SegmentSegment, SkewCrossingCollinearAndNearMiss) {
  EXPECT_TRUE(segmentsIntersect(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(0, -1, 0),
                                Vector3d(0, 1, 0)));
  EXPECT_FALSE(segmentsIntersect(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(0, -1, 1e-300),
                                 Vector3d(0, 1, 1e-300)));
  EXPECT_TRUE(segmentsIntersect(Vector3d(0, 0, 0), Vector3d(2, 2, 2), Vector3d(1, 1, 1),
                                Vector3d(3, 3, 3)));
  EXPECT_FALSE(segmentsIntersect(Vector3d(0, 0, 0), Vector3d(1, 1, 1),
                                 Vector3d(std::nextafter(1.0, 2.0), 1, 1), Vector3d(3, 3, 3)));
  EXPECT_TRUE(segmentsIntersect(Vector3d(0, 0, 0), Vector3d(1, 1, 1), Vector3d(1, 1, 1),
                                Vector3d(3, 0, 3)));
}

TEST(TriangleTriangle, PlantedIntersectionsAndNearMisses) {
  const Vector3d a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
  // Piercing through the middle.
  EXPECT_TRUE(
      trianglesIntersect(a, b, c, Vector3d(1, 1, -1), Vector3d(1, 1, 1), Vector3d(2, 0.5, 1)));
  // Touching the face with one corner, and the same corner one ulp above.
  EXPECT_TRUE(trianglesIntersect(a, b, c, Vector3d(1, 1, 0), Vector3d(1, 2, 1), Vector3d(2, 1, 1)));
  const double hair = std::nextafter(0.0, 1.0);
  EXPECT_FALSE(
      trianglesIntersect(a, b, c, Vector3d(1, 1, hair), Vector3d(1, 2, 1), Vector3d(2, 1, 1)));
  // Parallel planes.
  EXPECT_FALSE(
      trianglesIntersect(a, b, c, Vector3d(0, 0, 1), Vector3d(4, 0, 1), Vector3d(0, 4, 1)));
  // Coplanar: overlapping, one inside the other, sharing an edge, apart.
  EXPECT_TRUE(trianglesIntersect(a, b, c, Vector3d(1, 1, 0), Vector3d(5, 1, 0), Vector3d(1, 5, 0)));
  EXPECT_TRUE(
      trianglesIntersect(a, b, c, Vector3d(0.5, 0.5, 0), Vector3d(1, 0.5, 0), Vector3d(0.5, 1, 0)));
  EXPECT_TRUE(trianglesIntersect(a, b, c, b, c, Vector3d(4, 4, 0)));
  EXPECT_FALSE(
      trianglesIntersect(a, b, c, Vector3d(5, 5, 0), Vector3d(6, 5, 0), Vector3d(5, 6, 0)));
  // An edge of the second passing through the first's edge, not its interior, from above.
  EXPECT_TRUE(
      trianglesIntersect(a, b, c, Vector3d(2, -1, 1), Vector3d(2, 1, -1), Vector3d(2, -3, -1)));
  EXPECT_FALSE(
      trianglesIntersect(a, b, c, Vector3d(2, -1, 1), Vector3d(2, -0.5, -1), Vector3d(2, -3, -1)));
}

TEST(TriangleTriangle, SeededRandomPairsAreSymmetric) {
  std::mt19937_64 random(99);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  auto point = [&] { return Vector3d(coordinate(random), coordinate(random), coordinate(random)); };
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vector3d a = point(), b = point(), c = point(), d = point(), e = point(), f = point();
    const bool forward = trianglesIntersect(a, b, c, d, e, f);
    ASSERT_EQ(forward, trianglesIntersect(d, e, f, a, b, c)) << i;
    ASSERT_EQ(forward, trianglesIntersect(b, c, a, f, d, e)) << i;
    hits += forward;
  }
  EXPECT_GT(hits, 100);
  EXPECT_LT(hits, 4900);
}

}  // namespace
}  // namespace hirsute::dynamics
