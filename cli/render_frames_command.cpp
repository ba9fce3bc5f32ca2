// `hirsute render-frames DIR`: the POV-Ray scenes `hirsute simulate` wrote, rendered into PNG
// images beside them by POV-Ray, run by GNU parallel on this machine's cores or over ssh on
// others. Frames already rendered are kept, and no image appears before it is whole
// (docs/dynamics.md, "Rendering the frames").
//
// The scenes are untrusted (POV-Ray's language reads and writes files), so parallel and POV-Ray
// write only into a work folder of their own that this command makes inside DIR, confined to it
// (child_confinement.h); finished images and the job log are then renamed into DIR, which
// replaces a link planted there instead of writing through it. A scene's name reaches POV-Ray's
// option parser only when it is made of letters, digits, '.', '_' and '-'.
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "command.h"
#include "hirsute/core/child_confinement.h"
#include "hirsute/core/child_process.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/core/model_folder.h"
#include "hirsute/core/program_path.h"

namespace hirsute::cli {
namespace {

namespace fs = std::filesystem;

struct RenderFramesOptions {
  std::string folder;
  std::optional<int> width;
  std::optional<int> height;
  std::optional<int> jobs;
  std::vector<std::string> sshLogins;
  int frameTimeout = 3600;
  bool antialias = false;
  bool force = false;
  bool dryRun = false;
};

constexpr int kDefaultWidth = 800;  // simulate's own default size
constexpr int kDefaultHeight = 600;
constexpr int kMaxSide = kMaxImageSide;  // as every command that makes pictures
constexpr const char* kJobLog = "render-frames.log";
constexpr const char* kWorkPrefix = ".render-frames-";
// POV-Ray's exit status under `timeout` when a frame passed --frame-timeout (coreutils'
// timeout: 124 after SIGTERM, 128 + 9 when SIGKILL followed a second later).
constexpr int kTimedOut = 124;
constexpr int kKilledAfterTimeOut = 137;

// What each job runs, in /bin/sh whatever the user's shell: $1 the scene, $2 its name without
// .pov, $3 and $4 the size, $5 the antialiasing option, $6 the work folder, $7 the time limit.
// It marks the frame started, then POV-Ray, under `timeout` (which ends POV-Ray's whole process
// group), renders a hidden name in the work folder (it adds .png itself), renamed there only
// when it rendered; otherwise the hidden file goes and POV-Ray's last lines (its error, past its
// banner) are printed. Every name is made of letters, digits and `._-`, so that none is split or
// read as an option by POV-Ray's option parser. No single quote, no `!`, no braces: the script
// travels inside single quotes through GNU parallel and a remote login shell.
constexpr const char* kJobScript =
    R"sh(mkdir -p "$6" && : > "$6/$2.started" || exit 1; )sh"
    R"sh(o=$(timeout -k 1 "$7" povray "+I$1" "+O$6/.$2.part.png" "+W$3" "+H$4" "$5" -D +FN 2>&1); )sh"
    R"sh(s=$?; if [ $s -eq 0 ] && [ -s "$6/.$2.part.png" ] && )sh"
    R"sh(mv -f "$6/.$2.part.png" "$6/$2.png"; then exit 0; fi; rm -f "$6/.$2.part.png"; )sh"
    R"sh(if [ $s -ne 124 ] && [ $s -ne 137 ]; then printf "%s\n" "$o" | tail -n 6 >&2; fi; )sh"
    R"sh([ $s -eq 0 ] && s=1; exit $s)sh";

// Whether `name` can be handed to POV-Ray and parallel as it is: letters, digits, '.', '_' and
// '-' only (POV-Ray's option parser splits at spaces and reads quotes and +/- as options).
bool plainName(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
           c == '_' || c == '-';
  });
}

// One scene to render; names are file names in the folder.
struct Frame {
  std::string scene;                  // frame-0007.pov
  std::string stem;                   // frame-0007
  std::vector<std::string> textures;  // frame-0007_texture1.png, … written beside it
};

