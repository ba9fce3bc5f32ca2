// Colour maps (.map), material files (.mat), banks, and the default palette.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <tuple>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/core/diagnostic.h"
#include "support/diagnostic_of.h"

namespace hirsute {
namespace {

const std::filesystem::path kFixtures =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "interpreter";
const std::filesystem::path kConformance =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "conformance";

void expectColor(const glm::vec3& actual, float r, float g, float b) {
  EXPECT_NEAR(actual.r, r, 1e-6f);
  EXPECT_NEAR(actual.g, g, 1e-6f);
  EXPECT_NEAR(actual.b, b, 1e-6f);
}

using testing::diagnosticOf;

TEST(ColorFilesTest, ColorMapColoursAreAmbientAndDiffuse) {
  // ramp.map: colour i is (i, 255 − i, i/2).
  const std::vector<Material> map = loadColorMap(kFixtures / "ramp.map");
  ASSERT_EQ(map.size(), 256u);
  expectColor(map[0].diffuse, 0, 1, 0);
  expectColor(map[200].ambient, 200 / 255.0f, 55 / 255.0f, 100 / 255.0f);
  expectColor(map[200].diffuse, 200 / 255.0f, 55 / 255.0f, 100 / 255.0f);
  expectColor(map[200].specular, 0, 0, 0);
  expectColor(map[200].emission, 0, 0, 0);
  EXPECT_EQ(map[200].transparency, 0.0f);
}

TEST(ColorFilesTest, ColorMapMustHave768Bytes) {
  const Diagnostic d = diagnosticOf([] { loadColorMap(kFixtures / "short.map"); });
  EXPECT_EQ(d.where.fileName(), (kFixtures / "short.map").string());
  EXPECT_NE(d.message.find("this file has 767"), std::string::npos) << d.message;
  EXPECT_NE(diagnosticOf([] { loadColorMap(kFixtures / "none.map"); }).message.find("cannot open"),
            std::string::npos);
}

TEST(ColorFilesTest, MaterialRecordsGoToTheirIndex) {
  const std::vector<Material> materials = loadMaterials(kFixtures / "three.mat");
  ASSERT_EQ(materials.size(), 256u);
  // Record 0: emission is the background colour in material mode.
  expectColor(materials[0].diffuse, 0.8f, 0.8f, 0.8f);
  expectColor(materials[0].emission, 147 / 255.0f, 229 / 255.0f, 126 / 255.0f);
  // Index 5 appears twice; the later record wins.
  const Material& five = materials[5];
  EXPECT_NEAR(five.transparency, 0.6f, 1e-6f);
  expectColor(five.ambient, 58 / 255.0f, 39 / 255.0f, 63 / 255.0f);
  expectColor(five.diffuse, 1, 128 / 255.0f, 0);
  expectColor(five.specular, 0.2f, 0.2f, 0.2f);
  EXPECT_EQ(five.shininess, 128.0f);  // 200 is beyond OpenGL's 128
  const Material& last = materials[200];
  expectColor(last.emission, 70 / 255.0f, 80 / 255.0f, 90 / 255.0f);
  expectColor(last.specular, 100 / 255.0f, 110 / 255.0f, 120 / 255.0f);
  EXPECT_EQ(last.shininess, 64.0f);
  // Indices without a record keep OpenGL's default material.
  expectColor(materials[1].ambient, 0.2f, 0.2f, 0.2f);
  expectColor(materials[1].diffuse, 0.8f, 0.8f, 0.8f);
}

TEST(ColorFilesTest, MaterialFileMustBeWholeRecords) {
  const Diagnostic d = diagnosticOf([] { loadMaterials(kFixtures / "cut.mat"); });
  EXPECT_NE(d.message.find("15-byte records"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("16 bytes"), std::string::npos) << d.message;
}

TEST(ColorFilesTest, DefaultPaletteIsDistinctAndGreenAt128) {
  const std::vector<Material> palette = defaultPalette();
  ASSERT_EQ(palette.size(), 256u);
  expectColor(palette[0].diffuse, 0, 0, 0);  // background
  expectColor(palette[1].diffuse, 1, 0, 0);
  expectColor(palette[2].diffuse, 0, 1, 0);
  expectColor(palette[7].diffuse, 1, 1, 1);
  const glm::vec3 initial = palette[128].diffuse;  // cpfg's default initial colour
  EXPECT_GT(initial.g, initial.r + 0.3f);
  EXPECT_GT(initial.g, initial.b + 0.3f);
  std::set<std::tuple<float, float, float>> distinct;
  for (const Material& m : palette) {
    EXPECT_EQ(m.ambient, m.diffuse);
    distinct.insert({m.diffuse.r, m.diffuse.g, m.diffuse.b});
  }
  EXPECT_EQ(distinct.size(), 256u);
}

TEST(ColorFilesTest, BanksFillTheirOwn256Indices) {
  Diagnostics diagnostics;
  ColorFiles colors;
  colors.colormaps.push_back({2, kFixtures / "ramp.map"});
  const ModelResources resources = loadModelResources(std::nullopt, colors, diagnostics);
  // Bank 2 alone: bank 1 keeps the default palette (cpfg-Sedge-female gives only -m2).
  ASSERT_EQ(resources.palette.size(), 512u);
  EXPECT_FALSE(resources.materialMode);
  EXPECT_EQ(resources.palette[1].diffuse, defaultPalette()[1].diffuse);
  expectColor(resources.palette[256 + 10].diffuse, 10 / 255.0f, 245 / 255.0f, 5 / 255.0f);

  ColorFiles materials;
  materials.materials.push_back({1, kFixtures / "three.mat"});
  const ModelResources lit = loadModelResources(std::nullopt, materials, diagnostics);
  EXPECT_TRUE(lit.materialMode);
  ASSERT_EQ(lit.palette.size(), 256u);
  EXPECT_EQ(lit.palette[200].shininess, 64.0f);
  EXPECT_TRUE(diagnostics.warnings().empty());

  ColorFiles none;
  EXPECT_EQ(loadModelResources(std::nullopt, none, diagnostics).palette.size(), 256u);

  ColorFiles tooHigh;
  tooHigh.colormaps.push_back({13, kFixtures / "ramp.map"});
  const Diagnostic d =
      diagnosticOf([&] { loadModelResources(std::nullopt, tooHigh, diagnostics); });
  EXPECT_NE(d.message.find("colour bank 13 is outside 1 to 12"), std::string::npos) << d.message;
}

TEST(ColorFilesTest, ConformanceMaterialsMatchCpfgsRayshadeOutput) {
  if (!std::filesystem::is_directory(kConformance)) {
    GTEST_SKIP() << "no conformance set at " << kConformance;
  }
  // tools-LeafRandom's expected.ray: `surface s257 ambient 0.027451 0.0862745 0 diffuse
  // 0.266667 0.576471 0.164706 … specpow 65` is material 1.
  const std::vector<Material> leaf =
      loadMaterials(kConformance / "tools-LeafRandom" / "material.mat");
  expectColor(leaf[1].ambient, 0.027451f, 0.0862745f, 0);
  expectColor(leaf[1].diffuse, 0.266667f, 0.576471f, 0.164706f);
  EXPECT_EQ(leaf[1].shininess, 65.0f);
  // cpfg-Lilac's material 1: `transp 0.6`.
  const std::vector<Material> lilac = loadMaterials(kConformance / "cpfg-Lilac" / "materials.mat");
  EXPECT_NEAR(lilac[1].transparency, 0.6f, 1e-6f);

  int loaded = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kConformance)) {
    const std::string extension = entry.path().extension().string();
    SCOPED_TRACE(entry.path().string());
    if (extension == ".map" || extension == ".map2") {
      EXPECT_EQ(loadColorMap(entry.path()).size(), 256u);
      ++loaded;
    } else if (extension == ".mat") {
      EXPECT_EQ(loadMaterials(entry.path()).size(), 256u);
      ++loaded;
    }
  }
  EXPECT_EQ(loaded, 30 + 18);
}

}  // namespace
}  // namespace hirsute
