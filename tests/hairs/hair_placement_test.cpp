// Placing plant hairs (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3–4; docs/design.md, "Plant
// hairs"): each module's effect on the placed hairs, measured on fixture models in
// tests/fixtures/hairs built through the same steps as `hirsute render`.
#include "hirsute/hairs/plant/hair_placement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/plant_hairs.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kFixtures = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "hairs";
constexpr double kPi = std::numbers::pi;

double degrees(double radians) {
  return radians * 180.0 / kPi;
}

// The angle between two vectors, in degrees.
double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

// Keeps a measured figure in the test's record (--gtest_output=json or xml).
void measured(const std::string& name, double value) {
  std::ostringstream text;
  text.precision(6);
  text << value;
  ::testing::Test::RecordProperty(name, text.str());
}

struct PlacedHairs {
  Scene scene;
  HairPlacementReport report;
  std::vector<Diagnostic> warnings;
};

// A fixture model derived and interpreted as `hirsute render` does (cli/model_pipeline.cpp,
// buildScene).
struct Interpreted {
  ModelResources resources;
  Model model;
  Scene scene;
  Diagnostics diagnostics;
};

void interpretFixture(Interpreted& out, const std::string& lsystem, const std::string& view) {
  const fs::path viewFile = kFixtures / view;
  out.resources = loadModelResources(viewFile, {}, out.diagnostics);
  out.model = loadModel(kFixtures / lsystem, viewFile, out.diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(out.model.program, out.diagnostics, &out.model.functions, out.model.folder,
                      printed);
  Derivation derivation(out.model.program, evaluator, out.diagnostics);
  installQueryPass(derivation, out.resources, out.diagnostics);
  derivation.run();
  interpret(derivation, out.resources, out.scene, out.diagnostics);
}

// The same, then given its hairs by the pipeline's hair stage (hairs/plant_hairs.h).
PlacedHairs place(const std::string& lsystem, const std::string& view = "cylinder.v",
                  const PlantHairOptions& options = {}) {
  Interpreted interpreted;
  interpretFixture(interpreted, lsystem, view);
  PlacedHairs placed;
  if (hasHairs(interpreted.scene)) {
    placed.report = growPlantHairs(interpreted.scene, interpreted.resources,
                                   interpreted.model.functions, options, interpreted.diagnostics);
  }
  placed.scene = std::move(interpreted.scene);
  placed.warnings = interpreted.diagnostics.warnings();
  return placed;
}

// Every fixture is meant to be clean: a warning means the fixture does not say what it means to.
std::string warningsOf(const PlacedHairs& placed) {
  std::string text;
  for (const Diagnostic& d : placed.warnings) text += d.text() + "\n";
  return text;
}

// The area of a segment's triangles, from the mesh itself.
double segmentArea(const Scene& scene, const CylinderSegment& seg) {
  const TriangleMesh& mesh = scene.meshes.at(static_cast<std::size_t>(seg.mesh));
  double area = 0;
  for (std::uint32_t i = seg.firstIndex; i + 2 < seg.firstIndex + seg.indexCount; i += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[i]]), b(mesh.positions[mesh.indices[i + 1]]),
        c(mesh.positions[mesh.indices[i + 2]]);
    area += glm::length(glm::cross(b - a, c - a)) / 2;
  }
  return area;
}

double sceneArea(const Scene& scene) {
  double area = 0;
  for (const CylinderSegment& seg : scene.cylinderSegments) area += segmentArea(scene, seg);
  return area;
}

// A straight tube's axis: through the first segment's start, along its heading, with the ring
// frame's up (contour +x) and -left (contour +y).
struct StraightAxis {
  glm::dvec3 origin, heading, up, minusLeft;

  explicit StraightAxis(const Scene& scene) {
    const ControlFrame& f = scene.cylinderSegments.at(0).start;
    origin = f.position;
    heading = glm::normalize(glm::dvec3(f.heading));
    up = glm::normalize(glm::dvec3(f.up));
    minusLeft = -glm::normalize(glm::dvec3(f.left));
  }
  // Distance along the axis.
  double along(const glm::vec3& p) const { return glm::dot(glm::dvec3(p) - origin, heading); }
  // The outward radial unit vector at p: the shading normal of a round tube.
  glm::dvec3 radial(const glm::vec3& p) const {
    const glm::dvec3 r = glm::dvec3(p) - origin;
    return glm::normalize(r - heading * glm::dot(r, heading));
  }
  // The girth position s in [0, 1): the angle around the axis from contour sample 0 (on the
  // frame's up) toward -left, as the ring vertices C + r·cos θ·U − r·sin θ·L are laid out.
  double girth(const glm::vec3& p) const {
    const glm::dvec3 n = radial(p);
    const double s = std::atan2(glm::dot(n, minusLeft), glm::dot(n, up)) / (2 * kPi);
    return s < 0 ? s + 1 : s;
  }
};

struct Spread {
  double min = 1e300, max = -1e300, mean = 0;
};

template <typename F>
Spread spreadOf(const std::vector<Hair>& hairs, F value) {
  Spread s;
  for (const Hair& h : hairs) {
    const double v = value(h);
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
    s.mean += v;
  }
  if (!hairs.empty()) s.mean /= static_cast<double>(hairs.size());
  return s;
}

std::vector<Hair> onSide(const std::vector<Hair>& hairs, HairSide side) {
  std::vector<Hair> selected;
  for (const Hair& h : hairs) {
    if (h.side == side) selected.push_back(h);
  }
  return selected;
}

// ---- density (Sec. 3.1, 4.2) ---------------------------------------------------------------

