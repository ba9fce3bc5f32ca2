#include "hirsute/viewer/export/povray_runner.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

extern char** environ;

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

bool povrayAvailable() {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::string folders(path);
  std::size_t start = 0;
  while (start <= folders.size()) {
    std::size_t end = folders.find(':', start);
    if (end == std::string::npos) end = folders.size();
    std::filesystem::path folder =
        end > start ? folders.substr(start, end - start) : std::string(1, '.');
    if (access((folder / "povray").c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

PovrayRun runPovray(const std::filesystem::path& scene, const std::filesystem::path& image,
                    int width, int height, bool antialias) {
  PovrayRun run;
  std::filesystem::path absoluteScene = std::filesystem::absolute(scene);
  std::filesystem::path absoluteImage = std::filesystem::absolute(image);
  // (Appending rather than "+I" + name: GCC 12 warns falsely about the latter, -Wrestrict.)
  auto option = [](const char* flag, const std::string& value) {
    std::string text(flag);
    text += value;
    return text;
  };
  std::vector<std::string> arguments = {"povray",
                                        option("+I", absoluteScene.filename().string()),
                                        option("+O", absoluteImage.string()),
                                        option("+W", std::to_string(width)),
                                        option("+H", std::to_string(height)),
                                        "-D",    // no display window
                                        "+FN"};  // PNG
  if (antialias) arguments.push_back("+A0.3");
  std::vector<char*> argv;
  for (std::string& a : arguments) argv.push_back(a.data());
  argv.push_back(nullptr);

  int pipeFds[2];
  if (pipe(pipeFds) != 0) {
    run.messages = std::string("cannot start povray: ") + std::strerror(errno) + '\n';
    return run;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, absoluteScene.parent_path().c_str());
  posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipeFds[0]);
  posix_spawn_file_actions_addclose(&actions, pipeFds[1]);
  pid_t pid = 0;
  int spawned = posix_spawnp(&pid, "povray", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipeFds[1]);
  if (spawned != 0) {
    close(pipeFds[0]);
    run.messages = std::string("cannot start povray: ") + std::strerror(spawned) + '\n';
    return run;
  }
  std::string output;
  char buffer[65536];
  for (;;) {
    ssize_t n = read(pipeFds[0], buffer, sizeof buffer);
    if (n > 0) {
      output.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(pipeFds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.messages = problemsIn(output);
  if (run.exitStatus != 0 && run.messages.empty()) run.messages = output;  // failed before parsing
  run.parseSeconds = statisticSeconds(output, "Parse Time:");
  run.boundingSeconds = statisticSeconds(output, "Bounding Time:");
  run.traceSeconds = statisticSeconds(output, "Trace Time:");
  return run;
}

}  // namespace hirsute
