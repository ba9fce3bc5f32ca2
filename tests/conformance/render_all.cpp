// Render-all: every model drawn through the real command line, headless and through POV-Ray.
//
//   hirsute_render_all conformance DIR   every model of the conformance set (DIR/index.tsv) with
//                                        environment=no, with the index's colour options and
//                                        derivation length; exits 77 (skip) when DIR is absent
//   hirsute_render_all models DIR        every .l under DIR's model folders (DIR/bench aside),
//                                        with its folder's view and colour file, as a user runs it
//   … --part K/N                         only the models K, K+N, K+2N, … of the set (1 ≤ K ≤ N),
//                                        so that ctest runs the N parts side by side
//
// For each model, in a temporary folder of its own:
//   hirsute render L V … -o gl.png --size 160x120
//     exit code 0, no "error" in standard error, the PNG decodes at 160x120, and some pixel
//     differs from the corner pixel (the background): the model drew something;
//   hirsute render L V … -o traced.png --trace --spp 2 --size 80x60   (shipped models only)
//     the same checks for the path tracer;
//   hirsute export L V … --pov scene.pov --render --width 64 --height 48   (when povray is on
//   the PATH; skipped with a message otherwise)
//     exit code 0, no "error" in standard error, nothing printed beyond the model's own warnings
//     (which `render` printed too): what remains is POV-Ray's, and a clean run prints nothing;
//     scene.png decodes at 64x48.
// Prints one line per model with the times of both commands (export's includes POV-Ray's render)
// and a summary; exits 1 when a model fails.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "hirsute/viewer/export/povray_runner.h"
#include "hirsute/viewer/view/png_image.h"

extern char** environ;

namespace fs = std::filesystem;
using namespace hirsute;

namespace {

constexpr int kExitSkip = 77;
constexpr int kGlWidth = 160, kGlHeight = 120;
constexpr int kTraceWidth = 80, kTraceHeight = 60;  // render --trace, shipped models only
constexpr int kPovWidth = 64, kPovHeight = 48;

// One model to draw: the command-line arguments that name it (files, colour options, steps).
struct ModelCase {
  std::string id;
  std::vector<std::string> arguments;
};

// Models whose picture is empty in cpfg too, with the reason; for them the test asserts the
// opposite: every pixel is background.
struct DrawsNothing {
  const char* id;
  const char* reason;
};
constexpr DrawsNothing kDrawsNothing[] = {
    {"01-Introduction-02-snowflake-exercise",
     "an exercise left to the reader: its axiom, production and angle are the placeholder `?`, "
     "which draws nothing (cpfg's rayshade output of it is an empty grid)"},
};

const char* drawsNothing(const std::string& id) {
  for (const DrawsNothing& d : kDrawsNothing) {
    if (id == d.id) return d.reason;
  }
  return nullptr;
}

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

bool containsErrorWord(const std::string& text) {
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("error") != std::string::npos;
}

// The first lines of `text`, indented, for a failure message.
std::string excerpt(const std::string& text, std::size_t maxLines = 6) {
  std::vector<std::string> lines = linesOf(text);
  std::string out;
  for (std::size_t i = 0; i < lines.size() && i < maxLines; ++i)
    out += "        | " + lines[i] + '\n';
  if (lines.size() > maxLines) {
    out += "        | … (" + std::to_string(lines.size() - maxLines) + " more lines)\n";
  }
  return out;
}

// ---- the conformance index ------------------------------------------------------------------

// cpfg's colour options as ours: -m FILE and -M FILE name bank 1, -mN FILE and -MN FILE bank N
// (ours: -m N:FILE, -M N:FILE); files are relative to the model's folder.
std::vector<std::string> colourArguments(const std::string& cpfgOptions, const fs::path& folder) {
  std::istringstream in(cpfgOptions);
  std::vector<std::string> tokens;
  for (std::string token; in >> token;) tokens.push_back(token);
  std::vector<std::string> arguments;
  for (std::size_t i = 0; i < tokens.size(); i += 2) {
    const std::string& flag = tokens[i];
    bool known = flag.size() >= 2 && flag[0] == '-' && (flag[1] == 'm' || flag[1] == 'M') &&
                 std::all_of(flag.begin() + 2, flag.end(),
                             [](unsigned char c) { return std::isdigit(c) != 0; });
    if (!known || i + 1 >= tokens.size()) {
      throw std::runtime_error("index.tsv: cannot translate the colour options '" + cpfgOptions +
                               "'");
    }
    std::string bank = flag.substr(2);
    std::string file = (folder / tokens[i + 1]).string();
    arguments.push_back(std::string("-") + flag[1]);
    arguments.push_back(bank.empty() ? file : bank + ":" + file);
  }
  return arguments;
}

std::vector<ModelCase> conformanceCases(const fs::path& root) {
  std::ifstream in(root / "index.tsv");
  std::string line;
  std::getline(in, line);  // header: id lfile vfile afile colors steps environment modules notes
  std::vector<ModelCase> cases;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, '\t');) cells.push_back(cell);
    if (cells.size() < 7) continue;
    if (cells[6] != "no") continue;  // needs cpfg's environment programs (-e)
    fs::path folder = root / cells[0];
    ModelCase c{cells[0], {(folder / cells[1]).string()}};
    if (cells[2] != "-") c.arguments.push_back((folder / cells[2]).string());
    for (std::string& a : colourArguments(cells[4], folder)) c.arguments.push_back(std::move(a));
    c.arguments.insert(c.arguments.end(), {"-n", cells[5]});
    cases.push_back(std::move(c));
  }
  return cases;
}

