// `hirsute render --trace` and `export --trace-lights` from the command line, on a shipped model:
// the outputs for compositing are what their names say, the GL render refuses them, and the
// POV-Ray export takes the tracer's lights; --denoise filters a traced picture and nothing else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "hirsute/viewer/view/png_image.h"
#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kCrocus = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "wild-crocus";

std::string bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(TraceCommand, WritesOpenExrAndSixteenBitPngAndTheGlRenderRefusesThem) {
  TemporaryFolder folder;
  const std::string model = (kCrocus / "wild-crocus.l").string();
  const std::string view = (kCrocus / "closeup.v").string();
  const fs::path exr = folder.path() / "still.exr";
  RunResult run = runHirsute({"render", model, view, "--trace", "--spp", "1", "--size", "32x24",
                              "-o", exr.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(bytesOf(exr).substr(0, 4), std::string("\x76\x2f\x31\x01", 4));  // OpenEXR's magic
  const fs::path png = folder.path() / "still.png";
  run = runHirsute({"render", model, view, "--trace", "--spp", "1", "--size", "32x24", "--bits",
                    "16", "-o", png.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string bytes = bytesOf(png);
  ASSERT_GT(bytes.size(), 26u);
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(static_cast<int>(static_cast<unsigned char>(bytes[24])), 16);  // bits a channel
  const fs::path refused = folder.path() / "gl.png";
  run = runHirsute({"render", model, view, "--bits", "16", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("made by --trace only"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(refused));
}

TEST(TraceCommand, WritesTheSampleCountsOfAdaptiveSampling) {
  TemporaryFolder folder;
  const std::string model = (kCrocus / "wild-crocus.l").string();
  const std::string view = (kCrocus / "closeup.v").string();
  const fs::path png = folder.path() / "still.png", counts = folder.path() / "counts.png";
  RunResult run =
      runHirsute({"render", model, view, "--trace", "--spp", "32", "--noise", "3", "--size",
                  "40x24", "-o", png.string(), "--spp-image", counts.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const hirsute::RgbaImage image = hirsute::readPng(counts);
  ASSERT_EQ(image.width, 40);
  ASSERT_EQ(image.height, 24);
  // Grey, each pixel between the first 16 samples (half white) and the 32 at most (white).
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const glm::u8vec4 p = image.pixel(x, y);
      EXPECT_EQ(p.r, p.g);
      EXPECT_GE(p.r, 127);
    }
  }
  run = runHirsute({"render", model, view, "--spp-image", counts.string(), "-o", png.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("made by --trace only"), std::string::npos) << run.err;
  run = runHirsute({"render", model, view, "--trace", "--noise", "-1", "-o", png.string()});
  EXPECT_EQ(run.exitCode, 2);
}

TEST(TraceCommand, DenoisesATracedPictureOnlyAndSaysHowLongItTook) {
  TemporaryFolder folder;
  const std::string model = (kCrocus / "wild-crocus.l").string();
  const std::string view = (kCrocus / "closeup.v").string();
  const fs::path plain = folder.path() / "plain.png", filtered = folder.path() / "filtered.png";
  RunResult run = runHirsute({"render", model, view, "--trace", "--spp", "4", "--size", "40x30",
                              "-o", plain.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  run = runHirsute({"render", model, view, "--trace", "--spp", "4", "--size", "40x30",
                    "--denoise", "-v", "-o", filtered.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.err.find("(denoised in "), std::string::npos) << run.err;
  // The same samples, filtered: the same size, other pixels.
  const hirsute::RgbaImage a = hirsute::readPng(plain), b = hirsute::readPng(filtered);
  ASSERT_EQ(a.width, b.width);
  EXPECT_NE(a.rgba, b.rgba);
  const fs::path refused = folder.path() / "refused.png";
  run = runHirsute({"render", model, view, "--denoise", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("only a traced picture"), std::string::npos) << run.err;
  run = runHirsute({"render", model, view, "--trace", "--spp", "1", "--denoise", "-o",
                    refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("--spp 2 or more"), std::string::npos) << run.err;
  // The filter's memory grows with the picture: a limit, before any tracing.
  run = runHirsute({"render", model, view, "--trace", "--denoise", "--size", "8192x4097", "-o",
                    refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("at most 4096x4096 pixels"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(refused));
}

TEST(TraceCommand, ExportTakesTheTracersLights) {
  TemporaryFolder folder;
  const fs::path pov = folder.path() / "crocus.pov";
  const RunResult run =
      runHirsute({"export", (kCrocus / "wild-crocus.l").string(), (kCrocus / "wild-crocus.v").string(),
                  "--pov", pov.string(), "--trace-lights", "--width", "64", "--height", "48"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string text = bytesOf(pov);
  EXPECT_NE(text.find("area_light"), std::string::npos);
  EXPECT_NE(text.find("radiosity{"), std::string::npos);
  EXPECT_NE(text.find("no_image"), std::string::npos);
  EXPECT_NE(text.find("diffuse .5,.5"), std::string::npos);  // translucency: 5 0.5
}

const fs::path kFlatLeaf =
    fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "cli" / "flat-leaf";

// The picture's centre pixel of `view` of the flat leaf (tests/fixtures/cli/flat-leaf), 32x24,
// by GL or (`traced`) by the tracer at a few samples a pixel.
glm::u8vec4 leafCentre(const TemporaryFolder& folder, const std::string& view, bool traced) {
  const fs::path png = folder.path() / (view + (traced ? ".traced.png" : ".gl.png"));
  std::vector<std::string> arguments = {"render",
                                        (kFlatLeaf / "leaf.l").string(),
                                        (kFlatLeaf / view).string(),
                                        "--size",
                                        "32x24",
                                        "-o",
                                        png.string()};
  if (traced) arguments.insert(arguments.end(), {"--trace", "--spp", "4"});
  const RunResult run = runHirsute(arguments);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  const hirsute::RgbaImage image = hirsute::readPng(png);
  if (image.width != 32 || image.height != 24) {
    ADD_FAILURE() << "no 32x24 picture of " << view;
    return glm::u8vec4(0);
  }
  return image.pixel(16, 12);
}

// With a colour map, GL shades a surface along the palette, colour c showing entry c + 10
// (`diffuse reflection: 10`) where the light falls square on it; the tracer's light does the
// shading, and the leaf takes the colour GL shows in full light: lit from the viewer's side by
// a light that makes a white surface white (front.v), the traced leaf is GL's leaf within a few
// levels.
TEST(TraceCommand, ATracedLeafHasGlsColour) {
  TemporaryFolder folder;
  const glm::u8vec4 gl = leafCentre(folder, "front.v", false);
  const glm::u8vec4 traced = leafCentre(folder, "front.v", true);
  EXPECT_EQ(gl, glm::u8vec4(180, 220, 110, 255)) << "entry 30 of leaf.map";
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(traced[c], gl[c], 6) << "channel " << c;
}

// A leaf is thin: lit from behind, without a `translucency:` line and without sky, it passes
// light towards the viewer (a share of its colour), where an opaque one would be black.
TEST(TraceCommand, ABacklitLeafPassesLightByDefault) {
  TemporaryFolder folder;
  const glm::u8vec4 traced = leafCentre(folder, "backlit.v", true);
  EXPECT_GT(traced.g, 40);
  EXPECT_GT(traced.g, traced.r);  // its own green
  EXPECT_GT(traced.g, traced.b);
}

}  // namespace
