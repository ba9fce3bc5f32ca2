#include "hirsute/environment/external_program.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/ipc.h>
#include <sys/sem.h>
#include <sys/shm.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <ostream>
#include <sstream>
#include <thread>

#include "hirsute/core/model_folder.h"

namespace hirsute {
namespace {

using Clock = std::chrono::steady_clock;

// cpfg's shared memory: a block from cpfg to the program, then one back.
constexpr std::size_t kToProgramBytes = 50000;
constexpr std::size_t kFromProgramBytes = 10000;
// An answer file larger than this is a program gone wrong.
constexpr std::size_t kMaxAnswerFileBytes = std::size_t{256} << 20;

class ExternalProgram : public EnvironmentProgram {
 public:
  ExternalProgram(const CommunicationFile& file, int timeoutSeconds, std::ostream* log)
      : file_(file), timeout_(std::chrono::seconds(timeoutSeconds)), log_(log) {
    const ProgramCommand command = parseProgramCommand(file);
    if (command.program.empty()) fail("the executable: line names no program");
    name_ = command.program;
    folder_ = file.file.parent_path();
    if (folder_.empty()) folder_ = ".";
    const std::string efile = file.file.filename().string();
    const bool hasE = command.words.size() > 1 && command.words[1].rfind("-e", 0) == 0;
    std::vector<std::string> argv{command.words[0]};
    if (!hasE) {
      argv.push_back("-e");
      argv.push_back(efile);
    }
    if (file.transport == Transport::Sockets)
      fail("the sockets transport is not supported; use files, memory or pipes");
    try {
      if (file.transport == Transport::Pipes) {
        argv.insert(argv.end(), command.words.begin() + 1, command.words.end());
        startPipes(argv);
      } else {
        startShared(argv, command);
      }
    } catch (...) {
      stop();
      throw;
    }
  }

  ~ExternalProgram() override { stop(); }

  const std::string& name() const override { return name_; }

  // cpfg's parts: files and pipes by the .e's number of queries, shared memory by its blocks.
  PartLimits partLimits() const override {
    PartLimits limits;
    if (file_.transport == Transport::Memory) {
      limits.bytes = kToProgramBytes;
      limits.answerBytes = kFromProgramBytes;
    } else {
      limits.queries = static_cast<std::size_t>(file_.chunkLimit);
    }
    return limits;
  }

  std::string exchange(const std::string& batch) override {
    if (file_.transport == Transport::Pipes) {
      writeAll(toProgram_, batch);
      return readAnswersFromPipe();
    }
    send(batch);
    waitSemaphore();
    if (file_.transport == Transport::Memory) return readAnswersFromMemory();
    // The exchange files are confined to the folder as the model's own files are
    // (model_folder.h): a link planted in their place is not followed.
    std::string answers, failure;
    if (!ModelFolder(folder_).read(fromField_, answers, failure, kMaxAnswerFileBytes))
      fail("wrote no answer file " + (folder_ / fromField_).string() + " (" + failure + ")");
    if (answers.find("Control:") == std::string::npos) fail("answered without a Control: line");
    return answers;
  }

 private:
  // Sends the exit line, lets the program finish (or ends it) and removes what the exchange
  // made: semaphores, shared memory, the exchange files.
  void stop() {
    // The exit line; the program finishes on its own, or is ended.
    try {
      if (pid_ > 0 && !failed_ && alive()) {
        if (file_.transport == Transport::Pipes) {
          writeAll(toProgram_, std::string(kExitLine));
          char byte;
          waitReadable(fromProgram_, std::chrono::seconds(2)) && ::read(fromProgram_, &byte, 1);
        } else {
          send(std::string(kExitLine));
        }
      }
    } catch (const DiagnosticError&) {
    }
    if (toProgram_ >= 0) ::close(toProgram_);
    if (fromProgram_ >= 0) ::close(fromProgram_);
    toProgram_ = fromProgram_ = -1;
    if (pid_ > 0) {
      const auto until =
          Clock::now() + (failed_ ? std::chrono::seconds(0) : std::chrono::seconds(2));
      while (alive() && Clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      if (alive()) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, nullptr, 0);
      }
    }
    if (semaphores_ >= 0) ::semctl(semaphores_, 0, IPC_RMID);
    semaphores_ = -1;
    if (memory_ != nullptr) ::shmdt(memory_);
    memory_ = nullptr;
    if (segment_ >= 0) ::shmctl(segment_, IPC_RMID, nullptr);
    segment_ = -1;
    // What the program started (a `sleep`, a helper) ends with it.
    if (group_ > 0) ::kill(-group_, SIGKILL);
    group_ = -1;
    if (!toField_.empty()) ModelFolder(folder_).remove(toField_);
    if (!fromField_.empty()) ModelFolder(folder_).remove(fromField_);
  }

  [[noreturn]] void fail(const std::string& what) {
    failed_ = true;
    throw DiagnosticError(file_.executableWhere, "environmental program " + name_ + ": " + what);
  }

  bool alive() {
    if (pid_ <= 0) return false;
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == 0) return true;
    exitStatus_ = status;
    pid_ = -1;
    return false;
  }

