// `hirsute render-frames` from the command line: the frames `hirsute simulate` wrote, rendered by
// POV-Ray under GNU parallel into whole PNG images of the size asked; a second run renders only
// what is missing, --force everything; a scene POV-Ray cannot parse fails alone with exit code 1
// and leaves no image, whole or partial; over ssh (a stand-in that runs here) the scenes and their
// textures go out and the images come back. Skips without parallel or povray.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hirsute/core/program_path.h"
#include "hirsute/viewer/view/png_image.h"
#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kSource = HIRSUTE_SOURCE_DIR;
const fs::path kCoat = kSource / "models" / "coat-bending";

// Sets an environment variable for one scope, and puts back what was there.
class ScopedEnvironment {
 public:
  ScopedEnvironment(std::string name, const std::string& value) : name_(std::move(name)) {
    if (const char* old = std::getenv(name_.c_str())) old_ = old;
    setenv(name_.c_str(), value.c_str(), 1);
  }
  ~ScopedEnvironment() {
    if (old_)
      setenv(name_.c_str(), old_->c_str(), 1);
    else
      unsetenv(name_.c_str());
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

 private:
  std::string name_;
  std::optional<std::string> old_;
};

// What the command needs and this machine lacks; empty when nothing.
std::string missingTool() {
  if (hirsute::findOnPath("parallel").empty()) return "GNU parallel is not on the PATH";
  if (hirsute::findOnPath("povray").empty()) return "povray is not on the PATH";
  return "";
}

// Three frames of models/coat-bending's feathers in `folder`, fitted for 32 × 24.
void simulateThreeFrames(const fs::path& folder) {
  const RunResult run =
      runHirsute({"simulate", (kCoat / "bending.l").string(), (kCoat / "bending.v").string(),
                  (kCoat / "bending.a").string(), "-o", folder.string(), "--frames", "3", "--width",
                  "32", "--height", "24"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
}

// Each image's modification time, by its name.
std::map<std::string, fs::file_time_type> imageTimes(const fs::path& folder) {
  std::map<std::string, fs::file_time_type> times;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".png")
      times[entry.path().filename().string()] = entry.last_write_time();
  return times;
}

void expectImage(const fs::path& png, int width, int height) {
  SCOPED_TRACE(png.string());
  ASSERT_TRUE(fs::is_regular_file(png));
  const hirsute::RgbaImage image = hirsute::readPng(png);
  EXPECT_EQ(image.width, width);
  EXPECT_EQ(image.height, height);
}

// No hidden partial image (.frame-0002.part.png) is left in the folder.
void expectNoPartialImages(const TemporaryFolder& folder) {
  for (const std::string& name : folder.entries()) EXPECT_NE(name.front(), '.') << name;
}

TEST(RenderFramesCommand, RendersEveryFrameThenOnlyWhatIsMissing) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  TemporaryFolder folder;
  ASSERT_NO_FATAL_FAILURE(simulateThreeFrames(folder.path()));
  const std::string dir = folder.path().string();
  const std::vector<std::string> render = {"render-frames", dir,  "--width", "32",
                                           "--height",      "24", "--jobs",  "2"};

  RunResult run = runHirsute(render);
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("3 frames: 3 rendered, 0 already done, 0 failed in "), std::string::npos)
      << run.out;
  for (const char* name : {"frame-0001.png", "frame-0002.png", "frame-0003.png"})
    expectImage(folder.path() / name, 32, 24);
  EXPECT_EQ(countLinesStarting(readText(folder.path() / "render-frames.log"), "Seq\t"), 1u);
  EXPECT_EQ(linesOf(readText(folder.path() / "render-frames.log")).size(), 4u) << "a job a frame";
  expectNoPartialImages(folder);

