#include "hirsute/core/child_process.h"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <thread>

#include "hirsute/core/child_confinement.h"
#include "hirsute/core/model_folder.h"

extern char** environ;

namespace hirsute {
namespace {

using Clock = std::chrono::steady_clock;

// The write end of the pipe the signal handler reports on. A signal handler can reach nothing
// else: this is the one piece of process-wide state, set only while runChild waits.
volatile int gSignalPipe = -1;

void reportSignal(int signal) {
  const int saved = errno;
  const unsigned char byte = static_cast<unsigned char>(signal);
  if (gSignalPipe >= 0) (void)!::write(gSignalPipe, &byte, 1);
  errno = saved;
}

constexpr std::array<int, 3> kInterrupts = {SIGINT, SIGTERM, SIGHUP};

// While it lives: SIGINT, SIGTERM and SIGHUP are written to a pipe instead of ending us, and
// this process adopts the orphans of its descendants (PR_SET_CHILD_SUBREAPER).
class Watch {
 public:
  Watch() {
    if (pipe2(pipe_, O_CLOEXEC | O_NONBLOCK) != 0) pipe_[0] = pipe_[1] = -1;
    gSignalPipe = pipe_[1];
    using SignalAction = struct sigaction;
    SignalAction report{};
    report.sa_handler = reportSignal;
    sigemptyset(&report.sa_mask);
    report.sa_flags = SA_RESTART;
    for (std::size_t i = 0; i < kInterrupts.size(); ++i) {
      sigaction(kInterrupts[i], nullptr, &old_[i]);
      // A signal this process ignores (nohup, a shell's background job) stays ignored.
      if (old_[i].sa_handler != SIG_IGN) sigaction(kInterrupts[i], &report, nullptr);
    }
    int subreaper = 0;
    prctl(PR_GET_CHILD_SUBREAPER, &subreaper, 0, 0, 0);
    wasSubreaper_ = subreaper != 0;
    prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0);
  }
  ~Watch() {
    for (std::size_t i = 0; i < kInterrupts.size(); ++i)
      sigaction(kInterrupts[i], &old_[i], nullptr);
    gSignalPipe = -1;
    if (!wasSubreaper_) prctl(PR_SET_CHILD_SUBREAPER, 0, 0, 0, 0);
    for (int fd : pipe_)
      if (fd >= 0) close(fd);
  }
  Watch(const Watch&) = delete;
  Watch& operator=(const Watch&) = delete;

  int readEnd() const { return pipe_[0]; }
  // The signal that arrived, or 0.
  int received() const {
    unsigned char byte = 0;
    return pipe_[0] >= 0 && ::read(pipe_[0], &byte, 1) == 1 ? byte : 0;
  }

