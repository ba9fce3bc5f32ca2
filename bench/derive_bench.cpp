// hirsute_derive_bench: derivation figures for the benchmark models in models/bench.
//
// Each model runs in a forked child, so its peak resident size is its own and no model inherits
// another's heap. The peak is the child's VmHWM: wait4's ru_maxrss would also count the
// preprocessor, `cpp`, a separate process that the child spawns and that peaks near 18 MiB by
// itself before the derivation begins; that figure is printed beside it. The child times loading
// (preprocess, parse, compile), deriving, and writing the string in cpfg's -str format to a
// temporary file, and reports the figures through a pipe. docs/design.md, "Benchmarks": modules per
// second and bytes per module at the peak.
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/lsys/string_writer.h"

namespace {

struct BenchModel {
  const char* name;
  const char* file;  // relative to the models folder
  const char* exercises;
  // cpfg deriving a string of this kind and writing it with -str, whole process, best of 5 on
  // the machines the project is measured on (0 when no figure was taken), and Hirsute's goal.
  double cpfgSeconds;
  double cpfgPeakMiB;
  double goalSeconds;
  double goalPeakMiB;
};

constexpr BenchModel kModels[] = {
    {"parametric", "parametric.l", "context-free branching, every module parametric, -str writing",
     1.03, 56, 0.34, 56},
    {"branching", "branching.l", "context-free parametric branching, -str writing", 0, 0, 0, 0},
    {"signal", "signal.l", "left-context signal with branch skipping", 0.98, 18, 0.33, 18},
    {"loops", "loops.l", "blocks with while loops and math calls", 1.21, 18, 0.40, 18},
    {"stochastic", "stochastic.l", "seeded stochastic productions with weights", 0.16, 20, 0.053,
     20},
};

// What a child reports to the parent: plain data, written whole through a pipe.
struct Figures {
  bool ok = false;
  int steps = 0;
  std::size_t modules = 0;
  std::size_t textBytes = 0;
  double loadSeconds = 0;
  double deriveSeconds = 0;
  double writeSeconds = 0;
  long peakRssKiB = 0;      // the child's own peak (VmHWM)
  long treePeakRssKiB = 0;  // the child's or its cpp's, whichever is larger (wait4's ru_maxrss)
  char error[512] = {};