  std::string deathText() const {
    if (WIFEXITED(exitStatus_))
      return "exited with status " + std::to_string(WEXITSTATUS(exitStatus_));
    if (WIFSIGNALED(exitStatus_))
      return std::string("was killed by signal ") + strsignal(WTERMSIG(exitStatus_));
    return "ended";
  }

  pid_t spawn(const std::vector<std::string>& argv, int in, int out) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const std::string folder = folder_.string();
    if (log_ != nullptr) {
      // A .e file runs the program it names: -v shows what, before it starts.
      std::string line;
      for (const std::string& a : argv) {
        if (!line.empty()) line += ' ';
        line += a.find_first_of(" \t'\"") == std::string::npos ? a : "'" + a + "'";
      }
      *log_ << printableText("environment: running " + line + " in " + folder) << std::endl;
    }
    const pid_t pid = ::fork();
    if (pid < 0) fail(std::string("cannot start: ") + std::strerror(errno));
    if (pid == 0) {
      ::setpgid(0, 0);  // its own process group, ended with it (stop())
      if (in >= 0) ::dup2(in, 0);
      if (out >= 0) ::dup2(out, 1);
      if (::chdir(folder.c_str()) != 0) ::_exit(127);
      ::execvp(args[0], args.data());
      ::_exit(127);
    }
    ::setpgid(pid, pid);  // also here, whichever runs first
    group_ = pid;
    return pid;
  }

  void startPipes(const std::vector<std::string>& argv) {
    int down[2], up[2];
    if (::pipe2(down, O_CLOEXEC) != 0 || ::pipe2(up, O_CLOEXEC) != 0) fail("cannot make its pipes");
    pid_ = spawn(argv, down[0], up[1]);
    ::close(down[0]);
    ::close(up[1]);
    toProgram_ = down[1];
    fromProgram_ = up[0];
    // The program writes one byte of value 1 as soon as it starts.
    char byte = 0;
    if (!waitReadable(fromProgram_, timeout_) || ::read(fromProgram_, &byte, 1) != 1 || byte != 1) {
      fail(alive() ? "did not start (no start byte on its standard output)"
                   : "did not start: it " + deathText());
    }
  }

  void startShared(std::vector<std::string> argv, const ProgramCommand& command) {
    // Semaphores (0, 1); the program sets the second to 0 once it runs.
    int key = static_cast<int>((static_cast<unsigned>(::getpid()) * 4u) & 0xFFFFu);
    for (int tries = 0; tries < 1000; ++tries, key = (key + 4) & 0xFFFF) {
      if (key < 4) continue;
      semaphores_ = ::semget(key, 2, IPC_CREAT | IPC_EXCL | 0600);
      if (semaphores_ < 0) continue;
      if (file_.transport == Transport::Memory) {
        segment_ =
            ::shmget(key - 1, kToProgramBytes + kFromProgramBytes, IPC_CREAT | IPC_EXCL | 0600);
        if (segment_ < 0) {
          ::semctl(semaphores_, 0, IPC_RMID);
          semaphores_ = -1;
          continue;
        }
      }
      break;
    }
    if (semaphores_ < 0) fail("cannot make its semaphores");
    if (segment_ >= 0) {
      void* at = ::shmat(segment_, nullptr, 0);
      if (at == reinterpret_cast<void*>(-1)) fail("cannot attach its shared memory");
      memory_ = static_cast<char*>(at);
      std::memset(memory_, 0, kToProgramBytes + kFromProgramBytes);
    }
    unsigned short values[2] = {0, 1};
    ::semctl(semaphores_, 0, SETALL, values);
    argv.push_back("-k");
    argv.push_back(std::to_string(key));
    if (file_.transport == Transport::Files) {
      const std::string ext = std::to_string(::getpid()) + ".0";
      argv.push_back("-ext");
      argv.push_back(ext);
      toField_ = ".to_field" + ext;
      fromField_ = ".from_field" + ext;
    }
    argv.insert(argv.end(), command.words.begin() + 1, command.words.end());
    pid_ = spawn(argv, -1, -1);
    const auto until = Clock::now() + timeout_;
    while (::semctl(semaphores_, 1, GETVAL) != 0) {
      if (!alive()) fail("did not start: it " + deathText());
      if (Clock::now() > until) fail("did not start within the time limit");
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  // Files and memory: the batch goes out and semaphore 0 is raised.
  void send(const std::string& text) {
    if (file_.transport == Transport::Files) {
      ConfinedFile out = ModelFolder(folder_).open(toField_, FileAccess::Write);
      if (!out) fail("cannot write " + (folder_ / toField_).string() + ": " + out.failure);
      writeAll(out.fd.get(), text);
    } else {
      if (text.size() > kToProgramBytes)
        fail("a batch is larger than the shared memory block (50000 bytes)");
      std::memcpy(memory_, text.data(), text.size());
      if (text.size() < kToProgramBytes) memory_[text.size()] = '\0';
    }
    sembuf raise{0, 1, 0};
    if (::semop(semaphores_, &raise, 1) != 0) fail("cannot signal it");
  }

  // Waits for semaphore 1 (the program's answer), watching that the program lives.
  void waitSemaphore() {
    const auto until = Clock::now() + timeout_;
    while (true) {
      sembuf take{1, -1, 0};
      timespec slice{0, 50'000'000};
      if (::semtimedop(semaphores_, &take, 1, &slice) == 0) return;
      if (errno != EAGAIN && errno != EINTR)
        fail(std::string("cannot wait for it: ") + std::strerror(errno));
      if (!alive()) fail("died before answering: it " + deathText());
      if (Clock::now() > until) fail("did not answer within the time limit");
    }
  }

  bool waitReadable(int fd, Clock::duration limit) {
    const auto until = Clock::now() + limit;
    while (true) {
      pollfd p{fd, POLLIN, 0};
      const int r = ::poll(&p, 1, 50);
      if (r > 0) return true;
      if (r < 0 && errno != EINTR) return false;
      if (!alive()) {
        // What it wrote before it ended can still be read.
        return ::poll(&p, 1, 0) > 0;
      }
      if (Clock::now() > until) return false;
    }
  }

  void writeAll(int fd, const std::string& text) {
    // A program that has gone away must not take this process with it through SIGPIPE.
    sigset_t pipeSignal, old;
    sigemptyset(&pipeSignal);
    sigaddset(&pipeSignal, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipeSignal, &old);
    std::size_t done = 0;
    bool broken = false;
    while (done < text.size()) {
      const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        broken = true;
        break;
      }
      done += static_cast<std::size_t>(n);
    }
    if (broken) {
      timespec none{0, 0};
      sigtimedwait(&pipeSignal, nullptr, &none);
    }
    pthread_sigmask(SIG_SETMASK, &old, nullptr);
    if (broken) fail(alive() ? "stopped reading its queries" : "died: it " + deathText());
  }

  // Answers over shared memory come in parts when they do not fit the block back: a part whose
  // control line lacks the last-part bit (4) is taken, semaphore 0 asks for the next, and the
  // parts' answers are joined under one end line, as if they had come at once.
  std::string readAnswersFromMemory() {
    std::string answers;
    for (;;) {
      const char* block = memory_ + kToProgramBytes;
      const std::string part(block, strnlen(block, kFromProgramBytes));
      const std::size_t control = part.rfind("Control:");
      if (control == std::string::npos || (control > 0 && part[control - 1] != '\n'))
        fail("answered without a Control: line");
      const int flags = std::atoi(part.c_str() + control + 8);
      if ((flags & 4) != 0) {
        if (answers.empty()) return part;
        return answers.append(part, 0, control).append(kAnswersEndLine);
      }
      answers.append(part, 0, control);
      if (answers.size() > (std::size_t{1} << 30)) fail("answered more than 1 GiB");
      sembuf raise{0, 1, 0};
      if (::semop(semaphores_, &raise, 1) != 0) fail("cannot signal it");
      waitSemaphore();
    }
  }

  std::string readAnswersFromPipe() {
    const auto until = Clock::now() + timeout_;
    std::string answers;
    std::size_t lineStart = 0;
    while (true) {
      const auto left = until - Clock::now();
      if (left <= Clock::duration::zero() || !waitReadable(fromProgram_, left)) {
        fail(alive() ? "did not answer within the time limit"
                     : "died before answering: it " + deathText());
      }
      char buffer[4096];
      const ssize_t n = ::read(fromProgram_, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const auto until = Clock::now() + std::chrono::seconds(1);
        while (alive() && Clock::now() < until)
          std::this_thread::sleep_for(std::chrono::milliseconds(5));
        fail(alive() ? "closed its output before answering"
                     : "died before answering: it " + deathText());
      }
      answers.append(buffer, static_cast<std::size_t>(n));
      if (answers.size() > (std::size_t{1} << 30)) fail("answered more than 1 GiB");
      for (std::size_t nl; (nl = answers.find('\n', lineStart)) != std::string::npos;
           lineStart = nl + 1) {
        if (answers.compare(lineStart, 8, "Control:") == 0) return answers;
      }
    }
  }

  CommunicationFile file_;
  Clock::duration timeout_;
  std::string name_;
  std::filesystem::path folder_;
  pid_t pid_ = -1;
  int exitStatus_ = 0;
  bool failed_ = false;  // after an error the program is ended, not asked to finish
  int toProgram_ = -1, fromProgram_ = -1;
  int semaphores_ = -1, segment_ = -1;
  char* memory_ = nullptr;
  std::string toField_, fromField_;  // names in folder_
  std::ostream* log_ = nullptr;
  pid_t group_ = -1;  // the program's process group
};

}  // namespace

std::unique_ptr<EnvironmentProgram> startExternalProgram(const CommunicationFile& file,
                                                         int timeoutSeconds,
                                                         Diagnostics& /*diagnostics*/,
                                                         std::ostream* log) {
  return std::make_unique<ExternalProgram>(file, timeoutSeconds, log);
}

}  // namespace hirsute
