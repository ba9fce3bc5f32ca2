// `hirsute render-frames DIR`: the POV-Ray scenes `hirsute simulate` wrote, rendered into PNG
// images beside them by POV-Ray, run by GNU parallel on this machine's cores or over ssh on
// others. Frames already rendered are kept, and no image appears before it is whole
// (docs/dynamics.md, "Rendering the frames").
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
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
#include <string>
#include <utility>
#include <vector>

#include "command.h"
#include "hirsute/core/program_path.h"

extern char** environ;

namespace hirsute::cli {
namespace {

namespace fs = std::filesystem;

struct RenderFramesOptions {
  std::string folder;
  std::optional<int> width;
  std::optional<int> height;
  std::optional<int> jobs;
  std::vector<std::string> sshLogins;
  bool antialias = false;
  bool force = false;
  bool dryRun = false;
};

constexpr int kDefaultWidth = 800;  // simulate's own default size
constexpr int kDefaultHeight = 600;
constexpr const char* kJobLog = "render-frames.log";

// What each job runs, in /bin/sh whatever the user's shell: $1 the scene, $2 its name without
// .pov, $3 and $4 the size, $5 the antialiasing option. POV-Ray writes a hidden name (it adds
// .png itself), renamed over the image only when it rendered; otherwise the hidden file goes and
// POV-Ray's last lines (its error, past its banner) are printed. The names are in double quotes
// for POV-Ray's option parser too, which splits at spaces. No single quote, no `!`, no braces:
// the script travels inside single quotes through GNU parallel and a remote login shell.
constexpr const char* kJobScript =
    R"sh(o=$(povray "+I\"$1\"" "+O\".$2.part\"" "+W$3" "+H$4" "$5" -D +FN 2>&1); s=$?; )sh"
    R"sh(if [ $s -eq 0 ] && [ -s ".$2.part.png" ] && )sh"
    R"sh(mv -f ".$2.part.png" "$2.png"; then exit 0; fi; rm -f ".$2.part.png"; )sh"
    R"sh(printf "%s\n" "$o" | tail -n 6 >&2; [ $s -eq 0 ] && s=1; exit $s)sh";

// The hidden name the job script renders frame `stem` into.
std::string partialImageName(const std::string& stem) {
  std::string name = ".";
  name += stem;
  name += ".part.png";
  return name;
}