// The status of `file` itself (a link is not followed) when it is a regular file.
std::optional<struct stat> regularFileStatus(const fs::path& file) {
  struct stat st {};
  if (lstat(file.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  return st;
}

bool modifiedAfter(const struct stat& a, const struct stat& b) {
  return a.st_mtim.tv_sec != b.st_mtim.tv_sec ? a.st_mtim.tv_sec > b.st_mtim.tv_sec
                                              : a.st_mtim.tv_nsec > b.st_mtim.tv_nsec;
}

// Whether `image` is a whole PNG: it starts with the PNG signature and ends with the IEND chunk
// (PNG specification, 5.2 and 11.2.5), so that a file cut short is rendered again.
bool wholePng(const fs::path& image) {
  constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  constexpr std::array<unsigned char, 12> kEnd = {0,   0,   0,    0,    'I',  'E',
                                                  'N', 'D', 0xae, 0x42, 0x60, 0x82};
  std::ifstream in(image, std::ios::binary);
  std::array<char, 8> start{};
  std::array<char, 12> end{};
  if (!in.read(start.data(), start.size())) return false;
  if (!in.seekg(-static_cast<std::streamoff>(end.size()), std::ios::end)) return false;
  if (!in.read(end.data(), end.size())) return false;
  return std::equal(start.begin(), start.end(), kSignature.begin(),
                    [](char c, unsigned char u) { return static_cast<unsigned char>(c) == u; }) &&
         std::equal(end.begin(), end.end(), kEnd.begin(),
                    [](char c, unsigned char u) { return static_cast<unsigned char>(c) == u; });
}

// Whether the frame has its image already: a whole PNG, written after its scene.
bool rendered(const fs::path& folder, const Frame& frame) {
  const auto scene = regularFileStatus(folder / frame.scene);
  const auto image = regularFileStatus(folder / (frame.stem + ".png"));
  return scene && image && image->st_size > 0 && modifiedAfter(*image, *scene) &&
         wholePng(folder / (frame.stem + ".png"));
}

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.size() >= prefix.size() && text.compare(0, prefix.size(), prefix) == 0;
}

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The frame whose texture `name` is, when it is one: the POV-Ray writer names a scene's
// textures STEM_textureN.png beside it (viewer/export/texture_file.cpp).
std::optional<std::string> textureOwner(const std::string& name) {
  const std::size_t at = name.rfind("_texture");
  if (at == std::string::npos || !startsWith(name, "frame-") || !endsWith(name, ".png"))
    return std::nullopt;
  const std::string number = name.substr(at + 8, name.size() - at - 8 - 4);
  if (number.empty() ||
      !std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  return name.substr(0, at);
}

// The folder's scenes, frame-*.pov, in order, with their textures. Only regular files with plain
// names count: a link or a name POV-Ray would misread is left out with a warning, so that
// nothing outside the folder is read and no name becomes an option.
std::vector<Frame> framesIn(const fs::path& folder) {
  std::vector<Frame> frames;
  std::map<std::string, std::vector<std::string>> textures;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (const auto owner = textureOwner(name)) {
      if (regularFileStatus(entry.path()) && plainName(name)) textures[*owner].push_back(name);
      continue;
    }
    if (!startsWith(name, "frame-") || !endsWith(name, ".pov") || name.size() <= 10) continue;
    if (!regularFileStatus(entry.path())) {
      std::cerr << printableText((folder / name).string())
                << ": warning: not a regular file; left out\n";
      continue;
    }
    if (!plainName(name)) {
      std::cerr << printableText((folder / name).string())
                << ": warning: a scene's name may hold only letters, digits, '.', '_' and '-' "
                   "(POV-Ray would read the others as options); left out\n";
      continue;
    }
    frames.push_back({name, name.substr(0, name.size() - 4), {}});
  }
  std::sort(frames.begin(), frames.end(),
            [](const Frame& a, const Frame& b) { return a.scene < b.scene; });
  for (Frame& frame : frames) {
    auto found = textures.find(frame.stem);
    if (found == textures.end()) continue;
    frame.textures = found->second;
    std::sort(frame.textures.begin(), frame.textures.end());
  }
  return frames;
}

// The image size a scene was written for, from the render line at its top that the POV-Ray
// writer puts there ("// Render: povray +Iframe-0001.pov +Oframe-0001.png +W800 +H600 …"); the
// camera's aspect ratio is fitted to it. A size past the limits counts as none.
std::optional<std::pair<int, int>> sizeWrittenFor(const fs::path& scene) {
  std::ifstream in(scene);
  std::string line;
  for (int i = 0; i < 4 && std::getline(in, line); ++i) {
    if (!startsWith(line, "// Render: povray ")) continue;
    const std::size_t w = line.find(" +W");
    const std::size_t h = line.find(" +H");
    if (w == std::string::npos || h == std::string::npos) return std::nullopt;
    const long width = std::strtol(line.c_str() + w + 3, nullptr, 10);
    const long height = std::strtol(line.c_str() + h + 3, nullptr, 10);
    if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide) return std::nullopt;
    return std::pair{width, height};
  }
  return std::nullopt;
}

