// Plant hairs on a mesh surface (docs/design.md, "Meshes"; mesh_sampling.h): placed over
// the mesh's own area, whatever its texture atlas, measured on the surface in world distances.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/plant_hairs.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

// A unit sphere of `rings` × `sides` quads with a texture atlas cut along the meridian φ = 0
// (its vertices doubled there) and squeezed: u = (φ / 2π)², so one side of the sphere has a
// quarter of the atlas and the other three quarters. A tile over (u, v) would crowd one side and
// thin the other, and seam at the cut.
std::string squeezedSphere(int rings, int sides) {
  std::ostringstream obj;
  obj.precision(9);
  for (int i = 0; i <= rings; ++i) {
    const double theta = kPi * i / rings;
    for (int j = 0; j <= sides; ++j) {
      const double phi = 2 * kPi * j / sides;
      obj << "v " << std::sin(theta) * std::cos(phi) << ' ' << std::sin(theta) * std::sin(phi)
          << ' ' << std::cos(theta) << '\n';
      const double u = static_cast<double>(j) / sides;
      obj << "vt " << u * u << ' ' << 1.0 - static_cast<double>(i) / rings << '\n';
    }
  }
  const auto at = [&](int i, int j) { return i * (sides + 1) + j + 1; };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      const int a = at(i, j), b = at(i, j + 1), c = at(i + 1, j), d = at(i + 1, j + 1);
      // Outward: counter-clockwise seen from outside. The poles' rows give no-area triangles,
      // which the reader leaves out.
      if (i > 0) obj << "f " << a << '/' << a << ' ' << c << '/' << c << ' ' << b << '/' << b << '\n';
      if (i + 1 < rings) obj << "f " << b << '/' << b << ' ' << c << '/' << c << ' ' << d << '/' << d << '\n';
    }
  }
  return obj.str();
}

class MeshHairsTest : public testing::TemporaryFolderTest {
 protected:
  MeshHairsTest() : TemporaryFolderTest("hirsute_mesh_hairs_") {}

  // Derives and interprets a model of the folder as `hirsute render` does, then places hairs.
  void place(const std::string& axiom) {
    std::ofstream(file("ball.obj")) << squeezedSphere(40, 80);
    std::ofstream(file("ball.v")) << "surface: B ball.obj 1\nhair texture: 100 3\n";
    std::ofstream(file("ball.l")) << "Lsystem: 1\nderivation length: 0\nAxiom: " << axiom
                                  << "\nendlsystem\n";
    resources = loadModelResources(file("ball.v"), {}, diagnostics);
    model = loadModel(file("ball.l"), file("ball.v"), diagnostics);
    std::ostringstream printed;
    Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
    Derivation derivation(model.program, evaluator, diagnostics);
    installQueryPass(derivation, resources, diagnostics);
    derivation.run();
    interpret(derivation, resources, scene, diagnostics);
    growPlantHairs(scene, resources, model.functions, {}, diagnostics);
  }
  double area() const {
    double total = 0;
    for (const OrganSurface& record : scene.organSurfaces) {
      const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(record.mesh)];
      for (std::uint32_t i = record.firstIndex; i < record.firstIndex + record.indexCount; i += 3) {
        const glm::dvec3 a(mesh.positions[mesh.indices[i]]), b(mesh.positions[mesh.indices[i + 1]]),
            c(mesh.positions[mesh.indices[i + 2]]);
        total += 0.5 * glm::length(glm::cross(b - a, c - a));
      }
    }
    return total;
  }
  std::vector<glm::dvec3> roots(HairSide side) const {
    std::vector<glm::dvec3> points;
    for (const Hair& h : scene.organ<HairPart>().hairs) {
      if (h.side == side) points.emplace_back(h.root);
    }
    return points;
  }

  Diagnostics diagnostics;
  ModelResources resources;
  Model model;
  Scene scene;
};

