// The progress line (hirsute/core/progress.h) on a terminal (a pseudo-terminal here): a run that
// takes longer than a second names its stage on stderr, rewritten in place (`derive`'s steps,
// `simulate`'s frames with the time left, `export --render`'s share of POV-Ray's pixels,
// `render-frames`' frames finished and failed); with stderr on a pipe the same run writes
// nothing there at all.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hirsute/core/program_path.h"

extern char** environ;

namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

const std::string kSlowModel = std::string(HIRSUTE_SOURCE_DIR) + "/tests/fixtures/cli/slow_steps.l";

// `hirsute ARGS…` with stderr on `errorFd` and stdout on /dev/null.
pid_t spawnHirsute(const std::vector<std::string>& arguments, int errorFd) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, errorFd, 2);
  std::vector<std::string> argv = {HIRSUTE_BINARY};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  std::vector<char*> pointers;
  for (std::string& a : argv) pointers.push_back(a.data());
  pointers.push_back(nullptr);
  pid_t pid = 0;
  const int spawned =
      posix_spawn(&pid, HIRSUTE_BINARY, &actions, nullptr, pointers.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return spawned == 0 ? pid : -1;
}

// Reads `fd` until `wanted` appears in what was read or `limit` has passed; returns all of it.
std::string readUntil(int fd, const std::string& wanted, Clock::duration limit) {
  std::string text;
  const auto until = Clock::now() + limit;
  while (Clock::now() < until && (wanted.empty() || text.find(wanted) == std::string::npos)) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 50) <= 0) continue;
    char buffer[4096];
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

void stop(pid_t pid) {
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
}

TEST(Progress, ALongDerivationOnATerminalShowsItsStepsInPlace) {
  int master = -1, slave = -1;
  ASSERT_EQ(openpty(&master, &slave, nullptr, nullptr, nullptr), 0);
  const pid_t pid = spawnHirsute({"derive", kSlowModel}, slave);
  close(slave);
  ASSERT_GT(pid, 0);
  const auto started = Clock::now();
  // The first line appears after a second; a slow machine (a sanitizer build) gets time.
  const std::string text = readUntil(master, "/100000", 60s);
  const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
  stop(pid);
  close(master);
  const std::size_t at = text.find("\rderiving: step ");
  ASSERT_NE(at, std::string::npos) << "stderr: " << text;
  EXPECT_NE(text.find("/100000", at), std::string::npos);
  EXPECT_EQ(text.find('\n'), std::string::npos) << "the line is rewritten in place: " << text;
  EXPECT_GE(seconds, 1.0) << "nothing before the first second";
}

// A simulation counts its frames, the time since it started and, once a twentieth of them are
// done (a few seconds of fur in the wind here), the time it has left; it is stopped then.
TEST(Progress, ASimulationOnATerminalShowsItsFramesAndTheTimeLeft) {
  const std::string models = std::string(HIRSUTE_SOURCE_DIR) + "/models/fur-square/";
  char folder[] = "/tmp/hirsute_progress_XXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  int master = -1, slave = -1;
  ASSERT_EQ(openpty(&master, &slave, nullptr, nullptr, nullptr), 0);
  const pid_t pid =
      spawnHirsute({"simulate", models + "square.l", models + "square.v", "-o", folder, "--frames",
                    "100000", "--no-frames", "--wind", "3", "0", "0", "--gusts", "1"},
                   slave);
  close(slave);
  ASSERT_GT(pid, 0);
  const std::string text = readUntil(master, " left", 60s);
  stop(pid);
  close(master);
  std::filesystem::remove_all(folder);
  const std::size_t at = text.rfind("\rsimulating: ");
  ASSERT_NE(at, std::string::npos) << "stderr: " << text;
  const std::string line = text.substr(at + 1);
  EXPECT_NE(line.find("/100000 frames \u00b7 "), std::string::npos) << line;
  EXPECT_NE(line.find(" elapsed \u00b7 "), std::string::npos) << line;
  EXPECT_NE(line.find(" left"), std::string::npos) << line;
  EXPECT_EQ(text.find('\n'), std::string::npos) << "the line is rewritten in place: " << text;
}

