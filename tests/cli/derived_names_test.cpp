// The names a command makes up inside the folder it writes to (`simulate -o DIR`'s frames and
// tables, the .mtl and texture images beside an exported scene) are created there without
// following a link planted at the name: a link is replaced by the new file, the file it led to
// left alone; a FIFO at such a name is refused at once. Only the names the user typed may be
// links they chose (docs/files.md, "Output files").
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hirsute/core/program_path.h"
#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";
const fs::path kCoat = kModels / "coat-bending";
const fs::path kFur = kModels / "fur-square";

class DerivedNames : public ::testing::Test {
 protected:
  void SetUp() override {
    out_ = root_.path() / "out";
    outside_ = root_.path() / "outside";
    fs::create_directories(out_);
    fs::create_directories(outside_);
    std::ofstream(outside_ / "profile", std::ios::binary) << "# the user's own file\n";
  }
  std::string profile() const { return readText(outside_ / "profile"); }
  // A symbolic link at `name` in the output folder to the user's file outside.
  void plantLink(const std::string& name) const {
    fs::create_symlink(outside_ / "profile", out_ / name);
  }
  // The name is a regular file of the folder now, starting with `start`.
  void expectWrittenInPlace(const std::string& name, const std::string& start) const {
    EXPECT_FALSE(fs::is_symlink(out_ / name)) << name;
    EXPECT_TRUE(fs::is_regular_file(out_ / name)) << name;
    EXPECT_EQ(readText(out_ / name).rfind(start, 0), 0u) << name;
  }
  RunResult simulateCoat(std::vector<std::string> more) const {
    std::vector<std::string> arguments{"simulate", (kCoat / "bending.l").string(),
                                       (kCoat / "bending.v").string()};
    arguments.insert(arguments.end(), {"-o", out_.string(), "--width", "32", "--height", "24"});
    arguments.insert(arguments.end(), more.begin(), more.end());
    return runHirsute(arguments);
  }

  // `export` of the coat's first step, fitted for a small picture (its feathers built coarse).
  static RunResult exportCoat(std::vector<std::string> more) {
    std::vector<std::string> arguments{"export", (kCoat / "bending.l").string(),
                                       (kCoat / "bending.v").string()};
    arguments.insert(arguments.end(), {"-n", "1", "--width", "32", "--height", "24"});
    arguments.insert(arguments.end(), more.begin(), more.end());
    return runHirsute(arguments);
  }

  TemporaryFolder root_;
  fs::path out_, outside_;
};

