// hirsute_fur_export_bench: fur strand export figures (docs/design.md, "Benchmarks"; docs/fur.md).
//
// POV-Ray cannot draw shells, so the export turns fur into explicit strands (pov_fur.cpp). This
// scales the furry torus (models/fur-torus) to about a million strands by the texels along a
// strand's length of its `fur texture:` line (the strands per area go about with its square),
// written into a copy of its view file in a temporary folder (the shipped files are left as they
// are), builds it as `hirsute export` does, and prints the seconds the POV-Ray export takes
// (strands per second, bytes per strand), then runs POV-Ray on the file at 640×480 and prints its
// parse, bounding and trace (render) times and its peak resident memory. Figures are printed, never
// asserted.
#include <sys/resource.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_strands.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/export/povray_runner.h"
#include "model_pipeline.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string readText(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The peak resident memory of the largest child process waited for so far, in MiB (what
// `/usr/bin/time -v` reports as its maximum resident set size).
double childPeakMebibytes() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// This process's peak resident memory so far (the Scene and the export), in MiB.
double ownPeakMebibytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

std::size_t strandCount(const hirsute::Scene& scene) {
  std::size_t strands = 0;
  for (const hirsute::FurSurface& surface : scene.organ<hirsute::FurPart>().surfaces)
    strands += hirsute::fur::countStrands(scene, surface);
  return strands;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hirsute;
  double target = 1'000'000;
  int runs = 1, width = 640, height = 480;
  bool povray = true, antialias = false;
  std::string viewName = "torus.v", folderOption;
  CLI::App app{
      "Fur strand export: a torus of about a million strands to POV-Ray, and POV-Ray on it"};
  app.add_option("--strands", target, "About this many strands (default 1000000)")
      ->check(CLI::Range(1.0, 1e9));
  app.add_option("--view", viewName, "The model's view file (default torus.v; wet.v clumps)");
  app.add_option("--runs", runs, "Timed exports; the best is printed (default 1)")
      ->check(CLI::Range(1, 100));
  app.add_flag("!--no-povray", povray, "Do not run POV-Ray");
  app.add_option("--width", width, "POV-Ray's image width (default 640)");
  app.add_option("--height", height, "POV-Ray's image height (default 480)");
  app.add_flag("--antialias", antialias, "Render anti-aliased (+A0.3, as export --render does)");
  app.add_option("--folder", folderOption,
                 "Where the files are written and kept (default: a temporary folder, removed)");
  CLI11_PARSE(app, argc, argv);

  const fs::path model = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "fur-torus";
  const fs::path folder =
      folderOption.empty()
          ? fs::temp_directory_path() / ("hirsute_fur_export_bench_" + std::to_string(::getpid()))
          : fs::path(folderOption);
  fs::create_directories(folder);
  const std::string view = readText(model / viewName);
  const std::regex furTexture(R"(fur texture: *(\d+) +(\d+) +(\d+))");
  std::smatch line;
  if (!std::regex_search(view, line, furTexture)) {
    std::fprintf(stderr, "%s has no `fur texture: SIZE SEED TEXELS` line\n",
                 (model / viewName).c_str());
    return 2;
  }
  const double shippedTexels = std::stod(line[3].str());

  // Builds the torus with `texels` texels along a strand's length.
  auto build = [&](double texels) {
    std::ofstream(folder / "torus.v") << std::regex_replace(
        view, furTexture, "fur texture: $1 $2 " + std::to_string(std::lround(texels)));
    cli::ModelOptions options;
    options.lsystemFile = (model / "torus.l").string();
    options.viewFile = (folder / "torus.v").string();
    options.colormaps = {(model / "torus.map").string()};
    Diagnostics diagnostics(&std::cerr);
    return cli::buildScene(options, diagnostics);
  };
  int status = 0;
  try {
    // The strands go about with the square of the texels per length (not exactly: a closed
    // cylinder takes a whole number of texture tiles around its girth). From that estimate, the
    // whole number of texels nearest the target, counted without making the strands.
    const std::size_t shipped = strandCount(build(shippedTexels).scene);
    const double estimate =
        std::round(shippedTexels * std::sqrt(target / static_cast<double>(shipped)));
    double texels = 1;
    double closest = 1e300;
    for (double t = std::max(1.0, estimate - 6); t <= std::min(4096.0, estimate + 6); ++t) {
      const double miss = std::fabs(static_cast<double>(strandCount(build(t).scene)) - target);
      if (miss < closest) {
        closest = miss;
        texels = t;
      }
    }
    auto started = Clock::now();
    cli::BuiltScene built = build(texels);
    const double buildSeconds = secondsSince(started);
    std::printf(
        "model: models/fur-torus/torus.l with %s, `fur texture: %s %s %.0f` (shipped: "
        "%.0f texels, %zu strands)\n",
        viewName.c_str(), line[1].str().c_str(), line[2].str().c_str(), texels, shippedTexels,
        shipped);
    std::printf(
        "scene: %zu fur surfaces, %zu triangles, %zu strands; built (derived, "
        "interpreted, fur stage) in %.2f s\n",
        built.scene.organ<hirsute::FurPart>().surfaces.size(), built.scene.triangleCount(),
        strandCount(built.scene), buildSeconds);

    PovOptions options;
    options.view = built.resources.view;
    options.materialMode = built.resources.materialMode;
    options.width = width;
    options.height = height;
    const fs::path pov = folder / "torus.pov";
    PovExportStats stats;
    double best = 1e30;
    for (int i = 0; i < runs; ++i) {
      started = Clock::now();
      stats = writePov(built.scene, options, pov);
      best = std::min(best, secondsSince(started));
    }
    std::printf(
        "POV-Ray export: %.2f s for %zu strands: %.0f strands/s; %.1f MB (%.0f bytes a "
        "strand)\n",
        best, stats.organ("fur strands"), static_cast<double>(stats.organ("fur strands")) / best,
        static_cast<double>(stats.bytes) / 1e6,
        static_cast<double>(stats.bytes) /
            static_cast<double>(std::max<std::size_t>(stats.organ("fur strands"), 1)));
    std::printf("exporter's peak memory: %.0f MiB\n", ownPeakMebibytes());
    std::fflush(stdout);

    if (povray && !povrayAvailable()) {
      std::printf("POV-Ray: not installed (apt install povray); not run\n");
    } else if (povray) {
      started = Clock::now();
      const PovrayRun run = runPovray(pov, folder / "torus.png", width, height, antialias);
      const double wall = secondsSince(started);
      if (run.exitStatus != 0 || run.parseSeconds < 0) {
        std::printf("POV-Ray failed (exit %d):\n%s", run.exitStatus, run.messages.c_str());
        status = 1;
      } else {
        std::printf(
            "POV-Ray at %dx%d%s: parse %.2f s, bounding %.2f s, trace (render) %.2f s; "
            "whole run %.2f s; peak memory %.0f MiB\n",
            width, height, antialias ? " anti-aliased" : "", run.parseSeconds, run.boundingSeconds,
            run.traceSeconds, wall, childPeakMebibytes());
        if (!run.messages.empty()) std::printf("POV-Ray's warnings:\n%s", run.messages.c_str());
      }
    }
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    status = 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    status = 1;
  }
  if (folderOption.empty()) fs::remove_all(folder);
  return status;
}