// `word` as a POSIX shell reads it back, for the dry run's printout.
std::string shellQuoted(const std::string& word) {
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("+-_./:=,%@", c) != nullptr;
  });
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) {
    if (c == '\'')
      quoted += "'\\''";
    else
      quoted += c;
  }
  quoted += "'";
  return quoted;
}

// Whether an --sshlogin names this machine (`:`, alone or in a comma-separated list, perhaps
// after a job count as in `4/:`).
bool namesThisMachine(const std::string& sshLogin) {
  std::size_t start = 0;
  while (start <= sshLogin.size()) {
    std::size_t end = sshLogin.find(',', start);
    if (end == std::string::npos) end = sshLogin.size();
    std::string host = sshLogin.substr(start, end - start);
    const std::size_t slash = host.find('/');
    if (slash != std::string::npos) host = host.substr(slash + 1);
    if (host == ":") return true;
    start = end + 1;
  }
  return false;
}

// The file access a scene asks of POV-Ray, when it asks for one: `#fopen`, `#read`, `#write`,
// `#include` (also of the include files POV-Ray ships, since strings.inc's Parse_String writes
// and includes a file of its own) or a string naming a path ('/' in it). A host of --sshlogin runs
// POV-Ray where this machine cannot confine it, so such a scene does not travel.
std::optional<std::string> fileAccessIn(const fs::path& scene) {
  // Read as it streams (a scene of hairs may be hundreds of megabytes), past comments.
  enum class State { Code, Slash, String, Escape, LineComment, BlockComment, BlockStar, Directive };
  State state = State::Code;
  std::string word;
  const auto code = [&](char c) {
    if (c == '"') {
      state = State::String;
    } else if (c == '/') {
      state = State::Slash;
    } else if (c == '#') {
      state = State::Directive;
      word.clear();
    } else {
      state = State::Code;
    }
  };
  std::ifstream in(scene, std::ios::binary);
  for (std::istreambuf_iterator<char> it(in), end; it != end; ++it) {
    const char c = *it;
    switch (state) {
      case State::Code:
        code(c);
        break;
      case State::Slash:
        if (c == '/')
          state = State::LineComment;
        else if (c == '*')
          state = State::BlockComment;
        else
          code(c);
        break;
      case State::String:
        if (c == '/') return std::string("a path in a string");
        if (c == '\\') state = State::Escape;
        if (c == '"') state = State::Code;
        break;
      case State::Escape:
        state = State::String;
        break;
      case State::LineComment:
        if (c == '\n') state = State::Code;
        break;
      case State::BlockComment:
        if (c == '*') state = State::BlockStar;
        break;
      case State::BlockStar:
        state = c == '/' ? State::Code : c == '*' ? State::BlockStar : State::BlockComment;
        break;
      case State::Directive:
        if ((c == ' ' || c == '\t') && word.empty()) break;
        if (std::isalpha(static_cast<unsigned char>(c)) && word.size() < 16) {
          word += c;
          break;
        }
        for (const char* directive : {"fopen", "read", "write", "include"})
          if (word == directive) return "#" + word;
        code(c);
        break;
    }
  }
  if (state == State::Directive)
    for (const char* directive : {"fopen", "read", "write", "include"})
      if (word == directive) return "#" + word;
  return std::nullopt;
}

