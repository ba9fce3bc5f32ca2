#include "hirsute/hairs/plant/plant_hairs.h"

#include "hirsute/hairs/placement/mesh_sampling.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/hair_settings.h"
#include "hirsute/hairs/plant/hair_templates.h"

namespace hirsute {

bool hasHairs(const Scene& scene) {
  const std::vector<HairAttributes>& records = scene.organ<HairPart>().attributes;
  for (const CylinderSegment& segment : scene.cylinderSegments) {
    for (int index :
         {segment.organStart.of<HairAttributes>(), segment.organEnd.of<HairAttributes>()}) {
      if (index >= 0 && static_cast<std::size_t>(index) < records.size() &&
          records[static_cast<std::size_t>(index)].anyEnabled()) {
        return true;
      }
    }
  }
  for (const OrganSurface& surface : scene.organSurfaces) {
    const int index = surface.organs.of<HairAttributes>();
    if (index >= 0 && static_cast<std::size_t>(index) < records.size() &&
        records[static_cast<std::size_t>(index)].anyEnabled()) {
      return true;
    }
  }
  return false;
}

HairPlacementReport growPlantHairs(Scene& scene, const ModelResources& resources,
                                   const ViewFunctions& functions, const PlantHairOptions& options,
                                   Diagnostics& diagnostics) {
  scene.organ<HairPart>().templates = loadHairTemplates(resources, diagnostics);
  const ViewSettings& view = resources.view;
  HairPlacementSettings settings;
  const HairSettings& hairs = view.organ<HairSettings>();
  settings.texture.width = settings.texture.height = hairs.textureSize;
  settings.texture.seed = hairs.textureSeed;
  settings.texture.fill = hairs.textureFill;
  settings.seed = options.seed != 0 ? options.seed : hairs.textureSeed;
  settings.interpolation = hairs.interpolation;
  settings.maxHairs = options.maxHairs;
  settings.progress = options.progress;
  const std::vector<FunctionCurve>& curves = functions.functions;
  settings.function = [&curves](int index, double x) {
    if (index < 1 || static_cast<std::size_t>(index) > curves.size()) return std::nan("");
    return curves[static_cast<std::size_t>(index) - 1].evaluate(x);
  };
  HairPlacementReport report;
  try {
    report = placeHairs(scene, settings);
  } catch (const HairLimitError& e) {
    throw DiagnosticError(
        SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0}, e.what());
  } catch (const SamplingLimitError& e) {
    throw DiagnosticError(
        SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0}, e.what());
  }
  if (report.segmentsWithoutMesh > 0) {
    diagnostics.warn(
        SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0},
        fmt::format("{} hairy generalized-cylinder segments are drawn as lines and get no "
                    "hairs; hairs grow on cylinders drawn as triangles (`line style: "
                    "cylinder` in the view file)",
                    report.segmentsWithoutMesh));
  }
  return report;
}

}  // namespace hirsute

namespace hirsute {
namespace {

struct HairCommandOptions : OrganOptionsOf<HairCommandOptions> {
  std::size_t maxHairs = PlantHairOptions{}.maxHairs;
};

class PlantHairStage : public OrganStageOf<HairCommandOptions> {
 public:
  const char* activity() const override { return "placing hairs"; }

  bool wanted(const Scene& scene, const ModelResources&) const override { return hasHairs(scene); }

 protected:
  void declareOptions(CLI::App& command, HairCommandOptions& s) const override {
    command.add_flag("!--no-hairs", s.enabled, "Leave out the plant hairs (@H modules)");
    command.add_option("--max-hairs", s.maxHairs, "More hairs are an error (default 50000000)");
  }
  std::string growFrom(const OrganStageRun& run, const HairCommandOptions& chosen) const override {
    PlantHairOptions options;
    options.seed = run.seed;
    options.maxHairs = chosen.maxHairs;
    options.lsystemFile = run.lsystemFile;
    options.progress = run.progress;
    const HairPlacementReport report =
        growPlantHairs(run.scene, run.resources, run.functions, options, run.diagnostics);
    return fmt::format("placed {} hairs on {} segments and {} surfaces ({} templates)",
                       report.hairs, report.segments, report.surfaces,
                       run.scene.organ<HairPart>().templates.size());
  }
};

}  // namespace

const OrganStage& plantHairStage() {
  static const PlantHairStage stage;
  return stage;
}

}  // namespace hirsute
