// Every cost a model's input can drive has a limit that ends in an error naming it, or stays
// fast. Each case is a reproduction of an input that once took minutes or gigabytes, run end to
// end through the program; a run past kKillAfter counts as the hang it used to be.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";

class InputCosts : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path file = folder_.path() / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  // `hirsute export MODEL [VIEW] --pov` into the test's folder.
  RunResult exportPov(const fs::path& model, const fs::path& view = {},
                      std::vector<std::string> more = {}) const {
    std::vector<std::string> arguments{"export", model.string()};
    if (!view.empty()) arguments.push_back(view.string());
    arguments.insert(arguments.end(), {"--pov", (folder_.path() / "out.pov").string()});
    arguments.insert(arguments.end(), more.begin(), more.end());
    return runHirsute(arguments);
  }
  static void expectError(const RunResult& run, const std::string& where, const std::string& text) {
    EXPECT_FALSE(run.killed) << "the run did not end";
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find(where), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(text), std::string::npos) << run.err;
  }

  TemporaryFolder folder_;
};

TEST_F(InputCosts, APrintfFieldWidthHasALimit) {
  const fs::path model = write("model.l",
                               "Lsystem: 1\nderivation length: 1\n"
                               "Start: { printf(\"%2000000000d\", 1); }\nAxiom: A\nendlsystem\n");
  expectError(runHirsute({"derive", model.string()}), "model.l:3:",
              "error: the format asks for a field of 2000000000 characters; the limit is 1000");
  // Within the limit the field is written whole (printf writes to the standard error: the
  // standard output is the string's).
  const fs::path fine = write("fine.l",
                              "Lsystem: 1\nderivation length: 1\n"
                              "Start: { printf(\"[%900.3f]\", 2); }\nAxiom: A\nendlsystem\n");
  const RunResult run = runHirsute({"derive", fine.string()});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.err.find("[" + std::string(895, ' ') + "2.000]"), std::string::npos);
}

TEST_F(InputCosts, ALabelFieldPastTheLimitIsDrawnAsWritten) {
  const fs::path model = write("model.l",
                               "Lsystem: 1\nderivation length: 0\n"
                               "Axiom: @L(\"%2000000000d\", 1) F\nendlsystem\n");
  const RunResult run = exportPov(model);
  EXPECT_FALSE(run.killed) << "the label took more than " << kKillAfter.count() << " s";
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.err.find("@L: the format asks for a field of 2000000000 characters (the limit is "
                         "1000); it is drawn as written"),
            std::string::npos)
      << run.err;
}

TEST_F(InputCosts, AKeyBarbHasAtMost64ControlVertices) {
  std::string vertices;
  for (int i = 0; i < 1000; ++i) vertices += " (" + std::to_string(i / 1000.0) + " 0.1)";
  write("many.fea", "key barb: left 0.5" + vertices + "\n");
  const fs::path view = write("model.v", "feather: many.fea\n");
  const fs::path model =
      write("model.l", "Lsystem: 1\nderivation length: 0\nAxiom: @Fe(1)\nendlsystem\n");
  // The 65th vertex: "key barb: left 0.5" is 18 characters, each vertex " (0.000000 0.1)" 15.
  expectError(exportPov(model, view), "many.fea:1:" + std::to_string(20 + 64 * 15) + ": error:",
              "a key barb has at most 64 control vertices");
}

