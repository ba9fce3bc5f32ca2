// `hirsute render-frames` from the command line: the frames `hirsute simulate` wrote, rendered by
// POV-Ray under GNU parallel into whole PNG images of the size asked; a second run renders only
// what is missing, --force everything; a scene POV-Ray cannot parse fails alone with exit code 1
// and leaves no image, whole or partial; over ssh (a stand-in that runs here) the scenes and their
// textures go out and the images come back. The scenes are untrusted: links planted in the
// folder are replaced, never written through; a name POV-Ray would read as options is left out;
// POV-Ray reads and writes nothing outside; an endless frame is stopped; SIGTERM ends parallel and
// every renderer at once. Skips without parallel or povray.
#include <dirent.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <thread>
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
const fs::path kFrames = kSource / "tests" / "fixtures" / "cli" / "render_frames";

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
                  (kCoat / "bending.a").string(), "-o", folder.string(), "--frames", "3", "--size", "32x24"});
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
  const std::vector<std::string> render = {"render-frames", dir,  "--size", "32x24", "--jobs",  "2"};

  RunResult run = runHirsute(render);
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("3 frames: 3 rendered, 0 already done, 0 failed, 0 not started in "),
            std::string::npos)
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
  EXPECT_NE(run.out.find("3 frames: 1 rendered, 2 already done, 0 failed, 0 not started in "),
            std::string::npos)
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
  EXPECT_NE(run.out.find("--joblog .render-frames-XXXXXX/render-frames.log"), std::string::npos)
      << run.out;
  EXPECT_EQ(fs::file_size(folder.path() / "frame-0003.png"), 40u) << "a dry run renders nothing";

  // --force renders every frame again.
  after = imageTimes(folder.path());
  run = runHirsute({"render-frames", dir, "--size", "32x24", "--force"});
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("3 frames: 3 rendered, 0 already done, 0 failed, 0 not started in "),
            std::string::npos)
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
  EXPECT_NE(run.out.find(" sh {1} {1.} 32 24 -A .render-frames-XXXXXX 3600"), std::string::npos)
      << run.out;
}

TEST(RenderFramesCommand, ASceneThatDoesNotParseFailsAloneAndLeavesNoImage) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  TemporaryFolder folder;
  ASSERT_NO_FATAL_FAILURE(simulateThreeFrames(folder.path()));
  fs::remove(folder.path() / "frame-0003.pov");
  std::ofstream(folder.path() / "frame-0002.pov") << "#version 3.7;\nsphere { <0, 0, 0>,\n";
  const RunResult run = runHirsute(
      {"render-frames", folder.path().string(), "--size", "32x24", "--jobs", "2"});
  EXPECT_EQ(run.exitCode, 1) << run.err << run.out;
  EXPECT_NE(run.out.find("2 frames: 1 rendered, 0 already done, 1 failed, 0 not started in "),
            std::string::npos)
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
  const RunResult run = runHirsute({"render-frames", folder.path().string(), "--size", "32x24", "--sshlogin", "stand-in"});
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("2 frames: 2 rendered, 0 already done, 0 failed, 0 not started in "),
            std::string::npos)
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

// `folder`'s entries whose names start with `prefix`.
std::vector<std::string> entriesStarting(const fs::path& folder, const std::string& prefix) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.compare(0, prefix.size(), prefix) == 0) names.push_back(name);
  }
  return names;
}

TEST(RenderFramesCommand, LinksPlantedInTheFolderAreReplacedNotWrittenThrough) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  TemporaryFolder folder, outside, links;
  fs::copy_file(kFrames / "sphere.pov", folder.path() / "frame-0001.pov");
  std::ofstream(outside.path() / "log.txt") << "the user's file\n";
  std::ofstream(outside.path() / "image.png") << "the user's image\n";
  fs::create_symlink(outside.path() / "log.txt", folder.path() / "render-frames.log");
  fs::create_symlink(outside.path() / "image.png", folder.path() / "frame-0001.png");
  // DIR itself a link, as the user may name it.
  fs::create_directory_symlink(folder.path(), links.path() / "frames");
  const RunResult run = runHirsute(
      {"render-frames", (links.path() / "frames").string(), "--size", "32x24"});
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_EQ(readText(outside.path() / "log.txt"), "the user's file\n");
  EXPECT_EQ(readText(outside.path() / "image.png"), "the user's image\n");
  EXPECT_FALSE(fs::is_symlink(folder.path() / "render-frames.log"));
  EXPECT_FALSE(fs::is_symlink(folder.path() / "frame-0001.png"));
  EXPECT_EQ(linesOf(readText(folder.path() / "render-frames.log")).size(), 2u);
  expectImage(folder.path() / "frame-0001.png", 32, 24);
  expectNoPartialImages(folder);
}

