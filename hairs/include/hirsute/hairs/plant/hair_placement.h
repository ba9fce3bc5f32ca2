// Placing plant hairs on generalized-cylinder segments, `~` surfaces and polygons (Fuhrer, Jensen
// & Prusinkiewicz 2004, Sec. 3 and 4; docs/design.md, "Plant hairs") at the attachment points of
// shared placement engine (hairs/placement/surface_sampler.h). Reads the Scene's cylinder
// segments and organ surfaces, their hair attributes and the templates; appends to HairPart::hairs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "hirsute/core/progress.h"
#include "hirsute/hairs/placement/point_diffusion.h"
#include "hirsute/hairs/placement/segment_values.h"
#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

struct HairPlacementSettings {
  // The point-diffusion texture tiled over every segment (`hair texture: SIZE SEED [FILL]`).
  PointDiffusionSettings texture;
  // `hair interpolation: on`: every attribute varies linearly along a segment.
  bool interpolation = false;
  // Seeds the per-hair random offsets (rng parameters, template choice); the same seed places
  // the same hairs.
  std::uint64_t seed = 1;
  // More hairs than this is an error (HairLimitError), not an exhausted machine.
  std::size_t maxHairs = 50'000'000;
  // The model's function set for the `fun` parameters: function `index` (1-based) at x in
  // [0, 1]. Null, or an index it does not know (it returns NaN), reads as no function.
  GirthFunction function;
  // Shows `placing hairs: N` as the hairs are placed (null: nothing).
  Progress* progress = nullptr;
};

struct HairPlacementReport {
  std::size_t hairs = 0;                // placed by this call
  std::size_t segments = 0;             // segments that carried hairs
  std::size_t segmentsWithoutMesh = 0;  // hairy segments not drawn as triangles (line styles)
  std::size_t surfaces = 0;             // `~` surface patches and polygons that carried hairs
};

// Thrown when placement would exceed HairPlacementSettings::maxHairs.
struct HairLimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Places the hairs of every segment, surface patch and polygon whose attributes enable a side.
// HairPart::templates must hold the templates (a scene without templates gets a single straight
// template).
HairPlacementReport placeHairs(Scene& scene, const HairPlacementSettings& settings);

// The template used when the view file declares none: a straight hair of unit length.
HairTemplate straightHairTemplate();

}  // namespace hirsute