TEST(HairDensity, DensityGivesHairsPerUnitArea) {
  const PlacedHairs placed = place("straight_cylinder.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const Scene& scene = placed.scene;
  ASSERT_EQ(scene.cylinderSegments.size(), 4u);
  const double expected = 40 * sceneArea(scene);
  const double count = static_cast<double>(scene.organ<HairPart>().hairs.size());
  measured("hairs", count);
  measured("expected", expected);
  EXPECT_NEAR(count, expected, 0.02 * expected) << "area " << sceneArea(scene);
  EXPECT_EQ(placed.report.hairs, scene.organ<HairPart>().hairs.size());
  EXPECT_EQ(placed.report.segments, 4u);

  // The same density on every segment (the texture continues from one to the next), and every
  // root on the surface of the 32-sided tube of radius 1.
  const StraightAxis axis(scene);
  for (std::size_t i = 0; i < 4; ++i) {
    const CylinderSegment& seg = scene.cylinderSegments[i];
    const double from = seg.axisStart, to = seg.axisStart + seg.axisLength;
    const auto inSegment = std::count_if(
        scene.organ<HairPart>().hairs.begin(), scene.organ<HairPart>().hairs.end(),
        [&](const Hair& h) { return axis.along(h.root) >= from && axis.along(h.root) < to; });
    const double segmentExpected = 40 * segmentArea(scene, seg);
    measured("segment" + std::to_string(i) + "_ratio",
             static_cast<double>(inSegment) / segmentExpected);
    EXPECT_NEAR(static_cast<double>(inSegment), segmentExpected, 0.05 * segmentExpected)
        << "segment " << i;
  }
  for (const Hair& h : scene.organ<HairPart>().hairs) {
    const glm::dvec3 r = glm::dvec3(h.root) - axis.origin;
    const double distance = glm::length(r - axis.heading * glm::dot(r, axis.heading));
    ASSERT_GE(distance, std::cos(kPi / 32) - 1e-4);
    ASSERT_LE(distance, 1 + 1e-4);
    ASSERT_EQ(h.side, HairSide::Front);
  }
}

// The texture's tile is sized for the widest girth; where the tube is narrower, points are
// thinned so that the count still follows the surface area (hair_placement.cpp).
TEST(HairDensity, TaperedTubeKeepsHairsPerUnitArea) {
  const PlacedHairs placed = place("tapered_cylinder.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const Scene& scene = placed.scene;
  ASSERT_EQ(scene.cylinderSegments.size(), 1u);
  const CylinderSegment& seg = scene.cylinderSegments[0];
  const StraightAxis axis(scene);
  // The wide and the narrow half, by the triangles' centroids and the hairs' roots.
  double area[2] = {0, 0}, count[2] = {0, 0};
  const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(seg.mesh)];
  for (std::uint32_t i = seg.firstIndex; i + 2 < seg.firstIndex + seg.indexCount; i += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                    c = mesh.positions[mesh.indices[i + 2]];
    area[axis.along((a + b + c) / 3.0f) < 5 ? 0 : 1] +=
        glm::length(glm::cross(glm::dvec3(b - a), glm::dvec3(c - a))) / 2;
  }
  for (const Hair& h : scene.organ<HairPart>().hairs) ++count[axis.along(h.root) < 5 ? 0 : 1];
  // Thinning keeps each point at random: a count within 4 standard deviations of a Poisson
  // count, plus the texture's own 2% (point_diffusion.h).
  auto tolerance = [](double expected) { return 4 * std::sqrt(expected) + 0.02 * expected; };
  const double wide = 160 * area[0], narrow = 160 * area[1];
  measured("wide_over_expected", count[0] / wide);
  measured("narrow_over_expected", count[1] / narrow);
  EXPECT_NEAR(count[0] + count[1], wide + narrow, tolerance(wide + narrow));
  EXPECT_NEAR(count[0], wide, tolerance(wide));
  EXPECT_NEAR(count[1], narrow, tolerance(narrow));
}

// Sec. 4.2: the texture is laid out by arc length along the axis, so on a bent tube the inner
// arc, whose surface is shorter than the axis, carries more hairs per unit surface area than
// the outer arc. Surface area near a point at distance ρ from the centre of the bend is ρ/R of
// the (u, v) area, so the expected density there is density · R/ρ.
TEST(HairDensity, InnerArcOfABentTubeIsDenserThanTheOuterArc) {
  const PlacedHairs placed = place("bent_cylinder.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const Scene& scene = placed.scene;
  ASSERT_EQ(scene.cylinderSegments.size(), 12u);
  const glm::dvec3 centre(-2, 0, 0);
  constexpr double kBend = 2, kRadius = 1, kDensity = 60;
  auto rho = [&](const glm::dvec3& p) { return std::hypot(p.x - centre.x, p.y - centre.y); };
  const double innerLimit = kBend - kRadius * std::cos(kPi / 4);
  const double outerLimit = kBend + kRadius * std::cos(kPi / 4);

  double innerArea = 0, outerArea = 0, innerPredicted = 0, outerPredicted = 0;
  for (const CylinderSegment& seg : scene.cylinderSegments) {
    const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(seg.mesh)];
    for (std::uint32_t i = seg.firstIndex; i + 2 < seg.firstIndex + seg.indexCount; i += 3) {
      const glm::dvec3 a(mesh.positions[mesh.indices[i]]), b(mesh.positions[mesh.indices[i + 1]]),
          c(mesh.positions[mesh.indices[i + 2]]);
      const double area = glm::length(glm::cross(b - a, c - a)) / 2;
      const double r = rho((a + b + c) / 3.0);
      if (r < innerLimit) {
        innerArea += area;
        innerPredicted += kDensity * area * kBend / r;
      } else if (r > outerLimit) {
        outerArea += area;
        outerPredicted += kDensity * area * kBend / r;
      }
    }
  }
  double inner = 0, outer = 0;
  for (const Hair& h : scene.organ<HairPart>().hairs) {
    const double r = rho(glm::dvec3(h.root));
    if (r < innerLimit) ++inner;
    if (r > outerLimit) ++outer;
  }
  const double innerDensity = inner / innerArea, outerDensity = outer / outerArea;
  measured("inner_density", innerDensity);
  measured("outer_density", outerDensity);
  measured("inner_over_predicted", inner / innerPredicted);
  measured("outer_over_predicted", outer / outerPredicted);
  EXPECT_GT(innerDensity, 1.8 * outerDensity)
      << "inner " << innerDensity << " outer " << outerDensity;
  EXPECT_GT(innerDensity, kDensity);
  EXPECT_LT(outerDensity, kDensity);
  EXPECT_NEAR(inner, innerPredicted, 0.06 * innerPredicted);
  EXPECT_NEAR(outer, outerPredicted, 0.06 * outerPredicted);
}

// ---- spacing measured on the surface (closed tubes: the strip along the tube) --------------

// A tube around a straight axis, unrolled: `around` is arc length around the ring polygon at the
// root's height (ring vertex j at angle 2πj/n, as StraightAxis lays them out), a fraction `f` of
// the girth there, and z the distance along the axis; the surface distance of two near points is
// the unrolled one, the slant of a tapering tube included.
class UnrolledTube {
 public:
  UnrolledTube(const Scene& scene, int tube) {
    for (const CylinderSegment& seg : scene.cylinderSegments) {
      if (seg.tube == tube) segments_.push_back(&seg);
    }
    const ControlFrame& f = segments_.front()->start;
    origin_ = f.position;
    heading_ = glm::normalize(glm::dvec3(f.heading));
    up_ = glm::normalize(glm::dvec3(f.up));
    minusLeft_ = -glm::normalize(glm::dvec3(f.left));
    sides_ = segments_.front()->sides;
  }

  struct Point {
    double f = 0, z = 0;
  };

  double length() const { return segments_.back()->axisStart + segments_.back()->axisLength; }
  // The segment boundaries inside the tube, and the middles of the segments.
  std::vector<double> boundaries() const {
    std::vector<double> at;
    for (std::size_t i = 1; i < segments_.size(); ++i) at.push_back(segments_[i]->axisStart);
    return at;
  }
  std::vector<double> middles() const {
    std::vector<double> at;
    for (const CylinderSegment* s : segments_) at.push_back(s->axisStart + s->axisLength / 2);
    return at;
  }
  // The radius of the ring polygon's vertices, linear between the rings (the radius follows
  // the tube's interpolation from ring to ring, not a line from one control point to the next).
  double radius(double z) const {
    const CylinderRing* before = &segments_.front()->rings.front();
    for (const CylinderSegment* s : segments_) {
      for (const CylinderRing& ring : s->rings) {
        if (ring.axisDistance >= z) {
          const double span = ring.axisDistance - before->axisDistance;
          const double t = span > 0 ? (z - before->axisDistance) / span : 1.0;
          return (1 - t) * before->radius + t * ring.radius;
        }
        before = &ring;
      }
    }
    return before->radius;
  }
  double slope(double z) const {
    const double dz = 1e-4;
    return (radius(z + dz) - radius(z - dz)) / (2 * dz);
  }
  double girth(double z) const { return sides_ * 2 * radius(z) * std::sin(kPi / sides_); }
  bool contains(const glm::vec3& p) const {
    const glm::dvec3 r = glm::dvec3(p) - origin_;
    const double z = glm::dot(r, heading_);
    const double d = glm::length(r - heading_ * z);
    return z >= -1e-4 && z <= length() + 1e-4 && std::abs(d - radius(z)) < 0.02 * radius(z) + 1e-4;
  }
  Point unroll(const glm::vec3& p) const {
    const glm::dvec3 r = glm::dvec3(p) - origin_;
    const double z = glm::dot(r, heading_);
    const glm::dvec3 q = r - heading_ * z;
    double theta = std::atan2(glm::dot(q, minusLeft_), glm::dot(q, up_));
    if (theta < 0) theta += 2 * kPi;
    const double step = 2 * kPi / sides_;
    const int j = std::min(static_cast<int>(theta / step), sides_ - 1);
    auto vertex = [&](int k) {
      return radius(z) * (std::cos(k * step) * up_ + std::sin(k * step) * minusLeft_);
    };
    const glm::dvec3 a = vertex(j), b = vertex(j + 1);
    const double along = glm::dot(q - a, glm::normalize(b - a));
    const double around = j * glm::length(b - a) + along;
    return {around / girth(z), z};
  }
  // The unrolled distance of two near points.
  double distance(const Point& a, const Point& b) const {
    double df = b.f - a.f;
    df -= std::round(df);
    const double zm = (a.z + b.z) / 2;
    const double du = df * girth(zm);
    const double dz = (b.z - a.z) * std::sqrt(1 + slope(zm) * slope(zm));
    return std::hypot(du, dz);
  }

 private:
  std::vector<const CylinderSegment*> segments_;
  glm::dvec3 origin_, heading_, up_, minusLeft_;
  int sides_ = 0;
};

// For every point, the index of its nearest neighbour on the unrolled tube: buckets of side
// `reach` (rows along the axis, in each row as many columns as fit the narrowest girth of the
// row), searched one bucket around; a point without a neighbour that near is searched against
// all.
std::vector<std::size_t> nearestOnTube(const UnrolledTube& tube,
                                       const std::vector<UnrolledTube::Point>& points,
                                       double reach) {
  const int rows = std::max(1, static_cast<int>(std::ceil(tube.length() / reach)));
  std::vector<int> columns(static_cast<std::size_t>(rows));
  std::vector<std::vector<std::vector<std::size_t>>> grid(static_cast<std::size_t>(rows));
  auto rowOf = [&](double z) { return std::clamp(static_cast<int>(z / reach), 0, rows - 1); };
  for (int r = 0; r < rows; ++r) {
    const double narrowest = std::min(tube.girth(r * reach), tube.girth((r + 1) * reach));
    columns[static_cast<std::size_t>(r)] = std::max(1, static_cast<int>(narrowest / reach));
    grid[static_cast<std::size_t>(r)].resize(static_cast<std::size_t>(columns[r]));
  }
  auto columnOf = [&](int r, double f) {
    const int c = columns[static_cast<std::size_t>(r)];
    return std::clamp(static_cast<int>((f - std::floor(f)) * c), 0, c - 1);
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int r = rowOf(points[i].z);
    grid[static_cast<std::size_t>(r)][static_cast<std::size_t>(columnOf(r, points[i].f))].push_back(
        i);
  }
  std::vector<std::size_t> nearest(points.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = 1e300;
    auto consider = [&](std::size_t j) {
      if (j == i) return;
      const double d = tube.distance(points[i], points[j]);
      if (d < best) {
        best = d;
        nearest[i] = j;
      }
    };
    const int r0 = rowOf(points[i].z);
    for (int r = std::max(0, r0 - 1); r <= std::min(rows - 1, r0 + 1); ++r) {
      const int c = columns[static_cast<std::size_t>(r)], c0 = columnOf(r, points[i].f);
      for (int dc = -1; dc <= 1 && dc < c; ++dc) {
        for (std::size_t j :
             grid[static_cast<std::size_t>(r)][static_cast<std::size_t>(((c0 + dc) % c + c) % c)]) {
          consider(j);
        }
      }
    }
    if (best > reach) {
      for (std::size_t j = 0; j < points.size(); ++j) consider(j);
    }
  }
  return nearest;
}

// The spacing of one tube's hairs on its surface.
struct TubeSpacing {
  double count = 0, expected = 0, rho = 0;
  // Nearest-neighbour distances over r_max, of the points whose nearest neighbour lies across
  // the girth seam (s = 0, where the strip's rows wrap) and across the opposite line (s = 0.5);
  // across a segment boundary and across the middle line of a segment.
  std::vector<double> girthSeam, girthMiddle, segmentBoundary, segmentMiddle;
};

TubeSpacing spacingOnTube(const Scene& scene, int tubeNumber, double density) {
  const UnrolledTube tube(scene, tubeNumber);
  std::vector<UnrolledTube::Point> points;
  for (const Hair& h : scene.organ<HairPart>().hairs) {
    if (tube.contains(h.root)) points.push_back(tube.unroll(h.root));
  }
  TubeSpacing spacing;
  double area = 0;
  for (const CylinderSegment& seg : scene.cylinderSegments) {
    if (seg.tube == tubeNumber) area += segmentArea(scene, seg);
  }
  spacing.count = static_cast<double>(points.size());
  spacing.expected = density * area;
  if (points.size() < 2) return spacing;
  const std::vector<std::size_t> nearest = nearestOnTube(tube, points, 3 / std::sqrt(density));
  // Lagae & Dutré's r_max for N points on this area (point_spacing.h).
  const double rMax = std::sqrt(area / (2 * std::sqrt(3.0) * spacing.count));
  double smallest = 1e300;
  const std::vector<double> boundaries = tube.boundaries(), middles = tube.middles();
  auto crosses = [](double a, double b, double at) { return (a - at) * (b - at) < 0; };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const UnrolledTube::Point &a = points[i], &b = points[nearest[i]];
    const double d = tube.distance(a, b) / rMax;
    smallest = std::min(smallest, d);
    if (std::abs(a.f - b.f) > 0.5) spacing.girthSeam.push_back(d);
    if (crosses(a.f, b.f, 0.5)) spacing.girthMiddle.push_back(d);
    for (double z : boundaries) {
      if (crosses(a.z, b.z, z)) spacing.segmentBoundary.push_back(d);
    }
    for (double z : middles) {
      if (crosses(a.z, b.z, z)) spacing.segmentMiddle.push_back(d);
    }
  }
  spacing.rho = smallest / 2;
  return spacing;
}

