// The feather stage on shipped models (models/feather-coat, models/feather-types): @Fe puts a
// feather in the turtle's frame, coats have density × area follicles, hexagonal follicles sit
// at the lattice's spacing, the same seed gives the same coat, coats are drawn bottom to top,
// and a missing feather type file is an error at its view-file line.
#include "hirsute/hairs/feathers/feather_stage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/hairs/feathers/feather_instances.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";

struct Built {
  ModelResources resources;
  Model model;
  Scene scene;
  Diagnostics diagnostics;
  FeatherStageReport report;
};

// Derived, interpreted and given its feathers as `hirsute render` does (cli/model_pipeline.cpp).
void build(Built& out, const fs::path& lsystem, const fs::path& view, std::uint64_t seed = 0) {
  out.resources = loadModelResources(view, {}, out.diagnostics);
  out.model = loadModel(lsystem, view, out.diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(out.model.program, out.diagnostics, &out.model.functions, out.model.folder,
                      printed);
  Derivation derivation(out.model.program, evaluator, out.diagnostics);
  installQueryPass(derivation, out.resources, out.diagnostics);
  derivation.run();
  interpret(derivation, out.resources, out.scene, out.diagnostics);
  FeatherStageOptions options;
  options.lsystemFile = lsystem.string();
  options.seed = seed;
  out.report = growFeathers(out.scene, out.resources, out.model.functions, options, out.diagnostics);
}

double coatArea(const Scene& scene) {
  double area = 0;
  for (const CylinderSegment& seg : scene.cylinderSegments)
    area += 0.5 * (seg.girthStart + seg.girthEnd) * seg.axisLength;
  return area;
}

TEST(FeatherStage, SingleFeatherStandsInTheTurtlesFrame) {
  Built b;
  build(b, kModels / "feather-types" / "feather-types.l", kModels / "feather-types" / "feather-types.v");
  ASSERT_EQ(b.report.types, 8u);
  ASSERT_EQ(b.scene.organ<FeatherPart>().feathers.size(), 8u);
  for (std::size_t i = 0; i < b.scene.organ<FeatherPart>().feathers.size(); ++i) {
    const Feather& f = b.scene.organ<FeatherPart>().feathers[i];
    EXPECT_EQ(f.types[0], i + 1);
    EXPECT_EQ(f.origin, FeatherOrigin::Single);
    // The turtle's initial heading (+y) and the row along x, GAP apart.
    EXPECT_NEAR(f.heading.y, 1.0, 1e-6);
    EXPECT_NEAR(std::abs(f.position.x), 5.5 * static_cast<double>(i), 1e-4);
    EXPECT_NEAR(glm::dot(f.heading, f.up), 0.0, 1e-6);
  }
  EXPECT_FLOAT_EQ(b.scene.organ<FeatherPart>().feathers[1].size, 0.42f);
  EXPECT_FALSE(b.scene.organ<FeatherPart>().bounds.empty());
}

TEST(FeatherStage, CoatFollicleCountFollowsDensityTimesArea) {
  for (const char* layout : {"random", "hexagonal"}) {
    Built b;
    build(b, kModels / "feather-coat" / (std::string(layout) + ".l"),
          kModels / "feather-coat" / (std::string(layout) + ".v"));
    const double expected = 4.9 * coatArea(b.scene);
    const double placed = static_cast<double>(b.report.coat);
    RecordProperty(std::string(layout) + "_feathers", static_cast<int>(b.report.coat));
    EXPECT_NEAR(placed, expected, 0.1 * expected) << layout << ": " << placed << " of " << expected;
    EXPECT_GE(b.report.coat, 56u) << layout;
    for (const Feather& f : b.scene.organ<FeatherPart>().feathers)
      EXPECT_EQ(f.origin, FeatherOrigin::Coat);
  }
}

// The box the outputs frame a coat by is its feathers' own: it holds every feather's geometry,
// and where one key type is four times the others' size, it does not grow to that type's box
// around feathers that take little of it (models/feather-coat with grey.fea made large).
TEST(FeatherStage, ACoatIsFramedByItsFeathers) {
  const fs::path folder = fs::temp_directory_path() / "hirsute_coat_bounds_test";
  fs::remove_all(folder);
  fs::copy(kModels / "feather-coat", folder);
  {
    std::ifstream in(folder / "grey.fea");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string from = "rachis length:          1.3";
    ASSERT_NE(text.find(from), std::string::npos);
    text.replace(text.find(from), from.size(), "rachis length:          5.2");
    std::ofstream(folder / "grey.fea") << text;
  }
  for (const bool large : {false, true}) {
    const fs::path models = large ? folder : kModels / "feather-coat";
    Built b;
    build(b, models / "random.l", models / "random.v");
    const FeatherPart& part = b.scene.organ<FeatherPart>();
    ASSERT_GT(part.feathers.size(), 50u);
    Bounds real;
    for (const Feather& feather : part.feathers) {
      const FeatherGeometry geometry = featherGeometryOf(b.scene, feather, FeatherDetail{3, 3, 3});
      const glm::mat4 toWorld = featherToWorld(feather);
      forEachFeatherPart(geometry, [&](const FeatherGeometry& piece, bool) {
        for (const glm::vec3& p : piece.shaft.positions) real.add(glm::vec3(toWorld * glm::vec4(p, 1)));
        for (const glm::vec3& p : piece.vertices.positions) real.add(glm::vec3(toWorld * glm::vec4(p, 1)));
      });
    }
    const float slack = 0.01f * real.diagonal();
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_LE(part.bounds.min[axis], real.min[axis] + slack) << "large " << large;
      EXPECT_GE(part.bounds.max[axis], real.max[axis] - slack) << "large " << large;
    }
    RecordProperty(large ? "large_box_over_real" : "box_over_real",
                   std::to_string(part.bounds.diagonal() / real.diagonal()));
    EXPECT_LT(part.bounds.diagonal(), 1.15f * real.diagonal()) << "large " << large;
  }
  fs::remove_all(folder);
}

