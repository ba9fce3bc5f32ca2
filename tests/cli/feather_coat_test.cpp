// Dense feather coats (docs/feathers.md, "Dense coats"): the GL render thins the barbs of
// feathers too small in the picture to show them all, and the picture stays that of every barb;
// the POV-Ray export declares each template once and places the feathers as its instances, and
// POV-Ray's picture stays that of every feather built whole; a coat of thousands of feathers has
// a few hundred templates. The coats are models/bench/feather-coat.l at lower densities, run end
// to end through the program.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "hirsute/core/program_path.h"
#include "hirsute/viewer/view/png_image.h"
#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kBench = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "bench";

class FeatherCoat : public ::testing::Test {
 protected:
  // models/bench/feather-coat.l with `DENSITY` follicles a unit area, and its files, in the
  // test's folder; returns the model.
  fs::path coat(const std::string& density) const {
    for (const char* file :
         {"feather-coat.v", "strip.con", "brown.fea", "grey.fea", "green.fea", "blue.fea"})
      fs::copy_file(kBench / file, folder_.path() / file, fs::copy_options::overwrite_existing);
    const std::string text = readText(kBench / "feather-coat.l");
    const std::string model = std::regex_replace(text, std::regex("#define DENSITY [0-9.]+"),
                                                 "#define DENSITY " + density);
    EXPECT_NE(model.find("#define DENSITY " + density + "\n"), std::string::npos);
    const fs::path file = folder_.path() / ("coat-" + density + ".l");
    std::ofstream(file, std::ios::binary) << model;
    return file;
  }
  fs::path view() const { return folder_.path() / "feather-coat.v"; }
  fs::path path(const std::string& name) const { return folder_.path() / name; }

  TemporaryFolder folder_;
};

struct Difference {
  double meanAbsolute = 0;    // per channel, in 1/255, over the whole picture
  double meanColour[3] = {};  // of `a`'s coat (pixels off the background) minus `b`'s there
};

// How two pictures of one size differ; the background is the top-left pixel's colour.
Difference difference(const hirsute::RgbaImage& a, const hirsute::RgbaImage& b) {
  Difference d;
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  if (a.rgba.size() != b.rgba.size() || a.rgba.empty()) return d;
  const std::size_t pixels = a.rgba.size() / 4;
  double sumA[3] = {}, sumB[3] = {}, absolute = 0;
  std::size_t coat = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    bool background = true;
    for (int c = 0; c < 3; ++c) {
      absolute += std::abs(int(a.rgba[4 * p + c]) - int(b.rgba[4 * p + c]));
      background = background && a.rgba[4 * p + c] == a.rgba[c];
    }
    if (background) continue;
    ++coat;
    for (int c = 0; c < 3; ++c) {
      sumA[c] += a.rgba[4 * p + c];
      sumB[c] += b.rgba[4 * p + c];
    }
  }
  d.meanAbsolute = absolute / (3.0 * static_cast<double>(pixels));
  EXPECT_GT(coat, pixels / 4) << "the coat fills too little of the picture";
  for (int c = 0; c < 3; ++c)
    d.meanColour[c] = coat > 0 ? (sumA[c] - sumB[c]) / static_cast<double>(coat) : 0;
  return d;
}

// About 1 000 feathers, each some 25 pixels long at 640x480: the thinned coat (8 barbs a vane
// of 52, strips widened) against every barb (--full-feathers). Measured: the coat's mean colour
// within 0.8 levels in every channel; a mean absolute difference of 10 levels, where feathers'
// serrated edges move a pixel against the red patch between them (on the 10 000-feather coat at
// 800x600, 1.2).
TEST_F(FeatherCoat, AThinnedCoatLooksLikeEveryBarb) {
  const fs::path model = coat("80.5");
  // The groom as it grew (--no-deintersect): a lifted feather is built whole, in the world,
  // where these compare the thinned and instanced coat with every barb.
  const std::vector<std::string> render{"render", model.string(), view().string(),
                                        "--size", "640x480",      "--no-deintersect"};
  std::vector<std::string> thinned = render, full = render;
  thinned.insert(thinned.end(), {"-o", path("thinned.png").string()});
  full.insert(full.end(), {"-o", path("full.png").string(), "--full-feathers"});
  const RunResult a = runHirsute(thinned);
  ASSERT_EQ(a.exitCode, 0) << a.err;
  const RunResult b = runHirsute(full);
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const Difference d =
      difference(hirsute::readPng(path("thinned.png")), hirsute::readPng(path("full.png")));
  EXPECT_LT(d.meanAbsolute, 14.0);
  for (double channel : d.meanColour) EXPECT_LT(std::abs(channel), 3.0);
}

// About 250 feathers through POV-Ray at 160x120: each template declared once and placed by its
// feathers, its thinned barbs opaque ribbons, against every feather built whole in two meshes of
// transparent strips (--full-feathers). Measured: mean absolute difference 1.8 levels, the coat's
// mean colour within 1.5.
TEST_F(FeatherCoat, InstancedPovRayLooksLikeWholeFeathers) {
  if (hirsute::findOnPath("povray").empty()) GTEST_SKIP() << "povray is not on the PATH";
  const fs::path model = coat("20");
  auto exportRendered = [&](const std::string& name, bool full) {
    std::vector<std::string> arguments{
        "export",          model.string(), view().string(), "--pov", path(name + ".pov").string(),
        "--width",         "160",          "--height",      "120",   "--render",
        "--no-deintersect"};
    if (full) arguments.push_back("--full-feathers");
    const RunResult run = runHirsute(arguments);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return readText(path(name + ".pov"));
  };
  const std::string instanced = exportRendered("instanced", false);
  const std::string whole = exportRendered("whole", true);
  EXPECT_NE(instanced.find("#declare Feather0=mesh2{"), std::string::npos);
  EXPECT_NE(instanced.find("object{Feather0 matrix<"), std::string::npos);
  EXPECT_EQ(whole.find("#declare Feather"), std::string::npos);
  const Difference d =
      difference(hirsute::readPng(path("instanced.png")), hirsute::readPng(path("whole.png")));
  EXPECT_LT(d.meanAbsolute, 4.0);
  for (double channel : d.meanColour) EXPECT_LT(std::abs(channel), 3.0);
}

// The benchmark coat of about 10 000 feathers, as it grew (--no-deintersect: a feather the
// shingling lifts is a template of its own), exports as about a thousand templates (33 × 33
// blends), each feather an object of one.
TEST_F(FeatherCoat, TheBenchmarkCoatHasFarFewerTemplatesThanFeathers) {
  const fs::path model = coat("805");
  const RunResult run =
      runHirsute({"export", model.string(), view().string(), "--pov", path("coat.pov").string(),
                  "--width", "640", "--height", "480", "--no-deintersect"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  std::ifstream in(path("coat.pov"));
  std::size_t templates = 0, objects = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#declare Feather", 0) == 0) ++templates;
    if (line.rfind("object{Feather", 0) == 0) ++objects;
  }
  EXPECT_GT(objects, 9000u);
  EXPECT_GT(templates, 0u);
  EXPECT_LT(templates * 8, objects) << templates << " templates for " << objects << " feathers";
}

}  // namespace