// Lengths and radii in tile widths (radius_cylinders.v): at 1000 hairs per unit area the
// texture's 1000-point tile is one unit wide.
constexpr double kTileDensity = 1000;
constexpr double kTileRadii[] = {0.05, 0.1, 0.5, 1, 2, 5, 10, 20};

void expectIsotropic(const TubeSpacing& spacing, const std::string& name) {
  measured(name + "_rho", spacing.rho);
  measured(name + "_count_over_expected", spacing.count / spacing.expected);
  EXPECT_GE(spacing.rho, 0.65) << name;
  EXPECT_NEAR(spacing.count, spacing.expected, 0.02 * spacing.expected) << name;
  std::printf("%s: rho %.3f, %g hairs for %.0f expected (%+.2f%%)\n", name.c_str(), spacing.rho,
              spacing.count, spacing.expected, 100 * (spacing.count / spacing.expected - 1));
}

// Issue: a closed tube's tile was stretched to a whole number of tiles around the girth, so the
// roots on a tube of radius one tile width had ρ ≈ 0.61 on the surface. Measured on the surface
// (unrolled, world distances), ρ stays at the texture's ≥ 0.65 from 0.05 to 20 tile widths.
TEST(HairSpacing, RelativeRadiusOnTheSurfaceHoldsOnEveryRadius) {
  const PlacedHairs placed = place("radius_cylinders.l", "radius_cylinders.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  ASSERT_EQ(placed.scene.cylinderSegments.size(), 4 * std::size(kTileRadii));
  for (std::size_t i = 0; i < std::size(kTileRadii); ++i) {
    const int tube = placed.scene.cylinderSegments[4 * i].tube;
    ASSERT_NEAR(placed.scene.cylinderSegments[4 * i].radiusStart, kTileRadii[i], 1e-5);
    std::ostringstream name;
    name << "radius_" << kTileRadii[i];
    expectIsotropic(spacingOnTube(placed.scene, tube, kTileDensity), name.str());
  }
}

TEST(HairSpacing, RelativeRadiusOnTheSurfaceHoldsOnATaperingTube) {
  const PlacedHairs placed = place("tapering_cylinder.l", "radius_cylinders.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  ASSERT_EQ(placed.scene.cylinderSegments.size(), 2u);
  const TubeSpacing spacing =
      spacingOnTube(placed.scene, placed.scene.cylinderSegments[0].tube, kTileDensity);
  expectIsotropic(spacing, "tapering");
}

double meanOf(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v;
  return values.empty() ? 0 : sum / static_cast<double>(values.size());
}

double standardErrorOf(const std::vector<double>& values) {
  const double mean = meanOf(values);
  double sum = 0;
  for (double v : values) sum += (v - mean) * (v - mean);
  const double n = static_cast<double>(values.size());
  return n > 1 ? std::sqrt(sum / (n - 1) / n) : 1e300;
}

// No seam: pairs of nearest neighbours that straddle the girth seam, or a boundary between two
// segments, stand as far apart as pairs straddling a line where nothing joins (the opposite side
// of the girth, the middle of a segment; the same selection, so the same bias toward longer
// distances): the mean no lower by more than four standard errors, and none closer than ρ allows.
TEST(HairSpacing, NoSeamAroundTheGirthOrBetweenSegments) {
  TubeSpacing pooled;
  auto pool = [&](const PlacedHairs& placed) {
    std::set<int> tubes;
    for (const CylinderSegment& seg : placed.scene.cylinderSegments) tubes.insert(seg.tube);
    for (int tube : tubes) {
      const TubeSpacing s = spacingOnTube(placed.scene, tube, kTileDensity);
      for (auto member : {&TubeSpacing::girthSeam, &TubeSpacing::girthMiddle,
                          &TubeSpacing::segmentBoundary, &TubeSpacing::segmentMiddle}) {
        (pooled.*member).insert((pooled.*member).end(), (s.*member).begin(), (s.*member).end());
      }
    }
  };
  pool(place("radius_cylinders.l", "radius_cylinders.v"));
  pool(place("tapering_cylinder.l", "radius_cylinders.v"));
  auto compare = [](const std::vector<double>& joined, const std::vector<double>& plain,
                    const char* what) {
    ASSERT_GT(joined.size(), 200u) << what;
    ASSERT_GT(plain.size(), 200u) << what;
    const double error = std::hypot(standardErrorOf(joined), standardErrorOf(plain));
    std::printf(
        "%s: mean nearest distance %.4f r_max (%zu pairs) against %.4f (%zu), "
        "closest %.4f\n",
        what, meanOf(joined), joined.size(), meanOf(plain), plain.size(),
        *std::min_element(joined.begin(), joined.end()));
    measured(std::string(what) + "_mean", meanOf(joined));
    measured(std::string(what) + "_plain_mean", meanOf(plain));
    EXPECT_GE(meanOf(joined), meanOf(plain) - 4 * error) << what;
    EXPECT_GE(*std::min_element(joined.begin(), joined.end()), 2 * 0.65) << what;
  };
  compare(pooled.girthSeam, pooled.girthMiddle, "girth_seam");
  compare(pooled.segmentBoundary, pooled.segmentMiddle, "segment_boundary");
}

// Where the density changes from one segment to the next the strip goes on at the new cell size:
// each segment gets its density × area, and the pairs across the boundary keep the spacing of
// the denser side.
TEST(HairSpacing, StripGoesOnAcrossADensityStep) {
  const PlacedHairs placed = place("density_step.l", "radius_cylinders.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const Scene& scene = placed.scene;
  ASSERT_EQ(scene.cylinderSegments.size(), 2u);
  const UnrolledTube tube(scene, scene.cylinderSegments[0].tube);
  std::vector<UnrolledTube::Point> points;
  for (const Hair& h : scene.organ<HairPart>().hairs) points.push_back(tube.unroll(h.root));
  const double boundary = scene.cylinderSegments[1].axisStart;
  const double densities[2] = {1000, 2000};
  for (int i = 0; i < 2; ++i) {
    const double count = static_cast<double>(
        std::count_if(points.begin(), points.end(),
                      [&](const UnrolledTube::Point& p) { return (p.z >= boundary) == (i == 1); }));
    const double expected = densities[i] * segmentArea(scene, scene.cylinderSegments[i]);
    measured("segment" + std::to_string(i) + "_count_over_expected", count / expected);
    EXPECT_NEAR(count, expected, 0.02 * expected) << "segment " << i;
  }
  const std::vector<std::size_t> nearest = nearestOnTube(tube, points, 3 / std::sqrt(1000.0));
  // r_max of the denser side: 2·0.65·r_max is the closest its own pairs may stand.
  const double rMax = std::sqrt(1 / (2 * std::sqrt(3.0) * 2000));
  double closest = 1e300;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const UnrolledTube::Point &a = points[i], &b = points[nearest[i]];
    if ((a.z - boundary) * (b.z - boundary) < 0)
      closest = std::min(closest, tube.distance(a, b) / rMax);
  }
  measured("closest_across_boundary", closest);
  EXPECT_GE(closest, 2 * 0.65);
}

// ---- `~` surfaces and `{ }` polygons (in their own (u, v)) ---------------------------------

// The triangles of the scene's organ surfaces (scene.h, OrganSurface).
struct SurfaceTriangle {
  glm::dvec3 a, b, c;
  glm::dvec3 normal() const { return glm::normalize(glm::cross(b - a, c - a)); }
  double area() const { return glm::length(glm::cross(b - a, c - a)) / 2; }
};

std::vector<SurfaceTriangle> organSurfaceTriangles(const Scene& scene) {
  std::vector<SurfaceTriangle> triangles;
  for (const OrganSurface& record : scene.organSurfaces) {
    const TriangleMesh& mesh = scene.meshes.at(static_cast<std::size_t>(record.mesh));
    for (std::uint32_t i = record.firstIndex; i + 2 < record.firstIndex + record.indexCount;
         i += 3) {
      triangles.push_back({glm::dvec3(mesh.positions[mesh.indices[i]]),
                           glm::dvec3(mesh.positions[mesh.indices[i + 1]]),
                           glm::dvec3(mesh.positions[mesh.indices[i + 2]])});
    }
  }
  return triangles;
}

double areaOf(const std::vector<SurfaceTriangle>& triangles) {
  double area = 0;
  for (const SurfaceTriangle& t : triangles) area += t.area();
  return area;
}

// The distance from p to triangle t, and the closest triangle of a set (Ericson, Real-Time
// Collision Detection, 5.1.5: the closest point by Voronoi regions).
glm::dvec3 closestOnTriangle(const glm::dvec3& p, const SurfaceTriangle& t) {
  const glm::dvec3 ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return t.a;
  const glm::dvec3 bp = p - t.b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return t.b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return t.a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = p - t.c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return t.c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return t.a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return t.b + (t.c - t.b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1 / (va + vb + vc);
  return t.a + ab * (vb * denom) + ac * (vc * denom);
}

std::size_t nearestTriangle(const glm::dvec3& p, const std::vector<SurfaceTriangle>& triangles,
                            double& distance) {
  std::size_t best = 0;
  distance = 1e300;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const double d = glm::length(p - closestOnTriangle(p, triangles[i]));
    if (d < distance) {
      distance = d;
      best = i;
    }
  }
  return best;
}

// The count of one side against density × area, and every root on the surface with its hair
// on that side of the triangle it lies on (hairs point along the normal without angles).
void expectOnSurface(const std::vector<Hair>& hairs, const std::vector<SurfaceTriangle>& triangles,
                     double density, const std::string& name, double sign) {
  const double expected = density * areaOf(triangles);
  const double count = static_cast<double>(hairs.size());
  measured(name + "_count_over_expected", count / expected);
  std::printf("%s: %g hairs for %.0f expected (%+.2f%%)\n", name.c_str(), count, expected,
              100 * (count / expected - 1));
  EXPECT_NEAR(count, expected, 0.02 * expected) << name;
  double farthest = 0;
  for (const Hair& h : hairs) {
    double distance = 0;
    const std::size_t t = nearestTriangle(glm::dvec3(h.root), triangles, distance);
    farthest = std::max(farthest, distance);
    const double facing = glm::dot(glm::dvec3(h.direction()), triangles[t].normal());
    ASSERT_GT(sign * facing, 0) << name << ": a hair on the wrong side";
  }
  measured(name + "_farthest_root", farthest);
  EXPECT_LT(farthest, 1e-4) << name;
}

TEST(HairSurfaces, BicubicSurfaceGetsDensityTimesAreaOnItsFront) {
  const PlacedHairs placed = place("surface_front.l", "surface.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  ASSERT_EQ(placed.scene.organSurfaces.size(), 1u);
  EXPECT_EQ(placed.scene.organSurfaces[0].kind, OrganSurfaceKind::BicubicPatch);
  EXPECT_EQ(placed.report.surfaces, 1u);
  expectOnSurface(placed.scene.organ<HairPart>().hairs, organSurfaceTriangles(placed.scene), 4000,
                  "bicubic", 1);
}

TEST(HairSurfaces, BicubicSurfaceHasAFrontAndABackAndNoEdges) {
  const PlacedHairs placed = place("surface_sides.l", "surface.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const std::vector<SurfaceTriangle> triangles = organSurfaceTriangles(placed.scene);
  EXPECT_TRUE(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Edge).empty());
  expectOnSurface(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Front), triangles, 1000,
                  "front", 1);
  expectOnSurface(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Back), triangles, 500,
                  "back", -1);
}

TEST(HairSurfaces, ConcavePolygonHasAFrontAndABack) {
  const PlacedHairs placed = place("polygon_sides.l", "surface.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  ASSERT_EQ(placed.scene.organSurfaces.size(), 1u);
  EXPECT_EQ(placed.scene.organSurfaces[0].kind, OrganSurfaceKind::Polygon);
  const std::vector<SurfaceTriangle> triangles = organSurfaceTriangles(placed.scene);
  EXPECT_NEAR(areaOf(triangles), 12, 1e-4);
  expectOnSurface(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Front), triangles, 400,
                  "front", 1);
  expectOnSurface(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Back), triangles, 200,
                  "back", -1);
}