// The herb's leaf at PRECISION S: 1000 T: 1000 (after its first line), as `leaf.s`, and a view
// file that names it ~l.
fs::path writeLeafAtPrecision1000(
    const std::function<fs::path(const std::string&, const std::string&)>& write) {
  std::string surface;
  std::ifstream in(fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb" / "leaf.s");
  for (std::string line; std::getline(in, line);) {
    surface += line + "\n";
    if (surface.find('\n') == surface.size() - 1) surface += "PRECISION S: 1000 T: 1000\n";
  }
  write("leaf.s", surface);
  return write("model.v", "surface: l leaf.s 1\n");
}

TEST_F(InputCosts, ASurfaceIsCountedAgainstTheVertexLimitBeforeItIsBuilt) {
  const fs::path view = writeLeafAtPrecision1000(
      [this](const std::string& name, const std::string& text) { return write(name, text); });
  const fs::path model =
      write("model.l", "Lsystem: 1\nderivation length: 0\nAxiom: ~l(1)\nendlsystem\n");
  const RunResult run = exportPov(model, view, {"--max-vertices", "200000"});
  EXPECT_FALSE(run.killed) << "the run did not end";
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("surface ~l (1 patches at precision 1000 × 1000) would grow the geometry "
                         "past 200000 vertices"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(folder_.path() / "out.pov"));
}

// Within the vertex limit, a surface at a high precision may still need more memory than the
// machine (here a 2 GB address space) holds: the message names the surface and its precision,
// before the geometry is built, instead of "out of memory" after seconds.
TEST_F(InputCosts, ASurfaceThatNeedsMoreMemoryThanTheMachineHoldsIsNamed) {
  if (kAddressSanitizer) GTEST_SKIP() << "no address-space limit holds AddressSanitizer's shadow";
  const fs::path view = writeLeafAtPrecision1000(
      [this](const std::string& name, const std::string& text) { return write(name, text); });
  std::string axiom;
  for (int i = 0; i < 40; ++i) axiom += "~l(1)";
  const fs::path model =
      write("model.l", "Lsystem: 1\nderivation length: 0\nAxiom: " + axiom + "\nendlsystem\n");
  const RunResult run = runHirsute(
      {"export", model.string(), view.string(), "--pov", (folder_.path() / "out.pov").string()},
      std::size_t{2} << 30);
  EXPECT_FALSE(run.killed) << "the run did not end";
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("surface ~l (1 patches at precision 1000 × 1000) would grow the geometry "
                         "to "),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("more than this process may take (2.1 GB); lower its precision"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(folder_.path() / "out.pov"));
}

TEST_F(InputCosts, RandomDropletsHaveALimit) {
  const fs::path square = kModels / "fur-square";
  const RunResult run =
      exportPov(square / "square.l", square / "square.v", {"--droplets", "10000000"});
  EXPECT_FALSE(run.killed) << "the droplets took more than " << kKillAfter.count() << " s";
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("error: 10000000 random droplets (--droplets) would blend more than "
                         "1073741824 texels of the wetness masks (the limit)"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(folder_.path() / "out.pov"));
}

TEST_F(InputCosts, TheViewFilesDropletsOnALargeMaskHaveALimit) {
  for (const char* file : {"square.l", "flat.con"})
    fs::copy_file(kModels / "fur-square" / file, folder_.path() / file);
  std::string view = "line style: cylinder\ncontour: 1 flat.con\nwetness mask: 4096\n";
  for (int i = 0; i < 70; ++i) view += "droplet: 0.5 0.5 1 1\n";
  // Each droplet of radius 1 blends the whole 4096² mask: the 65th passes 2^30 texels.
  expectError(
      exportPov(folder_.path() / "square.l", write("square.v", view)),
      "square.v:68:1: error:", "the view file's droplets would blend more than 1073741824 texels");
}

// Feathers at the turtle count against --max-feathers before any output builds them.
TEST_F(InputCosts, FeathersAtTheTurtleCountAgainstTheFeatherLimit) {
  const fs::path peacock = kModels / "peacock-feather";
  for (const char* file : {"peacock.fea", "peacock-eye.png", "peacock-feather.v"})
    fs::copy_file(peacock / file, folder_.path() / file);
  std::string axiom;
  for (int i = 0; i < 4095; ++i) axiom += "@Fe(1)";
  const fs::path model =
      write("many.l", "Lsystem: 1\nderivation length: 0\nAxiom: " + axiom + "\nendlsystem\n");
  const fs::path view = folder_.path() / "peacock-feather.v";
  expectError(exportPov(model, view, {"--max-feathers", "100"}), "many.l: error:",
              "4095 feathers at the turtle (@Fe, @Fi), more than 100 (raise the limit with "
              "--max-feathers)");
  EXPECT_FALSE(fs::exists(folder_.path() / "out.pov"));
}

// The feathers' geometry, built by each output at the detail of the feathers' size in its
// picture, counts against --max-vertices as it is built: 4 095 peacock feathers at one spot
// once took 16 GB and 340 s to export, or ended in an allocation abort when rendered.
TEST_F(InputCosts, FeathersGeometryAtThePicturesDetailHasALimit) {
  const fs::path peacock = kModels / "peacock-feather";
  for (const char* file : {"peacock.fea", "peacock-eye.png", "peacock-feather.v"})
    fs::copy_file(peacock / file, folder_.path() / file);
  const fs::path model =
      write("few.l", "Lsystem: 1\nderivation length: 0\nAxiom: @Fe(1)@Fe(1)@Fe(1)\nendlsystem\n");
  const fs::path view = folder_.path() / "peacock-feather.v";
  const std::string message =
      "the feathers' geometry grew past 20000 vertices (--max-vertices) at feather ";
  expectError(exportPov(model, view, {"--max-vertices", "20000"}), "few.l: error:", message);
  EXPECT_FALSE(fs::exists(folder_.path() / "out.pov"));
  const fs::path picture = folder_.path() / "few.png";
  expectError(runHirsute({"render", model.string(), view.string(), "-o", picture.string(), "--size",
                          "320x240", "--max-vertices", "20000"}),
              "few.l: error:", message);
  EXPECT_FALSE(fs::exists(picture));
  // Within the limit the same feathers export.
  const RunResult within = exportPov(model, view);
  EXPECT_EQ(within.exitCode, 0) << within.err;
}

// 4 095 peacock feathers at one spot, at the default limits: one template, placed 4 095 times;
// the drawn geometry (every instance's vertices) passes --max-vertices before any is drawn, a
// clear error in about 2 s where it once took 19 to 28 s and 5 GB (and before that an
// allocation abort); a smaller picture, or a few hundred of them, renders.
TEST_F(InputCosts, ManyFeathersAtOneSpotRenderOrStopQuickly) {
  const fs::path peacock = kModels / "peacock-feather";
  for (const char* file : {"peacock.fea", "peacock-eye.png", "peacock-feather.v"})
    fs::copy_file(peacock / file, folder_.path() / file);
  std::string axiom;
  for (int i = 0; i < 4095; ++i) axiom += "@Fe(1)";
  const fs::path model =
      write("many.l", "Lsystem: 1\nderivation length: 0\nAxiom: " + axiom + "\nendlsystem\n");
  const fs::path view = folder_.path() / "peacock-feather.v";
  const fs::path picture = folder_.path() / "many.png";
  expectError(runHirsute({"render", model.string(), view.string(), "-o", picture.string(), "--size",
                          "800x600"}),
              "many.l: error:",
              "the feathers' geometry grew past 100000000 vertices (--max-vertices) at feather ");
  EXPECT_FALSE(fs::exists(picture));
  std::string few;
  for (int i = 0; i < 300; ++i) few += "@Fe(1)";
  const fs::path fewer =
      write("fewer.l", "Lsystem: 1\nderivation length: 0\nAxiom: " + few + "\nendlsystem\n");
  const RunResult run = runHirsute(
      {"render", fewer.string(), view.string(), "-o", picture.string(), "--size", "160x120"});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(fs::exists(picture));
}

// The fur's exported strands take points by their curl (up to 193 each): their points in all
// count against --max-vertices before they are made, in the exports and the tracer.
TEST_F(InputCosts, FurStrandsPointsHaveALimit) {
  const fs::path curls = kModels / "fur-curls";
  for (const char* file : {"curls.l", "curls.v", "curls.map", "flat.con"})
    fs::copy_file(curls / file, folder_.path() / file);
  const fs::path model = folder_.path() / "curls.l";
  const fs::path view = folder_.path() / "curls.v";
  const std::string message =
      "the fur's strands grew past 200000 points (--max-vertices) at fur surface ";
  expectError(exportPov(model, view, {"--max-vertices", "200000"}), "curls.l: error:", message);
  EXPECT_FALSE(fs::exists(folder_.path() / "out.pov"));
  const fs::path obj = folder_.path() / "out.obj";
  expectError(runHirsute({"export", model.string(), view.string(), "--obj", obj.string(),
                          "--max-vertices", "200000"}),
              "curls.l: error:", message);
  EXPECT_FALSE(fs::exists(obj));
  const fs::path picture = folder_.path() / "curls.png";
  expectError(runHirsute({"render", model.string(), view.string(), "--trace", "--spp", "1",
                          "--size", "80x60", "-o", picture.string(), "--max-vertices", "200000"}),
              "curls.l: error:", message);
  EXPECT_FALSE(fs::exists(picture));
  // The whole export within the limit takes some 30 s under AddressSanitizer on a busy machine,
  // past the runs' kill limit: the release build checks it.
  if (kAddressSanitizer) return;
  const RunResult within = exportPov(model, view);
  EXPECT_EQ(within.exitCode, 0) << within.err;
}

// The preprocessed text has a limit of its own (--max-source-bytes): the parsed program takes
// about a hundred bytes a byte of it (a 64 MiB axiom took some 7 GB).
TEST_F(InputCosts, TheSourceTextHasALimit) {
  std::string axiom;
  for (int i = 0; i < 400; ++i) axiom += "F(1.5)+(2)";
  const fs::path model =
      write("long.l", "Lsystem: 1\nderivation length: 0\nAxiom: " + axiom + "\nendlsystem\n");
  for (const char* command : {"derive", "export"}) {
    std::vector<std::string> arguments{command, model.string(), "--max-source-bytes", "2000"};
    if (std::string(command) == "export")
      arguments.insert(arguments.end(), {"--pov", (folder_.path() / "out.pov").string()});
    expectError(runHirsute(arguments), "long.l: error:",
                "the preprocessed text is larger than 2000 bytes (--max-source-bytes");
  }
  const RunResult within = runHirsute({"derive", model.string()});
  EXPECT_EQ(within.exitCode, 0) << within.err;
}

// The view file and the background scenes it names go through the preprocessor too, under the
// same limit: a scene that grows past --max-source-bytes is refused as the .l would be.
TEST_F(InputCosts, TheViewFilesAndBackgroundScenesHaveTheSameLimit) {
  const fs::path model =
      write("small.l", "Lsystem: 1\nderivation length: 0\nAxiom: F\nendlsystem\n");
  std::string spheres;
  for (int i = 0; i < 200; ++i) spheres += "pushmatrix\n translate 1 0 0\n sphere 0.5\npopmatrix\n";
  write("scene.dat", spheres);
  const fs::path view = write("scene.v", "background scene: scene.dat\n");
  for (const char* command : {"render", "export"}) {
    std::vector<std::string> arguments{command, model.string(), view.string(), "--max-source-bytes",
                                       "2000"};
    if (std::string(command) == "export")
      arguments.insert(arguments.end(), {"--pov", (folder_.path() / "out.pov").string()});
    else
      arguments.insert(arguments.end(), {"-o", (folder_.path() / "out.png").string()});
    expectError(runHirsute(arguments), "scene.dat: error:",
                "the preprocessed text is larger than 2000 bytes (--max-source-bytes");
  }
  std::string lines;
  for (int i = 0; i < 200; ++i) lines += "/* a comment kept out */ scale factor: 1.0\n";
  const fs::path longView = write("long.v", lines);
  expectError(
      runHirsute({"derive", model.string(), longView.string(), "--max-source-bytes", "2000"}),
      "long.v: error:", "the preprocessed text is larger than 2000 bytes");
}

// A block of 50 000 assignments, each with a number of its own, runs and computes what it
// says (its speed, which once grew with the square of the numbers, is in
// scripts/bench-input-costs.sh).
TEST_F(InputCosts, ABlockOfFiftyThousandAssignmentsRuns) {
  std::string body;
  double expected = 0;
  for (int i = 0; i < 50000; ++i) {
    body += "x = x + " + std::to_string(i) + ".5;\n";
    expected += i + 0.5;
  }
  const fs::path model = write(
      "sum.l", "Lsystem: 1\nStart: { x = 0;\n" + body +
                   "printf(\"sum %.1f\\n\", x); }\nderivation length: 0\nAxiom: A\nendlsystem\n");
  const RunResult run = runHirsute({"derive", model.string()});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  char text[64];
  std::snprintf(text, sizeof text, "sum %.1f", expected);
  EXPECT_NE((run.out + run.err).find(text), std::string::npos) << run.out.substr(0, 200);
}

// The turtle's values go to an environmental program through the .e file's printf formats: a
// field of 2·10⁹ characters once asked for gigabytes a query.
TEST_F(InputCosts, AnEnvironmentFormatsFieldHasALimit) {
  const fs::path model = kModels / "tip-collision";
  fs::copy_file(model / "density.spec", folder_.path() / "density.spec");
  struct Case {
    const char* format;
    int column;  // of the number
    const char* what;
  };
  for (const Case& c : {Case{"%2000000000f %f %f", 19, "field width"},
                        Case{"%f %.2000000000f %f", 23, "precision"}}) {
    const fs::path e = write("wide.e", std::string("executable: honda81 density.spec\n"
                                                   "turtle position: ") +
                                           c.format + "\n");
    const RunResult run = runHirsute({"derive", (model / "tip-collision.l").string(),
                                      (model / "tip-collision.v").string(), "-e", e.string()});
    expectError(run, "wide.e:2:" + std::to_string(c.column) + ": error:",
                std::string("the format asks for a ") + c.what +
                    " of 2000000000 characters; the limit is 1000");
  }
}

// A FIFO would wait for its writer and a device never ends: the environment file and a CCD
// query file are refused before they are read, whatever link leads to them.
TEST_F(InputCosts, AnEnvironmentFileOrAQueryFileThatIsADeviceIsRefused) {
  const fs::path model = kModels / "tip-collision";
  RunResult run = runHirsute({"derive", (model / "tip-collision.l").string(),
                              (model / "tip-collision.v").string(), "-e", "/dev/zero"});
  expectError(run, "/dev/zero: error:",
              "cannot read the file: it is a character device, not a regular file");

  fs::create_directory(folder_.path() / "edge-edge");
  const fs::path queries = folder_.path() / "edge-edge" / "queries.csv";
  fs::create_symlink("/dev/zero", queries);
  run = runHirsute({"bench", "ccd", queries.string()});
  expectError(run, queries.string() + ": error:",
              "cannot read: it is a character device, not a regular file");

  const fs::path fifo = folder_.path() / "edge-edge" / "fifo.csv";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  run = runHirsute({"bench", "ccd", fifo.string()});
  expectError(run, fifo.string() + ": error:", "cannot read: it is a FIFO, not a regular file");
}

}  // namespace

