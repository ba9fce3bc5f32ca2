// The fur stage of the pipeline (docs/design.md, "Fur"): after interpretation, every run of
// generalized-cylinder segments the turtle covered with fur (@Uf(1)) becomes a fur surface in the
// Scene, with its (u, v) around the girth and along the axis, its fur texture, its strands at
// rest under the view file's `fur force:`, and its wetness mask with the view file's droplets
// and any random ones blended in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "hirsute/core/diagnostic.h"
#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/organ_stage.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

// What the droplets of one run may cost; passing either is an error naming it. A droplet blends
// the texels of its square on the mask; a surface gets its mask (wetness mask² texels of 16
// bytes) when the first droplet falls on it, and a dry one has none.
struct DropletLimits {
  std::uint64_t texels = std::uint64_t{1} << 30;     // about 3 s of blending
  std::uint64_t maskBytes = std::uint64_t{1} << 30;  // 1 GiB: four 4096² masks, 4096 of 256²
};

struct FurStageOptions {
  // Random droplets (`--droplets N`), spread over the fur surfaces by area.
  std::size_t droplets = 0;
  float dropletRadius = 0.05f;   // in the surfaces' [0, 1] units
  float dropletWetness = 1.0f;
  std::uint32_t dropletSeed = 1;
  std::size_t maxSurfaces = 100'000;  // more fur surfaces are an error
  DropletLimits dropletLimits;
  std::string lsystemFile;  // where warnings about the model point
  std::size_t maxVertices = kDefaultMaxVertices;  // the exported strands' points, in all
};

struct FurStageReport {
  std::size_t surfaces = 0;
  std::size_t triangles = 0;
  std::size_t droplets = 0;  // blended, the view file's and the random ones
  double area = 0;
};

// Whether the turtle put fur on anything.
bool hasFur(const Scene& scene);

// Builds the surfaces and textures of the scene's FurPart. Throws DiagnosticError for a `droplet:`
// line naming a fur surface the model does not have (at that line) and for more surfaces than the
// limit.
FurStageReport growFur(Scene& scene, const ModelResources& resources,
                       const FurStageOptions& options, Diagnostics& diagnostics);

// Blends `count` droplets, seeded, at random points of the fur surfaces (each surface's chance
// its share of the area), as `--droplets` and the viewer's spray do. Returns how many landed.
// Throws DiagnosticError (no place in a file: the count is an option) when they would pass
// `limits`; the droplets blended before stay.
std::size_t sprayDroplets(Scene& scene, std::size_t count, float radius, float wetness,
                          std::uint32_t seed, const DropletLimits& limits = {});

// The fur's stage (organ_stage.h): --no-fur and the random droplets' options; growFur when hasFur.
const OrganStage& furStage();

}  // namespace hirsute
