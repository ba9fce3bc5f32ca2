// Generalized-cylinder contours: the built-in circle and `.con` files resampled as cpfg does
// (cpfg-generalized-cylinders.md §3).
#include "hirsute/interpreter/contour.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {
namespace {

const std::filesystem::path kFixtures =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "interpreter";
const std::filesystem::path kConformance =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "conformance";

Contour fixture(const std::string& name) {
  return loadContour((kFixtures / name).string());
}

void expectPoint(const glm::dvec2& actual, double x, double y, double tolerance) {
  EXPECT_NEAR(actual.x, x, tolerance);
  EXPECT_NEAR(actual.y, y, tolerance);
}

TEST(ContourTest, CircleSamplesLieOnTheUnitCircle) {
  const ContourLibrary library;
  const ContourSamples& circle = library.samples(0, 8);
  ASSERT_EQ(circle.points.size(), 8u);
  ASSERT_EQ(circle.normals.size(), 8u);
  EXPECT_TRUE(circle.closed);
  for (int j = 0; j < 8; ++j) {
    const double angle = 2.0 * std::numbers::pi * j / 8;
    expectPoint(circle.points[j], std::cos(angle), std::sin(angle), 1e-15);
    expectPoint(circle.normals[j], std::cos(angle), std::sin(angle), 1e-15);
    EXPECT_EQ(circle.z[j], 0.0);
  }
  // The girth of the octagon drawn, not of the circle.
  EXPECT_NEAR(circle.length, 16.0 * std::sin(std::numbers::pi / 8), 1e-12);
}

TEST(ContourTest, UnknownIdIsTheCircle) {
  ContourLibrary library;
  library.add(1, fixture("square.con"));
  EXPECT_FALSE(library.has(2));
  const ContourSamples& unknown = library.samples(2, 6);
  EXPECT_EQ(&unknown, &library.samples(0, 6));
  expectPoint(unknown.points[1], 0.5, std::sqrt(3.0) / 2, 1e-15);
}

TEST(ContourTest, SideCountsAreClamped) {
  const ContourLibrary library;
  EXPECT_EQ(library.samples(0, 2).points.size(), 3u);  // cpfg: fewer than 3 sides read as 3
  EXPECT_EQ(library.samples(0, -5).points.size(), 3u);
  EXPECT_EQ(library.samples(0, 1 << 20).points.size(), static_cast<std::size_t>(kMaxContourSides));
}

TEST(ContourTest, LoadsTheControlPolygon) {
  const Contour square = fixture("square.con");
  EXPECT_EQ(square.name, "square");
  EXPECT_TRUE(square.closed);
  ASSERT_EQ(square.controlPoints.size(), 4u);
  EXPECT_EQ(square.controlPoints[1], glm::dvec3(-1, 1, 0));
  const Contour line = fixture("line.con");
  EXPECT_FALSE(line.closed);
  EXPECT_EQ(line.controlPoints.size(), 6u);  // two points of multiplicity 3
}

TEST(ContourTest, SquareIsResampledByArcLengthAndTurnedToPlusX) {
  ContourLibrary library;
  library.add(1, fixture("square.con"));
  // Sample 0 is the spline's start (c0+4c1+c2)/6 = (−2/3, 2/3), on the diagonal; turned onto +x
  // it is (r, 0) with r = 2√2/3.
  const double r = 2.0 * std::sqrt(2.0) / 3.0;
  const ContourSamples& eight = library.samples(1, 8);
  ASSERT_EQ(eight.points.size(), 8u);
  EXPECT_TRUE(eight.closed);
  expectPoint(eight.points[0], r, 0, 1e-12);
  expectPoint(eight.normals[0], 1, 0, 1e-12);  // on the diagonal the normal points straight out
  // Equal steps along the curve: the samples go round counter-clockwise (the control polygon's
  // direction) an eighth of a turn apart, between the spline's flattest points (radius 11/12)
  // and its corners (radius r). cpfg's table leaves the last tenth of the last segment out of
  // the perimeter, so each step is 1/80 of the perimeter short of an eighth and the error grows
  // towards the seam: sample 7 lies 7/80 of a quarter turn, about 8°, short of 315°.
  double previousAngle = 0;
  for (std::size_t j = 0; j < 8; ++j) {
    const double radius = glm::length(eight.points[j]);
    EXPECT_GE(radius, 11.0 / 12.0 - 1e-9) << j;
    EXPECT_LE(radius, r + 1e-9) << j;
    EXPECT_NEAR(glm::length(eight.normals[j]), 1.0, 1e-12);
    EXPECT_GT(glm::dot(eight.normals[j], eight.points[j]), 0.0) << j;
    double angle = std::atan2(eight.points[j].y, eight.points[j].x);
    if (angle < 0) angle += 2 * std::numbers::pi;
    if (j > 0) {
      EXPECT_GT(angle, previousAngle) << j;
    }
    EXPECT_NEAR(angle, j * std::numbers::pi / 4, 0.15) << j;
    previousAngle = angle;
  }
  EXPECT_LT(previousAngle, 7 * std::numbers::pi / 4 - 0.05);
  // The girth is that of the octagon drawn.
  double girth = 0;
  for (std::size_t j = 0; j < 8; ++j)
    girth += glm::length(eight.points[(j + 1) % 8] - eight.points[j]);
  EXPECT_NEAR(eight.length, girth, 1e-12);
}

TEST(ContourTest, ClosedContourStartsOnPlusXWhateverItsOrientation) {
  // The same square turned by 30°: once sample 0 is turned onto +x, the samples are those of the
  // square itself.
  ContourLibrary library;
  library.add(1, fixture("square.con"));
  library.add(2, fixture("turned_square.con"));
  const ContourSamples& square = library.samples(1, 8);
  const ContourSamples& turned = library.samples(2, 8);
  EXPECT_NEAR(turned.points[0].y, 0.0, 1e-12);
  EXPECT_GT(turned.points[0].x, 0.0);
  for (std::size_t j = 0; j < 8; ++j) {
    expectPoint(turned.points[j], square.points[j].x, square.points[j].y, 1e-5);
    expectPoint(turned.normals[j], square.normals[j].x, square.normals[j].y, 1e-5);
  }
}

TEST(ContourTest, OpenContourRunsEdgeToEdgeUnturned) {
  ContourLibrary library;
  library.add(1, fixture("line.con"));
  const ContourSamples& line = library.samples(1, 4);
  EXPECT_FALSE(line.closed);
  ASSERT_EQ(line.points.size(), 5u);  // sides + 1, from one edge to the other
  // cpfg's arc-length table stops at u = segments − 0.1, where the line from (−1, 0) ×3 to
  // (1, 0) ×3 has come to x = 1 − 2·0.1³/6 = 1 − 1/3000: that is the last sample.
  const double end = 1.0 - 1.0 / 3000.0;
  for (int j = 0; j <= 4; ++j) {
    expectPoint(line.points[j], -1.0 + (1.0 + end) * j / 4, 0.0, 2e-3);
    // The line runs along +x; its normal (dy, −dx) is −y, also at the start where the spline's
    // derivative vanishes (multiplicity 3).
    expectPoint(line.normals[j], 0.0, -1.0, 1e-9);
  }
  expectPoint(line.points.front(), -1, 0, 1e-12);  // not turned onto +x
  EXPECT_NEAR(line.points.back().x, end, 1e-12);
  EXPECT_NEAR(line.length, 1.0 + end, 1e-9);
}

TEST(ContourTest, SamplesAreCachedAndReplacedWithTheContour) {
  ContourLibrary library;
  library.add(1, fixture("square.con"));
  const ContourSamples& first = library.samples(1, 5);
  EXPECT_EQ(&first, &library.samples(1, 5));
  EXPECT_TRUE(first.closed);
  library.add(1, fixture("line.con"));
  EXPECT_FALSE(library.samples(1, 5).closed);
  EXPECT_EQ(library.samples(1, 5).points.size(), 6u);
}

TEST(ContourTest, BrokenFileIsReportedAtItsLine) {
  try {
    fixture("broken.con");
    ADD_FAILURE() << "expected a DiagnosticError";
  } catch (const DiagnosticError& error) {
    EXPECT_EQ(error.diagnostic().where.fileName(), (kFixtures / "broken.con").string());
    EXPECT_EQ(error.diagnostic().where.line, 6);
  }
}

TEST(ContourTest, EveryConformanceContourLoadsAndResamples) {
  if (!std::filesystem::is_directory(kConformance)) {
    GTEST_SKIP() << "no conformance set at " << kConformance;
  }
  int loaded = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kConformance)) {
    if (entry.path().extension() != ".con") continue;
    SCOPED_TRACE(entry.path().string());
    ContourLibrary library;
    library.add(1, loadContour(entry.path().string()));
    for (int sides : {3, 8, 14}) {
      const ContourSamples& samples = library.samples(1, sides);
      const std::size_t expected = samples.closed ? sides : sides + 1;
      ASSERT_EQ(samples.points.size(), expected);
      ASSERT_EQ(samples.normals.size(), expected);
      for (std::size_t j = 0; j < expected; ++j) {
        EXPECT_TRUE(std::isfinite(samples.points[j].x) && std::isfinite(samples.points[j].y));
        EXPECT_NEAR(glm::length(samples.normals[j]), 1.0, 1e-9);
      }
      EXPECT_GT(samples.length, 0.0);
    }
    ++loaded;
  }
  EXPECT_EQ(loaded, 5);
  // cpfg-Ridley's profile.con is the older `version: 1.4` curve format.
  const Contour ridley = loadContour((kConformance / "cpfg-Ridley" / "profile.con").string());
  EXPECT_FALSE(ridley.closed);
  EXPECT_EQ(ridley.controlPoints.size(), 8u);
}