// A folder of this run's own inside DIR (.render-frames-XXXXXX, mode 0700) where parallel and
// POV-Ray write; removed with everything in it when the run ends.
class WorkFolder {
 public:
  explicit WorkFolder(const fs::path& folder) {
    std::string name = (folder / kWorkPrefix).string() + "XXXXXX";
    if (!mkdtemp(name.data())) {
      failure_ = std::strerror(errno);
      return;
    }
    path_ = name;
    fd_ = FileDescriptor(::open(name.c_str(), O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    if (!fd_) failure_ = std::strerror(errno);
  }
  ~WorkFolder() {
    std::error_code ignored;
    if (!path_.empty()) fs::remove_all(path_, ignored);  // links in it are removed, not followed
  }
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;

  explicit operator bool() const { return static_cast<bool>(fd_); }
  const std::string& failure() const { return failure_; }
  const fs::path& path() const { return path_; }
  std::string name() const { return path_.filename().string(); }
  int fd() const { return fd_.get(); }

 private:
  fs::path path_;
  FileDescriptor fd_;
  std::string failure_;
};

// GNU parallel's arguments (after the program) for the frames: their scene names come on its
// standard input, NUL-separated, each followed by its textures separated by `/` (which no file
// name holds) when they travel to other hosts. `work` is the work folder's name in DIR.
std::vector<std::string> parallelArguments(const RenderFramesOptions& o, int width, int height,
                                           std::size_t texturesPerFrame, const std::string& work) {
  std::vector<std::string> args = {"--joblog", work + "/" + kJobLog, "--null", "--tagstring",
                                   "{1}"};
  if (o.jobs) {
    args.push_back("--jobs");
    args.push_back(std::to_string(*o.jobs));
  } else if (o.sshLogins.empty()) {
    // Parallel counts the cores in /proc, which it may not read here (it runs confined).
    args.push_back("--jobs");
    args.push_back(std::to_string(std::max(1u, std::thread::hardware_concurrency())));
  }
  if (!o.sshLogins.empty()) {
    for (const std::string& login : o.sshLogins) {
      args.push_back("--sshlogin");
      args.push_back(login);
    }
    // Each job in a folder of its own on its host (~/.parallel/tmp/…), removed afterwards: the
    // scene and its textures go out, the image comes back into the work folder (rsync writes it
    // under a temporary name and renames it).
    args.insert(args.end(), {"--workdir", "...", "--transferfile", "{1}"});
    if (texturesPerFrame > 0) args.insert(args.end(), {"--colsep", "/"});
    for (std::size_t i = 0; i < texturesPerFrame; ++i) {
      args.push_back("--transferfile");
      std::string column = "{";
      column += std::to_string(i + 2);
      column += "}";
      args.push_back(column);
    }
    args.insert(args.end(), {"--return", work + "/{1.}.png", "--cleanup"});
  }
  // One word: parallel hands it to the shell with {1} and {1.} replaced, quoted.
  std::string command = "sh -c '";
  command += kJobScript;
  command += "' sh {1} {1.} ";
  command += std::to_string(width);
  command += ' ';
  command += std::to_string(height);
  command += o.antialias ? " +A0.3 " : " -A ";
  command += work;
  command += ' ';
  command += std::to_string(o.frameTimeout);
  args.push_back(command);
  return args;
}

// What parallel reads: each frame's scene, NUL-terminated; with textures that travel, the
// scene's columns padded to `texturesPerFrame` (with the scene again) so that every
// --transferfile names a file.
std::string parallelInput(const std::vector<Frame*>& frames, std::size_t texturesPerFrame) {
  std::string input;
  for (const Frame* frame : frames) {
    input += frame->scene;
    for (std::size_t i = 0; i < texturesPerFrame; ++i) {
      input += '/';
      input += i < frame->textures.size() ? frame->textures[i] : frame->scene;
    }
    input += '\0';
  }
  return input;
}

// A job's line of parallel's job log: "Seq Host Starttime JobRuntime Send Receive Exitval
// Signal Command", tab-separated; Seq counts the frames from 1 in the order they were given.
struct JobRecord {
  int exitStatus = 0;
  int signal = 0;
};

std::map<std::size_t, JobRecord> readJobLog(int workFd) {
  std::map<std::size_t, JobRecord> jobs;
  FileDescriptor log(::openat(workFd, kJobLog, O_RDONLY | O_NOFOLLOW | O_CLOEXEC));
  if (!log) return jobs;
  std::string text;
  char buffer[65536];
  for (ssize_t n; (n = ::read(log.get(), buffer, sizeof buffer)) > 0;)
    text.append(buffer, static_cast<std::size_t>(n));
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::istringstream columns(line);
    for (std::string field; fields.size() < 8 && std::getline(columns, field, '\t');)
      fields.push_back(field);
    if (fields.size() < 8 || fields[0].empty() ||
        !std::isdigit(static_cast<unsigned char>(fields[0][0])))
      continue;
    jobs[std::strtoul(fields[0].c_str(), nullptr, 10)] = {std::atoi(fields[6].c_str()),
                                                          std::atoi(fields[7].c_str())};
  }
  return jobs;
}

// Renames `name` from the work folder into DIR. A link in DIR is replaced, never followed;
// a folder, FIFO or device there is left as it is (false, with the reason).
bool moveIntoFolder(int workFd, int folderFd, const std::string& name, std::string& failure) {
  struct stat there {};
  if (fstatat(folderFd, name.c_str(), &there, AT_SYMLINK_NOFOLLOW) == 0 &&
      !S_ISREG(there.st_mode) && !S_ISLNK(there.st_mode)) {
    failure = "is no regular file; it is left as it is";
    return false;
  }
  if (renameat(workFd, name.c_str(), folderFd, name.c_str()) != 0) {
    failure = std::string("cannot write: ") + std::strerror(errno);
    return false;
  }
  return true;
}

// Whether the work folder holds `name` as a regular file (a link is none).
bool workHolds(int workFd, const std::string& name) {
  struct stat st {};
  return fstatat(workFd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode);
}

// Prints what parallel and its jobs say, line by line, with their control bytes escaped: a
// scene's text (in POV-Ray's error) must not reach the terminal raw.
class EscapedLines {
 public:
  explicit EscapedLines(Progress& progress) : progress_(progress) {}
  void add(std::string_view text) {
    pending_.append(text);
    for (std::size_t end; (end = pending_.find('\n')) != std::string::npos;) {
      progress_.clear();
      std::cerr << printableText(pending_.substr(0, end)) << '\n';
      pending_.erase(0, end + 1);
    }
  }
  // The last line, when it had no newline.
  void finish() {
    progress_.clear();
    if (!pending_.empty()) std::cerr << printableText(pending_) << '\n';
    pending_.clear();
  }

