// Running the `hirsute` program from a test: its exit, its output, a hang caught; a folder of
// its own for each run. HIRSUTE_BINARY names the program.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>

#include "support/test_files.h"
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace hirsute::testing {

namespace fs = std::filesystem;

// Whether this is a build with AddressSanitizer, whose shadow memory no address-space limit
// holds: a test that limits the program's memory skips there.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

// A run still going after this is a hang. Generous: the sanitizer build's renders take seconds,
// and on a busy machine (CI's two test jobs and another process) the herb's took over 5.
constexpr auto kKillAfter = std::chrono::seconds(20);
constexpr double kSlowSeconds = 1.0;  // worth a warning line, not a failure: timing is no test

struct RunResult {
  bool killed = false;  // still running after kKillAfter
  bool exited = false;
  int exitCode = -1;
  int signal = 0;
  double seconds = 0;
  std::string out;
  std::string err;
};

// A folder of its own for one test, removed afterwards.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (fs::path(::testing::TempDir()) / "hirsute-cli-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const fs::path& path() const { return path_; }

  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

// Runs `hirsute ARGS…` with its output in files; kills it after kKillAfter. With
// `addressSpaceBytes`, the run may take no more memory than that (util-linux's prlimit --as): a
// machine smaller than the run asks for.
inline RunResult runHirsute(const std::vector<std::string>& arguments,
                            std::size_t addressSpaceBytes = 0) {
  TemporaryFolder capture;
  const std::string outPath = (capture.path() / "stdout").string();
  const std::string errPath = (capture.path() / "stderr").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  std::vector<std::string> argv = {HIRSUTE_BINARY};
  std::string program = HIRSUTE_BINARY;
  if (addressSpaceBytes > 0) {
    program = "/usr/bin/prlimit";
    argv = {program, "--as=" + std::to_string(addressSpaceBytes), "--", HIRSUTE_BINARY};
  }
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  std::vector<char*> pointers;
  for (std::string& a : argv) pointers.push_back(a.data());
  pointers.push_back(nullptr);

  RunResult result;
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, pointers.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error("cannot run " + program);
  int status = 0;
  for (;;) {
    pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (std::chrono::steady_clock::now() - start > kKillAfter) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      result.killed = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.exited = WIFEXITED(status);
  result.exitCode = result.exited ? WEXITSTATUS(status) : -1;
  result.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  result.out = readText(outPath);
  result.err = readText(errPath);
  return result;
}

}  // namespace hirsute::testing