// The turtle records a surface for the organs only where some organ's attributes are set, and a
// surface whose hair sides are all off gets none.
TEST(HairSurfaces, SurfacesWithoutHairAttributesGetNoHairs) {
  const PlacedHairs placed = place("plain_surface.l", "surface.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  EXPECT_EQ(placed.scene.organSurfaces.size(), 1u);  // the last blade, @Hf(0) in force
  EXPECT_TRUE(placed.scene.organ<HairPart>().hairs.empty());
  EXPECT_EQ(placed.report.surfaces, 0u);
}

// A polygon's (u, v) are world distances in its plane: the tile is laid unstretched, so the
// roots keep the texture's spacing (ρ measured in the plane, r_max for the polygon's area).
TEST(HairSurfaces, FlatPolygonKeepsTheTexturesSpacing) {
  const PlacedHairs placed = place("square_polygon.l", "surface.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const std::vector<SurfaceTriangle> triangles = organSurfaceTriangles(placed.scene);
  expectOnSurface(placed.scene.organ<HairPart>().hairs, triangles, 100, "square", 1);
  // The square spans x in [-10, 0] or [0, 10] and y in [0, 10]; distances in that plane, found
  // through a bucket grid of unit cells.
  const std::vector<Hair>& hairs = placed.scene.organ<HairPart>().hairs;
  ASSERT_GT(hairs.size(), 1000u);
  std::map<std::pair<int, int>, std::vector<std::size_t>> grid;
  auto cellOf = [](const glm::vec3& p) {
    return std::make_pair(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)));
  };
  for (std::size_t i = 0; i < hairs.size(); ++i) {
    ASSERT_NEAR(hairs[i].root.z, 0, 1e-5);
    grid[cellOf(hairs[i].root)].push_back(i);
  }
  double smallest = 1e300;
  for (std::size_t i = 0; i < hairs.size(); ++i) {
    const auto [cx, cy] = cellOf(hairs[i].root);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        const auto found = grid.find({cx + dx, cy + dy});
        if (found == grid.end()) continue;
        for (std::size_t j : found->second) {
          if (j != i)
            smallest =
                std::min(smallest, static_cast<double>(glm::length(hairs[i].root - hairs[j].root)));
        }
      }
    }
  }
  const double rMax =
      std::sqrt(areaOf(triangles) / (2 * std::sqrt(3.0) * static_cast<double>(hairs.size())));
  const double rho = smallest / 2 / rMax;
  measured("rho", rho);
  std::printf("square polygon: rho %.3f\n", rho);
  EXPECT_GE(rho, 0.65);
}

