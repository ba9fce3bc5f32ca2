// The fur's view-file settings (organ_settings.h; docs/design.md, "Fur"; docs/fur.md): what
// `fur layers:`, `fur texture:`, `wetness mask:`, `droplet:` and `fur force:` set
// (fur_view_lines.cpp).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/interpreter/organ_settings.h"

namespace hirsute {

// A `droplet:` line: a drop of water blended into the wetness mask of fur surface `surface`
// (1-based, in the order the fur stage makes them; 0: every fur surface) at (u, v) of its
// [0, 1]² parametrization, with radius `radius` in those units and wetness rho.
struct Droplet {
  glm::vec2 centre{0.5f};
  float radius = 0.1f;
  float wetness = 1;
  int surface = 0;
  SourceLocation where;
};

// The limits of the fur lines: layers per shell stack and texture sizes.
inline constexpr int kMaxFurLayers = 256;
inline constexpr int kMaxFurTextureSize = 4096;

struct FurSettings : OrganSettingsOf<FurSettings> {
  int layers = 16;  // shells per stack
  // The fur geometry texture: SIZE² texels from SEED, one strand a texel, `texelsPerLength`
  // texels along a strand's length.
  int textureSize = 256;
  unsigned textureSeed = 1;
  float texelsPerLength = 40;
  int wetnessMaskSize = 256;
  std::vector<Droplet> droplets;
  glm::vec3 force{0.0f};  // on every strand, per unit mass: gravity and wind
};

}  // namespace hirsute