 private:
  int pipe_[2] = {-1, -1};
  struct sigaction old_[kInterrupts.size()] = {};
  bool wasSubreaper_ = false;
};

struct ProcessEntry {
  pid_t parent = 0;
  char state = '?';
};

// Every process /proc shows, by id: its parent and its state (Z for a zombie).
std::map<pid_t, ProcessEntry> processTable() {
  std::map<pid_t, ProcessEntry> table;
  DIR* proc = opendir("/proc");
  if (!proc) return table;
  while (const dirent* entry = readdir(proc)) {
    char* end = nullptr;
    const long pid = std::strtol(entry->d_name, &end, 10);
    if (pid <= 0 || *end != '\0') continue;
    char path[64];
    std::snprintf(path, sizeof path, "/proc/%ld/stat", pid);
    FileDescriptor stat(::open(path, O_RDONLY | O_CLOEXEC));
    if (!stat) continue;
    char text[1024];
    const ssize_t n = ::read(stat.get(), text, sizeof text - 1);
    if (n <= 0) continue;
    text[n] = '\0';
    // "pid (command) state ppid …": the command may hold spaces and parentheses.
    const char* close = std::strrchr(text, ')');
    if (!close) continue;
    char state = '?';
    long parent = 0;
    if (std::sscanf(close + 1, " %c %ld", &state, &parent) != 2) continue;
    table[static_cast<pid_t>(pid)] = {static_cast<pid_t>(parent), state};
  }
  closedir(proc);
  return table;
}

// Our children before the run, which are not the run's to end.
std::set<pid_t> childrenOfThisProcess() {
  std::set<pid_t> children;
  for (const auto& [pid, entry] : processTable())
    if (entry.parent == getpid()) children.insert(pid);
  return children;
}

// Kills every descendant of this process that is not a child it had before the run (nor one
// of theirs), round after round until none is left, reaping those that become our zombies.
// The run's own child is reaped here too when `child` is still ours: its status goes to
// `status`.
void endDescendants(const std::set<pid_t>& before, pid_t& child, int& status) {
  const auto until = Clock::now() + std::chrono::seconds(5);
  for (;;) {
    if (child > 0) kill(-child, SIGKILL);  // its group, while its id cannot be reused
    const std::map<pid_t, ProcessEntry> table = processTable();
    std::map<pid_t, std::vector<pid_t>> childrenOf;
    for (const auto& [pid, entry] : table) childrenOf[entry.parent].push_back(pid);
    std::vector<pid_t> alive, pending;
    bool zombies = false;  // dead descendants not yet reaped (ours once their parents go)
    for (pid_t pid : childrenOf[getpid()])
      if (!before.count(pid)) pending.push_back(pid);
    while (!pending.empty()) {
      const pid_t pid = pending.back();
      pending.pop_back();
      const ProcessEntry& entry = table.at(pid);
      if (entry.state == 'Z') {
        int reaped = 0;
        if (entry.parent == getpid() && waitpid(pid, &reaped, WNOHANG) == pid) {
          if (pid == child) {
            status = reaped;
            child = 0;
          }
        } else {
          zombies = true;
        }
      } else {
        alive.push_back(pid);
      }
      const auto found = childrenOf.find(pid);
      if (found != childrenOf.end())
        pending.insert(pending.end(), found->second.begin(), found->second.end());
    }
    if (alive.empty() && !zombies && child <= 0) return;
    for (pid_t pid : alive) kill(pid, SIGKILL);
    if (Clock::now() > until) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

// Why the child could not start, as it reports it on the status pipe before exec.
enum class StartStep : int { Input = 1, Output, Folder, Confinement, Exec };

[[noreturn]] void failInChild(int statusPipe, StartStep step) {
  const int report[2] = {static_cast<int>(step), errno};
  (void)!::write(statusPipe, report, sizeof report);
  _exit(127);
}

std::string describeFailure(StartStep step, int error, const ChildRequest& request) {
  std::string what;
  switch (step) {
    case StartStep::Input:
    case StartStep::Output:
      what = "cannot set up its input and output";
      break;
    case StartStep::Folder:
      what = "cannot enter " + request.folder.string();
      break;
    case StartStep::Confinement:
      what = "cannot confine it to its folders";
      break;
    case StartStep::Exec:
      what = "cannot run it";
      break;
  }
  return request.program + ": " + what + ": " + std::strerror(error);
}

}  // namespace

std::vector<std::string> environmentWith(const std::vector<std::string>& replacements) {
  std::vector<std::string> environment;
  for (char** e = environ; *e; ++e) {
    const std::string entry(*e);
    const std::string name = entry.substr(0, entry.find('='));
    const bool replaced = std::any_of(
        replacements.begin(), replacements.end(),
        [&](const std::string& r) { return r.compare(0, name.size() + 1, name + "=") == 0; });
    if (!replaced) environment.push_back(entry);
  }
  environment.insert(environment.end(), replacements.begin(), replacements.end());
  return environment;
}

ChildResult runChild(const ChildRequest& request) {
  ChildResult result;
  std::vector<std::string> arguments = request.arguments, environment = request.environment;
  std::vector<char*> argv, envp;
  for (std::string& a : arguments) argv.push_back(a.data());
  argv.push_back(nullptr);
  for (std::string& e : environment) envp.push_back(e.data());
  envp.push_back(nullptr);

  int output[2], status[2];
  if (pipe2(output, O_CLOEXEC) != 0) {
    result.failure = request.program + ": cannot make a pipe: " + std::strerror(errno);
    return result;
  }
  FileDescriptor outputRead(output[0]), outputWrite(output[1]);
  if (pipe2(status, O_CLOEXEC) != 0) {
    result.failure = request.program + ": cannot make a pipe: " + std::strerror(errno);
    return result;
  }
  FileDescriptor statusRead(status[0]), statusWrite(status[1]);

  Watch watch;
  const std::set<pid_t> before = childrenOfThisProcess();
  const char* folder = request.folder.empty() ? nullptr : request.folder.c_str();
  const auto start = Clock::now();
  pid_t child = fork();
  if (child < 0) {
    result.failure = request.program + ": cannot start it: " + std::strerror(errno);
    return result;
  }
  if (child == 0) {
    // The child: only system calls until exec. It ends with us, should we be killed outright.
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    for (int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGXFSZ}) signal(s, SIG_DFL);
    const int in = request.input >= 0 ? request.input : ::open("/dev/null", O_RDONLY);
    if (in < 0 || dup2(in, STDIN_FILENO) < 0) failInChild(statusWrite.get(), StartStep::Input);
    const int out = request.output >= 0 ? request.output : outputWrite.get();
    if (dup2(out, STDOUT_FILENO) < 0 || dup2(outputWrite.get(), STDERR_FILENO) < 0)
      failInChild(statusWrite.get(), StartStep::Output);
    if (folder && chdir(folder) != 0) failInChild(statusWrite.get(), StartStep::Folder);
    if (request.confinement && request.confinement->applyInChild() != 0)
      failInChild(statusWrite.get(), StartStep::Confinement);
    execve(request.program.c_str(), argv.data(), envp.data());
    failInChild(statusWrite.get(), StartStep::Exec);
  }
  setpgid(child, child);  // as the child does, whichever runs first
  outputWrite = FileDescriptor();
  statusWrite = FileDescriptor();
  int report[2] = {0, 0};
  ssize_t got = 0;
  while ((got = ::read(statusRead.get(), report, sizeof report)) < 0 && errno == EINTR) {
  }
  int exitStatus = 0;
  if (got == static_cast<ssize_t>(sizeof report)) {
    while (waitpid(child, &exitStatus, 0) < 0 && errno == EINTR) {
    }
    result.failure = describeFailure(static_cast<StartStep>(report[0]), report[1], request);
    return result;
  }
  result.started = true;

  FileDescriptor exited(static_cast<int>(::syscall(SYS_pidfd_open, child, 0)));
  char buffer[65536];
  bool childDone = false;
  auto lastCalled = Clock::now();
  for (;;) {
    if (request.whileRunning && Clock::now() - lastCalled >= kWhileRunningInterval) {
      lastCalled = Clock::now();
      request.whileRunning();
    }
    if (waitpid(child, &exitStatus, WNOHANG) == child) {
      childDone = true;
      child = 0;
      break;
    }
    if (const int received = watch.received()) {
      result.interruptedBy = received;
      break;
    }
    int wait = 1000;
    if (request.timeLimit.count() > 0) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          start + request.timeLimit - Clock::now());
      if (left.count() <= 0) {
        result.timedOut = true;
        break;
      }
      wait = static_cast<int>(std::min<long long>(left.count() + 1, wait));
    }
    if (!exited) wait = std::min(wait, 20);
    if (request.whileRunning)
      wait = std::min(wait, static_cast<int>(kWhileRunningInterval.count()));
    std::vector<pollfd> fds = {{watch.readEnd(), POLLIN, 0}};
    if (exited) fds.push_back({exited.get(), POLLIN, 0});
    if (outputRead) fds.push_back({outputRead.get(), POLLIN, 0});
    if (poll(fds.data(), fds.size(), wait) < 0 && errno != EINTR) break;
    if (outputRead && (fds.back().revents & (POLLIN | POLLHUP | POLLERR))) {
      const ssize_t n = ::read(outputRead.get(), buffer, sizeof buffer);
      if (n > 0) {
        if (request.onOutput) request.onOutput(std::string_view(buffer, static_cast<size_t>(n)));
      } else if (n == 0 || errno != EINTR) {
        outputRead = FileDescriptor();
      }
    }
  }
  // Whatever the child left running, and the child itself when it is stopped, ends here.
  int endedStatus = exitStatus;
  endDescendants(before, child, endedStatus);
  if (child > 0) {
    while (waitpid(child, &endedStatus, 0) < 0 && errno == EINTR) {
    }
  }
  if (!childDone) exitStatus = endedStatus;
  // What it wrote before it ended (every writer is gone, so the pipe ends).
  if (outputRead) {
    fcntl(outputRead.get(), F_SETFL, O_NONBLOCK);
    for (;;) {
      const ssize_t n = ::read(outputRead.get(), buffer, sizeof buffer);
      if (n > 0) {
        if (request.onOutput) request.onOutput(std::string_view(buffer, static_cast<size_t>(n)));
      } else if (n == 0 || errno != EINTR) {
        break;
      }
    }
  }
  if (WIFEXITED(exitStatus)) result.exitStatus = WEXITSTATUS(exitStatus);
  if (WIFSIGNALED(exitStatus)) result.signal = WTERMSIG(exitStatus);
  return result;
}

}  // namespace hirsute