// ---- length and radius, rng (Sec. 4.1, 4.3) ------------------------------------------------

TEST(HairSize, LengthAndRadiusStayWithinValuePlusMinusRangeAndUseIt) {
  const PlacedHairs placed = place("length_range.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const std::vector<Hair>& hairs = placed.scene.organ<HairPart>().hairs;
  ASSERT_GT(hairs.size(), 1000u);
  const double n = static_cast<double>(hairs.size());
  // A uniform offset in [-rng, rng] has standard deviation rng/√3; the mean of n of them is
  // within 4 standard errors.
  const Spread length = spreadOf(hairs, [](const Hair& h) { return h.length; });
  EXPECT_GE(length.min, 0.5 - 1e-6);
  EXPECT_LE(length.max, 1.5 + 1e-6);
  EXPECT_LT(length.min, 0.52);
  EXPECT_GT(length.max, 1.48);
  EXPECT_NEAR(length.mean, 1.0, 4 * 0.5 / std::sqrt(3 * n));
  measured("length_min", length.min);
  measured("length_max", length.max);
  measured("length_mean", length.mean);
  measured("hairs", n);
  const Spread radius = spreadOf(hairs, [](const Hair& h) { return h.radius; });
  measured("radius_min", radius.min);
  measured("radius_max", radius.max);
  measured("radius_mean", radius.mean);
  EXPECT_GE(radius.min, 0.01 - 1e-6);
  EXPECT_LE(radius.max, 0.03 + 1e-6);
  EXPECT_LT(radius.min, 0.0104);
  EXPECT_GT(radius.max, 0.0296);
  EXPECT_NEAR(radius.mean, 0.02, 4 * 0.01 / std::sqrt(3 * n));
  // The two are drawn independently: length and radius are not correlated.
  double covariance = 0;
  for (const Hair& h : hairs) covariance += (h.length - length.mean) * (h.radius - radius.mean);
  covariance /= n;
  const double correlation = covariance / ((0.5 / std::sqrt(3.0)) * (0.01 / std::sqrt(3.0)));
  measured("correlation", correlation);
  EXPECT_LT(std::abs(correlation), 4 / std::sqrt(n));
}

TEST(HairSize, DefaultsAreUnitLengthAndRadiusOneHundredth) {
  const PlacedHairs placed = place("plain.l");
  ASSERT_FALSE(placed.scene.organ<HairPart>().hairs.empty());
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    ASSERT_EQ(h.length, 1.0f);
    ASSERT_FLOAT_EQ(h.radius, 0.01f);
  }
}

// ---- orientation (Sec. 3.2, 4.4) -----------------------------------------------------------

// Sec. 3.2: the hair frame is (n, n × h, n × (n × h)): the template's x along the shading
// normal, its y along n × h.
TEST(HairOrientation, WithoutAnglesTheHairFrameIsTheNormalFrame) {
  const PlacedHairs placed = place("plain.l");
  const StraightAxis axis(placed.scene);
  double worst = 0, worstFrame = 0;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    const glm::dvec3 n = axis.radial(h.root);
    worst = std::max(worst, angleBetween(glm::dvec3(h.direction()), n));
    const glm::dvec3 y(h.rotation() * glm::vec3(0, 1, 0));
    worstFrame = std::max(worstFrame, angleBetween(y, glm::cross(n, axis.heading)));
  }
  measured("worst_degrees", worst);
  measured("worst_frame_degrees", worstFrame);
  EXPECT_LT(worst, 0.2) << "degrees between hair and normal";
  EXPECT_LT(worstFrame, 0.2) << "degrees between the frame's y and n × h";
}

TEST(HairOrientation, InclineTiltsHairsTowardTheSegmentEndByTheAngle) {
  const PlacedHairs placed = place("incline.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const StraightAxis axis(placed.scene);
  ASSERT_GT(placed.scene.organ<HairPart>().hairs.size(), 500u);
  double worst = 0, worstSideways = 0;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    const glm::dvec3 d(h.direction()), n = axis.radial(h.root);
    worst = std::max(worst, std::abs(angleBetween(d, n) - 30));
    // Toward the end: the tilt is in the plane of n and h, toward +h.
    ASSERT_GT(glm::dot(d, axis.heading), 0.49);
    worstSideways = std::max(worstSideways, std::abs(glm::dot(d, glm::cross(n, axis.heading))));
  }
  measured("worst_degrees_off", worst);
  measured("worst_sideways", worstSideways);
  EXPECT_LT(worst, 0.2) << "degrees off an incline of 30";
  EXPECT_LT(worstSideways, 0.005);
}