namespace {

// `simulate` writes a scene a frame: frames × the scene's size once filled a disc at gigabytes
// a minute. The first frame's files, before they land, tell what the run would write.
TEST_F(InputCosts, TheFramesOfASimulationHaveAByteLimit) {
  const fs::path coat = kModels / "coat-bending";
  const fs::path frames = folder_.path() / "frames";
  const auto simulate = [&](std::vector<std::string> more) {
    std::vector<std::string> arguments{"simulate", (coat / "bending.l").string(),
                                       (coat / "bending.v").string(), "-o", frames.string()};
    // Fitted for a small picture: 380 kB a frame.
    arguments.insert(arguments.end(), {"--width", "32", "--height", "24"});
    arguments.insert(arguments.end(), more.begin(), more.end());
    return runHirsute(arguments);
  };
  const auto frameFiles = [&] {
    std::size_t count = 0;
    for (const auto& entry : fs::directory_iterator(frames))
      count += entry.path().filename().string().rfind("frame-", 0) == 0;
    return count;
  };
  expectError(simulate({"--frames", "1000000"}), "hirsute: error: 1000000 frames of ",
              "more than --max-output-bytes 17179869184; write fewer frames or raise the limit");
  EXPECT_EQ(frameFiles(), 0u);
  expectError(simulate({"--frames", "3", "--max-output-bytes", "1000"}),
              "hirsute: error: 3 frames of ", "more than --max-output-bytes 1000");
  EXPECT_EQ(frameFiles(), 0u);
  // Within the limit the frames are written.
  const RunResult run = simulate({"--frames", "2", "--max-output-bytes", "100000000"});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(frameFiles(), 2u);
}

}  // namespace
