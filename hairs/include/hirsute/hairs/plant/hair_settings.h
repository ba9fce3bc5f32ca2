// The plant hairs' view-file settings (organ_settings.h; docs/design.md and docs/hairs.md):
// what `hair:`, `hair texture:` and `hair interpolation:` set (hair_view_lines.cpp).
#pragma once

#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/interpreter/organ_settings.h"

namespace hirsute {

// A `hair:` line: a template hair's L-system.
struct HairTemplateDeclaration {
  std::string file;      // resolved against the view file's folder
  SourceLocation where;  // the file name on its view-file line
};

struct HairSettings : OrganSettingsOf<HairSettings> {
  // The template L-systems in order.
  std::vector<HairTemplateDeclaration> templates;
  // The point-diffusion texture (`hair texture: SIZE SEED [FILL]`), which the feathers' coats
  // lay their follicles out with too: SIZE² cells from SEED, FILL points per cell.
  int textureSize = 100;
  unsigned textureSeed = 1;
  double textureFill = 0.1;
  // `hair interpolation:` blends the attributes of a segment's two ends along it.
  bool interpolation = false;
};

}  // namespace hirsute
