// hirsute_hair_placement_bench: how fast hairs are generated and what a placed hair costs
// (docs/design.md, "Benchmarks": hairs per second and bytes per placed hair; issue targets: a
// million hairs in at most 1 s, at most 48 bytes per hair).
//
// The model (default: the shipped Nankin cherry, about a million hairs) is derived and
// interpreted once, untimed; then the hair stage as `hirsute render` runs it (templates derived
// and placed: growPlantHairs) is timed on a fresh copy of that Scene, repeated, and the fastest
// run reported. Bytes per hair: the heap the stage leaves allocated (glibc's mallinfo2, after
// minus before: the hair vector, reserved once from the expected count, and the templates) over
// the hairs placed; the stage's transient allocations (the texture, 10⁴ cells and its points)
// are small beside it.
#include <malloc.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/plant_hairs.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"

namespace {

namespace fs = std::filesystem;

std::size_t heapInUse() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

// The colour file of a model folder, as the command line finds it (the single .map or .mat).
hirsute::ColorFiles colorFilesIn(const fs::path& folder) {
  hirsute::ColorFiles files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() == ".map") files.colormaps.push_back({1, entry.path()});
    if (entry.path().extension() == ".mat") files.materials.push_back({1, entry.path()});
  }
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Hair generation: hairs per second and bytes per placed hair");
  std::string lsystem = std::string(HIRSUTE_MODELS_DIR) + "/nankin-cherry/nankin-cherry.l";
  std::string view;
  int repeat = 5;
  app.add_option("--model", lsystem, "The .l file (default: models/nankin-cherry)");
  app.add_option("--view", view, "The .v file (default: the .l's name with .v)");
  app.add_option("--repeat", repeat, "Runs of the hair stage (the fastest is reported)")
      ->check(CLI::Range(1, 100));
  CLI11_PARSE(app, argc, argv);
  if (view.empty()) view = fs::path(lsystem).replace_extension(".v").string();

  hirsute::Diagnostics diagnostics(&std::cerr);
  try {
    const hirsute::ModelResources resources = hirsute::loadModelResources(
        fs::path(view), colorFilesIn(fs::path(lsystem).parent_path()), diagnostics);
    hirsute::Model model = hirsute::loadModel(lsystem, fs::path(view), diagnostics);
    hirsute::Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder,
                                 std::cerr);
    hirsute::Derivation derivation(model.program, evaluator, diagnostics);
    hirsute::installQueryPass(derivation, resources, diagnostics);
    derivation.run();
    hirsute::Scene plant;
    hirsute::interpret(derivation, resources, plant, diagnostics);
    std::printf("model %s: %zu triangles, %zu cylinder segments\n", lsystem.c_str(),
                plant.triangleCount(), plant.cylinderSegments.size());

    hirsute::PlantHairOptions options;
    options.lsystemFile = lsystem;
    double best = 1e30;
    std::size_t hairs = 0, kept = 0, capacity = 0;
    for (int run = 0; run < repeat; ++run) {
      hirsute::Scene scene = plant;
      malloc_trim(0);
      const std::size_t before = heapInUse();
      const auto start = std::chrono::steady_clock::now();
      const hirsute::HairPlacementReport report =
          hirsute::growPlantHairs(scene, resources, model.functions, options, diagnostics);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const std::size_t after = heapInUse();
      best = std::min(best, seconds);
      hairs = report.hairs;
      kept = after - before;
      capacity = scene.organ<hirsute::HairPart>().hairs.capacity();
    }
    std::printf("hairs placed          %zu\n", hairs);
    std::printf("hair stage (best of %d) %.3f s   %.3g hairs/s   %.3f s per million hairs\n",
                repeat, best, hairs / best, best * 1e6 / std::max<std::size_t>(hairs, 1));
    std::printf(
        "bytes per placed hair %.1f on the heap (a Hair is %zu bytes; the vector holds %.3f× the "
        "hairs placed)\n",
        static_cast<double>(kept) / std::max<std::size_t>(hairs, 1), sizeof(hirsute::Hair),
        static_cast<double>(capacity) / std::max<std::size_t>(hairs, 1));
  } catch (const hirsute::DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    return 2;
  }
  return 0;
}
