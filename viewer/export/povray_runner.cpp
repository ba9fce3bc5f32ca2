#include "hirsute/viewer/export/povray_runner.h"

#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "hirsute/core/child_confinement.h"
#include "hirsute/core/child_process.h"
#include "hirsute/core/output_folder.h"
#include "hirsute/core/output_target.h"
#include "hirsute/core/program_path.h"

namespace hirsute {
namespace {

// POV-Ray's report of a problem, and its continuation lines (it wraps at 80 columns and
// indents what follows by one space).
std::string problemsIn(const std::string& output) {
  std::istringstream lines(output);
  std::string line, problems;
  bool parsing = false, inProblem = false;
  while (std::getline(lines, line)) {
    if (line.find("==== [Parsing...]") != std::string::npos) parsing = true;
    if (!parsing) continue;  // the banner and the option listing ("Warning Stream to console…")
    bool problem =
        line.find("Warning") != std::string::npos || line.find("Error") != std::string::npos ||
        line.find("error") != std::string::npos || line.find("Render failed") != std::string::npos;
    if (problem || (inProblem && !line.empty() && line[0] == ' ')) {
      problems += line + '\n';
      inProblem = true;
    } else {
      inProblem = false;
    }
  }
  return problems;
}

// What POV-Ray said before it failed, when it failed before parsing reported a problem: its last
// lines, without its progress ("Rendered 1200 of 4800 pixels", thousands of them in a long run).
std::string lastLinesOf(const std::string& output) {
  constexpr std::size_t kShown = 20;
  std::vector<std::string> kept;
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    // POV-Ray rewrites its progress in place: the part after the last carriage return shows.
    if (const std::size_t cr = line.rfind('\r'); cr != std::string::npos) line.erase(0, cr + 1);
    if (line.empty() ||
        (line.find("Rendered ") != std::string::npos && line.find(" pixels") != std::string::npos))
      continue;
    kept.push_back(line);
  }
  std::string shown = kept.size() > kShown ? "...\n" : "";
  for (std::size_t i = kept.size() > kShown ? kept.size() - kShown : 0; i < kept.size(); ++i)
    shown += kept[i] + '\n';
  return shown;
}

// The seconds POV-Ray's statistics give for `what`, in the parentheses of the line
// "  Parse Time:       0 hours  0 minutes  1 seconds (1.234 seconds)"; -1 when it printed none.
double statisticSeconds(const std::string& output, const std::string& what) {
  std::size_t at = output.find(what);
  if (at == std::string::npos) return -1;
  std::size_t open = output.find('(', at);
  std::size_t end = output.find('\n', at);
  if (open == std::string::npos || open > end) return -1;
  return std::strtod(output.c_str() + open + 1, nullptr);
}

}  // namespace