TEST_F(DerivedNames, SimulateReplacesLinkedFramesAndTablesInsteadOfWritingThroughThem) {
  for (const char* name :
       {"frame-0001.pov", "frame-0002.pov", "frame-0001.obj", "frame-0001.mtl", "simulation.csv"})
    plantLink(name);
  const RunResult run = simulateCoat({"--frames", "2", "--obj"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(profile(), "# the user's own file\n");
  expectWrittenInPlace("frame-0001.pov", "// Hirsute");
  expectWrittenInPlace("frame-0002.pov", "// Hirsute");
  expectWrittenInPlace("frame-0001.obj", "# Hirsute");
  expectWrittenInPlace("frame-0001.mtl", "# Hirsute");
  expectWrittenInPlace("simulation.csv", "frame,time,");
}

TEST_F(DerivedNames, SimulateReplacesALinkedFurTable) {
  plantLink("fur.csv");
  const RunResult run =
      runHirsute({"simulate", (kFur / "square.l").string(), (kFur / "square.v").string(), "-o",
                  out_.string(), "--frames", "2", "--no-frames"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(profile(), "# the user's own file\n");
  expectWrittenInPlace("fur.csv", "frame,time,droplets,");
}

TEST_F(DerivedNames, SimulateReplacesAHardLinkedFrame) {
  ASSERT_EQ(link((outside_ / "profile").c_str(), (out_ / "frame-0001.pov").c_str()), 0);
  const RunResult run = simulateCoat({"--frames", "1"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(profile(), "# the user's own file\n");
  expectWrittenInPlace("frame-0001.pov", "// Hirsute");
}

TEST_F(DerivedNames, SimulateRefusesAFifoAtAFrameAtOnce) {
  ASSERT_EQ(mkfifo((out_ / "frame-0001.pov").c_str(), 0600), 0);
  const RunResult run = simulateCoat({"--frames", "1"});
  EXPECT_FALSE(run.killed) << "the run waited on the FIFO";
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("frame-0001.pov: cannot write: it is a FIFO"), std::string::npos)
      << run.err;
  EXPECT_TRUE(fs::is_fifo(out_ / "frame-0001.pov"));
}

TEST_F(DerivedNames, TheOutputFolderMayBeALinkTheUserChose) {
  fs::create_directory_symlink(outside_, root_.path() / "chosen");
  const RunResult run = runHirsute(
      {"simulate", (kCoat / "bending.l").string(), (kCoat / "bending.v").string(), "-o",
       (root_.path() / "chosen").string(), "--frames", "1", "--width", "32", "--height", "24"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(fs::is_regular_file(outside_ / "frame-0001.pov"));
}

TEST_F(DerivedNames, ExportReplacesALinkedMaterialLibraryBesideTheObj) {
  plantLink("side.mtl");
  const RunResult run = exportCoat({"--obj", (out_ / "side.obj").string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(profile(), "# the user's own file\n");
  expectWrittenInPlace("side.mtl", "# Hirsute: the materials of side.obj");
  expectWrittenInPlace("side.obj", "# Hirsute");
}

// A .gltf's buffer, FILE.bin beside it, is a name Hirsute derives too.
TEST_F(DerivedNames, ExportReplacesALinkedGltfBufferBesideTheGltf) {
  plantLink("side.bin");
  const RunResult run = exportCoat({"--gltf", (out_ / "side.gltf").string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(profile(), "# the user's own file\n");
  EXPECT_FALSE(fs::is_symlink(out_ / "side.bin"));
  EXPECT_TRUE(fs::is_regular_file(out_ / "side.bin"));
  expectWrittenInPlace("side.gltf", "{");
}

TEST_F(DerivedNames, ExportRefusesAFifoAtTheMaterialLibraryAndWritesNothing) {
  ASSERT_EQ(mkfifo((out_ / "side.mtl").c_str(), 0600), 0);
  const RunResult run = exportCoat({"--obj", (out_ / "side.obj").string()});
  EXPECT_FALSE(run.killed) << "the run waited on the FIFO";
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("side.mtl: cannot write: it is a FIFO"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out_ / "side.obj"));
}

// The name the user typed is theirs: a link there is written through, as documented, while the
// .mtl goes beside the typed name without following a link planted there.
TEST_F(DerivedNames, ExportWritesThroughTheLinkTheUserTyped) {
  std::ofstream(outside_ / "mine.obj", std::ios::binary) << "an older export\n";
  fs::create_symlink(outside_ / "mine.obj", out_ / "side.obj");
  plantLink("side.mtl");
  const RunResult run = exportCoat({"--obj", (out_ / "side.obj").string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(fs::is_symlink(out_ / "side.obj"));
  EXPECT_EQ(readText(outside_ / "mine.obj").rfind("# Hirsute", 0), 0u);
  EXPECT_EQ(profile(), "# the user's own file\n");
  expectWrittenInPlace("side.mtl", "# Hirsute");
}

// POV-Ray writes the image of `export --render` by name: into a temporary file of the folder,
// renamed over the .png's name.
TEST_F(DerivedNames, ExportRenderReplacesALinkedImage) {
  if (hirsute::findOnPath("povray").empty()) GTEST_SKIP() << "povray is not on the PATH";
  plantLink("side.png");
  const RunResult run = exportCoat({"--pov", (out_ / "side.pov").string(), "--render"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(profile(), "# the user's own file\n");
  expectWrittenInPlace("side.png", "\x89PNG");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(out_))
    names.push_back(entry.path().filename().string());
  EXPECT_EQ(names.size(), 2u) << "a temporary image was left";
}

}  // namespace
