// Everything the view file names, loaded together: texture images (PNG through stb_image, SGI
// .rgb decoded by Hirsute), contours, and how missing or broken files are reported.
#include "hirsute/interpreter/model_resources.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include "hirsute/interpreter/texture_image.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/model.h"
#include "support/diagnostic_of.h"

namespace hirsute {
namespace {

const std::filesystem::path kFixtures =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "interpreter";
const std::filesystem::path kConformance =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "conformance";

std::array<int, 4> pixel(const Texture& texture, int x, int y) {
  const std::size_t at = 4 * (static_cast<std::size_t>(y) * texture.width + x);
  return {texture.rgba[at], texture.rgba[at + 1], texture.rgba[at + 2], texture.rgba[at + 3]};
}

using testing::diagnosticOf;

TEST(TextureImageTest, PngIsDecodedTopRowFirst) {
  const Texture texture = loadTexture(kFixtures / "checker.png");
  ASSERT_EQ(texture.width, 2);
  ASSERT_EQ(texture.height, 2);
  EXPECT_EQ(pixel(texture, 0, 0), (std::array<int, 4>{255, 0, 0, 255}));
  EXPECT_EQ(pixel(texture, 1, 0), (std::array<int, 4>{0, 255, 0, 255}));
  EXPECT_EQ(pixel(texture, 0, 1), (std::array<int, 4>{0, 0, 255, 255}));
  EXPECT_EQ(pixel(texture, 1, 1), (std::array<int, 4>{255, 255, 255, 128}));
}

TEST(TextureImageTest, SgiRunLengthImageIsDecodedTopRowFirst) {
  // SGI files store the bottom row first; runs and literal stretches are both used.
  const Texture texture = loadTexture(kFixtures / "rle.rgb");
  ASSERT_EQ(texture.width, 3);
  ASSERT_EQ(texture.height, 2);
  EXPECT_EQ(pixel(texture, 0, 0), (std::array<int, 4>{10, 20, 30, 255}));
  EXPECT_EQ(pixel(texture, 1, 0), (std::array<int, 4>{10, 20, 30, 255}));
  EXPECT_EQ(pixel(texture, 2, 0), (std::array<int, 4>{40, 50, 60, 255}));
  EXPECT_EQ(pixel(texture, 0, 1), (std::array<int, 4>{1, 2, 3, 255}));
  EXPECT_EQ(pixel(texture, 2, 1), (std::array<int, 4>{7, 8, 9, 255}));
}

TEST(TextureImageTest, SgiVerbatimGreyImage) {
  const Texture texture = loadTexture(kFixtures / "verbatim.bw");
  ASSERT_EQ(texture.width, 2);
  ASSERT_EQ(texture.height, 2);
  EXPECT_EQ(pixel(texture, 0, 0), (std::array<int, 4>{128, 128, 128, 255}));
  EXPECT_EQ(pixel(texture, 1, 1), (std::array<int, 4>{64, 64, 64, 255}));
}

TEST(TextureImageTest, BrokenImagesAreErrors) {
  Diagnostic d = diagnosticOf([] { loadTexture(kFixtures / "broken.rgb"); });
  EXPECT_EQ(d.where.fileName(), (kFixtures / "broken.rgb").string());
  EXPECT_NE(d.message.find("broken SGI image"), std::string::npos) << d.message;
  d = diagnosticOf([] { loadTexture(kFixtures / "square.con"); });
  EXPECT_NE(d.message.find("cannot decode the texture image"), std::string::npos) << d.message;
  d = diagnosticOf([] { loadTexture(kFixtures / "nowhere.png"); });
  EXPECT_NE(d.message.find("cannot open"), std::string::npos) << d.message;
}

TEST(ModelResourcesTest, LoadsWhatTheViewFileNames) {
  Diagnostics diagnostics;
  const ModelResources resources =
      loadModelResources(kFixtures / "model.v", ColorFiles{}, diagnostics);
  EXPECT_EQ(resources.folder, kFixtures);
  EXPECT_EQ(resources.view.contourSides, 6);
  EXPECT_FALSE(resources.materialMode);
  EXPECT_EQ(resources.palette.size(), 256u);

  // Textures by id − 1; the missing one keeps its place without pixels.
  ASSERT_EQ(resources.textures.size(), 3u);
  EXPECT_EQ(resources.textures[0].width, 2);
  EXPECT_EQ(resources.textures[1].width, 3);
  EXPECT_EQ(resources.view.textures[1].mode, 'd');
  EXPECT_EQ(resources.textures[2].width, 0);
  EXPECT_TRUE(resources.textures[2].rgba.empty());

  EXPECT_TRUE(resources.contours.has(1));
  EXPECT_FALSE(resources.contours.has(2));  // missing.con: the circle stands in
  EXPECT_EQ(resources.contours.samples(1, 6).points.size(), 6u);

  // One warning per missing file, at the file name on its line.
  ASSERT_EQ(diagnostics.warnings().size(), 3u);
  const std::string view = (kFixtures / "model.v").string();
  EXPECT_EQ(diagnostics.warnings()[0].where.text(), view + ":7:13");
  EXPECT_NE(diagnostics.warnings()[0].message.find("texture image missing.png"), std::string::npos);
  EXPECT_EQ(diagnostics.warnings()[1].where.text(), view + ":4:12");
  EXPECT_NE(diagnostics.warnings()[1].message.find("contour 2 is drawn as a circle"),
            std::string::npos);
  EXPECT_EQ(diagnostics.warnings()[2].where.text(), view + ":10:12");
}

TEST(ModelResourcesTest, BrokenFilesAreReportedAtTheViewLineWithTheirOwnPlace) {
  Diagnostics diagnostics;
  Diagnostic d = diagnosticOf(
      [&] { loadModelResources(kFixtures / "broken_contour.v", ColorFiles{}, diagnostics); });
  EXPECT_EQ(d.where.fileName(), (kFixtures / "broken_contour.v").string());
  EXPECT_EQ(d.where.line, 1);
  EXPECT_EQ(d.where.column, 12);
  EXPECT_NE(d.message.find("contour file 'broken.con' is broken: " +
                           (kFixtures / "broken.con").string() + ":6:"),
            std::string::npos)
      << d.message;
  d = diagnosticOf(
      [&] { loadModelResources(kFixtures / "broken_texture.v", ColorFiles{}, diagnostics); });
  EXPECT_EQ(d.where.line, 1);
  EXPECT_EQ(d.where.column, 13);
  EXPECT_NE(d.message.find("texture file 'broken.rgb' is broken"), std::string::npos) << d.message;
}

// A load runs the view file through the preprocessor once (preprocessViewFile) and hands the
// text to both readers: given it, loadModelResources reads its settings from that text and does
// not read the file again (model.v names files, some missing, that would be loaded and warned of).
TEST(ModelResourcesTest, ThePreprocessedViewTextIsReadInsteadOfTheFile) {
  Diagnostics diagnostics;
  const std::string text = "angle increment: 30\n";
  const ModelResources resources =
      loadModelResources(kFixtures / "model.v", ColorFiles{}, diagnostics, kDefaultMaxMeshTriangles,
                         kDefaultMaxSourceBytes, &text);
  EXPECT_FLOAT_EQ(resources.view.angleIncrement, 30);
  EXPECT_TRUE(resources.textures.empty());
  EXPECT_FALSE(resources.contours.has(1));
  EXPECT_TRUE(diagnostics.warnings().empty());

  // The one read takes the command's limit on the preprocessed text (--max-source-bytes).
  const Diagnostic d =
      diagnosticOf([&] { preprocessViewFile(kFixtures / "model.v", 20, diagnostics); });
  EXPECT_NE(d.message.find("--max-source-bytes"), std::string::npos) << d.message;
  EXPECT_FALSE(
      preprocessViewFile(kFixtures / "model.v", kDefaultMaxSourceBytes, diagnostics).empty());
}

TEST(ModelResourcesTest, WithoutAViewFileEverythingIsDefault) {
  Diagnostics diagnostics;
  const ModelResources resources = loadModelResources(std::nullopt, ColorFiles{}, diagnostics);
  EXPECT_FLOAT_EQ(resources.view.angleIncrement, 45);
  EXPECT_EQ(resources.palette.size(), 256u);
  EXPECT_TRUE(resources.textures.empty());
  EXPECT_TRUE(resources.surfaces.empty());
  EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(ModelResourcesTest, ConformanceSgiTextureDecodes) {
  if (!std::filesystem::is_directory(kConformance)) {
    GTEST_SKIP() << "no conformance set at " << kConformance;
  }
  // enviro-CPFG-Clover: `texture: F: light08.rgb`, a run-length SGI image.
  const Texture light = loadTexture(kConformance / "enviro-CPFG-Clover" / "light08.rgb");
  EXPECT_EQ(light.width, 512);
  EXPECT_EQ(light.height, 512);
  EXPECT_EQ(light.rgba.size(), 512u * 512u * 4u);
}

}  // namespace
}  // namespace hirsute