  double totalSeconds() const { return loadSeconds + deriveSeconds + writeSeconds; }
};

// The peak resident size of this process, from /proc/self/status; 0 when unknown.
long ownPeakRssKiB() {
  std::FILE* status = std::fopen("/proc/self/status", "r");
  if (!status) return 0;
  char line[256];
  long kib = 0;
  while (std::fgets(line, sizeof line, status)) {
    if (std::sscanf(line, "VmHWM: %ld kB", &kib) == 1) break;
  }
  std::fclose(status);
  return kib;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void setError(Figures& figures, const std::string& message) {
  std::snprintf(figures.error, sizeof figures.error, "%s", message.c_str());
}

// The child's work: load, derive, write, with each phase timed apart.
Figures measure(const std::filesystem::path& file) {
  Figures figures;
  try {
    hirsute::Diagnostics diagnostics(&std::cerr);
    auto start = std::chrono::steady_clock::now();
    hirsute::Model model = hirsute::loadModel(file, std::nullopt, diagnostics);
    figures.loadSeconds = secondsSince(start);

    // The text goes to a real file, as `hirsute derive -o` writes it, and is deleted after.
    std::string path = (std::filesystem::temp_directory_path() / "hirsute_bench_XXXXXX").string();
    int fd = mkstemp(path.data());
    if (fd < 0) {
      setError(figures, "cannot create a temporary file: " + std::string(std::strerror(errno)));
      return figures;
    }
    std::FILE* out = fdopen(fd, "wb");
    if (!out) {
      setError(figures, "cannot open the temporary file: " + std::string(std::strerror(errno)));
      close(fd);
      std::remove(path.c_str());
      return figures;
    }
    // As `hirsute derive -o` does: the last step's string is written while it is derived
    // (Derivation::runStreamingLastStep), so "derive" includes writing it, and "write" is only
    // what remains (the whole string when it could not stream).
    start = std::chrono::steady_clock::now();
    hirsute::Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder,
                                 std::cerr);
    hirsute::Derivation derivation(model.program, evaluator, diagnostics);
    bool written;
    {
      hirsute::StringWriter writer(out, hirsute::StringFormat::Cpfg);
      const bool streamed = derivation.runStreamingLastStep(writer, false);
      figures.deriveSeconds = secondsSince(start);
      figures.steps = derivation.stepsDone();
      figures.modules = streamed ? derivation.streamedModules() : derivation.string().moduleCount();
      start = std::chrono::steady_clock::now();
      if (!streamed) derivation.emit(writer, false);
      written = writer.finish();
    }
    written = std::fclose(out) == 0 && written;
    figures.writeSeconds = secondsSince(start);
    struct stat info {};
    if (written && stat(path.c_str(), &info) == 0)
      figures.textBytes = static_cast<std::size_t>(info.st_size);
    std::remove(path.c_str());
    if (!written) {
      setError(figures, "cannot write the temporary file");
      return figures;
    }
    figures.peakRssKiB = ownPeakRssKiB();
    figures.ok = figures.peakRssKiB > 0;
    if (!figures.ok) setError(figures, "cannot read VmHWM from /proc/self/status");
  } catch (const hirsute::DiagnosticError& e) {
    setError(figures, e.diagnostic().text());
  } catch (const std::exception& e) {
    setError(figures, e.what());
  }
  return figures;
}

// Runs `measure` in a child process and collects its figures and peak resident size.
Figures measureInChild(const std::filesystem::path& file) {
  Figures figures;
  int fds[2];
  if (pipe(fds) != 0) {
    setError(figures, "pipe: " + std::string(std::strerror(errno)));
    return figures;
  }
  std::fflush(nullptr);
  std::cout.flush();
  pid_t pid = fork();
  if (pid < 0) {
    setError(figures, "fork: " + std::string(std::strerror(errno)));
    return figures;
  }
  if (pid == 0) {
    close(fds[0]);
    Figures result = measure(file);
    const char* at = reinterpret_cast<const char*>(&result);
    std::size_t left = sizeof result;
    while (left > 0) {
      ssize_t n = write(fds[1], at, left);
      if (n <= 0) _exit(3);
      at += n;
      left -= static_cast<std::size_t>(n);
    }
    // _exit: the parent's buffered output must not be flushed twice.
    _exit(0);
  }
  close(fds[1]);
  char* at = reinterpret_cast<char*>(&figures);
  std::size_t got = 0;
  while (got < sizeof figures) {
    ssize_t n = read(fds[0], at + got, sizeof figures - got);
    if (n <= 0) break;
    got += static_cast<std::size_t>(n);
  }
  close(fds[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  if (got != sizeof figures) {
    figures = Figures{};
    setError(figures, "the child ended without figures (status " + std::to_string(status) + ")");
    return figures;
  }
  figures.treePeakRssKiB = usage.ru_maxrss;  // kibibytes on Linux
  return figures;
}

std::string grouped(std::size_t n) {
  std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

void printHeader() {
  std::printf("%-11s %5s %11s %12s %8s %8s %8s %8s %11s %9s %9s %8s %9s\n", "model", "steps",
              "modules", "text bytes", "load s", "derive s", "write s", "total s", "modules/s",
              "steps/s", "peak MiB", "B/module", "+cpp MiB");
}

void printRow(const char* name, const Figures& f) {
  double peakBytes = static_cast<double>(f.peakRssKiB) * 1024.0;
  std::printf("%-11s %5d %11s %12s %8.3f %8.3f %8.3f %8.3f %11.3e %9.1f %9.1f %8.2f %9.1f\n", name,
              f.steps, grouped(f.modules).c_str(), grouped(f.textBytes).c_str(), f.loadSeconds,
              f.deriveSeconds, f.writeSeconds, f.totalSeconds(),
              static_cast<double>(f.modules) / f.totalSeconds(), f.steps / f.deriveSeconds,
              peakBytes / (1024.0 * 1024.0),
              f.modules ? peakBytes / static_cast<double>(f.modules) : 0.0,
              static_cast<double>(f.treePeakRssKiB) / 1024.0);
}

void printCpfgComparison(const std::vector<std::pair<const BenchModel*, Figures>>& rows) {
  std::printf("\nagainst cpfg (whole process, string written with -str; goals are Hirsute's):\n");
  std::printf("%-11s %9s %9s %9s %10s %10s %10s\n", "model", "total s", "cpfg s", "goal s",
              "peak MiB", "cpfg MiB", "goal MiB");
  for (const auto& [m, f] : rows) {
    if (m->cpfgSeconds == 0) continue;
    std::printf("%-11s %9.3f %9.3f %9.3f %10.1f %10.1f %10.1f\n", m->name, f.totalSeconds(),
                m->cpfgSeconds, m->goalSeconds, static_cast<double>(f.peakRssKiB) / 1024.0,
                m->cpfgPeakMiB, m->goalPeakMiB);
  }
  std::printf(
      "(in-process figures: no program start-up, GL or preprocessor; scripts/bench.sh prints the "
      "whole\nprocess of `hirsute derive` beside them)\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Derivation benchmark: times and peak memory of the models in models/bench"};
  std::string only;
  int repeat = 1;
  std::string modelFolder = HIRSUTE_BENCH_MODEL_DIR;
  app.add_option("--model", only,
                 "Run only this model (parametric, branching, signal, loops, stochastic)");
  app.add_option("--repeat", repeat, "Runs per model; the fastest is reported")
      ->check(CLI::Range(1, 1000));
  app.add_option("--models", modelFolder, "The folder of the benchmark models")
      ->check(CLI::ExistingDirectory);
  CLI11_PARSE(app, argc, argv);

  std::vector<const BenchModel*> chosen;
  for (const BenchModel& m : kModels) {
    if (only.empty() || only == m.name) chosen.push_back(&m);
  }
  if (chosen.empty()) {
    std::cerr << "hirsute_derive_bench: no model named '" << only << "'\n";
    return 2;
  }

  std::printf("%d run(s) per model, fastest reported; each in its own process\n\n", repeat);
  printHeader();
  int failures = 0;
  std::vector<std::pair<const BenchModel*, Figures>> measured;
  for (const BenchModel* m : chosen) {
    std::optional<Figures> best;
    for (int run = 0; run < repeat; ++run) {
      Figures f = measureInChild(std::filesystem::path(modelFolder) / m->file);
      if (!f.ok) {
        std::fprintf(stderr, "%s: %s\n", m->name, f.error);
        best.reset();
        break;
      }
      if (!best || f.totalSeconds() < best->totalSeconds()) best = f;
    }
    if (!best) {
      ++failures;
      continue;
    }
    printRow(m->name, *best);
    measured.emplace_back(m, *best);
  }
  std::printf(
      "\nmodules/s: final modules / total seconds (load + derive + write); steps/s: steps / derive "
      "seconds;\n"
      "B/module: peak resident bytes of the model's process (VmHWM) / final modules; +cpp MiB: the "
      "larger\n"
      "of that peak and the preprocessor's (wait4's ru_maxrss). Text is cpfg's -str format.\n");
  for (const BenchModel* m : chosen)
    std::printf("  %-11s %s (models/bench/%s)\n", m->name, m->exercises, m->file);
  printCpfgComparison(measured);
  return failures ? 1 : 0;
}
