// The plant hairs' lines of the view file (view_lines.h; docs/hairs.md): gathered by
// organViewLines().
#include <cmath>
#include <limits>
#include <string>

#include "hirsute/hairs/plant/hair_attributes.h"
#include "hirsute/hairs/plant/hair_settings.h"
#include "hirsute/interpreter/view_lines.h"

namespace hirsute {
namespace {

// The settings these lines set.
HairSettings& hairs(ViewLine& c) {
  return c.view.organ<HairSettings>();
}

using view_text::inQuotes;

// `hair texture: SIZE SEED [FILL]`: the point-diffusion texture is SIZE×SIZE cells
// with FILL points per cell (0.02 to 0.3 measured; default 0.1).
void hairTexture(ViewLine& c) {
  hairs(c).textureSize = static_cast<int>(c.requiredInteger("the texture size", 4, 4096));
  hairs(c).textureSeed =
      static_cast<unsigned>(c.requiredInteger("the seed", 0, std::numeric_limits<unsigned>::max()));
  if (!c.args.atEnd()) {
    const SourceLocation where = c.args.here();
    const double fill = c.requiredNumber("the fill (points per cell)");
    if (!(fill >= 0.02 && fill <= 0.3))
      c.fail(where, "the fill must be from 0.02 to 0.3 points per cell");
    hairs(c).textureFill = fill;
  }
}

void hairInterpolation(ViewLine& c) {
  const SourceLocation where = c.args.here();
  const std::string_view word = c.requiredWord("on or off");
  if (word != "on" && word != "off") c.fail(where, "expected on or off, found " + inQuotes(word));
  hairs(c).interpolation = word == "on";
}

const ViewLineCommand kLines[] = {
    {"hair:",
     [](ViewLine& c) {
       const SourceLocation where = c.args.here();
       const std::string file = c.resolve(c.requiredWord("a template L-system file"), where);
       if (hairs(c).templates.size() >= static_cast<std::size_t>(kMaxHairTemplates)) {
         c.fail(where,
                "at most " + std::to_string(kMaxHairTemplates) + " template hairs per model");
       }
       hairs(c).templates.push_back(HairTemplateDeclaration{file, where});
     }},
    {"hair texture:", &hairTexture},
    {"hair interpolation:", &hairInterpolation},
};

}  // namespace

std::span<const ViewLineCommand> plantHairViewLines() {
  return kLines;
}

}  // namespace hirsute