std::optional<PixelsRendered> lastPixelsRendered(std::string_view output) {
  constexpr std::string_view kStart = "Rendered ", kOf = " of ", kEnd = " pixels";
  for (std::size_t at = output.rfind(kStart); at != std::string_view::npos;
       at = at == 0 ? std::string_view::npos : output.rfind(kStart, at - 1)) {
    const std::string_view rest = output.substr(at + kStart.size());
    const std::size_t of = rest.find(kOf);
    const std::size_t end = of == std::string_view::npos ? of : rest.find(kEnd, of);
    if (end == std::string_view::npos || end > 48) continue;  // cut short: an earlier one
    const std::string done(rest.substr(0, of));
    const std::string total(rest.substr(of + kOf.size(), end - of - kOf.size()));
    const auto digits = [](const std::string& t) {
      return !t.empty() && t.size() < 19 &&
             std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (!digits(done) || !digits(total)) continue;
    return PixelsRendered{std::stoll(done), std::stoll(total)};
  }
  return std::nullopt;
}

bool povrayAvailable() {
  return !findOnPath("povray").empty();
}

PovrayRun runPovray(const std::filesystem::path& scene, const std::filesystem::path& image,
                    int width, int height, bool antialias, std::chrono::seconds timeLimit,
                    Progress* progress) {
  PovrayRun run;
  const std::string povray = findOnPath("povray");
  if (povray.empty()) {
    run.messages = "cannot start povray: it is not on the PATH\n";
    return run;
  }
  std::error_code error;
  const std::filesystem::path absoluteScene = std::filesystem::absolute(scene, error);
  const std::filesystem::path folder = absoluteScene.parent_path();
  // The work folder, in the scene's folder: a link to the scene under a fixed name, and
  // whatever POV-Ray writes of its own; removed with all in it.
  std::string work = (folder / ".hirsute-povray-XXXXXX").string();
  if (!mkdtemp(work.data())) {
    run.messages = "cannot start povray: cannot make a work folder in " + folder.string() + ": " +
                   std::strerror(errno) + '\n';
    return run;
  }
  struct RemovedAtEnd {
    std::filesystem::path path;
    ~RemovedAtEnd() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  } removed{work};
  const std::string workName = std::filesystem::path(work).filename().string();
  const std::string target = "../" + absoluteScene.filename().string();
  if (symlink(target.c_str(), (std::filesystem::path(work) / "scene.pov").c_str()) != 0) {
    run.messages = std::string("cannot start povray: ") + std::strerror(errno) + '\n';
    return run;
  }
  std::optional<OutputTarget> output;
  try {
    // The image's name is derived from the scene's: made in its folder without following a
    // link planted at the name (output_folder.h).
    output.emplace(OutputFolder(image.parent_path()), image.filename().string());
  } catch (const std::runtime_error& e) {
    run.messages = std::string(e.what()) + '\n';
    return run;
  }

  ConfinementRules rules;
  rules.read = {folder, "/usr/share/povray-3.7", "/etc/povray"};
  rules.write = {work};
  rules.run = {std::filesystem::canonical(povray, error)};
  rules.devices = {"/dev/null", "/dev/urandom"};
  const ChildConfinement confinement(rules);

  ChildRequest request;
  request.program = std::filesystem::absolute(povray).string();
  // Every option is ours: the scene's own name never reaches POV-Ray's option parser.
  request.arguments = {"povray",
                       "+I" + workName + "/scene.pov",
                       "+O-",  // the image on the standard output
                       "+W" + std::to_string(width),
                       "+H" + std::to_string(height),
                       "-D",    // no display window
                       "+FN"};  // PNG
  if (antialias) request.arguments.push_back("+A0.3");
  request.environment = environmentWith({"TMPDIR=" + work});
  request.folder = folder;
  request.output = output->descriptor();
  request.confinement = &confinement;
  request.timeLimit = timeLimit;
  std::string text;
  constexpr std::size_t kMaxOutput = 4 << 20;  // a scene's #debug may say much more
  // The progress line: the time elapsed while POV-Ray parses, then the share of the pixels it
  // reports, read from the end of what it has written (a report may come in two parts).
  std::string recent;
  bool counting = false;
  if (progress != nullptr && progress->enabled()) {
    progress->begin("rendering with POV-Ray", Progress::Unit::None);
    request.whileRunning = [&] {
      const std::optional<PixelsRendered> pixels = lastPixelsRendered(recent);
      // The stage, and the clock of its time left, starts with the render, past the parsing.
      if (!counting && (pixels || recent.find("==== [Rendering...]") != std::string::npos)) {
        const double total = pixels ? static_cast<double>(pixels->total)
                                    : static_cast<double>(width) * static_cast<double>(height);
        progress->begin("rendering with POV-Ray", Progress::Unit::Percent, total, "of the pixels");
        counting = true;
      }
      progress->update(pixels ? static_cast<double>(pixels->done) : 0.0);
    };
  }
  request.onOutput = [&](std::string_view part) {
    if (text.size() < kMaxOutput) text.append(part.substr(0, kMaxOutput - text.size()));
    if (!request.whileRunning) return;
    recent.append(part);
    constexpr std::size_t kKept = 4096;
    if (recent.size() > 2 * kKept) recent.erase(0, recent.size() - kKept);
  };
  const ChildResult child = runChild(request);
  if (progress != nullptr) progress->clear();
  if (!child.started) {
    run.messages = "cannot start povray: " + child.failure + '\n';
    return run;
  }
  run.timedOut = child.timedOut;
  run.interruptedBy = child.interruptedBy;
  run.exitStatus = child.signal != 0 ? 128 + child.signal : child.exitStatus;
  run.messages = problemsIn(text);
  // Failed before parsing, on its own: its last lines say why. Stopped (a signal, the time
  // limit): the caller says so.
  if (run.exitStatus != 0 && run.messages.empty() && !run.timedOut && run.interruptedBy == 0)
    run.messages = lastLinesOf(text);
  run.parseSeconds = statisticSeconds(text, "Parse Time:");
  run.boundingSeconds = statisticSeconds(text, "Bounding Time:");
  run.traceSeconds = statisticSeconds(text, "Trace Time:");
  if (run.exitStatus == 0) {
    struct stat written {};
    if (fstat(output->descriptor(), &written) != 0 || written.st_size == 0) {
      run.exitStatus = 1;
      run.messages += "povray wrote no image\n";
      return run;
    }
    try {
      output->commit();
    } catch (const std::runtime_error& e) {
      run.exitStatus = 1;
      run.messages += std::string(e.what()) + '\n';
    }
  }
  return run;
}

}  // namespace hirsute