 private:
  Progress& progress_;
  std::string pending_;
};

// The progress line while parallel runs: the frames finished (rendered or failed) of those it
// was given, from its job log, which it writes a line to as each job ends.
void showFramesFinished(Progress& progress, int workFd) {
  std::size_t finished = 0, failed = 0;
  for (const auto& [seq, job] : readJobLog(workFd)) {
    ++finished;
    if (job.exitStatus != 0 || job.signal != 0) ++failed;
  }
  progress.note(failed > 0 ? fmt::format(", {} failed", failed) : std::string());
  progress.update(static_cast<double>(finished));
}

int runRenderFrames(const RenderFramesOptions& o) {
  // DIR is the user's choice, link or not; everything beneath it is reached without links.
  std::error_code error;
  const fs::path folder = fs::canonical(o.folder, error);
  FileDescriptor folderFd(::open(o.folder.c_str(), O_DIRECTORY | O_CLOEXEC));
  if (error || !folderFd) {
    std::cerr << "hirsute: error: " << printableText(o.folder)
              << ": cannot open: " << (error ? error.message() : std::strerror(errno)) << '\n';
    return kExitBadInput;
  }
  std::vector<Frame> frames = framesIn(folder);
  if (frames.empty()) {
    std::cerr << "hirsute: error: " << printableText(o.folder)
              << " holds no frame-*.pov scenes (hirsute simulate writes them)\n";
    return kExitBadInput;
  }
  for (const std::string& login : o.sshLogins) {
    if (namesThisMachine(login)) {
      std::cerr << "hirsute: error: --sshlogin " << printableText(login)
                << ": ':' (this machine) cannot be one of the hosts, since each host renders in "
                   "a folder of its own that this machine's jobs would not see; name it as "
                   "localhost, or leave --sshlogin out to render here\n";
      return kExitBadInput;
    }
  }

  std::vector<Frame*> toRender;
  std::size_t refused = 0;
  for (Frame& frame : frames) {
    if (!o.force && rendered(folder, frame)) continue;
    if (!o.sshLogins.empty()) {
      if (const auto access = fileAccessIn(folder / frame.scene)) {
        std::cerr << (folder / frame.scene).string() << ": error: the scene uses " << *access
                  << ", and the hosts of --sshlogin run POV-Ray unconfined; render it here\n";
        ++refused;
        continue;
      }
    }
    toRender.push_back(&frame);
  }
  const std::size_t alreadyDone = frames.size() - toRender.size() - refused;
  struct Counts {
    std::size_t rendered = 0, failed = 0, stopped = 0, notStarted = 0;
  };
  const auto summary = [&](const Counts& c, double seconds) {
    std::cout << fmt::format(
        "{} frame{}: {} rendered, {} already done, {} failed{}, {} not started in {:.1f} s\n",
        frames.size(), frames.size() == 1 ? "" : "s", c.rendered, alreadyDone, c.failed,
        c.stopped > 0 ? fmt::format(", {} stopped while rendering", c.stopped) : std::string(),
        c.notStarted, seconds);
  };
  if (toRender.empty()) {
    summary({0, refused, 0, 0}, 0);
    return refused == 0 ? kExitOk : kExitIoError;
  }

  const std::string parallel = findOnPath("parallel");
  if (parallel.empty()) {
    std::cerr << "hirsute: error: GNU parallel is not on the PATH (Debian's package parallel; "
                 "scripts/install-deps.sh installs it)\n";
    return kExitBadInput;
  }
  const std::string povray = findOnPath("povray");
  if (o.sshLogins.empty() && povray.empty()) {
    std::cerr << "hirsute: error: povray is not on the PATH (Debian's package povray; "
                 "scripts/install-deps.sh installs it)\n";
    return kExitBadInput;
  }
  const auto written = sizeWrittenFor(folder / toRender.front()->scene);
  const int width = o.width.value_or(written ? written->first : kDefaultWidth);
  const int height = o.height.value_or(written ? written->second : kDefaultHeight);
  std::size_t texturesPerFrame = 0;
  if (!o.sshLogins.empty())
    for (const Frame* frame : toRender)
      texturesPerFrame = std::max(texturesPerFrame, frame->textures.size());

  if (o.dryRun) {
    const std::vector<std::string> arguments =
        parallelArguments(o, width, height, texturesPerFrame, std::string(kWorkPrefix) + "XXXXXX");
    std::cout << "in " << shellQuoted(printableText(folder.string()))
              << (texturesPerFrame > 0 ? ", with each frame's scene and textures ('/'-separated)"
                                       : ", with each frame's scene")
              << " NUL-terminated on its standard input:\n"
              << shellQuoted(printableText(parallel));
    for (const std::string& a : arguments) std::cout << ' ' << shellQuoted(a);
    std::cout << '\n';
    for (const Frame* frame : toRender) {
      std::cout << frame->scene;
      if (texturesPerFrame > 0)
        for (const std::string& texture : frame->textures) std::cout << ' ' << texture;
      std::cout << '\n';
    }
    std::cout << fmt::format("{} frame{}: {} to render, {} already done{}\n", frames.size(),
                             frames.size() == 1 ? "" : "s", toRender.size(), alreadyDone,
                             refused > 0 ? fmt::format(", {} refused", refused) : std::string());
    return kExitOk;
  }

  const WorkFolder work(folder);
  if (!work) {
    std::cerr << "hirsute: error: " << printableText(folder.string())
              << ": cannot make a work folder in it: " << work.failure() << '\n';
    return kExitIoError;
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> list(std::tmpfile(), std::fclose);
  const std::string input = parallelInput(toRender, texturesPerFrame);
  if (!list || std::fwrite(input.data(), 1, input.size(), list.get()) != input.size() ||
      std::fflush(list.get()) != 0 || std::fseek(list.get(), 0, SEEK_SET) != 0) {
    std::cerr << "hirsute: error: cannot write the list of frames to a temporary file: "
              << std::strerror(errno) << '\n';
    return kExitIoError;
  }

  // Here, parallel and all it starts read beneath DIR and POV-Ray's own folders and write in the
  // work folder only. Remote hosts run the jobs out of reach; ssh and rsync here need the
  // user's keys and settings, so parallel runs unconfined then (the scenes that travel ask
  // for no file, fileAccessIn).
  ConfinementRules rules;
  rules.read = {folder, "/usr/share/povray-3.7", "/etc/povray"};
  rules.write = {work.path()};
  rules.run = {fs::canonical(parallel, error)};
  if (!povray.empty()) rules.run.push_back(fs::canonical(povray, error));
  rules.devices = {"/dev/null", "/dev/urandom"};
  const ChildConfinement confinement(rules);
  if (o.sshLogins.empty() && !confinement.available())
    std::cerr << "hirsute: warning: this kernel has no Landlock; POV-Ray runs unconfined\n";

  ChildRequest request;
  request.program = fs::absolute(parallel).string();
  request.arguments = {"parallel"};
  const std::vector<std::string> arguments =
      parallelArguments(o, width, height, texturesPerFrame, work.name());
  request.arguments.insert(request.arguments.end(), arguments.begin(), arguments.end());
  // Its jobs' shell is /bin/sh, not the user's (which may be csh or fish); its temporary files
  // go in the work folder.
  request.environment =
      environmentWith({"PARALLEL_SHELL=/bin/sh", "TMPDIR=" + work.path().string()});
  request.folder = folder;
  request.input = fileno(list.get());
  if (o.sshLogins.empty()) request.confinement = &confinement;
  Progress progress = Progress::onTerminal(stderr);
  EscapedLines lines(progress);
  request.onOutput = [&lines](std::string_view text) { lines.add(text); };
  if (progress.enabled()) {
    progress.begin("rendering frames", Progress::Unit::Steps, static_cast<double>(toRender.size()),
                   "frames");
    request.whileRunning = [&progress, &work] { showFramesFinished(progress, work.fd()); };
  }
  const auto start = std::chrono::steady_clock::now();
  const ChildResult run = runChild(request);
  lines.finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!run.started) {
    std::cerr << "hirsute: error: " << printableText(run.failure) << '\n';
    return kExitIoError;
  }

  // Whole images go into DIR; what the jobs left half-done goes with the work folder.
  const std::map<std::size_t, JobRecord> jobs = readJobLog(work.fd());
  Counts counts;
  counts.failed = refused;
  std::size_t seq = 0;
  for (const Frame* frame : toRender) {
    ++seq;
    const std::string image = frame->stem + ".png";
    const fs::path scene = folder / frame->scene;
    std::string failure;
    if (workHolds(work.fd(), image) && wholePng(work.path() / image)) {
      if (moveIntoFolder(work.fd(), folderFd.get(), image, failure)) {
        ++counts.rendered;
      } else {
        std::cerr << (folder / image).string() << ": error: " << failure << '\n';
        ++counts.failed;
      }
      continue;
    }
    const auto job = jobs.find(seq);
    if (job != jobs.end()) {
      ++counts.failed;
      const int status = job->second.exitStatus;
      if (status == kTimedOut || status == kKilledAfterTimeOut) {
        std::cerr << scene.string() << ": error: not rendered: POV-Ray ran for more than "
                  << o.frameTimeout << " s (--frame-timeout) and was stopped\n";
      } else {
        std::cerr << scene.string() << ": error: not rendered\n";
      }
    } else if (workHolds(work.fd(), frame->stem + ".started")) {
      ++counts.stopped;
    } else {
      ++counts.notStarted;
    }
  }
  std::string failure;
  const bool logKept =
      workHolds(work.fd(), kJobLog) && moveIntoFolder(work.fd(), folderFd.get(), kJobLog, failure);
  if (!failure.empty())
    std::cerr << (folder / kJobLog).string() << ": warning: the job log " << failure << '\n';
  if (run.interruptedBy != 0) {
    std::cerr << "hirsute: stopped by signal " << run.interruptedBy
              << "; parallel and POV-Ray were ended, and a second run renders what is missing\n";
  } else if (run.exitStatus == 255 || run.signal != 0) {
    std::cerr << "hirsute: error: parallel stopped before the end ("
              << (run.signal != 0 ? "signal " + std::to_string(run.signal)
                                  : std::string("exit status 255"))
              << ")\n";
  }
  if (counts.failed > refused && logKept)
    std::cerr << "hirsute: the jobs and their exit codes are in " << (folder / kJobLog).string()
              << '\n';
  summary(counts, seconds);
  if (run.interruptedBy != 0) return 128 + run.interruptedBy;
  return counts.failed + counts.stopped + counts.notStarted == 0 ? kExitOk : kExitIoError;
}

}  // namespace

