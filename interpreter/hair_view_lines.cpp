// The plant hairs' lines of the view file (view_lines.h; docs/hairs.md): gathered by
// organViewLines().
#include <cmath>
#include <limits>
#include <string>

#include "hirsute/interpreter/hair_attributes.h"
#include "hirsute/interpreter/view_lines.h"

namespace hirsute {
namespace {

using view_text::inQuotes;

// `hair texture: SIZE SEED [FILL]` (DESIGN.md): the point-diffusion texture is SIZE×SIZE cells
// with FILL points per cell (0.02 to 0.3 measured; default 0.1).
void hairTexture(ViewLine& c) {
  c.view.hairTextureSize = static_cast<int>(c.requiredInteger("the texture size", 4, 4096));
  c.view.hairTextureSeed =
      static_cast<unsigned>(c.requiredInteger("the seed", 0, std::numeric_limits<unsigned>::max()));
  if (!c.args.atEnd()) {
    const SourceLocation where = c.args.here();
    const double fill = c.requiredNumber("the fill (points per cell)");
    if (!(fill >= 0.02 && fill <= 0.3))
      c.fail(where, "the fill must be from 0.02 to 0.3 points per cell");
    c.view.hairTextureFill = fill;
  }
}

void hairInterpolation(ViewLine& c) {
  const SourceLocation where = c.args.here();
  const std::string_view word = c.requiredWord("on or off");
  if (word != "on" && word != "off") c.fail(where, "expected on or off, found " + inQuotes(word));
  c.view.hairInterpolation = word == "on";
}

const ViewLineCommand kLines[] = {
    {"hair:",
     [](ViewLine& c) {
       const SourceLocation where = c.args.here();
       const std::string file = c.resolve(c.requiredWord("a template L-system file"), where);
       if (c.view.hairTemplates.size() >= static_cast<std::size_t>(kMaxHairTemplates)) {
         c.fail(where,
                "at most " + std::to_string(kMaxHairTemplates) + " template hairs per model");
       }
       c.view.hairTemplates.push_back(HairTemplateDeclaration{file, where});
     }},
    {"hair texture:", &hairTexture},
    {"hair interpolation:", &hairInterpolation},
};

}  // namespace

std::span<const ViewLineCommand> hairViewLines() {
  return kLines;
}

}  // namespace hirsute
