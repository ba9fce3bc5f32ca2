// The progress line of `hirsute derive` (hirsute/core/progress.h): on a terminal (a pseudo-
// terminal here) a run that takes longer than a second names its stage on stderr; with stderr on
// a pipe the same run writes nothing there at all.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <vector>

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
