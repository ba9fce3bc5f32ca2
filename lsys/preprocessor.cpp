#include "hirsute/lsys/preprocessor.h"

#include "hirsute/core/child_confinement.h"
#include "hirsute/core/model_folder.h"
#include "hirsute/core/program_path.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/syscall.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
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

// Waits for the child `pid` to exit, at most `limit`: true with its status, or false after
// killing and reaping it when the limit passed. The wait wakes as the child exits (a pidfd
// polled with the time left), so a fast cpp costs no more than it runs; kernels without
// pidfd_open fall back to polling every millisecond.
bool waitForExit(pid_t pid, std::chrono::milliseconds limit, int& status) {
  using Clock = std::chrono::steady_clock;
  const auto until = Clock::now() + limit;
  const int pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid || (done < 0 && errno != EINTR)) break;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
    if (left.count() <= 0) {
      kill(pid, SIGKILL);
      while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      if (pidfd >= 0) close(pidfd);
      return false;
    }
    if (pidfd >= 0) {
      pollfd readable{pidfd, POLLIN, 0};
      (void)poll(&readable, 1, static_cast<int>(std::min<long long>(left.count() + 1, 1'000'000)));
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  if (pidfd >= 0) close(pidfd);
  return true;
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

// Traditional-mode cpp reports a missing `#include` file one line late, at the word `include`.
// Moves `where` to the file name on the directive's own line, as the user would look for it.
// The file is read beneath the model's folder (a `#line` may name any file).
void locateMissingInclude(SourceLocation& where, const std::string& header,
                          const std::filesystem::path& folder) {
  const ModelFolder model(folder.empty() ? std::filesystem::path(".") : folder);
  const std::filesystem::path file(where.fileName());
  std::string source, failure;
  const std::string relative =
      file.is_absolute() == model.path().is_absolute()
          ? file.lexically_relative(model.path()).string()
          : std::string();
  if (relative.empty() || !model.read(relative, source, failure, std::size_t{64} << 20)) return;
  std::istringstream in(source);
  std::string text;
  for (int number = 1; std::getline(in, text) && number <= where.line; ++number) {
    if (number < where.line - 1) continue;
    std::size_t directive = text.find('#');
    std::size_t include = text.find("include", directive == std::string::npos ? 0 : directive);
    if (directive == std::string::npos || include == std::string::npos) continue;
    std::size_t name = text.find(header, include);
    // cpp names a file found through -I by its path there; the line has the name as written.
    if (name == std::string::npos) {
      const std::string written = std::filesystem::path(header).filename().string();
      name = written.empty() ? std::string::npos : text.find(written, include);
      if (name != std::string::npos) name = text.find_last_of("\"<", name);
      if (name != std::string::npos) ++name;
    }
    if (name == std::string::npos || name == 0) continue;
    where.line = number;
    where.column = static_cast<int>(name);  // the opening quote or angle bracket, 1-based
    return;
  }
}

// A line number or column as cpp printed it; absurd values (a `#line` beyond int) read as 0.
int cppNumber(const std::string& digits) {
  return digits.size() > 9 ? 0 : std::stoi(digits);
}

// Turns cpp's messages into diagnostics: the first error is thrown, warnings are passed on.
void reportCppMessages(const std::string& messages, bool failed, const std::string& fallbackFile,
                       const std::filesystem::path& folder, Diagnostics& diagnostics) {
  static const std::regex kLine(R"(^(.*?):(\d+):(?:(\d+):)? *(fatal error|error|warning): (.*)$)");
  std::istringstream lines(messages);
  std::string line;
  while (std::getline(lines, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, kLine)) continue;
    SourceLocation where{std::make_shared<const std::string>(m[1].str()), cppNumber(m[2].str()),
                         m[3].matched ? cppNumber(m[3].str()) : 0};
    const std::string message = m[5].str();
    if (m[4].str() == "warning") {
      diagnostics.warn(where, message);
      continue;
    }
    static const std::string kMissing = ": No such file or directory";
    if (message.size() > kMissing.size() &&
        message.compare(message.size() - kMissing.size(), kMissing.size(), kMissing) == 0) {
      locateMissingInclude(where, message.substr(0, message.size() - kMissing.size()), folder);
    }
    // The confinement's refusal (child_confinement.h) reads as a denied permission.
    static const std::string kDenied = ": Permission denied";
    if (message.size() > kDenied.size() &&
        message.compare(message.size() - kDenied.size(), kDenied.size(), kDenied) == 0) {
      locateMissingInclude(where, message.substr(0, message.size() - kDenied.size()), folder);
      throw DiagnosticError(where, message +
                                       " (an #include reads only files beneath the model's "
                                       "folder; no link out of it is followed)");
    }
    throw DiagnosticError(where, message);
  }
  if (failed) {
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(fallbackFile), 0, 0},
                          "the C preprocessor failed: " + messages);
  }
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

  TemporaryFile input, output, errors;
  // A line marker first, so cpp names the user's file in its own markers and messages.
  std::string marked = "# 1 \"" + name + "\"\n" + prepareForTraditionalCpp(text);
  if (!marked.empty() && marked.back() != '\n') marked += '\n';
  input.write(marked);

  std::vector<std::string> args = {options.program, "-traditional-cpp", "-undef", "-nostdinc",
                                   "-x", "c", "-fno-diagnostics-show-caret"};
  std::filesystem::path folder = file.parent_path();
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
  const pid_t pid = fork();
  if (pid < 0) {
    throw DiagnosticError(fileLocation, "cannot run the C preprocessor: " + std::string(std::strerror(errno)));
  }
  if (pid == 0) {
    // The child: only system calls until exec.
    if (dup2(in.get(), 0) < 0 || dup2(output.fd(), 1) < 0 || dup2(errors.fd(), 2) < 0) _exit(127);
    // The text it writes is capped: past the limit cpp gets SIGXFSZ.
    if (setrlimit(RLIMIT_FSIZE, &size) != 0) _exit(127);
    signal(SIGXFSZ, SIG_DFL);  // an ignored signal would stay ignored across exec
    if (confinement.applyInChild() != 0) {
      static const char kMessage[] = "cannot confine the C preprocessor to the model's folder\n";
      (void)!::write(2, kMessage, sizeof kMessage - 1);
      _exit(126);
    }
    execve(executable.c_str(), argv.data(), environ);
    _exit(127);
  }
  int status = 0;
  const bool timedOut = !waitForExit(pid, std::chrono::seconds(options.timeoutSeconds), status);
  if (timedOut) {
    throw DiagnosticError(fileLocation, "the C preprocessor ran for more than " +
                                            std::to_string(options.timeoutSeconds) +
                                            " s (an #include of a FIFO or a device waits for "
                                            "ever); it was stopped");
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
  bool failed = !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  reportCppMessages(errors.read(), failed, name, folder, diagnostics);
  return output.read();
}

}  // namespace hirsute