TEST(RenderFramesCommand, ASceneNameThatPovRayWouldReadAsOptionsIsLeftOut) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  TemporaryFolder folder;
  fs::copy_file(kFrames / "sphere.pov", folder.path() / "frame-0001.pov");
  fs::copy_file(kFrames / "sphere.pov", folder.path() / "frame-7.pov");
  fs::copy_file(kFrames / "sphere.pov",
                folder.path() / "frame-7\" +GAinjected.log +I\"frame-7.pov");
  fs::copy_file(kFrames / "sphere.pov", folder.path() / "frame-8\x1b]0;owned\x07.pov");
  const RunResult run =
      runHirsute({"render-frames", folder.path().string(), "--size", "32x24"});
  ASSERT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("2 frames: 2 rendered, 0 already done, 0 failed, 0 not started in "),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.err.find("+GAinjected.log +I\"frame-7.pov: warning: a scene's name may hold only "
                         "letters, digits"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(folder.path() / "injected.log"));
  // The name is printed with its control bytes escaped.
  EXPECT_NE(run.err.find("frame-8\\x1b]0;owned\\x07.pov: warning"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find('\x1b'), std::string::npos);
  expectImage(folder.path() / "frame-0001.png", 32, 24);
  expectImage(folder.path() / "frame-7.png", 32, 24);
}

TEST(RenderFramesCommand, POVRayReadsAndWritesNothingOutsideTheFolder) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  TemporaryFolder outer;
  const fs::path folder = outer.path() / "frames";
  fs::create_directory(folder);
  fs::copy_file(kFrames / "sphere.pov", folder / "frame-0001.pov");
  fs::copy_file(kFrames / "include_passwd.pov", folder / "frame-0002.pov");
  fs::copy_file(kFrames / "include_outside.pov", folder / "frame-0003.pov");
  fs::copy_file(kFrames / "fopen_outside.pov", folder / "frame-0004.pov");
  fs::copy_file(kFrames / "secret.inc", outer.path() / "secret.inc");
  fs::create_symlink(outer.path() / "secret.inc", folder / "secret.inc");
  const RunResult run = runHirsute(
      {"render-frames", folder.string(), "--size", "32x24", "--jobs", "2"});
  EXPECT_EQ(run.exitCode, 1) << run.err << run.out;
  EXPECT_NE(run.out.find("4 frames: 1 rendered, 0 already done, 3 failed, 0 not started in "),
            std::string::npos)
      << run.out;
  for (const char* scene : {"frame-0002.pov", "frame-0003.pov", "frame-0004.pov"}) {
    std::string message = scene;
    message += ": error: not rendered";
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
  }
  EXPECT_EQ(run.err.find("root:"), std::string::npos) << "/etc/passwd was read: " << run.err;
  EXPECT_FALSE(fs::exists(outer.path() / "written-outside.txt"));
  expectImage(folder / "frame-0001.png", 32, 24);
  for (const char* image : {"frame-0002.png", "frame-0003.png", "frame-0004.png"})
    EXPECT_FALSE(fs::exists(folder / image)) << image;
  EXPECT_TRUE(entriesStarting(folder, ".").empty());
}

TEST(RenderFramesCommand, AFrameThatRendersForeverIsStoppedAtTheFrameTimeout) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  TemporaryFolder folder;
  fs::copy_file(kFrames / "sphere.pov", folder.path() / "frame-0001.pov");
  fs::copy_file(kFrames / "endless.pov", folder.path() / "frame-0002.pov");
  const RunResult run = runHirsute({"render-frames", folder.path().string(), "--size", "32x24", "--frame-timeout", "1"});
  EXPECT_FALSE(run.killed);
  EXPECT_EQ(run.exitCode, 1) << run.err << run.out;
  EXPECT_NE(run.err.find("frame-0002.pov: error: not rendered: POV-Ray ran for more than 1 s "
                         "(--frame-timeout) and was stopped"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.out.find("2 frames: 1 rendered, 0 already done, 1 failed, 0 not started in "),
            std::string::npos)
      << run.out;
  EXPECT_LT(run.seconds, 15.0);
  expectImage(folder.path() / "frame-0001.png", 32, 24);
  expectNoPartialImages(folder);
}

TEST(RenderFramesCommand, TheImageSizeHasTheLimitsOfEveryCommand) {
  TemporaryFolder folder;
  fs::copy_file(kFrames / "sphere.pov", folder.path() / "frame-0001.pov");
  for (const char* option : {"--width", "--height"}) {
    const RunResult run = runHirsute({"render-frames", folder.path().string(), option, "65536"});
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find("16384"), std::string::npos) << run.err;
  }
}

