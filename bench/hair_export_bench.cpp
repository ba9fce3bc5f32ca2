// hirsute_hair_export_bench: hair export figures (docs/design.md, "Benchmarks").
//
// One million hairs (the synthetic plant of synthetic_hairs.h: three four-segment templates) as a
// POV-Ray scene of instances (pov_writer.h: a tube per template and radius/length bucket, an
// `object` per hair): the seconds the writer takes and the bytes it writes, and, when povray is
// installed, the seconds POV-Ray takes to parse it and its peak memory; with --render, POV-Ray's
// whole run at 640×480 (parse, bounding, trace). Beside it: the same hairs as OBJ polylines, as
// curves of the scene for Blender (blender_writer.h) and as CSV rows. Figures are printed, never
// asserted.
#include <sys/resource.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "hirsute/hairs/plant/hair_csv_writer.h"
#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/viewer/export/blender_writer.h"
#include "hirsute/viewer/export/obj_writer.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/export/povray_runner.h"
#include "synthetic_hairs.h"

namespace {

namespace fs = std::filesystem;

template <typename F>
double bestSeconds(int runs, F&& run) {
  double best = 1e30;
  for (int i = 0; i < runs; ++i) {
    auto start = std::chrono::steady_clock::now();
    run();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

// The peak resident memory of the largest child process waited for so far, in MB.
double childPeakMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Hair export figures: a million hairs as POV-Ray instances, OBJ polylines, Blender "
      "curves, CSV"};
  std::size_t hairCount = 1'000'000;
  int runs = 3, width = 640, height = 480;
  bool parse = true, render = false;
  std::string folderOption;
  app.add_option("--hairs", hairCount, "Hairs in the synthetic scene (default 1000000)");
  app.add_option("--runs", runs, "Timed runs of each export; the best is reported (default 3)")
      ->check(CLI::Range(1, 100));
  app.add_flag("!--no-povray", parse, "Do not run POV-Ray");
  app.add_flag("--render", render, "Also render the POV-Ray scene (default 640x480, no AA)");
  app.add_option("--width", width, "Render width (default 640)");
  app.add_option("--height", height, "Render height (default 480)");
  app.add_option("--folder", folderOption,
                 "Where the files are written (default: a temporary folder, removed)");
  CLI11_PARSE(app, argc, argv);

  fs::path folder =
      folderOption.empty()
          ? fs::temp_directory_path() / ("hirsute_hair_export_bench_" + std::to_string(getpid()))
          : fs::path(folderOption);
  fs::create_directories(folder);
  try {
    hirsute::Scene scene = hirsute::bench::syntheticHairScene(hairCount, 20240522);
    std::printf("scene: %zu hairs of %zu templates (4 segments each)\n",
                scene.organ<hirsute::HairPart>().hairs.size(),
                scene.organ<hirsute::HairPart>().templates.size());
    double million = static_cast<double>(scene.organ<hirsute::HairPart>().hairs.size()) / 1e6;

    hirsute::PovOptions options;
    options.width = width;
    options.height = height;
    hirsute::PovExportStats pov;
    double povSeconds =
        bestSeconds(runs, [&] { pov = hirsute::writePov(scene, options, folder / "hairs.pov"); });
    std::printf(
        "POV-Ray export: %.3f s  %llu bytes  (%zu hairs in %zu tubes, %.1f bytes/hair, %.3f s "
        "per million hairs)\n",
        povSeconds, static_cast<unsigned long long>(pov.bytes), pov.organ("hairs"),
        pov.organ("hair meshes"),
        static_cast<double>(pov.bytes) /
            static_cast<double>(std::max<std::size_t>(pov.organ("hairs"), 1)),
        povSeconds / million);

    hirsute::ObjExportStats obj;
    double objSeconds =
        bestSeconds(runs, [&] { obj = hirsute::writeObj(scene, folder / "hairs.obj"); });
    std::printf(
        "OBJ export:     %.3f s  %llu bytes  (%llu polylines of %llu `l` segments, %llu "
        "vertices)\n",
        objSeconds, static_cast<unsigned long long>(obj.bytes),
        static_cast<unsigned long long>(obj.polylines),
        static_cast<unsigned long long>(obj.lineElements),
        static_cast<unsigned long long>(obj.vertices));

    hirsute::BlenderExportStats blender;
    double blenderSeconds = bestSeconds(runs, [&] {
      blender = hirsute::writeBlender(scene, hirsute::BlenderOptions{}, folder / "hairs.hirsute");
    });
    std::printf("Blender export: %.3f s  %llu bytes  (%llu curves, %llu points)\n", blenderSeconds,
                static_cast<unsigned long long>(blender.bytes),
                static_cast<unsigned long long>(blender.curves),
                static_cast<unsigned long long>(blender.points));

    hirsute::HairCsvStats csv;
    double csvSeconds =
        bestSeconds(runs, [&] { csv = hirsute::writeHairCsv(scene, folder / "hairs.csv"); });
    std::printf("CSV export:     %.3f s  %llu bytes  (%llu rows)\n", csvSeconds,
                static_cast<unsigned long long>(csv.bytes),
                static_cast<unsigned long long>(csv.rows));

    if (parse && hirsute::povrayAvailable()) {
      auto start = std::chrono::steady_clock::now();
      hirsute::PovrayRun run =
          hirsute::runPovray(folder / "hairs.pov", folder / "parse.png", 32, 24, false);
      double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (run.exitStatus != 0 || run.parseSeconds < 0) {
        std::printf("POV-Ray failed (exit %d):\n%s", run.exitStatus, run.messages.c_str());
      } else {
        std::printf("POV-Ray parse:  %.3f s  (whole run at 32x24: %.3f s, peak memory %.0f MB)%s\n",
                    run.parseSeconds, wall, childPeakMegabytes(),
                    run.messages.empty() ? "" : "  with warnings:");
        if (!run.messages.empty()) std::printf("%s", run.messages.c_str());
      }
      if (render) {
        start = std::chrono::steady_clock::now();
        run = hirsute::runPovray(folder / "hairs.pov", folder / "hairs.png", width, height, false);
        wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf(
            "POV-Ray render: %.3f s at %dx%d (parse %.3f s), exit %d, peak memory %.0f MB%s\n",
            wall, width, height, run.parseSeconds, run.exitStatus, childPeakMegabytes(),
            run.messages.empty() ? "" : "  with warnings:");
        if (!run.messages.empty()) std::printf("%s", run.messages.c_str());
      }
    } else if (parse) {
      std::printf("POV-Ray: povray is not installed\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hirsute_hair_export_bench: %s\n", e.what());
    if (folderOption.empty()) fs::remove_all(folder);
    return 1;
  }
  if (folderOption.empty()) fs::remove_all(folder);
  return 0;
}