TEST(FeatherStage, HexagonalFolliclesSitAtTheLatticeSpacing) {
  Built b;
  build(b, kModels / "feather-coat" / "hexagonal.l", kModels / "feather-coat" / "hexagonal.v");
  const std::vector<Feather>& f = b.scene.organ<FeatherPart>().feathers;
  ASSERT_GE(f.size(), 32u);
  // Nearest-neighbour distances on the flat patch: a regular lattice of density ρ has spacing
  // sqrt(2 / (√3 ρ)); the tile is stretched to a whole number around the contour, a few %.
  const double spacing = std::sqrt(2.0 / (std::sqrt(3.0) * 4.9));
  double smallest = std::numeric_limits<double>::max(), largest = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    double nearest = std::numeric_limits<double>::max();
    for (std::size_t j = 0; j < f.size(); ++j) {
      if (i != j) nearest = std::min<double>(nearest, glm::distance(f[i].position, f[j].position));
    }
    smallest = std::min(smallest, nearest);
    largest = std::max(largest, nearest);
  }
  EXPECT_GT(smallest, 0.8 * spacing);
  EXPECT_LT(largest, 1.25 * spacing);
}

TEST(FeatherStage, SameSeedSameCoatOtherSeedOtherCoat) {
  Built a, b, c;
  const fs::path l = kModels / "feather-coat" / "random.l", v = kModels / "feather-coat" / "random.v";
  build(a, l, v, 7);
  build(b, l, v, 7);
  build(c, l, v, 8);
  ASSERT_EQ(a.scene.organ<FeatherPart>().feathers.size(),
            b.scene.organ<FeatherPart>().feathers.size());
  for (std::size_t i = 0; i < a.scene.organ<FeatherPart>().feathers.size(); ++i) {
    EXPECT_EQ(a.scene.organ<FeatherPart>().feathers[i].position,
              b.scene.organ<FeatherPart>().feathers[i].position);
    EXPECT_EQ(a.scene.organ<FeatherPart>().feathers[i].across,
              b.scene.organ<FeatherPart>().feathers[i].across);
  }
  bool differs =
      a.scene.organ<FeatherPart>().feathers.size() != c.scene.organ<FeatherPart>().feathers.size();
  for (std::size_t i = 0; !differs && i < a.scene.organ<FeatherPart>().feathers.size(); ++i)
    differs = a.scene.organ<FeatherPart>().feathers[i].size !=
                  c.scene.organ<FeatherPart>().feathers[i].size ||
              a.scene.organ<FeatherPart>().feathers[i].position !=
                  c.scene.organ<FeatherPart>().feathers[i].position;
  EXPECT_TRUE(differs);
}

