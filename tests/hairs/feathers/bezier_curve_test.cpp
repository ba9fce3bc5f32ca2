// Bézier curves (Streit & Heidrich 2002, Sec. 4.2.1): evaluation and exact degree elevation.
#include "hirsute/hairs/feathers/bezier_curve.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <random>
#include <vector>

namespace hirsute {
namespace {

double maxDeviation(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b, int samples) {
  double worst = 0;
  for (int i = 0; i <= samples; ++i) {
    const double t = static_cast<double>(i) / samples;
    worst = std::max(worst, glm::length(bezierPoint(a, t) - bezierPoint(b, t)));
  }
  return worst;
}

TEST(BezierCurve, EndsAreTheFirstAndLastVertices) {
  const std::vector<glm::vec3> cubic = {{0, 0, 0}, {1, 2, 0}, {2, 2, 1}, {3, 0, 0}};
  EXPECT_EQ(glm::vec3(bezierPoint(cubic, 0)), cubic.front());
  EXPECT_EQ(glm::vec3(bezierPoint(cubic, 1)), cubic.back());
  // The middle of a cubic: (cv0 + 3 cv1 + 3 cv2 + cv3) / 8.
  const glm::dvec3 middle = bezierPoint(cubic, 0.5);
  EXPECT_NEAR(middle.x, 1.5, 1e-12);
  EXPECT_NEAR(middle.y, 1.5, 1e-12);
  EXPECT_NEAR(middle.z, 0.375, 1e-12);
  // Derivative at the ends: n (cv1 - cv0) and n (cv3 - cv2).
  EXPECT_NEAR(glm::length(bezierDerivative(cubic, 0) - glm::dvec3(3, 6, 0)), 0, 1e-12);
  EXPECT_NEAR(glm::length(bezierDerivative(cubic, 1) - glm::dvec3(3, -6, -3)), 0, 1e-12);
}

TEST(BezierCurve, DegreeElevationKeepsTheCurve) {
  std::mt19937 random(5);
  std::uniform_real_distribution<float> coordinate(-1, 1);
  for (std::size_t count = 2; count <= 8; ++count) {
    std::vector<glm::vec3> vertices(count);
    for (glm::vec3& v : vertices) v = {coordinate(random), coordinate(random), coordinate(random)};
    const std::vector<glm::vec3> once = elevateBezierDegree(vertices);
    ASSERT_EQ(once.size(), count + 1);
    EXPECT_EQ(once.front(), vertices.front());
    EXPECT_EQ(once.back(), vertices.back());
    EXPECT_LT(maxDeviation(vertices, once, 1000), 1e-6) << count << " vertices";
    const std::vector<glm::vec3> many = elevateBezierTo(vertices, count + 5);
    ASSERT_EQ(many.size(), count + 5);
    EXPECT_LT(maxDeviation(vertices, many, 1000), 1e-6) << count << " vertices, +4";
  }
}

TEST(BezierCurve, ElevatedLineHasEvenlySpacedVertices) {
  // A straight segment elevated to a cubic has its inner vertices at 1/3 and 2/3.
  const std::vector<glm::vec3> line = {{0, 0, 0}, {3, 0, 0}};
  const std::vector<glm::vec3> cubic = elevateBezierTo(line, 4);
  ASSERT_EQ(cubic.size(), 4u);
  EXPECT_NEAR(cubic[1].x, 1, 1e-6);
  EXPECT_NEAR(cubic[2].x, 2, 1e-6);
}

}  // namespace
}  // namespace hirsute