void registerRenderFramesCommand(CLI::App& app, Action& action) {
  auto o = std::make_shared<RenderFramesOptions>();
  CLI::App* command = app.add_subcommand(
      "render-frames",
      "Render the POV-Ray frames of `hirsute simulate` (DIR/frame-*.pov) into PNG images beside "
      "them with POV-Ray under GNU parallel, here or on other machines; frames already rendered "
      "are kept");
  command->add_option("folder", o->folder, "The folder of the frames (simulate's -o DIR)")
      ->required()
      ->check(CLI::ExistingDirectory);
  addImageSizeOption(*command, o->width, o->height,
                     "The pictures' size in pixels, WIDTHxHEIGHT (default: the size the scenes "
                     "were written for, else 800x600)");
  command
      ->add_option("-j,--jobs", o->jobs,
                   "Frames rendered at once on each machine (default: one a core)")
      ->check(CLI::Range(1, 100000));
  command
      ->add_option("-S,--sshlogin", o->sshLogins,
                   "A host to render on over ssh, as GNU parallel's --sshlogin takes it "
                   "([N/][user@]host, or several separated by commas); repeatable")
      ->allow_extra_args(false);
  command
      ->add_option("--frame-timeout", o->frameTimeout,
                   "Seconds a frame may render before POV-Ray is stopped and the frame fails "
                   "(default 3600)")
      ->check(CLI::Range(1, 7 * 24 * 3600));
  command->add_flag("--antialias", o->antialias, "Anti-alias (POV-Ray's +A0.3)");
  command->add_flag("--force", o->force, "Render every frame, also those already rendered");
  command->add_flag(
      "--dry-run", o->dryRun,
      "Print the parallel command and the frames it would render, and render nothing");
  command->callback([o, &action] { action = [o] { return runRenderFrames(*o); }; });
}

}  // namespace hirsute::cli