TEST(FeatherStage, CoatIsDrawnFromItsBottomFeatherToItsTop) {
  Built b;
  build(b, kModels / "feather-coat" / "random.l", kModels / "feather-coat" / "random.v");
  // The feathers point along the patch: those further along lie under the ones before them and
  // come first.
  const std::vector<Feather>& f = b.scene.organ<FeatherPart>().feathers;
  ASSERT_GE(f.size(), 2u);
  ASSERT_EQ(b.scene.cylinderSegments.size(), 1u);
  const CylinderSegment& patch = b.scene.cylinderSegments.front();
  const glm::vec3 along = glm::normalize(patch.end.position - patch.start.position);
  EXPECT_GT(glm::dot(f.front().heading, along), 0.9f);
  for (std::size_t i = 1; i < f.size(); ++i)
    EXPECT_GE(glm::dot(f[i - 1].position - f[i].position, along), -1e-4f) << i;
}

TEST(FeatherStage, KeyFeathersBlendBilinearly) {
  Built b;
  build(b, kModels / "feather-coat" / "random.l", kModels / "feather-coat" / "random.v");
  float lowest = 1, highest = 0;
  for (const Feather& f : b.scene.organ<FeatherPart>().feathers) {
    EXPECT_EQ(f.types, (std::array<std::uint16_t, 4>{1, 2, 3, 4}));
    EXPECT_FLOAT_EQ(f.across[0], f.across[1]);  // both key feathers blend linearly across
    lowest = std::min(lowest, f.along);
    highest = std::max(highest, f.along);
  }
  EXPECT_LT(lowest, 0.2f);
  EXPECT_GT(highest, 0.8f);
}

// A unit sphere of 30 × 60 quads in `folder` (ball.obj) whose atlas's v grows from its south
// pole to its north one, its vertex colours' red from 0 at the south pole to 1 at the north
// one; with brown.fea and grey.fea, the view file `view` and the axiom `axiom`.
fs::path writeBall(const std::string& name, const std::string& view, const std::string& axiom) {
  const fs::path folder = fs::temp_directory_path() / name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  fs::copy(kModels / "feather-coat" / "brown.fea", folder / "brown.fea");
  fs::copy(kModels / "feather-coat" / "grey.fea", folder / "grey.fea");
  std::ofstream obj(folder / "ball.obj");
  constexpr int kRings = 30, kSides = 60;
  const double pi = std::acos(-1.0);
  for (int i = 0; i <= kRings; ++i) {
    for (int j = 0; j <= kSides; ++j) {
      const double theta = pi * i / kRings, phi = 2 * pi * j / kSides;
      obj << "v " << std::sin(theta) * std::cos(phi) << ' ' << std::sin(theta) * std::sin(phi)
          << ' ' << std::cos(theta) << ' ' << (1 + std::cos(theta)) / 2 << " 0.5 0.5\nvt "
          << static_cast<double>(j) / kSides << ' ' << 1 - static_cast<double>(i) / kRings << '\n';
    }
  }
  for (int i = 0; i < kRings; ++i) {
    for (int j = 0; j < kSides; ++j) {
      const int a = i * (kSides + 1) + j + 1, b = a + 1, c = a + kSides + 1, d = c + 1;
      obj << "f " << a << '/' << a << ' ' << c << '/' << c << ' ' << b << '/' << b << '\n';
      obj << "f " << b << '/' << b << ' ' << c << '/' << c << ' ' << d << '/' << d << '\n';
    }
  }
  std::ofstream(folder / "ball.v") << "surface: B ball.obj 1\nfeather: brown.fea\nfeather: grey.fea\n"
                                   << view;
  std::ofstream(folder / "ball.l") << "Lsystem: 1\nderivation length: 0\nAxiom: " << axiom
                                   << "\nendlsystem\n";
  return folder;
}

double meshArea(const Scene& scene) {
  double area = 0;
  const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(scene.organSurfaces.at(0).mesh)];
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    area += 0.5 * glm::length(glm::cross(mesh.positions[mesh.indices[i + 1]] - mesh.positions[mesh.indices[i]],
                                         mesh.positions[mesh.indices[i + 2]] - mesh.positions[mesh.indices[i]]));
  }
  return area;
}

