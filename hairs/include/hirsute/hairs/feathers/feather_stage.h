// The feather stage of the pipeline (docs/design.md, "Feathers"): after interpretation, the feather
// types the view file names are read into the Scene, the feathers whose types the model lacks
// are dropped with a warning, and the box that holds every feather is measured for the camera.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "hirsute/core/diagnostic.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/organ_stage.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/lsys/function_curve.h"

namespace hirsute {

struct FeatherStageOptions {
  std::string lsystemFile;  // where warnings and limit errors about the L-system's feathers point
  std::uint64_t seed = 0;   // of the coats' follicles; 0: the view file's `hair texture:` seed
  std::size_t maxFeathers = 1'000'000;  // more feathers (@Fe and @Fi ones and coats) are an error
  std::size_t maxVertices = kDefaultMaxVertices;  // FeatherPart::maxVertices
  bool fullDetail = false;                        // FeatherPart::fullDetail (--full-feathers)
  Progress* progress = nullptr;         // shows the coats' placement (null: nothing)
};

struct FeatherStageReport {
  std::size_t types = 0;     // feather types read
  std::size_t feathers = 0;  // feathers kept, coats included
  std::size_t coat = 0;      // coat feathers placed
  std::size_t dropped = 0;   // feathers of types the view file does not declare
};

// Whether the scene has feathers, or the view file feather types, for the stage to handle.
bool hasFeathers(const Scene& scene, const ModelResources& resources);

// Reads the types into scene.organ<FeatherPart>().types, places the coats (feather_coats.h) and
// measures scene.organ<FeatherPart>().bounds. Throws DiagnosticError for a broken .fea file (at its
// own line:col), a missing one (at the view file's `feather:` line) and more feathers than
// maxFeathers.
FeatherStageReport growFeathers(Scene& scene, const ModelResources& resources,
                                const ViewFunctions& functions, const FeatherStageOptions& options,
                                Diagnostics& diagnostics);

// The feathers' stage (organ_stage.h): --no-feathers, --max-feathers, --full-feathers; growFeathers with the run's
// seed when hasFeathers; switched off, the turtle's feathers are taken out.
const OrganStage& featherStage();

}  // namespace hirsute
