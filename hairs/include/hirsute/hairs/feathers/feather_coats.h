// Feather coats (Streit & Heidrich 2002, Sec. 4.4; docs/design.md, "Feathers"): follicles on the
// generalized-cylinder segments whose @F attributes switch a side on, placed by the shared
// placement engine, each growing one feather whose type is the bilinear blend of the key
// feathers (@Fk) at the segment's two control points: across the girth by each control point's
// function, along the axis linearly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "hirsute/core/progress.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_settings.h"
#include "hirsute/hairs/placement/point_diffusion.h"
#include "hirsute/hairs/placement/segment_values.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

struct FeatherCoatSettings {
  FollicleLayout layout = FollicleLayout::Diffusion;
  // The point-diffusion texture of `diffusion` follicles (`hair texture:` sets its size).
  PointDiffusionSettings texture;
  std::uint64_t seed = 1;  // the per-follicle random offsets
  std::size_t maxFeathers = 1'000'000;
  GirthFunction function;  // the model's function set, for the `fun` parameters and @Fk's
  Progress* progress = nullptr;  // shows `placing feather coats: N` (null: nothing)
};

struct FeatherCoatReport {
  std::size_t feathers = 0;  // coat feathers placed
  std::size_t segments = 0;  // segments that carried a coat
  std::size_t surfaces = 0;  // mesh surfaces that carried a coat
  std::size_t segmentsWithoutMesh = 0;
};

struct FeatherLimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The follicles of the `hexagonal` layout in the unit tile: a regular hexagonal lattice of
// `columns` × `rows` points (rows even, so that the tile repeats; 26 × 30 keeps the spacing
// regular within 0.1%).
std::vector<TexturePoint> hexagonalFollicles(int columns = 26, int rows = 30);

// Appends the coat feathers to scene.organ<FeatherPart>().feathers, each coat from its bottom
// feather to its top one.
FeatherCoatReport placeFeatherCoats(Scene& scene, const FeatherCoatSettings& settings);

}  // namespace hirsute
