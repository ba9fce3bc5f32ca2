// Work run in a child process with limits (isolated_call.h).
#include "hirsute/core/isolated_call.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <new>
#include <system_error>
#include <thread>

#include "hirsute/core/child_confinement.h"

#if defined(__SANITIZE_ADDRESS__)
#define HIRSUTE_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HIRSUTE_ADDRESS_SANITIZER 1
#endif
#endif

namespace hirsute {
namespace {

using Clock = std::chrono::steady_clock;

// The child's exit codes other than 0 (its output written whole).
constexpr int kOutOfMemoryExit = 90;
constexpr int kThrewExit = 91;
constexpr int kNotConfinedExit = 92;
constexpr int kNotWrittenExit = 93;

// The address space this process has now (/proc/self/statm's first field), 0 when unknown.
std::size_t addressSpaceNow() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0;
  if (!(statm >> pages)) return 0;
  return pages * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

// Lowers a limit to `wanted` (a process may already run under a smaller one, which it cannot
// raise).
void lowerLimit(int resource, rlim_t soft, rlim_t hard) {
  rlimit now{};
  if (getrlimit(resource, &now) != 0) return;
  if (now.rlim_max == RLIM_INFINITY || now.rlim_max > hard) now.rlim_max = hard;
  if (now.rlim_cur == RLIM_INFINITY || now.rlim_cur > soft) now.rlim_cur = soft;
  if (now.rlim_cur > now.rlim_max) now.rlim_cur = now.rlim_max;
  (void)setrlimit(resource, &now);
}

bool writeAll(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// The child's side: limits, confinement, the work, its bytes (length first) down the pipe.
[[noreturn]] void runChild(const std::function<std::string()>& work,
                           const IsolatedCallLimits& limits, const ChildConfinement* confinement,
                           std::size_t addressSpace, int out, pid_t parent) {
  setpgid(0, 0);
  // The child never outlives the program: it is killed when the parent ends (Ctrl-C reaches
  // only the parent's process group).
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(kNotWrittenExit);
  for (int signal : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGXCPU, SIGPIPE}) {
    ::signal(signal, SIG_DFL);
  }
  lowerLimit(RLIMIT_CORE, 0, 0);
  const auto seconds = static_cast<rlim_t>(
      (limits.time.count() + 999) / 1000 > 0 ? (limits.time.count() + 999) / 1000 : 1);
  lowerLimit(RLIMIT_CPU, seconds, seconds + 1);
#ifndef HIRSUTE_ADDRESS_SANITIZER
  if (limits.memoryBytes > 0) {
    const auto bytes = static_cast<rlim_t>(addressSpace + limits.memoryBytes);
    lowerLimit(RLIMIT_AS, bytes, bytes);
  }
#else
  (void)addressSpace;
#endif
  if (confinement != nullptr && confinement->applyInChild() != 0) _exit(kNotConfinedExit);
  try {
    const std::string output = work();
    const std::uint64_t size = output.size();
    char header[sizeof size];
    std::memcpy(header, &size, sizeof size);
    if (!writeAll(out, header, sizeof header) || !writeAll(out, output.data(), output.size())) {
      _exit(kNotWrittenExit);
    }
  } catch (const std::bad_alloc&) {
    _exit(kOutOfMemoryExit);
  } catch (...) {
    _exit(kThrewExit);
  }
  // No exit handlers, no flushing of the parent's buffers: they are the parent's.
  _exit(0);
}

void killGroup(pid_t pid) {
  kill(-pid, SIGKILL);
  kill(pid, SIGKILL);
}

// Waits until `pid` has ended, at most until `until`, leaving it a zombie (its process group
// cannot be taken by another while it is one); false when the time passed first.
bool waitForEnd(pid_t pid, Clock::time_point until) {
  for (;;) {
    siginfo_t info{};
    const int done = waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT);
    if (done == 0 && info.si_pid == pid) return true;
    if (done < 0 && errno != EINTR) return true;
    if (Clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace

std::string signalDescription(int signal) {
  switch (signal) {
    case SIGSEGV:
      return "a segmentation fault";
    case SIGBUS:
      return "a bus error";
    case SIGABRT:
      return "an abort (a failed assertion)";
    case SIGILL:
      return "an illegal instruction";
    case SIGFPE:
      return "an arithmetic exception";
    case SIGKILL:
      return "being killed (by the system: out of memory?)";
    default:
      return std::string("signal ") + std::to_string(signal) + " (" + strsignal(signal) + ")";
  }
}

IsolatedCallResult callIsolated(const std::function<std::string()>& work,
                                const IsolatedCallLimits& limits) {
  IsolatedCallResult result;
  std::unique_ptr<ChildConfinement> confinement;
  if (!limits.readableFolder.empty()) {
    confinement = std::make_unique<ChildConfinement>(limits.readableFolder);
  }
  const std::size_t addressSpace = addressSpaceNow();
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::system_error(errno, std::generic_category(), "pipe");
  const FileDescriptor readEnd(fds[0]);
  FileDescriptor writeEnd(fds[1]);
  const auto until = Clock::now() + limits.time;
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::system_error(errno, std::generic_category(), "fork");
  if (pid == 0) runChild(work, limits, confinement.get(), addressSpace, writeEnd.get(), parent);
  setpgid(pid, pid);  // as the child does, so that the group exists whichever runs first
  writeEnd = FileDescriptor();

  // The child's bytes as they come, until it closes the pipe (it ends), the time passes or it
  // sends more than it may.
  std::string received;
  const std::size_t most = limits.maxOutputBytes + sizeof(std::uint64_t);
  bool timedOut = false, tooMuch = false;
  char buffer[1 << 16];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
    if (left.count() <= 0) {
      timedOut = true;
      break;
    }
    pollfd readable{readEnd.get(), POLLIN, 0};
    const int ready =
        poll(&readable, 1, static_cast<int>(std::min<long long>(left.count() + 1, 1'000'000)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t n = ::read(readEnd.get(), buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      break;
    }
    if (n == 0) break;
    if (received.size() + static_cast<std::size_t>(n) > most) {
      tooMuch = true;
      break;
    }
    received.append(buffer, static_cast<std::size_t>(n));
  }
  if (!timedOut && !tooMuch && !waitForEnd(pid, until)) timedOut = true;
  // Anything the child left in its group ends with it (the child itself, past a limit); the
  // group is still the child's, whose zombie holds its number until it is reaped.
  killGroup(pid);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }

  if (timedOut || (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU)) {
    result.end = IsolatedCallResult::End::TimedOut;
  } else if (tooMuch) {
    result.why = "it sent more than " + std::to_string(limits.maxOutputBytes) + " bytes";
  } else if (WIFSIGNALED(status)) {
    result.end = IsolatedCallResult::End::Crashed;
    result.signal = WTERMSIG(status);
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == kOutOfMemoryExit) {
    result.end = IsolatedCallResult::End::OutOfMemory;
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    std::uint64_t size = 0;
    if (received.size() >= sizeof size) std::memcpy(&size, received.data(), sizeof size);
    if (received.size() >= sizeof size && size == received.size() - sizeof size) {
      result.end = IsolatedCallResult::End::Finished;
      result.output = received.substr(sizeof size);
    } else {
      result.why = "it ended without sending its whole answer";
    }
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == kThrewExit) {
    result.why = "it ended on an unexpected exception";
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == kNotConfinedExit) {
    result.why = "it could not be confined to the model's folder";
  } else {
    result.why =
        "it ended with status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  }
  return result;
}

}  // namespace hirsute
