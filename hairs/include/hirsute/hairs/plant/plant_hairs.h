// The hair stage (docs/design.md, "Plant hairs"): after interpretation, the templates the view file
// names are derived and the hairs placed on every hairy generalized-cylinder segment, with the
// view file's texture, seed and interpolation and the model's function set.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "hirsute/core/diagnostic.h"
#include "hirsute/hairs/organ_stage.h"
#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/hair_placement.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/lsys/function_curve.h"

namespace hirsute {

struct PlantHairOptions {
  std::uint64_t seed = 0;             // 0: the view file's `hair texture:` seed
  std::size_t maxHairs = 50'000'000;  // more is an error
  std::string lsystemFile;            // where the limit error points
  Progress* progress = nullptr;       // shows the placement's progress (null: nothing)
};

// Whether any segment of the scene has a side with hairs switched on.
bool hasHairs(const Scene& scene);

// Loads the templates into the scene's HairPart and places the hairs. Throws DiagnosticError for
// a broken template or more hairs than the limit; warns about hairy segments drawn as lines.
HairPlacementReport growPlantHairs(Scene& scene, const ModelResources& resources,
                                   const ViewFunctions& functions, const PlantHairOptions& options,
                                   Diagnostics& diagnostics);

// The plant hairs' stage (organ_stage.h): --no-hairs, --max-hairs; growPlantHairs with the run's
// seed; it runs when hasHairs.
const OrganStage& plantHairStage();

}  // namespace hirsute