TEST(RenderFramesCommand, OverSshAScenesThatAsksForFilesDoesNotTravel) {
  TemporaryFolder folder;
  fs::copy_file(kFrames / "sphere.pov", folder.path() / "frame-0001.pov");
  fs::copy_file(kFrames / "include_passwd.pov", folder.path() / "frame-0002.pov");
  fs::copy_file(kFrames / "fopen_outside.pov", folder.path() / "frame-0003.pov");
  const RunResult run =
      runHirsute({"render-frames", folder.path().string(), "--sshlogin", "stand-in", "--dry-run"});
  EXPECT_EQ(run.exitCode, 0) << run.err << run.out;
  EXPECT_NE(run.err.find("frame-0002.pov: error: the scene uses #include, and the hosts of "
                         "--sshlogin run POV-Ray unconfined"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("frame-0003.pov: error: the scene uses #fopen"), std::string::npos)
      << run.err;
  EXPECT_NE(run.out.find("\nframe-0001.pov\n"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("\nframe-0002.pov\n"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("3 frames: 1 to render, 0 already done, 2 refused"), std::string::npos)
      << run.out;
}

// The processes descended from `root`, by id, with their command names.
std::map<pid_t, std::string> descendantsOf(pid_t root) {
  std::map<pid_t, std::pair<pid_t, std::string>> table;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || !std::all_of(name.begin(), name.end(), ::isdigit)) continue;
    const std::string stat = readText(entry.path() / "stat");
    const std::size_t open = stat.find('('), close = stat.rfind(')');
    if (open == std::string::npos || close == std::string::npos || close + 4 >= stat.size())
      continue;
    if (stat[close + 2] == 'Z') continue;
    const pid_t parent = static_cast<pid_t>(std::atol(stat.c_str() + close + 4));
    table[static_cast<pid_t>(std::stol(name))] = {parent, stat.substr(open + 1, close - open - 1)};
  }
  std::map<pid_t, std::string> found;
  bool grew = true;
  while (grew) {
    grew = false;
    for (const auto& [pid, entry] : table) {
      if (found.count(pid) || (entry.first != root && !found.count(entry.first))) continue;
      found[pid] = entry.second;
      grew = true;
    }
  }
  return found;
}

bool alive(pid_t pid) {
  const std::string stat = readText(fs::path("/proc") / std::to_string(pid) / "stat");
  const std::size_t close = stat.rfind(')');
  return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] != 'Z';
}

TEST(RenderFramesCommand, SigtermEndsParallelAndEveryRendererAndSaysWhatWasNotRendered) {
  if (const std::string missing = missingTool(); !missing.empty()) GTEST_SKIP() << missing;
  TemporaryFolder folder, capture;
  fs::copy_file(kFrames / "sphere.pov", folder.path() / "frame-0001.pov");
  for (const char* scene : {"frame-0002.pov", "frame-0003.pov", "frame-0004.pov"})
    fs::copy_file(kFrames / "endless.pov", folder.path() / scene);
  // frame-0001 renders; two endless frames start (two jobs at once); the last never starts.
  const std::string out = (capture.path() / "out").string(),
                    err = (capture.path() / "err").string();
  std::vector<std::string> argv = {HIRSUTE_BINARY,
                                   "render-frames",
                                   folder.path().string(),
                                   "--size", "32x24",
                                   "--jobs",
                                   "2"};
  std::vector<char*> pointers;
  for (std::string& a : argv) pointers.push_back(a.data());
  pointers.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t hirsute = 0;
  ASSERT_EQ(posix_spawn(&hirsute, HIRSUTE_BINARY, &actions, nullptr, pointers.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);

  // Waits until two renderers run and the first frame is done.
  std::map<pid_t, std::string> children;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  for (;;) {
    children = descendantsOf(hirsute);
    const auto renderers = std::count_if(children.begin(), children.end(),
                                         [](const auto& c) { return c.second == "povray"; });
    bool firstDone = fs::exists(folder.path() / "frame-0001.png");
    for (const std::string& work : entriesStarting(folder.path(), ".render-frames-"))
      firstDone = firstDone || fs::exists(folder.path() / work / "frame-0001.png");
    if ((renderers == 2 && firstDone) || std::chrono::steady_clock::now() > until) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GE(children.size(), 3u) << "parallel and two renderers";
  ASSERT_EQ(kill(hirsute, SIGTERM), 0);
  const auto signalled = std::chrono::steady_clock::now();
  int status = 0;
  while (waitpid(hirsute, &status, WNOHANG) == 0 &&
         std::chrono::steady_clock::now() - signalled < std::chrono::seconds(10))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
  std::vector<std::string> left;
  for (const auto& [pid, name] : children) {
    if (alive(pid)) left.push_back(name + " " + std::to_string(pid));
    kill(pid, SIGKILL);  // whatever was left, so that the test leaves nothing behind
  }
  if (seconds >= 10) {
    kill(hirsute, SIGKILL);
    waitpid(hirsute, &status, 0);
  }
  EXPECT_LT(seconds, 2.0) << "hirsute ended within a second or so of SIGTERM";
  EXPECT_TRUE(left.empty()) << "still running: " << ::testing::PrintToString(left);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM) << status;
  const std::string said = readText(out);
  EXPECT_NE(said.find("4 frames: 1 rendered, 0 already done, 0 failed, 2 stopped while rendering, "
                      "1 not started in "),
            std::string::npos)
      << said << readText(err);
  EXPECT_NE(readText(err).find("stopped by signal 15"), std::string::npos) << readText(err);
  expectImage(folder.path() / "frame-0001.png", 32, 24);
  EXPECT_TRUE(entriesStarting(folder.path(), ".").empty()) << "the work folder is removed";
  EXPECT_FALSE(fs::exists(folder.path() / "frame-0002.png"));
}

}  // namespace