// Each point's distance to its nearest neighbour in space (brute force over a grid of cells).
std::vector<double> nearestDistances(const std::vector<glm::dvec3>& points, double cell) {
  std::vector<double> nearest(points.size(), 1e300);
  const auto cellOf = [cell](const glm::dvec3& p) { return glm::ivec3(glm::floor(p / cell)); };
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order[i] = i;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::ivec3 c = cellOf(points[i]);
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (j == i) continue;
      const glm::ivec3 d = glm::abs(cellOf(points[j]) - c);
      if (d.x > 1 || d.y > 1 || d.z > 1) continue;
      nearest[i] = std::min(nearest[i], glm::distance(points[i], points[j]));
    }
  }
  return nearest;
}

TEST_F(MeshHairsTest, HairsCoverTheMeshAtDensityTimesAreaEvenlyAndWithoutSeams) {
  constexpr double kDensity = 300;
  place("@Hf(1) @Hd(300) ~B(1)");
  for (const Diagnostic& d : diagnostics.warnings()) ADD_FAILURE() << d.text();
  ASSERT_EQ(scene.organSurfaces.size(), 1u);
  EXPECT_EQ(scene.organSurfaces[0].kind, OrganSurfaceKind::Mesh);
  const std::vector<glm::dvec3> points = roots(HairSide::Front);
  const double expected = kDensity * area();
  std::printf("mesh: %zu hairs for %.0f expected (%+.2f%%)\n", points.size(), expected,
              100 * (static_cast<double>(points.size()) / expected - 1));
  EXPECT_NEAR(static_cast<double>(points.size()), expected, 0.02 * expected);

  // ρ on the surface: the smallest distance between two roots over that of the densest packing
  // of as many points on the area (Lagae & Dutré's r_max).
  const double rMax = std::sqrt(area() / (2 * std::sqrt(3.0) * static_cast<double>(points.size())));
  const std::vector<double> nearest = nearestDistances(points, 3 * rMax);
  const double rho = *std::min_element(nearest.begin(), nearest.end()) / (2 * rMax);
  std::printf("mesh: rho %.3f\n", rho);
  EXPECT_GE(rho, 0.65);

  // No seam along the atlas's cut (the meridian φ = 0: y ≈ 0, x > 0) and no crowding on the side
  // the atlas squeezes (y > 0 has a quarter of it): the mean spacing is the same everywhere.
  double seam = 0, squeezed = 0, stretched = 0;
  int seamCount = 0, squeezedCount = 0, stretchedCount = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3& p = points[i];
    if (std::abs(p.y) < 1.5 * rMax && p.x > 0) {
      seam += nearest[i];
      ++seamCount;
    } else if (p.y > 0) {
      squeezed += nearest[i];
      ++squeezedCount;
    } else {
      stretched += nearest[i];
      ++stretchedCount;
    }
  }
  ASSERT_GT(seamCount, 30);
  seam /= seamCount;
  squeezed /= squeezedCount;
  stretched /= stretchedCount;
  std::printf("mesh: mean spacing over 2 r_max: seam %.3f, squeezed %.3f, stretched %.3f; "
              "%d and %d roots on the two halves\n",
              seam / (2 * rMax), squeezed / (2 * rMax), stretched / (2 * rMax), squeezedCount,
              stretchedCount);
  EXPECT_NEAR(seam / stretched, 1, 0.06);
  EXPECT_NEAR(squeezed / stretched, 1, 0.03);
  EXPECT_NEAR(static_cast<double>(squeezedCount) / stretchedCount, 1, 0.05);

  // Every hair stands out of the sphere (the front is the outward side).
  for (const Hair& h : scene.organ<HairPart>().hairs) {
    ASSERT_GT(glm::dot(glm::dvec3(h.direction()), glm::dvec3(h.root)), 0);
  }
}

TEST_F(MeshHairsTest, TheBackIsCoveredToo) {
  place("@Hf(0) @Hb(1) @Hd(100, 0, 0, 2) ~B(1)");
  const std::vector<glm::dvec3> points = roots(HairSide::Back);
  const double expected = 100 * area();
  EXPECT_NEAR(static_cast<double>(points.size()), expected, 0.02 * expected);
  EXPECT_TRUE(roots(HairSide::Front).empty());
  for (const Hair& h : scene.organ<HairPart>().hairs) {
    ASSERT_LT(glm::dot(glm::dvec3(h.direction()), glm::dvec3(h.root)), 0);
  }
}

}  // namespace
}  // namespace hirsute