// The largest angle, in degrees, between a coat feather's rachis laid on the surface and the
// flow `along(n)` at its root (n the outward normal), away from where the flow meets the normal.
template <class Flow>
double worstDeviation(const std::vector<Feather>& feathers, Flow along) {
  double worst = 0;
  for (const Feather& f : feathers) {
    const glm::vec3 n = glm::normalize(f.position);
    const glm::vec3 flow = along(n);
    const glm::vec3 tangent = flow - glm::dot(flow, n) * n;
    if (glm::length(tangent) < 0.45f) continue;  // within 27 degrees of a pole of the flow
    const glm::vec3 rachis = glm::normalize(f.heading - glm::dot(f.heading, n) * n);
    const double off = std::acos(std::min(1.0f, glm::dot(rachis, glm::normalize(tangent))));
    worst = std::max(worst, off * 180 / 3.14159265);
  }
  return worst;
}

// A coat on a mesh surface (docs/meshes.md). Follicles cover its area at the density (the count
// is density × area exactly), every feather stands on the outside, lifted by the lie angle, and
// lies along the flow: the tangent part of its rachis points north along its meridian (the
// file's north, which ~B draws along the turtle's up vector, world −z); with `mesh flow: B 1 0 0`
// it points along the file's x instead (the turtle's left, world −x).
TEST(FeatherStage, ACoatOnAMeshLiesAlongItsFlow) {
  const fs::path folder = writeBall("hirsute_mesh_coat_test", "", "@Ff(1) @Fd(40) @Fl(10) @Fk(1) ~B(1)");
  Built b;
  build(b, folder / "ball.l", folder / "ball.v");
  ASSERT_EQ(b.scene.organSurfaces.size(), 1u);
  const std::vector<Feather>& feathers = b.scene.organ<FeatherPart>().feathers;
  const double area = meshArea(b.scene);
  EXPECT_NEAR(static_cast<double>(feathers.size()), 40 * area, 0.02 * 40 * area);
  const float lie = std::sin(10.0f * 3.14159265f / 180.0f);
  for (const Feather& f : feathers) {
    EXPECT_EQ(f.origin, FeatherOrigin::Coat);
    const glm::vec3 n = glm::normalize(f.position);
    EXPECT_NEAR(glm::dot(f.heading, n), lie, 0.03f);
    EXPECT_GT(glm::dot(f.up, n), 0.95f);
  }
  // Within the tessellation: the rings are 6 degrees apart.
  EXPECT_LT(worstDeviation(feathers, [](const glm::vec3&) { return glm::vec3(0, 0, -1); }), 6.0)
      << "degrees off the flow";

  std::ofstream(folder / "ball.v", std::ios::app) << "mesh flow: B 1 0 0\n";
  Built across;
  build(across, folder / "ball.l", folder / "ball.v");
  EXPECT_LT(worstDeviation(across.scene.organ<FeatherPart>().feathers,
                           [](const glm::vec3&) { return glm::vec3(-1, 0, 0); }),
            6.0)
      << "degrees off the view file's flow";
  fs::remove_all(folder);
}

// On a mesh with vertex colours, @Fk(k1, k2) without a function blends k1 into k2 by the colours'
// red: here from brown at the file's south pole to grey at its north one.
TEST(FeatherStage, AMeshsVertexColoursChooseItsKeyFeathers) {
  const fs::path folder = writeBall("hirsute_mesh_keys_test", "", "@Ff(1) @Fd(20) @Fk(1, 2) ~B(1)");
  Built b;
  build(b, folder / "ball.l", folder / "ball.v");
  const std::vector<Feather>& feathers = b.scene.organ<FeatherPart>().feathers;
  ASSERT_GT(feathers.size(), 100u);
  double worst = 0;
  for (const Feather& f : feathers) {
    EXPECT_EQ(f.types[0], 1);
    EXPECT_EQ(f.types[1], 2);
    // The file's z is drawn along the turtle's up vector, world −z.
    const double red = (1 - glm::normalize(f.position).z) / 2;
    worst = std::max(worst, std::abs(f.across[0] - red));
  }
  // The colours are linear over each triangle, the sphere's z is not: within a ring's height.
  EXPECT_LT(worst, 0.02);
  fs::remove_all(folder);
}

}  // namespace
}  // namespace hirsute
