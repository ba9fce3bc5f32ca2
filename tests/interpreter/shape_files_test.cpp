// The curve and surface files as the viewer's editors read, change and write them
// (function_curve.h CurveFile, surface.h SurfaceFile): every shipped and conformance file reads
// and writes back unchanged, and each edit changes exactly what it says.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/interpreter/surface.h"
#include "hirsute/lsys/function_curve.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";
const fs::path kConformance = fs::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "conformance";

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The files of these extensions under `folder`, sorted.
std::vector<fs::path> filesIn(const fs::path& folder, const std::vector<std::string>& extensions) {
  std::vector<fs::path> files;
  if (!fs::is_directory(folder)) return files;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder)) {
    const std::string extension = entry.path().extension().string();
    if (entry.is_regular_file() &&
        std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

CurveFile::Kind kindOf(const fs::path& file) {
  if (file.extension() == ".func") return CurveFile::Kind::Function;
  if (file.extension() == ".fset") return CurveFile::Kind::FunctionSet;
  return CurveFile::Kind::Contour;
}

// Reads every curve file, checks that it writes back byte for byte, then rewrites every row in
// the editors' spelling and checks that the values read back are the same.
void checkCurveRoundTrips(const fs::path& folder, int& count) {
  for (const fs::path& path : filesIn(folder, {".func", ".fset", ".con"})) {
    SCOPED_TRACE(path.string());
    const std::string original = readText(path);
    CurveFile file = CurveFile::parse(original, path.string(), kindOf(path));
    EXPECT_EQ(file.text(), original);
    const std::vector<CurveFileBlock> before = file.blocks();
    for (std::size_t b = 0; b < before.size(); ++b) {
      for (std::size_t r = 0; r < before[b].rows.size(); ++r) {
        ASSERT_EQ(file.setPoint(b, r, before[b].rows[r].point), "");
      }
    }
    const CurveFile reread = CurveFile::parse(file.text(), path.string(), kindOf(path));
    ASSERT_EQ(reread.blocks().size(), before.size());
    for (std::size_t b = 0; b < before.size(); ++b) {
      EXPECT_EQ(reread.blocks()[b].name, before[b].name);
      EXPECT_EQ(reread.blocks()[b].closed, before[b].closed);
      ASSERT_EQ(reread.blocks()[b].rows.size(), before[b].rows.size());
      for (std::size_t r = 0; r < before[b].rows.size(); ++r) {
        EXPECT_EQ(reread.blocks()[b].rows[r].point, before[b].rows[r].point);
        EXPECT_EQ(reread.blocks()[b].rows[r].multiplicity, before[b].rows[r].multiplicity);
      }
    }
    ++count;
  }
}

void checkSurfaceRoundTrips(const fs::path& folder, int& count) {
  for (const fs::path& path : filesIn(folder, {".s"})) {
    SCOPED_TRACE(path.string());
    const std::string original = readText(path);
    SurfaceFile file = SurfaceFile::parse(original, path.string());
    EXPECT_EQ(file.text(), original);
    const Surface before = file.surface();
    for (std::size_t p = 0; p < before.patches.size(); ++p) {
      for (std::size_t i = 0; i < 16; ++i) {
        ASSERT_EQ(file.setPoint(p, i, before.patches[p].points[i]), "");
      }
    }
    const Surface after = SurfaceFile::parse(file.text(), path.string()).surface();
    ASSERT_EQ(after.patches.size(), before.patches.size());
    for (std::size_t p = 0; p < before.patches.size(); ++p) {
      EXPECT_EQ(after.patches[p].points, before.patches[p].points);
      EXPECT_EQ(after.patches[p].name, before.patches[p].name);
      EXPECT_EQ(after.patches[p].neighbours, before.patches[p].neighbours);
    }
    EXPECT_EQ(after.contact, before.contact);
    EXPECT_EQ(after.fileSize, before.fileSize);
    ++count;
  }
}

TEST(ShapeFiles, ShippedModelsRoundTrip) {
  int count = 0;
  checkCurveRoundTrips(kModels, count);
  checkSurfaceRoundTrips(kModels, count);
  EXPECT_GE(count, 20);
}

TEST(ShapeFiles, ConformanceFilesRoundTrip) {
  if (!fs::is_directory(kConformance)) GTEST_SKIP() << "no conformance set at " << kConformance;
  int count = 0;
  checkCurveRoundTrips(kConformance, count);
  checkSurfaceRoundTrips(kConformance, count);
  EXPECT_GE(count, 50);
}

constexpr const char* kFunction =
    "fver 1 1\n"
    "name: width\n"
    "samples: 20\n"
    "flip: off\n"
    "points: 4\n"
    "0.000000 0.000000 1\n"
    "0.300000 0.500000 1\n"
    "0.600000 0.900000 1\n"
    "1.000000 1.000000 1\n";

TEST(ShapeFiles, FunctionPointMovesAddsAndRemoves) {
  CurveFile file = CurveFile::parse(kFunction, "width.func", CurveFile::Kind::Function);
  EXPECT_EQ(file.setPoint(0, 1, {0.25, 0.75, 0}), "");
  EXPECT_EQ(file.insertPoint(0, 2, {0.4, 0.8, 0}), "");
  EXPECT_EQ(file.text(),
            "fver 1 1\nname: width\nsamples: 20\nflip: off\npoints: 5\n"
            "0.000000 0.000000 1\n0.250000 0.750000 1\n0.400000 0.800000 1\n"
            "0.600000 0.900000 1\n1.000000 1.000000 1\n");
  // The curve evaluated is the one cpfg reads from the new text.
  EXPECT_NEAR(file.function(0, 0).evaluate(0.0), 0.0, 1e-2);
  EXPECT_GT(file.function(0, 0).evaluate(0.4),
            FunctionCurve::parse(kFunction, "w", 0).evaluate(0.4));
  EXPECT_EQ(file.removePoint(0, 2), "");
  EXPECT_EQ(file.blocks()[0].rows.size(), 4u);
  EXPECT_EQ(file.text(),
            "fver 1 1\nname: width\nsamples: 20\nflip: off\npoints: 4\n"
            "0.000000 0.000000 1\n0.250000 0.750000 1\n"
            "0.600000 0.900000 1\n1.000000 1.000000 1\n");
}

TEST(ShapeFiles, FunctionEditsThatCannotBeWrittenAreRefused) {
  CurveFile file = CurveFile::parse(kFunction, "width.func", CurveFile::Kind::Function);
  const std::string before = file.text();
  EXPECT_NE(file.setPoint(0, 1, {0.7, 0.5, 0}).find("between its neighbours"), std::string::npos);
  EXPECT_NE(file.setPoint(0, 0, {0.1, 0.5, 0}).find("keep their x"), std::string::npos);
  EXPECT_NE(file.removePoint(0, 3).find("first and last"), std::string::npos);
  // Down to 3 points reads no more: the reader's own message, at its line.
  EXPECT_EQ(file.removePoint(0, 1),
            "width.func:5: error: a function needs at least 4 control points (counting "
            "multiplicities), found 3");
  EXPECT_EQ(file.blocks()[0].rows.size(), 4u);
  EXPECT_EQ(before, file.text());
}

TEST(ShapeFiles, ContourCountsFollowTheRows) {
  const std::string text = readText(kModels / "hairy-leaf" / "leaf.con");
  CurveFile file = CurveFile::parse(text, "leaf.con", CurveFile::Kind::Contour);
  EXPECT_EQ(file.insertPoint(0, 3, {-0.1, -0.05, 0.0}), "");
  EXPECT_NE(file.text().find("points: 8 12\n"), std::string::npos);
  EXPECT_NE(file.text().find("\n-0.100000 -0.050000 0.000000 1\n0.000000 -0.060000"),
            std::string::npos);
  EXPECT_EQ(file.removePoint(0, 0), "");  // the first row's multiplicity 3 goes with it
  EXPECT_NE(file.text().find("points: 7 9\n"), std::string::npos);
  EXPECT_EQ(file.setPoint(0, 0, {-0.5, 0.25, 0.0}), "");
  EXPECT_EQ(file.contour().controlPoints()[0][1], 0.25);
}

TEST(ShapeFiles, SurfacePointMovesItsRowOnly) {
  const std::string text = readText(kModels / "herb" / "leaf.s");
  SurfaceFile file = SurfaceFile::parse(text, "leaf.s");
  EXPECT_EQ(file.setPoint(0, 5, glm::dvec3(-0.125, 0.3, 0.2)), "");
  EXPECT_EQ(file.surface().patches[0].points[5], glm::dvec3(-0.125, 0.3, 0.2));
  EXPECT_NE(
      file.text().find("\n0.00 0.00 0.00  -0.125 0.30 0.20  -0.10 0.70 0.15  0.00 1.00 0.15  \n"),
      std::string::npos);
  EXPECT_EQ(file.setPoint(1, 0, glm::dvec3(0)), "no such control point");
}

}  // namespace
}  // namespace hirsute