// On a tapering tube the surface slopes: a hair of incline 0 stands square on it, along the
// surface's normal, which leans towards the narrow end by the slope's angle (atan of the
// radius's fall per unit length between the two rings about the root), not along the
// cylinder's radial shading normal.
TEST(HairOrientation, HairsStandSquareOnTheSurfaceOfATaperingTube) {
  const PlacedHairs placed = place("cone.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const StraightAxis axis(placed.scene);
  ASSERT_GT(placed.scene.organ<HairPart>().hairs.size(), 200u);
  const std::vector<CylinderRing>& rings = placed.scene.cylinderSegments.at(0).rings;
  ASSERT_GT(rings.size(), 2u);
  double worst = 0, least = 90;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    const glm::dvec3 d(h.direction()), n = axis.radial(h.root);
    const double along = axis.along(h.root);
    std::size_t k = 1;
    while (k + 1 < rings.size() && axis.along(rings[k].frame.position) < along) ++k;
    const double fall = rings[k - 1].radius - rings[k].radius;
    const double run =
        axis.along(rings[k].frame.position) - axis.along(rings[k - 1].frame.position);
    const double slope = std::atan2(fall, run) * 180 / kPi;
    least = std::min(least, slope);
    // Tilted from the radial towards the narrow end (+heading), by the slope.
    EXPECT_GT(glm::dot(d, axis.heading), 0);
    worst = std::max(worst, std::abs(angleBetween(d, n) - slope));
  }
  measured("worst_degrees_off_the_surface_normal", worst);
  EXPECT_GT(least, 5) << "the tube tapers all along";
  EXPECT_LT(worst, 0.5) << "degrees off the surface's lean";
}

TEST(HairOrientation, InclineRangeSpreadsTheAngleOverValuePlusMinusRange) {
  const PlacedHairs placed = place("incline_range.l");
  const StraightAxis axis(placed.scene);
  const Spread angle = spreadOf(placed.scene.organ<HairPart>().hairs, [&](const Hair& h) {
    return angleBetween(glm::dvec3(h.direction()), axis.radial(h.root));
  });
  measured("angle_min", angle.min);
  measured("angle_max", angle.max);
  measured("angle_mean", angle.mean);
  EXPECT_GE(angle.min, 20 - 0.2);
  EXPECT_LE(angle.max, 40 + 0.2);
  EXPECT_LT(angle.min, 21);
  EXPECT_GT(angle.max, 39);
  EXPECT_NEAR(
      angle.mean, 30,
      4 * 10 / std::sqrt(3.0 * static_cast<double>(placed.scene.organ<HairPart>().hairs.size())));
}

TEST(HairOrientation, WrapTiltsHairsAroundTheGirthByTheAngle) {
  const PlacedHairs placed = place("wrap.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const StraightAxis axis(placed.scene);
  double worst = 0, worstAlong = 0;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    const glm::dvec3 d(h.direction()), n = axis.radial(h.root);
    worst = std::max(worst, std::abs(angleBetween(d, n) - 40));
    // Around the girth, toward n × h; not along the axis.
    ASSERT_GT(glm::dot(d, glm::cross(n, axis.heading)), 0.63);
    worstAlong = std::max(worstAlong, std::abs(glm::dot(d, axis.heading)));
  }
  measured("worst_degrees_off", worst);
  measured("worst_along", worstAlong);
  EXPECT_LT(worst, 0.2) << "degrees off a wrap of 40";
  EXPECT_LT(worstAlong, 0.005);
}

TEST(HairOrientation, TwistRotatesTheHairFrameAboutItsDirection) {
  const PlacedHairs plain = place("plain.l");
  const PlacedHairs twisted = place("twist.l");
  ASSERT_TRUE(twisted.warnings.empty()) << warningsOf(twisted);
  ASSERT_EQ(plain.scene.organ<HairPart>().hairs.size(),
            twisted.scene.organ<HairPart>().hairs.size());
  ASSERT_GT(plain.scene.organ<HairPart>().hairs.size(), 500u);
  double worstDirection = 0, worstTwist = 0;
  for (std::size_t i = 0; i < plain.scene.organ<HairPart>().hairs.size(); ++i) {
    const Hair& a = plain.scene.organ<HairPart>().hairs[i];
    const Hair& b = twisted.scene.organ<HairPart>().hairs[i];
    ASSERT_EQ(a.root, b.root) << "hair " << i;
    const glm::dvec3 d(b.direction());
    worstDirection = std::max(worstDirection, angleBetween(glm::dvec3(a.direction()), d));
    // The signed angle from the untwisted frame's second axis to the twisted one, about d.
    const glm::dvec3 y0(a.rotation() * glm::vec3(0, 1, 0)), y1(b.rotation() * glm::vec3(0, 1, 0));
    const double twist = degrees(std::atan2(glm::dot(glm::cross(y0, y1), d), glm::dot(y0, y1)));
    worstTwist = std::max(worstTwist, std::abs(twist - 50));
  }
  measured("worst_direction_degrees", worstDirection);
  measured("worst_twist_degrees_off", worstTwist);
  EXPECT_LT(worstDirection, 0.02) << "degrees: twist must leave the direction alone";
  EXPECT_LT(worstTwist, 0.05) << "degrees off a twist of 50";
}

// ---- modulating functions (Sec. 4.1) -------------------------------------------------------

TEST(HairFunction, FunctionOfTheGirthPositionModulatesTheValue) {
  const PlacedHairs placed = place("girth_function.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const StraightAxis axis(placed.scene);
  ASSERT_GT(placed.scene.organ<HairPart>().hairs.size(), 1000u);
  double worst = 0, shortest = 1e9, longest = 0;
  std::size_t counted = 0;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    const double s = axis.girth(h.root);
    if (s < 0.01 || s > 0.99) continue;  // at the seam, s = 0 and s = 1 meet
    // hairs.fset's ramp: 0.2 + 0.8 s (a B-spline over collinear points is that line).
    worst = std::max(worst, std::abs(h.length - (0.2 + 0.8 * s)));
    shortest = std::min(shortest, static_cast<double>(h.length));
    longest = std::max(longest, static_cast<double>(h.length));
    ++counted;
  }
  EXPECT_GT(counted, 1000u);
  measured("worst_length_off", worst);
  measured("shortest", shortest);
  measured("longest", longest);
  EXPECT_LT(worst, 0.01) << "length off 0.2 + 0.8 s";
  EXPECT_LT(shortest, 0.22);
  EXPECT_GT(longest, 0.98);
}

// A function of the girth position on the density: the count in each quarter of the girth
// follows the function's mean over it.
TEST(HairFunction, FunctionOfTheGirthPositionModulatesTheDensity) {
  const PlacedHairs placed = place("girth_density.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const StraightAxis axis(placed.scene);
  const double area = sceneArea(placed.scene);
  double count[4] = {0, 0, 0, 0};
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    ++count[std::min(3, static_cast<int>(axis.girth(h.root) * 4))];
  }
  for (int q = 0; q < 4; ++q) {
    // The mean of 0.2 + 0.8 s over [q/4, (q+1)/4].
    const double points = 60 * area / 4;  // the pattern's points in the quarter
    const double kept = 0.2 + 0.8 * (q + 0.5) / 4;
    const double expected = points * kept;
    measured("quarter" + std::to_string(q) + "_over_expected", count[q] / expected);
    // Each point is kept at random: within 4 standard deviations of a binomial count, plus the
    // pattern's own 2% (the quarters' expected counts lie 40% apart, far outside this).
    const double tolerance = 4 * std::sqrt(points * kept * (1 - kept)) + 0.02 * expected;
    EXPECT_NEAR(count[q], expected, tolerance) << "quarter " << q;
  }
}

// ---- placement probabilities (Sec. 4.5) ----------------------------------------------------

