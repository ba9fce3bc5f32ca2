// Running a program Hirsute starts on a model's files (POV-Ray, GNU parallel and the renderers
// parallel starts) so that it never outlives its time limit, an interrupt, or us.
//
// The child runs in a process group of its own, confined when asked (child_confinement.h).
// While it runs this process is the "child subreaper" of everything the child starts, so that a
// grandchild whose parent has gone stays among our descendants (parallel puts each job in a
// process group of its own, so a group alone does not hold them). Past the time limit, on
// SIGINT, SIGTERM or SIGHUP to this process, and when the child itself has ended, every
// descendant it left is killed (SIGKILL, round after round until none is left) and reaped.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace hirsute {

class ChildConfinement;

struct ChildRequest {
  std::string program;                   // the executable's path
  std::vector<std::string> arguments;    // its argv, its name first
  std::vector<std::string> environment;  // its whole environment
  std::filesystem::path folder;          // where it runs (empty: here)
  int input = -1;                        // its standard input (-1: /dev/null)
  int output = -1;                       // its standard output (-1: with its errors, to onOutput)
  const ChildConfinement* confinement = nullptr;
  std::chrono::milliseconds timeLimit{0};  // 0: none
  // What it writes to its standard error (and output, where `output` is -1), as it comes.
  std::function<void(std::string_view)> onOutput;
  // Called about every kWhileRunningInterval while it runs, on this thread: to show how far it
  // has got (the progress line). The limits and signals are watched between the calls.
  std::function<void()> whileRunning;
};

inline constexpr std::chrono::milliseconds kWhileRunningInterval{250};

struct ChildResult {
  bool started = false;
  std::string failure;    // why it did not start
  int exitStatus = -1;    // its exit status when it exited
  int signal = 0;         // the signal that ended it, when one did
  bool timedOut = false;  // ended because it passed the time limit
  int interruptedBy = 0;  // SIGINT, SIGTERM or SIGHUP that this process received; it was ended
};

ChildResult runChild(const ChildRequest& request);

// This process's environment, with `NAME=value` entries replacing those of the same names.
std::vector<std::string> environmentWith(const std::vector<std::string>& replacements);

}  // namespace hirsute