// export --render shows the share of the pixels POV-Ray reports rendered (a large picture of the
// herb, stopped as soon as the line shows it).
TEST(Progress, ExportRenderOnATerminalShowsTheShareOfThePixelsPovRayRendered) {
  if (hirsute::findOnPath("povray").empty()) GTEST_SKIP() << "needs povray";
  const std::string herb = std::string(HIRSUTE_SOURCE_DIR) + "/models/herb/";
  char folder[] = "/tmp/hirsute_progress_XXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  int master = -1, slave = -1;
  ASSERT_EQ(openpty(&master, &slave, nullptr, nullptr, nullptr), 0);
  const pid_t pid =
      spawnHirsute({"export", herb + "herb.l", herb + "herb.v", "--pov",
                    std::string(folder) + "/herb.pov", "--render", "--size", "1600x1200"},
                   slave);
  close(slave);
  ASSERT_GT(pid, 0);
  const std::string text = readUntil(master, "% of the pixels \u00b7 ", 60s);
  // Stopped: hirsute ends POV-Ray and says what it said, read to the end so that it can write.
  kill(pid, SIGTERM);
  readUntil(master, "", 20s);
  stop(pid);
  close(master);
  std::filesystem::remove_all(folder);
  const std::size_t at = text.rfind("\rrendering with POV-Ray: ");
  ASSERT_NE(at, std::string::npos) << "stderr: " << text;
  EXPECT_NE(text.find("% of the pixels \u00b7 0:0", at), std::string::npos) << text.substr(at);
}

// render-frames counts the frames finished and failed as GNU parallel's job log records them:
// one renders, one cannot be parsed, one never ends and is stopped at --frame-timeout.
TEST(Progress, RenderFramesOnATerminalCountsTheFramesFinishedAndFailed) {
  if (hirsute::findOnPath("parallel").empty() || hirsute::findOnPath("povray").empty())
    GTEST_SKIP() << "needs GNU parallel and povray";
  const std::filesystem::path scenes =
      std::filesystem::path(HIRSUTE_SOURCE_DIR) / "tests/fixtures/cli/render_frames";
  char folder[] = "/tmp/hirsute_progress_XXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  const std::filesystem::path frames = folder;
  std::filesystem::copy_file(scenes / "sphere.pov", frames / "frame-0001.pov");
  std::ofstream(frames / "frame-0002.pov") << "#version 3.7;\nsphere { <0, 0, 0>,\n";
  std::filesystem::copy_file(scenes / "endless.pov", frames / "frame-0003.pov");
  int master = -1, slave = -1;
  ASSERT_EQ(openpty(&master, &slave, nullptr, nullptr, nullptr), 0);
  const pid_t pid = spawnHirsute(
      {"render-frames", folder, "--size", "32x24", "--jobs", "3", "--frame-timeout", "3"}, slave);
  close(slave);
  ASSERT_GT(pid, 0);
  // To its end: the endless frame is stopped after three seconds.
  const std::string text = readUntil(master, "", 30s);
  int status = 0;
  waitpid(pid, &status, 0);
  close(master);
  std::filesystem::remove_all(folder);
  EXPECT_NE(text.find("\rrendering frames: 2/3 frames, 1 failed \u00b7 0:0"), std::string::npos)
      << "stderr: " << text;
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << status;
}

TEST(Progress, StderrThatIsNoTerminalStaysEmpty) {
  int pipeFds[2];
  ASSERT_EQ(pipe(pipeFds), 0);
  const pid_t pid = spawnHirsute({"derive", kSlowModel}, pipeFds[1]);
  close(pipeFds[1]);
  ASSERT_GT(pid, 0);
  // Well past the second after which a terminal would have shown the line.
  const std::string text = readUntil(pipeFds[0], "", 2500ms);
  stop(pid);
  close(pipeFds[0]);
  EXPECT_EQ(text, "");
}

}  // namespace
