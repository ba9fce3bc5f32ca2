#include "hirsute/lsys/preprocessor.h"

#include "hirsute/core/child_confinement.h"
#include "hirsute/core/model_folder.h"
#include "hirsute/core/program_path.h"
#include "hirsute/lsys/preprocessor_messages.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string_view>
#include <thread>

extern char** environ;

namespace hirsute {
namespace {

std::string readWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool isDirectiveName(const std::string& word) {
  static const char* const kNames[] = {"define", "undef", "include", "if",    "ifdef", "ifndef",
                                       "else",   "elif",  "endif",   "error", "line",  "pragma"};
  for (const char* name : kNames) {
    if (word == name) return true;
  }
  return false;
}

// Waits for the child `pid`, the leader of a process group of its own, to exit, at most `limit`,
// then ends every process left in its group (cpp's driver runs cc1, which a kill of the driver
// alone would leave behind, blocked or running, with no parent) and reaps the child: true with
// its status, or false when the limit passed. The group is ended before the leader is reaped, so
// that its number cannot have been given to another process. The wait wakes as the child exits
// (a pidfd polled with the time left); kernels without pidfd_open fall back to polling every
// millisecond.
bool waitForGroup(pid_t pid, std::chrono::milliseconds limit, int& status) {
  using Clock = std::chrono::steady_clock;
  const auto until = Clock::now() + limit;
  const int pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
  bool exited = false;
  for (;;) {
    siginfo_t info{};
    const int done = waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT);
    if ((done == 0 && info.si_pid == pid) || (done < 0 && errno != EINTR)) {
      exited = true;
      break;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
    if (left.count() <= 0) break;
    if (pidfd >= 0) {
      pollfd readable{pidfd, POLLIN, 0};
      (void)poll(&readable, 1, static_cast<int>(std::min<long long>(left.count() + 1, 1'000'000)));
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  if (pidfd >= 0) close(pidfd);
  kill(-pid, SIGKILL);
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return exited;
}

// A temporary file removed when it goes out of scope.
class TemporaryFile {
 public:
  TemporaryFile() {
    const char* dir = std::getenv("TMPDIR");
    path_ = std::string(dir && *dir ? dir : "/tmp") + "/hirsute-cpp-XXXXXX";
    fd_ = mkstemp(path_.data());
    if (fd_ < 0) throw DiagnosticError({}, "cannot create a temporary file: " + std::string(std::strerror(errno)));
  }
  ~TemporaryFile() {
    if (fd_ >= 0) close(fd_);
    unlink(path_.c_str());
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::string& path() const { return path_; }
  int fd() const { return fd_; }
  void write(const std::string& text) {
    const char* p = text.data();
    std::size_t left = text.size();
    while (left) {
      ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        throw DiagnosticError({}, "cannot write a temporary file: " + std::string(std::strerror(errno)));
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
  }
  std::string read() const { return readWholeFile(path_); }

 private:
  std::string path_;
  int fd_ = -1;
};

// The name an `#include "NAME"` or `#include <NAME>` line names (also `#include_next` and
// `#import`), and the 1-based column of its opening quote or bracket; false for other lines and
// for a name a macro makes. Any line that reads as a directive counts, also one in a comment:
// the check errs on the side of refusing.
bool includedName(std::string_view line, std::string& name, bool& quoted, int& column) {
  std::size_t at = 0;
  const auto blanks = [&] {
    while (at < line.size() && (line[at] == ' ' || line[at] == '\t')) ++at;
  };
  blanks();
  if (at >= line.size() || line[at] != '#') return false;
  ++at;
  blanks();
  const std::size_t word = at;
  while (at < line.size() &&
         (std::isalpha(static_cast<unsigned char>(line[at])) || line[at] == '_')) {
    ++at;
  }
  const std::string_view directive = line.substr(word, at - word);
  if (directive != "include" && directive != "include_next" && directive != "import") return false;
  blanks();
  if (at >= line.size() || (line[at] != '"' && line[at] != '<')) return false;
  quoted = line[at] == '"';
  const std::size_t close = line.find(quoted ? '"' : '>', at + 1);
  if (close == std::string_view::npos) return false;
  name = std::string(line.substr(at + 1, close - at - 1));
  column = static_cast<int>(at) + 1;
  return true;
}

// Whether ModelFolder's refusal says the file is a FIFO, socket or device (a folder, a link out
// of the folder and a `..` are left to cpp and its confinement).
bool isSpecialFile(const std::string& refusal) {
  for (const char* kind : {"it is a FIFO", "it is a socket", "it is a character device",
                           "it is a block device", "it is a special file"}) {
    if (refusal.rfind(kind, 0) == 0) return true;
  }
  return false;
}

// cpp opens an `#include`d FIFO and waits for its writer, and a device for as long as the device
// likes; Landlock cannot tell file types apart. Every name the model's files spell out in an
// `#include` is resolved beneath the folder as cpp looks for it (beside the including file for
// "NAME", then in the folder, its -I), and one that is no regular file is an error at its
// directive before cpp runs. Included files are read beneath the folder and checked in turn, each
// once, up to kMaxCheckedFiles files and 4 × maxBytes bytes; a name made by a macro, or one past
// those, is left to the run's time limit and the end of cpp's whole process group.
void refuseSpecialIncludes(const std::string& text, const std::string& fileName,
                           const std::filesystem::path& folder, std::size_t maxBytes) {
  constexpr std::size_t kMaxCheckedFiles = 4096;
  struct Pending {
    std::string text;
    std::shared_ptr<const std::string> location;
    std::filesystem::path beside;  // the including file's folder, relative to the model's
  };
  const ModelFolder model(folder.empty() ? std::filesystem::path(".") : folder);
  std::vector<Pending> pending;
  pending.push_back({text, std::make_shared<const std::string>(fileName), {}});
  std::set<std::string> checked;
  std::size_t bytesRead = 0;
  const std::size_t maxBytesRead = maxBytes > SIZE_MAX / 4 ? SIZE_MAX : 4 * maxBytes;
  while (!pending.empty()) {
    const Pending current = std::move(pending.back());
    pending.pop_back();
    int number = 0;
    for (std::size_t start = 0; start < current.text.size();) {
      std::size_t end = current.text.find('\n', start);
      if (end == std::string::npos) end = current.text.size();
      const std::string_view line(current.text.data() + start, end - start);
      start = end + 1;
      ++number;
      std::string name;
      bool quoted = false;
      int column = 0;
      if (!includedName(line, name, quoted, column) || name.empty()) continue;
      std::vector<std::string> places;
      if (quoted && !current.beside.empty()) {
        places.push_back((current.beside / name).lexically_normal().string());
      }
      places.push_back(name);
      for (const std::string& place : places) {
        const ConfinedFile opened = model.open(place, FileAccess::Read);
        if (opened.refused && isSpecialFile(opened.failure)) {
          throw DiagnosticError(SourceLocation{current.location, number, column},
                                "cannot include '" +
                                    shortenedMessage(name, kMaxPreprocessorMessageBytes) +
                                    "': " + opened.failure);
        }
        if (opened.refused) break;  // cpp's confinement refuses it in its turn
        if (!opened) continue;      // missing: cpp looks in the next place
        if (checked.size() < kMaxCheckedFiles && bytesRead < maxBytesRead &&
            checked.insert(place).second) {
          std::string included, failure;
          if (model.read(place, included, failure, maxBytes)) {
            bytesRead += included.size();
            pending.push_back({std::move(included),
                               std::make_shared<const std::string>(model.pathOf(place).string()),
                               std::filesystem::path(place).parent_path()});
          }
        }
        break;
      }
    }
  }
}
// Whether cpp's messages say that it ran out of memory (cc1: "out of memory allocating N bytes",
// or "virtual memory exhausted"): in a line of its own, not in a message about the model's
// text, which a model writes itself (`#error out of memory`).
bool ranOutOfMemory(const std::string& messages) {
  std::istringstream lines(messages);
  PreprocessorMessage message;
  for (std::string line; std::getline(lines, line);) {
    if (parsePreprocessorMessage(line, message)) continue;
    if (line.find("out of memory") != std::string::npos ||
        line.find("memory exhausted") != std::string::npos) {
      return true;
    }
  }
  return false;
}

}  // namespace

std::string prepareForTraditionalCpp(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool inBlockComment = false;
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    // At a line start outside comments: an indented directive moves to column 1.
    if (!inBlockComment && (i == 0 || text[i - 1] == '\n')) {
      std::size_t j = i;
      while (j < n && (text[j] == ' ' || text[j] == '\t')) ++j;
      if (j > i && j < n && text[j] == '#') {
        std::size_t k = j + 1;
        while (k < n && (text[k] == ' ' || text[k] == '\t')) ++k;
        std::size_t w = k;
        while (w < n && std::isalpha(static_cast<unsigned char>(text[w]))) ++w;
        if (isDirectiveName(text.substr(k, w - k))) i = j;
      }
    }
    char c = text[i];
    if (inBlockComment) {
      out += c;
      if (c == '*' && i + 1 < n && text[i + 1] == '/') {
        out += '/';
        i += 2;
        inBlockComment = false;
        continue;
      }
      ++i;
      continue;
    }
    if (c == '/' && i + 1 < n && text[i + 1] == '*') {
      out += "/*";
      i += 2;
      inBlockComment = true;
      continue;
    }
    if (c == '/' && i + 1 < n && text[i + 1] == '/') {
      while (i < n && text[i] != '\n') ++i;
      continue;
    }
    if (c == '"') {
      // A string literal runs to its closing quote or the end of the line.
      out += c;
      ++i;
      while (i < n && text[i] != '"' && text[i] != '\n') {
        if (text[i] == '\\' && i + 1 < n && text[i + 1] != '\n') out += text[i++];
        out += text[i++];
      }
      if (i < n && text[i] == '"') out += text[i++];
      continue;
    }
    out += c;
    ++i;
  }
  return out;
}

std::string preprocessFile(const std::filesystem::path& file, const PreprocessorOptions& options,
                           Diagnostics& diagnostics) {
  const std::string name = file.string();
  auto fileLocation = SourceLocation{std::make_shared<const std::string>(name), 0, 0};
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw DiagnosticError(fileLocation, "no such file");
  if (std::filesystem::is_directory(file, ec)) throw DiagnosticError(fileLocation, "is a directory, not a file");
  std::ifstream probe(file, std::ios::binary);
  if (!probe) throw DiagnosticError(fileLocation, "cannot read the file");
  probe.close();

  return preprocessText(readWholeFile(file), file, options, diagnostics);
}

std::string preprocessText(const std::string& text, const std::filesystem::path& file,
                           const PreprocessorOptions& options, Diagnostics& diagnostics) {
  const std::string name = file.string();
  auto fileLocation = SourceLocation{std::make_shared<const std::string>(name), 0, 0};
  if (text.find('\0') != std::string::npos) {
    // Find the line of the first NUL byte for the message.
    std::size_t at = text.find('\0');
    int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
    std::size_t lineStart = text.rfind('\n', at);
    int column = static_cast<int>(at - (lineStart == std::string::npos ? 0 : lineStart + 1)) + 1;
    throw DiagnosticError(SourceLocation{fileLocation.file, line, column},
                          "the file contains NUL bytes; it is not an L-system text file");
  }

  std::filesystem::path folder = file.parent_path();
  refuseSpecialIncludes(text, name, folder, options.maxOutputBytes);

  TemporaryFile input, output, errors;
  // A line marker first, so cpp names the user's file in its own markers and messages.
  std::string marked = "# 1 \"" + name + "\"\n" + prepareForTraditionalCpp(text);
  if (!marked.empty() && marked.back() != '\n') marked += '\n';
  input.write(marked);

  std::vector<std::string> args = {options.program, "-traditional-cpp", "-undef", "-nostdinc",
                                   "-x", "c", "-fno-diagnostics-show-caret"};
  args.push_back("-I" + (folder.empty() ? std::string(".") : folder.string()));
  for (const auto& [macro, value] : options.defines) args.push_back("-D" + macro + "=" + value);
  args.push_back("-");

  // cpp opens the model's #include files itself: it runs confined to reading beneath the
  // model's folder (child_confinement.h), so that an include cannot read through a link out of it.
  const std::string executable = findOnPath(options.program);
  if (executable.empty()) {
    throw DiagnosticError(fileLocation, "cannot run the C preprocessor '" + options.program +
                                            "': " + std::strerror(ENOENT) +
                                            " (scripts/install-deps.sh installs it)");
  }
  const ChildConfinement confinement(folder.empty() ? std::filesystem::path(".") : folder);
  FileDescriptor in(::open(input.path().c_str(), O_RDONLY | O_CLOEXEC));
  if (!in) throw DiagnosticError(fileLocation, "cannot read a temporary file: " + std::string(std::strerror(errno)));
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // A limit is only ever lowered: a process may already run under a smaller one (the fuzzers'
  // harness does), which it cannot raise.
  rlimit size{};
  getrlimit(RLIMIT_FSIZE, &size);
  const rlim_t wanted = static_cast<rlim_t>(options.maxOutputBytes) + 1;
  if (size.rlim_max == RLIM_INFINITY || size.rlim_max > wanted) size.rlim_max = wanted;
  if (size.rlim_cur == RLIM_INFINITY || size.rlim_cur > size.rlim_max) size.rlim_cur = size.rlim_max;
  const std::size_t memoryLimit = preprocessorMemoryLimit(options.maxOutputBytes);
  rlimit memory{};
  getrlimit(RLIMIT_AS, &memory);
  if (memory.rlim_max == RLIM_INFINITY || memory.rlim_max > memoryLimit) {
    memory.rlim_max = memoryLimit;
  }
  if (memory.rlim_cur == RLIM_INFINITY || memory.rlim_cur > memory.rlim_max) {
    memory.rlim_cur = memory.rlim_max;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    throw DiagnosticError(fileLocation, "cannot run the C preprocessor: " + std::string(std::strerror(errno)));
  }
  if (pid == 0) {
    // The child: only system calls until exec. It leads a process group of its own, which
    // waitForGroup ends as a whole.
    if (setpgid(0, 0) != 0) _exit(127);
    if (dup2(in.get(), 0) < 0 || dup2(output.fd(), 1) < 0 || dup2(errors.fd(), 2) < 0) _exit(127);
    // The text it writes is capped: past the limit cpp gets SIGXFSZ.
    if (setrlimit(RLIMIT_FSIZE, &size) != 0) _exit(127);
    // Its memory too: a macro that doubles at every level grows cc1 without end.
    if (setrlimit(RLIMIT_AS, &memory) != 0) _exit(127);
    signal(SIGXFSZ, SIG_DFL);  // an ignored signal would stay ignored across exec
    if (confinement.applyInChild() != 0) {
      static const char kMessage[] = "cannot confine the C preprocessor to the model's folder\n";
      (void)!::write(2, kMessage, sizeof kMessage - 1);
      _exit(126);
    }
    execve(executable.c_str(), argv.data(), environ);
    _exit(127);
  }
  // Also in the parent, so that the group exists before any kill of it.
  (void)setpgid(pid, pid);
  int status = 0;
  const bool timedOut = !waitForGroup(pid, std::chrono::seconds(options.timeoutSeconds), status);
  if (timedOut) {
    throw DiagnosticError(fileLocation, "the C preprocessor ran for more than its time limit of " +
                                            std::to_string(options.timeoutSeconds) +
                                            " s and was stopped (does an #include name a FIFO or "
                                            "a device through a macro?)");
  }
  // cpp's driver reports its cc1's SIGXFSZ as a failure of its own: the file's size tells.
  struct stat written {};
  const bool full = fstat(output.fd(), &written) == 0 &&
                    static_cast<std::size_t>(written.st_size) >= options.maxOutputBytes;
  if ((WIFSIGNALED(status) && WTERMSIG(status) == SIGXFSZ) ||
      (full && !(WIFEXITED(status) && WEXITSTATUS(status) == 0))) {
    throw DiagnosticError(fileLocation, "the preprocessed text is larger than " +
                                            std::to_string(options.maxOutputBytes) +
                                            " bytes (--max-source-bytes; are #include files "
                                            "included again and again?)");
  }
  const std::string messages = errors.read();
  const bool failed = !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  if (failed && ranOutOfMemory(messages)) {
    throw DiagnosticError(fileLocation, "the C preprocessor ran out of memory (its limit is " +
                                            std::to_string(memoryLimit >> 20) +
                                            " MiB, 64 times --max-source-bytes; does a macro "
                                            "expand to ever longer text?)");
  }
  std::string failure;
  if (WIFSIGNALED(status)) {
    failure =
        "killed by signal " + std::to_string(WTERMSIG(status)) + ", " + strsignal(WTERMSIG(status));
  } else if (failed) {
    failure = "exit status " + std::to_string(WEXITSTATUS(status));
  }
  reportPreprocessorMessages(messages, failure, name, folder, diagnostics);
  return output.read();
}

std::size_t preprocessorMemoryLimit(std::size_t maxOutputBytes) {
  constexpr std::size_t kFloor = std::size_t{128} << 20;
  const std::size_t scaled = maxOutputBytes > SIZE_MAX / 64 ? SIZE_MAX : 64 * maxOutputBytes;
  return std::max(kFloor, scaled);
}

}  // namespace hirsute