// One scene to render; names are file names in the folder.
struct Frame {
  std::string scene;                       // frame-0007.pov
  std::string stem;                        // frame-0007
  std::vector<std::string> textures;       // frame-0007_texture1.png, … written beside it
  std::optional<struct stat> imageBefore;  // frame-0007.png before the run
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

bool sameFile(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino && a.st_size == b.st_size &&
         a.st_mtim.tv_sec == b.st_mtim.tv_sec && a.st_mtim.tv_nsec == b.st_mtim.tv_nsec;
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

// The folder's scenes, frame-*.pov, in order, with their textures. Only regular files count:
// a link is left out with a warning, so that nothing outside the folder is read or written.
std::vector<Frame> framesIn(const fs::path& folder) {
  std::vector<Frame> frames;
  std::map<std::string, std::vector<std::string>> textures;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (const auto owner = textureOwner(name)) {
      if (regularFileStatus(entry.path())) textures[*owner].push_back(name);
      continue;
    }
    if (!startsWith(name, "frame-") || !endsWith(name, ".pov") || name.size() <= 10) continue;
    if (!regularFileStatus(entry.path())) {
      std::cerr << (folder / name).string() << ": warning: not a regular file; left out\n";
      continue;
    }
    frames.push_back({name, name.substr(0, name.size() - 4), {}, std::nullopt});
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
// camera's aspect ratio is fitted to it.
std::optional<std::pair<int, int>> sizeWrittenFor(const fs::path& scene) {
  std::ifstream in(scene);
  std::string line;
  for (int i = 0; i < 4 && std::getline(in, line); ++i) {
    if (!startsWith(line, "// Render: povray ")) continue;
    const std::size_t w = line.find(" +W");
    const std::size_t h = line.find(" +H");
    if (w == std::string::npos || h == std::string::npos) return std::nullopt;
    const int width = std::atoi(line.c_str() + w + 3);
    const int height = std::atoi(line.c_str() + h + 3);
    if (width < 1 || height < 1) return std::nullopt;
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

// GNU parallel's arguments (after the program) for the frames: their scene names come on its
// standard input, NUL-separated, each followed by its textures separated by `/` (which no file
// name holds) when they travel to other hosts.
std::vector<std::string> parallelArguments(const RenderFramesOptions& o, int width, int height,
                                           std::size_t texturesPerFrame) {
  std::vector<std::string> args = {"--joblog", kJobLog, "--null", "--tagstring", "{1}"};
  if (o.jobs) {
    args.push_back("--jobs");
    args.push_back(std::to_string(*o.jobs));
  }
  if (!o.sshLogins.empty()) {
    for (const std::string& login : o.sshLogins) {
      args.push_back("--sshlogin");
      args.push_back(login);
    }
    // Each job in a folder of its own on its host (~/.parallel/tmp/…), removed afterwards: the
    // scene and its textures go out, the image comes back (rsync writes it under a temporary
    // name and renames it).
    args.insert(args.end(), {"--workdir", "...", "--transferfile", "{1}"});
    if (texturesPerFrame > 0) args.insert(args.end(), {"--colsep", "/"});
    for (std::size_t i = 0; i < texturesPerFrame; ++i) {
      args.push_back("--transferfile");
      std::string column = "{";
      column += std::to_string(i + 2);
      column += "}";
      args.push_back(column);
    }
    args.insert(args.end(), {"--return", "{1.}.png", "--cleanup"});
  }
  // One word: parallel hands it to the shell with {1} and {1.} replaced, quoted.
  std::string command = "sh -c '";
  command += kJobScript;
  command += "' sh {1} {1.} ";
  command += std::to_string(width);
  command += ' ';
  command += std::to_string(height);
  command += o.antialias ? " +A0.3" : " -A";
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

struct ParallelRun {
  int exitStatus = -1;  // -1: could not start
  int signal = 0;
  std::string failure;  // why it could not start
};

// Runs parallel in `folder` with `input` on its standard input (an unlinked temporary file, so
// that nothing is left in the folder and no pipe can fill). While it runs, this process ignores
// the terminal's interrupt and quit keys, as system(3) does: parallel and its jobs get them and
// stop, and the summary still comes.
ParallelRun runParallel(const std::string& program, const std::vector<std::string>& arguments,
                        const fs::path& folder, const std::string& input) {
  ParallelRun run;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> list(std::tmpfile(), std::fclose);
  if (!list || std::fwrite(input.data(), 1, input.size(), list.get()) != input.size() ||
      std::fflush(list.get()) != 0 || std::fseek(list.get(), 0, SEEK_SET) != 0) {
    run.failure =
        std::string("cannot write the list of frames to a temporary file: ") + std::strerror(errno);
    return run;
  }
  std::vector<std::string> argv = {program};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  std::vector<char*> argPointers;
  for (std::string& a : argv) argPointers.push_back(a.data());
  argPointers.push_back(nullptr);
  // Its jobs' shell is /bin/sh, not the user's (which may be csh or fish).
  std::vector<std::string> environment;
  for (char** e = environ; *e; ++e)
    if (!startsWith(*e, "PARALLEL_SHELL=")) environment.emplace_back(*e);
  environment.emplace_back("PARALLEL_SHELL=/bin/sh");
  std::vector<char*> envPointers;
  for (std::string& e : environment) envPointers.push_back(e.data());
  envPointers.push_back(nullptr);

  using SignalAction = struct sigaction;
  SignalAction ignore{}, oldInterrupt{}, oldQuit{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGINT, &ignore, &oldInterrupt);
  sigaction(SIGQUIT, &ignore, &oldQuit);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
  posix_spawn_file_actions_adddup2(&actions, fileno(list.get()), STDIN_FILENO);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGQUIT);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, program.c_str(), &actions, &attributes, argPointers.data(),
                                  envPointers.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned == 0) {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    run.exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  } else {
    run.failure = std::string("cannot run ") + program + ": " + std::strerror(spawned);
  }
  sigaction(SIGINT, &oldInterrupt, nullptr);
  sigaction(SIGQUIT, &oldQuit, nullptr);
  return run;
}

int runRenderFrames(const RenderFramesOptions& o) {
  const fs::path folder = o.folder;
  std::vector<Frame> frames = framesIn(folder);
  if (frames.empty()) {
    std::cerr << "hirsute: error: " << o.folder
              << " holds no frame-*.pov scenes (hirsute simulate writes them)\n";
    return kExitBadInput;
  }
  for (const std::string& login : o.sshLogins) {
    if (namesThisMachine(login)) {
      std::cerr << "hirsute: error: --sshlogin " << login
                << ": ':' (this machine) cannot be one of the hosts, since each host renders in "
                   "a folder of its own that this machine's jobs would not see; name it as "
                   "localhost, or leave --sshlogin out to render here\n";
      return kExitBadInput;
    }
  }

  std::vector<Frame*> toRender;
  for (Frame& frame : frames) {
    if (!o.force && rendered(folder, frame)) continue;
    frame.imageBefore = regularFileStatus(folder / (frame.stem + ".png"));
    toRender.push_back(&frame);
  }
  const std::size_t alreadyDone = frames.size() - toRender.size();
  const auto summary = [&](std::size_t renderedNow, std::size_t failed, double seconds) {
    std::cout << fmt::format("{} frame{}: {} rendered, {} already done, {} failed in {:.1f} s\n",
                             frames.size(), frames.size() == 1 ? "" : "s", renderedNow, alreadyDone,
                             failed, seconds);
  };
  if (toRender.empty()) {
    summary(0, 0, 0);
    return kExitOk;
  }

  const std::string parallel = findOnPath("parallel");
  if (parallel.empty()) {
    std::cerr << "hirsute: error: GNU parallel is not on the PATH (Debian's package parallel; "
                 "scripts/install-deps.sh installs it)\n";
    return kExitBadInput;
  }
  if (o.sshLogins.empty() && findOnPath("povray").empty()) {
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
  const std::vector<std::string> arguments = parallelArguments(o, width, height, texturesPerFrame);

  if (o.dryRun) {
    std::cout << "in " << shellQuoted(o.folder)
              << (texturesPerFrame > 0 ? ", with each frame's scene and textures ('/'-separated)"
                                       : ", with each frame's scene")
              << " NUL-terminated on its standard input:\n"
              << shellQuoted(parallel);
    for (const std::string& a : arguments) std::cout << ' ' << shellQuoted(a);
    std::cout << '\n';
    for (const Frame* frame : toRender) {
      std::cout << frame->scene;
      if (texturesPerFrame > 0)
        for (const std::string& texture : frame->textures) std::cout << ' ' << texture;
      std::cout << '\n';
    }
    std::cout << fmt::format("{} frame{}: {} to render, {} already done\n", frames.size(),
                             frames.size() == 1 ? "" : "s", toRender.size(), alreadyDone);
    return kExitOk;
  }

  // A run that was interrupted may have left its hidden partial images; they go first.
  std::error_code ignored;
  for (const Frame* frame : toRender) fs::remove(folder / partialImageName(frame->stem), ignored);
  const auto start = std::chrono::steady_clock::now();
  const ParallelRun run =
      runParallel(parallel, arguments, folder, parallelInput(toRender, texturesPerFrame));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (run.exitStatus < 0 && run.signal == 0) {
    std::cerr << "hirsute: error: " << run.failure << '\n';
    return kExitIoError;
  }

  std::size_t renderedNow = 0;
  std::vector<const Frame*> failed;
  for (const Frame* frame : toRender) {
    fs::remove(folder / partialImageName(frame->stem), ignored);  // left by a job that was killed
    const auto image = regularFileStatus(folder / (frame->stem + ".png"));
    const bool fresh = image && (!frame->imageBefore || !sameFile(*image, *frame->imageBefore));
    if (fresh && rendered(folder, *frame)) {
      ++renderedNow;
    } else {
      failed.push_back(frame);
    }
  }
  // Parallel stopped (interrupted, or an error of its own): the frames it never started are no
  // failures worth a line each.
  const bool stopped = run.signal != 0 || run.exitStatus == 255;
  if (run.signal != 0) {
    std::cerr << "hirsute: error: parallel was stopped by signal " << run.signal << '\n';
  } else if (run.exitStatus == 255) {
    std::cerr << "hirsute: error: parallel stopped before the end (exit status 255)\n";
  } else {
    for (const Frame* frame : failed)
      std::cerr << (folder / frame->scene).string() << ": error: not rendered\n";
  }
  if (!failed.empty())
    std::cerr << "hirsute: the jobs and their exit codes are in " << (folder / kJobLog).string()
              << '\n';
  summary(renderedNow, failed.size(), seconds);
  return failed.empty() && !stopped ? kExitOk : kExitIoError;
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
  command
      ->add_option("--width", o->width,
                   "The image's width (default: the size the scenes were written for, else 800)")
      ->check(CLI::Range(1, 65536));
  command
      ->add_option("--height", o->height,
                   "The image's height (default: the size the scenes were written for, else 600)")
      ->check(CLI::Range(1, 65536));
  command
      ->add_option("-j,--jobs", o->jobs,
                   "Frames rendered at once on each machine (default: parallel's, one a core)")
      ->check(CLI::Range(1, 100000));
  command
      ->add_option("-S,--sshlogin", o->sshLogins,
                   "A host to render on over ssh, as GNU parallel's --sshlogin takes it "
                   "([N/][user@]host, or several separated by commas); repeatable")
      ->allow_extra_args(false);
  command->add_flag("--antialias", o->antialias, "Anti-alias (POV-Ray's +A0.3)");
  command->add_flag("--force", o->force, "Render every frame, also those already rendered");
  command->add_flag(
      "--dry-run", o->dryRun,
      "Print the parallel command and the frames it would render, and render nothing");
  command->callback([o, &action] { action = [o] { return runRenderFrames(*o); }; });
}

}  // namespace hirsute::cli