TEST(HairProbability, TemplateFrequenciesFollowTheNormalisedProbabilities) {
  const PlacedHairs placed = place("probabilities.l", "three_templates.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  ASSERT_EQ(placed.scene.organ<HairPart>().templates.size(), 3u);
  const std::vector<Hair>& hairs = placed.scene.organ<HairPart>().hairs;
  const double n = static_cast<double>(hairs.size());
  ASSERT_GT(n, 3000);
  const double probability[] = {1.0 / 8, 2.0 / 8, 5.0 / 8};
  for (int t = 0; t < 3; ++t) {
    const auto count = std::count_if(hairs.begin(), hairs.end(),
                                     [t](const Hair& h) { return h.templateIndex == t; });
    const double p = probability[t];
    measured("template" + std::to_string(t) + "_frequency", static_cast<double>(count) / n);
    EXPECT_NEAR(static_cast<double>(count), n * p, 4 * std::sqrt(n * p * (1 - p)))
        << "template " << t;
  }
}

TEST(HairProbability, AllZeroProbabilitiesPlaceNoHairs) {
  const PlacedHairs placed = place("zero_probabilities.l", "three_templates.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  EXPECT_TRUE(placed.scene.organ<HairPart>().hairs.empty());
  EXPECT_EQ(placed.report.hairs, 0u);
}

TEST(HairProbability, WithoutTemplatesEveryHairIsTheStraightDefault) {
  const PlacedHairs placed = place("plain.l");
  ASSERT_EQ(placed.scene.organ<HairPart>().templates.size(), 1u);
  EXPECT_EQ(placed.scene.organ<HairPart>().templates[0].polylines.size(), 1u);
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) ASSERT_EQ(h.templateIndex, 0);
}

// Interpolation mixes the probabilities, normalised at each end, linearly along the segment
// (docs/design.md, "Placement": attributes vary linearly between the two ends).
TEST(HairProbability, InterpolatedProbabilitiesVaryLinearlyAlongTheSegment) {
  const PlacedHairs placed = place("probability_ramp.l", "three_templates_interpolated.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const StraightAxis axis(placed.scene);
  constexpr int kBins = 5;
  double total[kBins] = {}, first[kBins] = {}, second[kBins] = {};
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    const int bin = std::clamp(static_cast<int>(axis.along(h.root) / 10 * kBins), 0, kBins - 1);
    ++total[bin];
    first[bin] += h.templateIndex == 0;
    second[bin] += h.templateIndex == 1;
  }
  for (int b = 0; b < kBins; ++b) {
    const double tau = (b + 0.5) / kBins;
    const double p = 1 - tau;  // template 1; templates 2 and 3 share the rest equally
    measured("bin" + std::to_string(b) + "_template0", first[b] / total[b]);
    EXPECT_NEAR(first[b], total[b] * p, 4 * std::sqrt(total[b] * p * (1 - p)) + 0.02 * total[b])
        << "at tau " << tau;
    const double q = tau / 2;
    EXPECT_NEAR(second[b], total[b] * q, 4 * std::sqrt(total[b] * q * (1 - q)) + 0.02 * total[b])
        << "at tau " << tau;
  }
}

TEST(HairProbability, TrailingLocSetsOneSidesProbabilities) {
  const PlacedHairs placed = place("leaf_probabilities.l", "three_templates.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  ASSERT_FALSE(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Back).empty());
  ASSERT_FALSE(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Front).empty());
  ASSERT_FALSE(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Edge).empty());
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    ASSERT_EQ(h.templateIndex, h.side == HairSide::Back ? 2 : 0);
  }
}

// ---- sides and loc (Sec. 2, 3.2, 4.1) ------------------------------------------------------

TEST(HairLocation, LocChangesOnlyItsSide) {
  const PlacedHairs placed = place("leaf.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  ASSERT_EQ(placed.scene.cylinderSegments.size(), 1u);
  EXPECT_FALSE(placed.scene.cylinderSegments[0].closed);
  const std::vector<Hair> front = onSide(placed.scene.organ<HairPart>().hairs, HairSide::Front);
  const std::vector<Hair> back = onSide(placed.scene.organ<HairPart>().hairs, HairSide::Back);
  const std::vector<Hair> edge = onSide(placed.scene.organ<HairPart>().hairs, HairSide::Edge);
  ASSERT_GT(front.size(), 300u);
  ASSERT_GT(back.size(), 300u);
  ASSERT_GT(edge.size(), 50u);
  for (const Hair& h : back) ASSERT_EQ(h.length, 2.0f);
  for (const Hair& h : front) ASSERT_EQ(h.length, 1.0f);
  for (const Hair& h : edge) ASSERT_EQ(h.length, 1.0f);
  // Both faces of the flat leaf at density 40: the back's hairs are as many as the front's, and
  // stand on the other side.
  const double area = sceneArea(placed.scene);
  measured("front_over_expected", static_cast<double>(front.size()) / (40 * area));
  measured("back_over_expected", static_cast<double>(back.size()) / (40 * area));
  EXPECT_NEAR(static_cast<double>(front.size()), 40 * area, 0.04 * 40 * area);
  EXPECT_NEAR(static_cast<double>(back.size()), 40 * area, 0.04 * 40 * area);
  const glm::dvec3 frontNormal = glm::normalize(glm::dvec3(front.front().direction()));
  for (const Hair& h : front) ASSERT_LT(angleBetween(glm::dvec3(h.direction()), frontNormal), 0.1);
  for (const Hair& h : back) ASSERT_LT(angleBetween(glm::dvec3(h.direction()), -frontNormal), 0.1);
}

TEST(HairLocation, SwitchedOffSideGetsNoHairs) {
  const PlacedHairs placed = place("leaf_front_off.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  EXPECT_TRUE(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Front).empty());
  EXPECT_GT(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Back).size(), 300u);
  EXPECT_GT(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Edge).size(), 50u);
}

TEST(HairLocation, ClosedCylinderHasNoEdgeHairs) {
  const PlacedHairs placed = place("closed_edges.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  ASSERT_TRUE(placed.scene.cylinderSegments.at(0).closed);
  EXPECT_GT(placed.scene.organ<HairPart>().hairs.size(), 500u);
  EXPECT_TRUE(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Edge).empty());
  EXPECT_TRUE(onSide(placed.scene.organ<HairPart>().hairs, HairSide::Back).empty());
}

// Sec. 3.2: edge hairs grow along the two outer edges of an open cylinder, along the edge
// vector h × n, away from the segment; √density per unit length along each edge.
TEST(HairLocation, OpenLeafHasEdgeHairsPointingAwayAtBothEdges) {
  const PlacedHairs placed = place("leaf.l");
  const StraightAxis axis(placed.scene);
  const std::vector<Hair> edge = onSide(placed.scene.organ<HairPart>().hairs, HairSide::Edge);
  // The leaf spans contour x in [-1, 1] (times the radius 1) along the frame's up.
  double halfWidth = 0;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    halfWidth = std::max(halfWidth, std::abs(glm::dot(glm::dvec3(h.root) - axis.origin, axis.up)));
  }
  std::size_t atPlus = 0, atMinus = 0;
  double worst = 0;
  for (const Hair& h : edge) {
    const double across = glm::dot(glm::dvec3(h.root) - axis.origin, axis.up);
    ASSERT_NEAR(std::abs(across), halfWidth, 1e-4) << "an edge hair off the edge";
    (across > 0 ? atPlus : atMinus)++;
    const glm::dvec3 outward = across > 0 ? axis.up : -axis.up;
    worst = std::max(worst, angleBetween(glm::dvec3(h.direction()), outward));
  }
  measured("worst_edge_degrees", worst);
  measured("edge_plus", static_cast<double>(atPlus));
  measured("edge_minus", static_cast<double>(atMinus));
  measured("edge_expected", std::sqrt(40.0) * 10);
  EXPECT_LT(worst, 0.5) << "degrees between an edge hair and the outward edge vector";
  const double perEdge = std::sqrt(40.0) * 10;
  EXPECT_NEAR(static_cast<double>(atPlus), perEdge, 0.03 * perEdge);
  EXPECT_NEAR(static_cast<double>(atMinus), perEdge, 0.03 * perEdge);
}

// ---- the attributes the turtle carries -----------------------------------------------------

TEST(HairAttributeState, AttributesSetInsideABranchDoNotLeakPastItsEnd) {
  const PlacedHairs placed = place("branch.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  ASSERT_EQ(placed.scene.cylinderSegments.size(), 2u);
  std::size_t inBranch = 0, afterBranch = 0;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    if (h.root.x > 0) {  // the branch's tube, along +x
      ++inBranch;
      ASSERT_EQ(h.length, 3.0f);
      ASSERT_FLOAT_EQ(h.radius, 0.05f);
    } else {  // the tube after `]`, along -x
      ++afterBranch;
      ASSERT_EQ(h.length, 1.0f);
      ASSERT_FLOAT_EQ(h.radius, 0.01f);
    }
  }
  EXPECT_GT(inBranch, 200u);
  EXPECT_GT(afterBranch, 200u);
}