  // One image gone: only its frame renders again; the others stay as they were.
  const auto before = imageTimes(folder.path());
  fs::remove(folder.path() / "frame-0002.png");
  run = runHirsute(render);
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("3 frames: 1 rendered, 2 already done, 0 failed in "), std::string::npos)
      << run.out;
  expectImage(folder.path() / "frame-0002.png", 32, 24);
  auto after = imageTimes(folder.path());
  EXPECT_EQ(after["frame-0001.png"], before.at("frame-0001.png"));
  EXPECT_EQ(after["frame-0003.png"], before.at("frame-0003.png"));

  // An image cut short, or older than its scene, is no rendered frame.
  fs::resize_file(folder.path() / "frame-0003.png", 40);
  run = runHirsute({"render-frames", dir, "--dry-run"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("3 frames: 1 to render, 2 already done"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("\nframe-0003.pov\n"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("--joblog render-frames.log"), std::string::npos) << run.out;
  EXPECT_EQ(fs::file_size(folder.path() / "frame-0003.png"), 40u) << "a dry run renders nothing";

  // --force renders every frame again.
  after = imageTimes(folder.path());
  run = runHirsute({"render-frames", dir, "--width", "32", "--height", "24", "--force"});
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("3 frames: 3 rendered, 0 already done, 0 failed in "), std::string::npos)
      << run.out;
  const auto forced = imageTimes(folder.path());
  for (const auto& [name, time] : after) EXPECT_NE(forced.at(name), time) << name;
  for (const char* name : {"frame-0001.png", "frame-0002.png", "frame-0003.png"})
    expectImage(folder.path() / name, 32, 24);
  expectNoPartialImages(folder);
}

TEST(RenderFramesCommand, TheSizeDefaultsToTheOneTheScenesWereWrittenFor) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  TemporaryFolder folder;
  ASSERT_NO_FATAL_FAILURE(simulateThreeFrames(folder.path()));
  const RunResult run = runHirsute({"render-frames", folder.path().string(), "--dry-run"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find(" sh {1} {1.} 32 24 -A"), std::string::npos) << run.out;
}

TEST(RenderFramesCommand, ASceneThatDoesNotParseFailsAloneAndLeavesNoImage) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  TemporaryFolder folder;
  ASSERT_NO_FATAL_FAILURE(simulateThreeFrames(folder.path()));
  fs::remove(folder.path() / "frame-0003.pov");
  std::ofstream(folder.path() / "frame-0002.pov") << "#version 3.7;\nsphere { <0, 0, 0>,\n";
  const RunResult run = runHirsute(
      {"render-frames", folder.path().string(), "--width", "32", "--height", "24", "--jobs", "2"});
  EXPECT_EQ(run.exitCode, 1) << run.err << run.out;
  EXPECT_NE(run.out.find("2 frames: 1 rendered, 0 already done, 1 failed in "), std::string::npos)
      << run.out;
  EXPECT_NE(run.err.find("frame-0002.pov: error: not rendered"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("Parse Error"), std::string::npos) << "POV-Ray's own message: " << run.err;
  EXPECT_NE(run.err.find("render-frames.log"), std::string::npos) << run.err;
  expectImage(folder.path() / "frame-0001.png", 32, 24);
  EXPECT_FALSE(fs::exists(folder.path() / "frame-0002.png"));
  expectNoPartialImages(folder);
}

TEST(RenderFramesCommand, AFolderWithoutScenesIsBadInput) {
  TemporaryFolder folder;
  std::ofstream(folder.path() / "frame-0001.png") << "not a scene";
  std::ofstream(folder.path() / "scene.pov") << "not a frame\n";
  fs::create_directory(folder.path() / "frame-0002.pov");  // no regular file
  const RunResult run = runHirsute({"render-frames", folder.path().string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  std::string message = "hirsute: error: ";
  message += folder.path().string();
  message += " holds no frame-*.pov scenes (hirsute simulate writes them)";
  EXPECT_NE(run.err.find(message), std::string::npos) << run.err;

  const RunResult absent = runHirsute({"render-frames", (folder.path() / "absent").string()});
  EXPECT_EQ(absent.exitCode, 2) << absent.err;
}

TEST(RenderFramesCommand, MissingToolsAreBadInput) {
  TemporaryFolder folder, bin;
  std::ofstream(folder.path() / "frame-0001.pov") << "// a scene\n";
  {
    const ScopedEnvironment path("PATH", bin.path().string());
    const RunResult run = runHirsute({"render-frames", folder.path().string()});
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find("error: GNU parallel is not on the PATH"), std::string::npos) << run.err;
  }
  const std::string parallel = hirsute::findOnPath("parallel");
  if (parallel.empty()) GTEST_SKIP() << "GNU parallel is not on the PATH";
  fs::create_symlink(parallel, bin.path() / "parallel");
  const ScopedEnvironment path("PATH", bin.path().string());
  const RunResult run = runHirsute({"render-frames", folder.path().string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("error: povray is not on the PATH"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(folder.path() / "render-frames.log")) << "parallel never ran";
}

TEST(RenderFramesCommand, OverSshTheScenesAndTheirTexturesTravelAndTheImagesComeBack) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  if (hirsute::findOnPath("rsync").empty()) GTEST_SKIP() << "rsync is not on the PATH";
  TemporaryFolder folder, remoteHome;
  const std::string scene = readText(kSource / "tests" / "fixtures" / "cli" / "textured_frame.pov");
  for (const std::string frame : {"0001", "0002"}) {
    std::string stem = "frame-";
    stem += frame;
    std::string text = scene;
    text.replace(text.find("frame-0001_texture1.png"), stem.size(), stem);
    std::ofstream(folder.path() / (stem + ".pov")) << text;
    fs::copy_file(kSource / "tests" / "fixtures" / "interpreter" / "checker.png",
                  folder.path() / (stem + "_texture1.png"));
  }
  const ScopedEnvironment ssh(
      "PARALLEL_SSH", (kSource / "tests" / "fixtures" / "cli" / "stand_in_ssh.sh").string());
  const ScopedEnvironment home("STAND_IN_REMOTE_HOME", remoteHome.path().string());
  const RunResult run = runHirsute({"render-frames", folder.path().string(), "--width", "32",
                                    "--height", "24", "--sshlogin", "stand-in"});
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("2 frames: 2 rendered, 0 already done, 0 failed in "), std::string::npos)
      << run.out;
  expectImage(folder.path() / "frame-0001.png", 32, 24);
  expectImage(folder.path() / "frame-0002.png", 32, 24);
  const std::string log = readText(folder.path() / "render-frames.log");
  EXPECT_EQ(countOccurrences(log, "\tstand-in\t"), 2u) << log;
  for (const auto& entry : fs::recursive_directory_iterator(remoteHome.path()))
    EXPECT_FALSE(entry.is_regular_file()) << entry.path() << ": the remote's copies are removed";

  // This machine as `:` among the hosts would render where the scenes are not.
  const RunResult mixed = runHirsute(
      {"render-frames", folder.path().string(), "--force", "--sshlogin", "stand-in,2/:"});
  EXPECT_EQ(mixed.exitCode, 2) << mixed.err;
  EXPECT_NE(mixed.err.find("name it as localhost"), std::string::npos) << mixed.err;
}

}  // namespace