// ---- the shipped models -----------------------------------------------------------------------

// The files a view file names on `hair:` lines: template hairs, L-systems that are part of a
// model rather than models of their own.
std::vector<fs::path> hairTemplatesOf(const fs::path& view) {
  std::vector<fs::path> templates;
  std::istringstream lines(readText(view));
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line.compare(start, 5, "hair:") != 0) continue;
    std::istringstream rest(line.substr(start + 5));
    std::string file;
    if (rest >> file) templates.push_back(view.parent_path() / file);
  }
  return templates;
}

// Every .l in every model folder under `root` (the benchmark models aside: they are sized for
// the benchmarks, not for looking at; and the template hairs the folder's view files name), with
// the .v of the same name, else the .v named after the folder, else the folder's only .v.
// Colour files are left to hirsute, which takes the folder's only .map or .mat.
std::vector<ModelCase> shippedCases(const fs::path& root) {
  std::vector<fs::path> folders;
  for (const auto& entry : fs::directory_iterator(root)) {
    if (entry.is_directory() && entry.path().filename() != "bench") folders.push_back(entry.path());
  }
  std::sort(folders.begin(), folders.end());
  std::vector<ModelCase> cases;
  for (const fs::path& folder : folders) {
    std::vector<fs::path> lsystems, views;
    for (const auto& entry : fs::directory_iterator(folder)) {
      if (entry.path().extension() == ".l") lsystems.push_back(entry.path());
      if (entry.path().extension() == ".v") views.push_back(entry.path());
    }
    std::sort(lsystems.begin(), lsystems.end());
    std::vector<fs::path> templates;
    for (const fs::path& v : views) {
      for (const fs::path& t : hairTemplatesOf(v)) templates.push_back(t.lexically_normal());
    }
    const fs::path folderView = folder / (folder.filename().string() + ".v");
    for (const fs::path& l : lsystems) {
      if (std::find(templates.begin(), templates.end(), l.lexically_normal()) != templates.end())
        continue;
      ModelCase c{folder.filename().string() + "/" + l.filename().string(), {l.string()}};
      fs::path sameName = fs::path(l).replace_extension(".v");
      if (fs::exists(sameName)) {
        c.arguments.push_back(sameName.string());
      } else if (fs::exists(folderView)) {
        c.arguments.push_back(folderView.string());
      } else if (views.size() == 1) {
        c.arguments.push_back(views.front().string());
      }
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

// ---- running hirsute --------------------------------------------------------------------------

struct CommandRun {
  int exitCode = -1;
  double seconds = 0;
  std::string standardError;
};

// Runs the hirsute binary once with `arguments`, standard output and error into files in
// `folder` named after `name`.
CommandRun runHirsuteOnce(const std::vector<std::string>& arguments, const fs::path& folder,
                          const std::string& name) {
  CommandRun run;
  std::vector<std::string> argvText = {HIRSUTE_BINARY};
  argvText.insert(argvText.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : argvText) argv.push_back(a.data());
  argv.push_back(nullptr);
  fs::path out = folder / (name + ".stdout"), err = folder / (name + ".stderr");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    run.standardError = std::string("cannot start ") + HIRSUTE_BINARY + '\n';
    return run;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.standardError = readText(err);
  return run;
}

// LeakSanitizer's tracer can crash at exit (a failure of the sanitizer, not a leak, which reads
// "detected memory leaks"): such a run is repeated, twice at most, and said so.
// scripts/test-sanitized.sh sets the options that kept it from crashing.
bool leakCheckerCrashed(const CommandRun& run) {
  return run.exitCode != 0 &&
         run.standardError.find("LeakSanitizer has encountered a fatal error") != std::string::npos;
}

CommandRun runHirsute(const std::vector<std::string>& arguments, const fs::path& folder,
                      const std::string& name) {
  CommandRun run = runHirsuteOnce(arguments, folder, name);
  for (int retry = 0; retry < 2 && leakCheckerCrashed(run); ++retry) {
    std::printf("     (%s: LeakSanitizer's own tracer crashed at exit; run again)\n", name.c_str());
    run = runHirsuteOnce(arguments, folder, name);
  }
  return run;
}

// ---- checks -----------------------------------------------------------------------------------

// Problems with a PNG: it must decode at width × height; with `drawn`, some pixel must differ
// from the corner pixel (the background), and without, none may.
void checkImage(const fs::path& png, int width, int height, std::optional<bool> drawn,
                const std::string& what, std::vector<std::string>& problems) {
  RgbaImage image;
  try {
    image = readPng(png);
  } catch (const std::exception& e) {
    problems.push_back(what + ": " + e.what());
    return;
  }
  if (image.width != width || image.height != height) {
    problems.push_back(what + " is " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + ", not " + std::to_string(width) + "x" +
                       std::to_string(height));
    return;
  }
  if (!drawn) return;
  glm::u8vec4 corner = image.pixel(0, 0);
  std::size_t differing = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      glm::u8vec4 p = image.pixel(x, y);
      differing += p.r != corner.r || p.g != corner.g || p.b != corner.b;
    }
  }
  if (*drawn && differing == 0) problems.push_back(what + " is all background: nothing drawn");
  if (!*drawn && differing > 0) {
    problems.push_back(what + " has " + std::to_string(differing) +
                       " pixels unlike the background, where cpfg draws nothing");
  }
}

struct ModelResult {
  std::vector<std::string> problems;
  double renderSeconds = 0, exportSeconds = 0;
};

ModelResult drawModel(const ModelCase& model, const fs::path& folder, bool withPovray,
                      bool traced) {
  ModelResult result;
  std::vector<std::string>& problems = result.problems;
  const char* emptyReason = drawsNothing(model.id);

  std::vector<std::string> render = {"render"};
  render.insert(render.end(), model.arguments.begin(), model.arguments.end());
  fs::path png = folder / "gl.png";
  render.insert(render.end(), {"-o", png.string(), "--size",
                               std::to_string(kGlWidth) + "x" + std::to_string(kGlHeight)});
  CommandRun rendered = runHirsute(render, folder, "render");
  result.renderSeconds = rendered.seconds;
  if (rendered.exitCode != 0) {
    problems.push_back("render exited with " + std::to_string(rendered.exitCode) + ":\n" +
                       excerpt(rendered.standardError));
  } else {
    if (containsErrorWord(rendered.standardError)) {
      problems.push_back("render printed an error:\n" + excerpt(rendered.standardError));
    }
    checkImage(png, kGlWidth, kGlHeight, emptyReason == nullptr, "render's PNG", problems);
  }
  if (traced) {
    // The path tracer (render --trace) at a small size and two samples a pixel.
    std::vector<std::string> trace = {"render"};
    trace.insert(trace.end(), model.arguments.begin(), model.arguments.end());
    const fs::path tracedPng = folder / "traced.png";
    trace.insert(trace.end(), {"-o", tracedPng.string(), "--trace", "--spp", "2", "--size",
                               std::to_string(kTraceWidth) + "x" + std::to_string(kTraceHeight)});
    CommandRun run = runHirsute(trace, folder, "render --trace");
    if (run.exitCode != 0) {
      problems.push_back("render --trace exited with " + std::to_string(run.exitCode) + ":\n" +
                         excerpt(run.standardError));
    } else {
      if (containsErrorWord(run.standardError)) {
        problems.push_back("render --trace printed an error:\n" + excerpt(run.standardError));
      }
      checkImage(tracedPng, kTraceWidth, kTraceHeight, emptyReason == nullptr,
                 "render --trace's PNG", problems);
    }
  }
  if (!withPovray) return result;

  std::vector<std::string> exported = {"export"};
  exported.insert(exported.end(), model.arguments.begin(), model.arguments.end());
  fs::path pov = folder / "scene.pov";
  exported.insert(exported.end(),
                  {"--pov", pov.string(), "--render", "--width", std::to_string(kPovWidth),
                   "--height", std::to_string(kPovHeight)});
  CommandRun run = runHirsute(exported, folder, "export");
  result.exportSeconds = run.seconds;
  if (run.exitCode != 0) {
    problems.push_back("export exited with " + std::to_string(run.exitCode) + ":\n" +
                       excerpt(run.standardError));
    return result;
  }
  if (containsErrorWord(run.standardError)) {
    problems.push_back("export printed an error:\n" + excerpt(run.standardError));
  }
  // The model's own warnings are printed by both commands; anything else export printed is
  // POV-Ray's report of a problem with the scene.
  std::vector<std::string> renderLines = linesOf(rendered.standardError);
  std::set<std::string> modelWarnings(renderLines.begin(), renderLines.end());
  std::string povray;
  for (const std::string& line : linesOf(run.standardError)) {
    if (!modelWarnings.contains(line)) povray += line + '\n';
  }
  if (!povray.empty()) problems.push_back("POV-Ray printed:\n" + excerpt(povray));
  checkImage(fs::path(pov).replace_extension(".png"), kPovWidth, kPovHeight, std::nullopt,
             "POV-Ray's PNG", problems);
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t part = 1, parts = 1;
  if (argc == 5 && std::string(argv[3]) == "--part") {
    if (std::sscanf(argv[4], "%zu/%zu", &part, &parts) != 2 || part < 1 || part > parts) {
      std::cerr << "render_all: --part takes K/N with 1 <= K <= N\n";
      return 2;
    }
    argc = 3;
  }
  if (argc != 3 || (std::string(argv[1]) != "conformance" && std::string(argv[1]) != "models")) {
    std::cerr << "usage: hirsute_render_all conformance|models DIR [--part K/N]\n";
    return 2;
  }
  const std::string set = argv[1];
  const fs::path root = argv[2];
  std::vector<ModelCase> cases;
  try {
    if (set == "conformance") {
      if (!fs::exists(root / "index.tsv")) {
        std::cout << "render_all: " << root.string()
                  << " is absent; skipping (it holds the conformance models)\n";
        return kExitSkip;
      }
      cases = conformanceCases(root);
    } else {
      cases = shippedCases(root);
    }
  } catch (const std::exception& e) {
    std::cerr << "render_all: " << e.what() << '\n';
    return 1;
  }
  if (cases.empty()) {
    std::cerr << "render_all: no models found under " << root.string() << '\n';
    return 1;
  }
  if (parts > 1) {
    std::vector<ModelCase> mine;
    for (std::size_t i = part - 1; i < cases.size(); i += parts) mine.push_back(cases[i]);
    cases = std::move(mine);
  }
  const bool withPovray = povrayAvailable();
  if (!withPovray) {
    std::cout << "render_all: povray is not on the PATH; the POV-Ray half of each model is "
                 "skipped (apt install povray)\n";
  }

  const fs::path work =
      fs::temp_directory_path() /
      ("hirsute_render_all_" + set + "_" + std::to_string(part) + "_" + std::to_string(getpid()));
  fs::remove_all(work);
  std::printf("%-4s %-42s %9s %16s\n", "", "model", "render s", "export+povray s");
  int passed = 0, failed = 0;
  double renderTotal = 0, exportTotal = 0;
  auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const ModelCase& model = cases[i];
    fs::path folder = work / std::to_string(i);
    fs::create_directories(folder);
    ModelResult result = drawModel(model, folder, withPovray, set == "models");
    renderTotal += result.renderSeconds;
    exportTotal += result.exportSeconds;
    bool ok = result.problems.empty();
    (ok ? passed : failed) += 1;
    char exportTime[32] = "skipped";
    if (withPovray) std::snprintf(exportTime, sizeof exportTime, "%.2f", result.exportSeconds);
    std::printf("%-4s %-42s %9.2f %16s\n", ok ? "ok" : "FAIL", model.id.c_str(),
                result.renderSeconds, exportTime);
    if (const char* reason = drawsNothing(model.id)) {
      std::printf("       (expected empty: %s)\n", reason);
    }
    for (const std::string& problem : result.problems) {
      std::printf("       - %s%s", problem.c_str(), problem.back() == '\n' ? "" : "\n");
    }
    std::fflush(stdout);
    if (ok) fs::remove_all(folder);
  }
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%d of %zu models pass (%s); render %.1f s, export+povray %.1f s, %.1f s in all\n",
              passed, cases.size(), set.c_str(), renderTotal, exportTotal, wall);
  if (failed == 0) {
    fs::remove_all(work);
  } else {
    std::printf("the failing models' outputs are kept in %s\n", work.c_str());
  }
  return failed == 0 ? 0 : 1;
}
