// Bicubic surfaces (.s, bezieredit's format) and their `surface:` lines in the view file.
#include "hirsute/interpreter/surface.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/core/diagnostic.h"

namespace hirsute {
namespace {

const std::filesystem::path kFixtures =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "interpreter";
const std::filesystem::path kConformance =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "conformance";

Diagnostic errorLoading(const std::string& name) {
  try {
    loadSurface((kFixtures / name).string());
  } catch (const DiagnosticError& error) {
    return error.diagnostic();
  }
  ADD_FAILURE() << "expected a DiagnosticError";
  return Diagnostic{};
}

TEST(SurfaceTest, ReadsTheHeaderAndEveryPatch) {
  const Surface surface = loadSurface((kFixtures / "two_patches.s").string());
  EXPECT_EQ(surface.boundsMin, glm::dvec3(-1, 0, -0.5));
  EXPECT_EQ(surface.boundsMax, glm::dvec3(1, 2, 0.5));
  EXPECT_EQ(surface.contact, glm::dvec3(0, -0.5, 0));
  EXPECT_EQ(surface.endPoint, glm::dvec3(0, 2, 0.25));
  EXPECT_EQ(surface.heading, glm::dvec3(0, 1, 0));
  EXPECT_EQ(surface.up, glm::dvec3(0, 0, 1));
  EXPECT_EQ(surface.fileSize, 2.0);
  // No PRECISION line: cpfg's 5 × 5 quads per patch.
  EXPECT_EQ(surface.sPrecision, kDefaultSurfacePrecision);
  EXPECT_EQ(surface.tPrecision, kDefaultSurfacePrecision);

  ASSERT_EQ(surface.patches.size(), 2u);
  const BezierPatch& lower = surface.patches[0];
  EXPECT_EQ(lower.name, "lower");
  EXPECT_EQ(lower.topColor, 3);
  EXPECT_EQ(lower.topDiffuse, 0.5);
  EXPECT_EQ(lower.bottomColor, 260);  // a colour of bank 2
  EXPECT_EQ(lower.bottomDiffuse, 0.25);
  // AL A AR L R BL B BR; `~` is none.
  const std::array<std::string, 8> lowerNeighbours = {"", "upper", "", "", "", "", "", ""};
  EXPECT_EQ(lower.neighbours, lowerNeighbours);
  EXPECT_EQ(surface.patches[1].neighbours[6], "lower");
  // Row 2, column 3 of the control net.
  EXPECT_EQ(lower.points[1 * 4 + 2], glm::dvec3(0.33, 0.33, 0.2));
  EXPECT_EQ(surface.patches[1].points[15], glm::dvec3(0.5, 2.0, 0.0));
}

TEST(SurfaceTest, ReadsPrecisionAndLabelsWithoutSpaces) {
  // stedit's `X:0.5` and tab-separated numbers.
  const Surface surface = loadSurface((kFixtures / "precision.s").string());
  EXPECT_EQ(surface.sPrecision, 3);
  EXPECT_EQ(surface.tPrecision, 7);
  EXPECT_EQ(surface.contact, glm::dvec3(0.5, 0, 0));
  EXPECT_EQ(surface.up, glm::dvec3(0, 0, -1));
  ASSERT_EQ(surface.patches.size(), 1u);
  EXPECT_EQ(surface.patches[0].points[7], glm::dvec3(3, 1, 0));
}

TEST(SurfaceTest, BrokenFileIsReportedAtItsLine) {
  Diagnostic d = errorLoading("short_row.s");
  EXPECT_EQ(d.where.fileName(), (kFixtures / "short_row.s").string());
  EXPECT_EQ(d.where.line, 14);
  EXPECT_NE(d.message.find("row 3 of patch 'lower'"), std::string::npos) << d.message;
  d = errorLoading("no_size.s");
  EXPECT_EQ(d.where.line, 6);
  EXPECT_NE(d.message.find("SIZE: s"), std::string::npos) << d.message;
  d = errorLoading("nowhere.s");
  EXPECT_NE(d.message.find("cannot open"), std::string::npos) << d.message;
}

TEST(SurfaceTest, ViewLineGivesSizePrecisionAndTexture) {
  Diagnostics diagnostics;
  const ModelResources resources =
      loadModelResources(kFixtures / "model.v", ColorFiles{}, diagnostics);
  ASSERT_EQ(resources.surfaces.count('l'), 1u);
  const Surface& leaf = resources.surfaces.at('l');
  EXPECT_EQ(leaf.id, 'l');
  EXPECT_EQ(leaf.viewSize, 2.0);
  EXPECT_EQ(leaf.sPrecision, 8);
  EXPECT_EQ(leaf.tPrecision, 4);
  EXPECT_EQ(leaf.texture, 1);
  // Without precisions on its line the file's PRECISION stays.
  const Surface& p = resources.surfaces.at('p');
  EXPECT_EQ(p.viewSize, 1.5);
  EXPECT_EQ(p.sPrecision, 3);
  EXPECT_EQ(p.tPrecision, 7);
  // A missing file is a warning (cpfg-Sedge names a bract.s that is not there); ~m draws nothing.
  EXPECT_EQ(resources.surfaces.count('m'), 0u);
  bool warned = false;
  for (const Diagnostic& w : diagnostics.warnings()) {
    if (w.message.find("missing.s") != std::string::npos) {
      warned = true;
      EXPECT_EQ(w.where.line, 10);
      EXPECT_EQ(w.where.column, 12);
    }
  }
  EXPECT_TRUE(warned);
}

TEST(SurfaceTest, BrokenSurfaceIsReportedAtTheViewLine) {
  Diagnostics diagnostics;
  try {
    loadModelResources(kFixtures / "broken_surface.v", ColorFiles{}, diagnostics);
    ADD_FAILURE() << "expected a DiagnosticError";
  } catch (const DiagnosticError& error) {
    const Diagnostic& d = error.diagnostic();
    EXPECT_EQ(d.where.fileName(), (kFixtures / "broken_surface.v").string());
    EXPECT_EQ(d.where.line, 3);
    EXPECT_EQ(d.where.column, 12);
    EXPECT_NE(d.message.find("surface file 'short_row.s' is broken"), std::string::npos)
        << d.message;
    EXPECT_NE(d.message.find("short_row.s:14"), std::string::npos) << d.message;
  }
}

TEST(SurfaceTest, EveryConformanceSurfaceLoads) {
  if (!std::filesystem::is_directory(kConformance)) {
    GTEST_SKIP() << "no conformance set at " << kConformance;
  }
  int loaded = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kConformance)) {
    if (entry.path().extension() != ".s") continue;
    SCOPED_TRACE(entry.path().string());
    const Surface surface = loadSurface(entry.path().string());
    // Six header lines, then nine lines per patch.
    std::ifstream in(entry.path());
    int lines = 0;
    for (std::string line; std::getline(in, line);) {
      if (line.find_first_not_of(" \t\r") != std::string::npos) ++lines;
    }
    EXPECT_EQ(static_cast<int>(surface.patches.size()), (lines - 6) / 9);
    EXPECT_GT(surface.fileSize, 0.0);
    ++loaded;
  }
  EXPECT_EQ(loaded, 24);
  const Surface nmale = loadSurface((kConformance / "cpfg-Sedge" / "nmale.s").string());
  ASSERT_EQ(nmale.patches.size(), 4u);
  EXPECT_EQ(nmale.patches[0].topColor, 426);
  EXPECT_EQ(nmale.patches[0].neighbours[6], "Patch_2");
}

}  // namespace
}  // namespace hirsute
