// `hirsute render --trace` and `export --trace-lights` from the command line, on a shipped model:
// the outputs for compositing are what their names say, the GL render refuses them, and the
// POV-Ray export takes the tracer's lights; --denoise filters a traced picture and nothing else.
// Options that are no numbers of their kind are refused, a failed run keeps the outputs it
// would have replaced, and a picture larger than memory is named as the cause.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

TEST(TraceCommand, ExposureBrightensAndTheFilmicCurveKeepsHighlightsOffWhite) {
  TemporaryFolder folder;
  const std::string model = (kCrocus / "wild-crocus.l").string();
  const std::string view = (kCrocus / "closeup.v").string();
  auto render = [&](const std::string& name, std::vector<std::string> extra) {
    const fs::path png = folder.path() / name;
    std::vector<std::string> args = {"render", model,    view,    "--trace", "--spp",
                                     "2",      "--size", "32x24", "-o",      png.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult run = runHirsute(args);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return hirsute::readPng(png);
  };
  auto sum = [](const hirsute::RgbaImage& image) {
    long total = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) total += image.rgba[i + 1];
    return total;
  };
  auto white = [](const hirsute::RgbaImage& image) {
    int count = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
      count += image.rgba[i] == 255 || image.rgba[i + 1] == 255 || image.rgba[i + 2] == 255;
    }
    return count;
  };
  const hirsute::RgbaImage plain = render("plain.png", {});
  const hirsute::RgbaImage same = render("same.png", {"--exposure", "0", "--tone", "none"});
  EXPECT_EQ(plain.rgba, same.rgba);  // the defaults leave the picture as it was
  const hirsute::RgbaImage bright = render("bright.png", {"--exposure", "3"});
  const hirsute::RgbaImage filmic = render("filmic.png", {"--exposure", "3", "--tone", "filmic"});
  EXPECT_GT(sum(bright), sum(plain));
  EXPECT_GT(white(bright), 20);                 // eight times brighter: the petals clip
  EXPECT_LT(white(filmic), white(bright) / 2);  // the filmic curve keeps most of them off white
  // The 16-bit PNG of linear light takes the exposure.
  const fs::path linear = folder.path() / "linear.png", exposed = folder.path() / "exposed.png";
  ASSERT_EQ(runHirsute({"render", model, view, "--trace", "--spp", "2", "--size", "32x24", "--bits",
                        "16", "-o", linear.string()})
                .exitCode,
            0);
  ASSERT_EQ(runHirsute({"render", model, view, "--trace", "--spp", "2", "--size", "32x24", "--bits",
                        "16", "--exposure", "1", "-o", exposed.string()})
                .exitCode,
            0);
  EXPECT_NE(bytesOf(linear), bytesOf(exposed));

  const fs::path refused = folder.path() / "refused.png";
  RunResult run = runHirsute({"render", model, view, "--exposure", "1", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("for traced pictures"), std::string::npos) << run.err;
  run = runHirsute({"render", model, view, "--trace", "--tone", "aces", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  run = runHirsute({"render", model, view, "--trace", "--tone", "filmic", "--bits", "16", "-o",
                    refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("a tone curve is for 8-bit pictures"), std::string::npos) << run.err;
  run = runHirsute({"render", model, view, "--trace", "--exposure", "inf", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  run = runHirsute({"render", model, view, "--trace", "--exposure", "1", "-o",
                    (folder.path() / "refused.exr").string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_FALSE(fs::exists(refused));
  EXPECT_FALSE(fs::exists(folder.path() / "refused.exr"));
}

TEST(TraceCommand, APixelFilterSpreadsTheSamplesAndTheGlRenderRefusesIt) {
  TemporaryFolder folder;
  const std::string model = (kCrocus / "wild-crocus.l").string();
  const std::string view = (kCrocus / "closeup.v").string();
  const fs::path box = folder.path() / "box.png", gaussian = folder.path() / "gaussian.png";
  RunResult run = runHirsute({"render", model, view, "--trace", "--spp", "2", "--size", "32x24",
                              "--filter", "box", "-o", box.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  run = runHirsute({"render", model, view, "--trace", "--spp", "2", "--size", "32x24", "--filter",
                    "gaussian", "-o", gaussian.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const hirsute::RgbaImage a = hirsute::readPng(box), b = hirsute::readPng(gaussian);
  ASSERT_EQ(a.width, b.width);
  EXPECT_NE(a.rgba, b.rgba);
  const fs::path refused = folder.path() / "refused.png";
  run = runHirsute({"render", model, view, "--filter", "gaussian", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("pixel filters are for traced pictures"), std::string::npos) << run.err;
  run =
      runHirsute({"render", model, view, "--trace", "--filter", "lanczos", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_FALSE(fs::exists(refused));
}

TEST(TraceCommand, ALensBlursWhatIsOutOfFocusAndTheGlRenderRefusesIt) {
  TemporaryFolder folder;
  const std::string model = (kCrocus / "wild-crocus.l").string();
  const std::string view = (kCrocus / "closeup.v").string();
  const fs::path sharp = folder.path() / "sharp.png", blurred = folder.path() / "blurred.png";
  RunResult run = runHirsute(
      {"render", model, view, "--trace", "--spp", "2", "--size", "32x24", "-o", sharp.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  run = runHirsute({"render", model, view, "--trace", "--spp", "2", "--size", "32x24", "--aperture",
                    "0.5", "--focus", "100", "-o", blurred.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const hirsute::RgbaImage a = hirsute::readPng(sharp), b = hirsute::readPng(blurred);
  ASSERT_EQ(a.width, b.width);
  EXPECT_NE(a.rgba, b.rgba);
  const fs::path refused = folder.path() / "refused.png";
  run = runHirsute({"render", model, view, "--aperture", "1", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("depth of field is for traced pictures"), std::string::npos) << run.err;
  run = runHirsute({"render", model, view, "--trace", "--focus", "3", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("give the lens an --aperture"), std::string::npos) << run.err;
  run = runHirsute({"render", model, view, "--trace", "--aperture", "-1", "-o", refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  run = runHirsute({"render", model, view, "--trace", "--aperture", "1", "--focus", "0", "-o",
                    refused.string()});
  EXPECT_EQ(run.exitCode, 2);
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

TEST(TraceCommand, OptionsThatAreNoNumbersOfTheirKindAreRefused) {
  TemporaryFolder folder;
  const std::string model = (kCrocus / "wild-crocus.l").string();
  const std::string view = (kCrocus / "closeup.v").string();
  const fs::path png = folder.path() / "still.png";
  struct Case {
    std::vector<std::string> option;
    std::string message;
  };
  const Case cases[] = {
      {{"--noise", "nan"}, "'nan' is not a finite number from 0 to 255"},
      {{"--time", "nan"}, "'nan' is not a finite number from 0 to 1e+07"},
      {{"--seed", "-1"}, "'-1' is not an integer from 0 to 18446744073709551615"},
      {{"--seed", "18446744073709551616"},
       "'18446744073709551616' is not an integer from 0 to 18446744073709551615"},
      {{"--spp", "1e3"}, "'1e3' is not an integer"},
      {{"--spp", "0"}, "'0' is not an integer from 1 to 1048576"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> arguments{"render", model, view, "--trace",
                                       "--size", "8x6", "-o", png.string()};
    arguments.insert(arguments.end(), c.option.begin(), c.option.end());
    const RunResult run = runHirsute(arguments);
    EXPECT_EQ(run.exitCode, 2) << c.option[0] << " " << c.option[1] << ": " << run.err;
    EXPECT_NE(run.err.find(c.message), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(png)) << c.option[0] << " " << c.option[1];
  }
  // The largest seed is one.
  const RunResult run = runHirsute({"render", model, view, "--trace", "--size", "8x6", "--spp", "1",
                                    "--seed", "18446744073709551615", "-o", png.string()});
  EXPECT_EQ(run.exitCode, 0) << run.err;
}

TEST(TraceCommand, AFailedRunLeavesThePictureAsItWas) {
  TemporaryFolder folder;
  const fs::path png = folder.path() / "keep.png";
  std::ofstream(png) << "the picture of an earlier run\n";
  const RunResult run =
      runHirsute({"render", (kCrocus / "wild-crocus.l").string(), (kCrocus / "closeup.v").string(),
                  "--trace", "--spp", "1", "--size", "8x6", "--spp-image",
                  (folder.path() / "nowhere" / "counts.png").string(), "-o", png.string()});
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("counts.png: cannot create the output file"), std::string::npos)
      << run.err;
  EXPECT_EQ(bytesOf(png), "the picture of an earlier run\n");
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"keep.png"});
}

// `hirsute ARGUMENTS…` with its address space limited to `bytes`: a machine that holds less
// than the run asks for. Its standard error is returned.
std::string runWithMemoryLimit(const std::vector<std::string>& arguments, rlim_t bytes,
                               int& exitCode) {
  TemporaryFolder capture;
  const fs::path err = capture.path() / "stderr";
  const pid_t pid = fork();
  if (pid == 0) {
    const rlimit limit{bytes, bytes};
    setrlimit(RLIMIT_AS, &limit);
    if (!freopen(err.c_str(), "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(126);
    std::vector<std::string> all{HIRSUTE_BINARY};
    all.insert(all.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(HIRSUTE_BINARY, argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return bytesOf(err);
}

TEST(TraceCommand, APictureLargerThanMemoryIsNamedBeforeTheModelIsBuilt) {
  if (kAddressSanitizer) GTEST_SKIP() << "no address-space limit holds AddressSanitizer's shadow";
  TemporaryFolder folder;
  const fs::path png = folder.path() / "large.png";
  int exitCode = 0;
  // 16384x16384 pixels take some 17 GB of buffers; the run may have 4 GB.
  const std::string err = runWithMemoryLimit(
      {"render", (kCrocus / "wild-crocus.l").string(), (kCrocus / "closeup.v").string(), "--trace",
       "--spp", "1", "--size", "16384x16384", "-o", png.string()},
      rlim_t{4} << 30, exitCode);
  EXPECT_EQ(exitCode, 2) << err;
  EXPECT_NE(err.find("hirsute: error: out of memory for the traced picture's buffers: "
                     "16384x16384 pixels take 17.2 GB"),
            std::string::npos)
      << err;
  EXPECT_EQ(err.find("the model made more"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(png));
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

// The skies and the camera's lines of the view file: the crocus in its evening garden and the
// poppy outdoors render; the view's tone curve is overridden by --tone; a broken map is an
// error at its name on the view file's line, with no picture.
TEST(TraceCommand, ViewFileSkiesAndCameraLines) {
  TemporaryFolder folder;
  const fs::path poppy = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "oriental-poppy";
  const fs::path garden = folder.path() / "garden.png", outdoors = folder.path() / "outdoors.png",
                 clipped = folder.path() / "clipped.png";
  RunResult run = runHirsute({"render", (kCrocus / "wild-crocus.l").string(),
                              (kCrocus / "garden.v").string(), "--trace", "--spp", "2", "--size",
                              "32x24", "-o", garden.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  run = runHirsute({"render", (poppy / "oriental-poppy.l").string(),
                    (poppy / "outdoors.v").string(), "--trace", "--spp", "2", "--size", "32x24",
                    "-o", outdoors.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  run = runHirsute({"render", (poppy / "oriental-poppy.l").string(),
                    (poppy / "outdoors.v").string(), "--trace", "--spp", "2", "--size", "32x24",
                    "--tone", "none", "-o", clipped.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(bytesOf(outdoors), bytesOf(clipped));

  {
    std::ofstream(folder.path() / "tiny.l") << "Lsystem: 1\nderivation length: 1\nAxiom: F\nendlsystem\n";
    std::ofstream(folder.path() / "tiny.v") << "/* a sky */\ntrace environment: broken.exr S: 2\n";
    std::ofstream(folder.path() / "broken.exr") << std::string("\x76\x2f\x31\x01", 4) << "garbage";
  }
  const fs::path refused = folder.path() / "refused.png";
  run = runHirsute({"render", (folder.path() / "tiny.l").string(),
                    (folder.path() / "tiny.v").string(), "--trace", "--size", "32x24", "-o",
                    refused.string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("tiny.v:2:20: error: cannot read the environment map 'broken.exr' as "
                         "OpenEXR"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(refused));
}

}  // namespace