std::string readGzip(const std::filesystem::path& file) {
  gzFile in = gzopen(file.c_str(), "rb");
  std::string text;
  if (in == nullptr) return text;
  char buffer[1 << 16];
  int n = 0;
  while ((n = gzread(in, buffer, sizeof buffer)) > 0)
    text.append(buffer, static_cast<std::size_t>(n));
  gzclose(in);
  return text;
}

// A ring of the first tube in cpfg's rayshade output of a conformance model. cpfg draws each
// strip between rings k−1 and k as triangles (k[j], k[j+1], k−1[j]), (k−1[j], k[j+1], k−1[j+1]),
// j = 0 … sides−1; `ring` 0 or 1 picks k−1 or k of the first strip.
std::vector<std::array<double, 3>> firstTubeRing(const std::string& model,
                                                 const std::string& surface, int sides, int ring) {
  std::istringstream ray(readGzip(kConformance / model / "expected.ray.gz"));
  std::string line;
  while (std::getline(ray, line) && line != "applysurf " + surface) {
  }
  std::vector<std::array<std::array<double, 3>, 3>> triangles;
  while (static_cast<int>(triangles.size()) < 2 * sides && std::getline(ray, line) &&
         line == "triangle") {
    std::array<std::array<double, 3>, 3> triangle{};
    for (auto& corner : triangle) {
      std::getline(ray, line);
      std::istringstream(line) >> corner[0] >> corner[1] >> corner[2];
    }
    triangles.push_back(triangle);
  }
  std::vector<std::array<double, 3>> out;
  if (static_cast<int>(triangles.size()) < 2 * sides) return out;
  for (int j = 0; j < sides; ++j) out.push_back(triangles[2 * j][ring == 0 ? 2 : 0]);
  out.push_back(ring == 0 ? triangles[2 * sides - 1][2] : triangles[2 * sides - 2][1]);
  return out;
}