// The same inside one forked tube: the branch's segment takes the branch's length, the parent's
// next segment the length of before the branch.
TEST(HairAttributeState, BranchOfAForkedTubeKeepsItsOwnAttributes) {
  const PlacedHairs placed = place("fork.l");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const Scene& scene = placed.scene;
  ASSERT_EQ(scene.cylinderSegments.size(), 3u);
  EXPECT_GT(scene.organ<HairPart>().hairs.size(), 300u);
  int branches = 0;
  for (const CylinderSegment& seg : scene.cylinderSegments) {
    ASSERT_GE(seg.organEnd.of<HairAttributes>(), 0);
    const float length =
        scene.organ<HairPart>()
            .attributes.at(static_cast<std::size_t>(seg.organEnd.of<HairAttributes>()))
            .side(HairSide::Front)
            .length.value;
    // The branch ends heading along -x (a left turn from +y); the parent's segments along +y.
    const bool branch = seg.end.heading.x < -0.9f;
    branches += branch;
    EXPECT_EQ(length, branch ? 3.0f : 1.0f)
        << "segment ending at " << seg.end.position.x << "," << seg.end.position.y;
  }
  EXPECT_EQ(branches, 1);
  std::size_t three = 0;
  for (const Hair& h : scene.organ<HairPart>().hairs) three += h.length == 3.0f;
  EXPECT_GT(three, 50u);
  EXPECT_LT(three, scene.organ<HairPart>().hairs.size());
}

// The two segments (of length 4, along y) of a straight tube carry one hair length each, and
// both have many hairs.
void expectSegmentLengths(const PlacedHairs& placed, float first, float second) {
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const StraightAxis axis(placed.scene);
  std::size_t inFirst = 0, inSecond = 0;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    const double y = axis.along(h.root);
    if (y < 4 - 1e-3) {
      ++inFirst;
      ASSERT_EQ(h.length, first) << "at " << y;
    } else if (y > 4 + 1e-3) {
      ++inSecond;
      ASSERT_EQ(h.length, second) << "at " << y;
    }
  }
  EXPECT_GT(inFirst, 500u);
  EXPECT_GT(inSecond, 500u);
}

// A segment keeps the attributes of its control points: modules after its @Gc change the next
// segment only, even when the first of them repeats a value already set.
TEST(HairAttributeState, ModulesAfterAControlPointLeaveTheClosedSegmentAlone) {
  expectSegmentLengths(place("repeated_value.l"), 1.0f, 2.0f);
}

// ---- reproducibility -----------------------------------------------------------------------

bool sameHairs(const std::vector<Hair>& a, const std::vector<Hair>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Hair)) == 0;
}

TEST(HairSeeding, SameSeedPlacesIdenticalHairs) {
  const PlacedHairs first = place("length_range.l");
  const PlacedHairs second = place("length_range.l");
  ASSERT_FALSE(first.scene.organ<HairPart>().hairs.empty());
  EXPECT_TRUE(sameHairs(first.scene.organ<HairPart>().hairs, second.scene.organ<HairPart>().hairs));
}

TEST(HairSeeding, AnotherSeedDrawsOtherValues) {
  const PlacedHairs first = place("length_range.l");
  PlantHairOptions reseed;
  reseed.seed = 2;  // as `--placement-seed 2`
  const PlacedHairs reseeded = place("length_range.l", "cylinder.v", reseed);
  // The attachment points are the texture's (same texture seed), the random offsets are not.
  ASSERT_EQ(first.scene.organ<HairPart>().hairs.size(),
            reseeded.scene.organ<HairPart>().hairs.size());
  std::size_t sameRoot = 0, sameLength = 0;
  for (std::size_t i = 0; i < first.scene.organ<HairPart>().hairs.size(); ++i) {
    sameRoot += first.scene.organ<HairPart>().hairs[i].root ==
                reseeded.scene.organ<HairPart>().hairs[i].root;
    sameLength += first.scene.organ<HairPart>().hairs[i].length ==
                  reseeded.scene.organ<HairPart>().hairs[i].length;
  }
  EXPECT_EQ(sameRoot, first.scene.organ<HairPart>().hairs.size());
  EXPECT_LT(sameLength, first.scene.organ<HairPart>().hairs.size() / 100);
}

TEST(HairSeeding, AnotherTextureSeedPlacesOtherRoots) {
  const PlacedHairs first = place("length_range.l");
  const PlacedHairs other = place("length_range.l", "other_texture.v");
  ASSERT_FALSE(other.scene.organ<HairPart>().hairs.empty());
  std::size_t shared = 0;
  for (const Hair& a : first.scene.organ<HairPart>().hairs) {
    for (const Hair& b : other.scene.organ<HairPart>().hairs) {
      if (glm::length(a.root - b.root) < 1e-4f) {
        ++shared;
        break;
      }
    }
  }
  EXPECT_LT(shared, first.scene.organ<HairPart>().hairs.size() / 100);
}

// ---- interpolation (Sec. 4.1) --------------------------------------------------------------

TEST(HairInterpolation, WithoutInterpolationEachSegmentTakesItsEndValues) {
  expectSegmentLengths(place("two_lengths.l", "cylinder.v"), 3.0f, 2.0f);
}

TEST(HairInterpolation, WithInterpolationValuesVaryLinearlyAlongEachSegment) {
  const PlacedHairs placed = place("two_lengths.l", "interpolated.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const StraightAxis axis(placed.scene);
  double worst = 0;
  Spread first, second;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    const double y = axis.along(h.root);
    // 1 at y = 0, 3 at y = 4, 2 at y = 8.
    const double expected = y < 4 ? 1 + 2 * y / 4 : 3 - (y - 4) / 4;
    worst = std::max(worst, std::abs(h.length - expected));
    Spread& s = y < 4 ? first : second;
    s.min = std::min(s.min, static_cast<double>(h.length));
    s.max = std::max(s.max, static_cast<double>(h.length));
  }
  measured("worst_length_off", worst);
  EXPECT_LT(worst, 0.002) << "length off the line between the segment's ends";
  EXPECT_LT(first.min, 1.05);
  EXPECT_GT(first.max, 2.95);
  EXPECT_LT(second.min, 2.05);
  EXPECT_GT(second.max, 2.95);
}

TEST(HairInterpolation, SideSwitchedOnAfterTheFirstControlPointTakesTheEndValues) {
  const PlacedHairs placed = place("switched_on_after_start.l", "interpolated.v");
  ASSERT_TRUE(placed.warnings.empty()) << warningsOf(placed);
  const StraightAxis axis(placed.scene);
  std::size_t first = 0;
  for (const Hair& h : placed.scene.organ<HairPart>().hairs) {
    const double y = axis.along(h.root);
    if (y < 4 - 1e-3) {
      ++first;
      ASSERT_EQ(h.length, 3.0f) << "at " << y << ": the default length leaked into the first segment";
    } else {
      ASSERT_NEAR(h.length, 3 - (y - 4) / 4, 0.002) << "at " << y;
    }
  }
  EXPECT_GT(first, 500u);
}

// ---- the hair limit ------------------------------------------------------------------------

TEST(HairLimit, MoreThanMaxHairsThrows) {
  const std::size_t n = place("plain.l").scene.organ<HairPart>().hairs.size();
  ASSERT_GT(n, 100u);
  // placeHairs itself, with the settings the pipeline derives from cylinder.v.
  Interpreted interpreted;
  interpretFixture(interpreted, "plain.l", "cylinder.v");
  HairPlacementSettings settings;  // cylinder.v: the default 100 × 100 texture, seed 1
  settings.maxHairs = n;
  Scene exact = interpreted.scene;
  EXPECT_EQ(placeHairs(exact, settings).hairs, n);
  settings.maxHairs = n - 1;
  Scene over = interpreted.scene;
  EXPECT_THROW(placeHairs(over, settings), HairLimitError);
  // Through the pipeline's hair stage: a diagnostic at the model's file.
  PlantHairOptions options;
  options.maxHairs = n - 1;
  options.lsystemFile = (kFixtures / "plain.l").string();
  try {
    place("plain.l", "cylinder.v", options);
    FAIL() << "more hairs than the limit were placed";
  } catch (const DiagnosticError& e) {
    EXPECT_EQ(fs::path(e.diagnostic().where.fileName()).filename(), "plain.l") << e.what();
  }
}

}  // namespace
}  // namespace hirsute