// A ring is the resampled contour scaled by the radius and placed in the turtle's frame: the
// same shape up to a similarity, so ratios of distances between its vertices must agree.
void expectSameShape(const std::vector<std::array<double, 3>>& ring, const ContourSamples& samples,
                     double tolerance) {
  ASSERT_EQ(ring.size(), samples.points.size());
  const auto distance = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
  };
  const std::size_t middle = ring.size() / 2;
  const double rayUnit = distance(ring[0], ring[middle]);
  const double ourUnit = glm::length(samples.points[0] - samples.points[middle]);
  for (std::size_t a = 0; a < ring.size(); ++a) {
    for (std::size_t b = a + 1; b < ring.size(); ++b) {
      EXPECT_NEAR(distance(ring[a], ring[b]) / rayUnit,
                  glm::length(samples.points[a] - samples.points[b]) / ourUnit, tolerance)
          << a << " " << b;
    }
  }
}

TEST(ContourTest, RingsMatchCpfgsRayshadeOutput) {
  if (!std::filesystem::is_directory(kConformance)) {
    GTEST_SKIP() << "no conformance set at " << kConformance;
  }
  // tools-LilyLeaf: one tube with leaf.con and 16 sides (polygonization level 3); its ring 0 sits
  // at @Gs. The fit is 4.7e-6; a table that includes the curve's end point is off by 9.5e-5,
  // 5 or 20 samples per segment by far more.
  {
    ContourLibrary library;
    library.add(1, loadContour((kConformance / "tools-LilyLeaf" / "leaf.con").string()));
    const auto ring = firstTubeRing("tools-LilyLeaf", "s272", 16, 0);
    ASSERT_EQ(ring.size(), 17u);
    expectSameShape(ring, library.samples(1, 16), 2e-5);
  }
  // tools-FernLeaf: each leaf is a tube with leaf.con and 14 sides starting at radius 0
  // (`!(0) @Gs`), so ring 1 is the first with a shape. The fit is 2.9e-5, with the end point in
  // the table 6.2e-5, with 20 samples per segment 6.7e-4.
  {
    ContourLibrary library;
    library.add(1, loadContour((kConformance / "tools-FernLeaf" / "leaf.con").string()));
    const auto ring = firstTubeRing("tools-FernLeaf", "s258", 14, 1);
    ASSERT_EQ(ring.size(), 15u);
    expectSameShape(ring, library.samples(1, 14), 4e-5);
  }
}

}  // namespace
}  // namespace hirsute
