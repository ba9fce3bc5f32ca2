// The fur's lines of the view file (view_lines.h; docs/fur.md): gathered by organViewLines().
#include <cmath>
#include <limits>
#include <string>

#include "hirsute/hairs/fur/fur_attributes.h"
#include "hirsute/hairs/fur/fur_settings.h"
#include "hirsute/interpreter/view_lines.h"

namespace hirsute {
namespace {

// The settings these lines set.
FurSettings& fur(ViewLine& c) {
  return c.view.organ<FurSettings>();
}

using view_text::inQuotes;

// `fur texture: SIZE SEED [TEXELS]` (docs/fur.md): SIZE² texels from SEED, TEXELS texels along
// the length of a strand (default 40: strands are a fortieth of their length thick).
void furTexture(ViewLine& c) {
  fur(c).textureSize =
      static_cast<int>(c.requiredInteger("the texture size", 16, kMaxFurTextureSize));
  fur(c).textureSeed =
      static_cast<unsigned>(c.requiredInteger("the seed", 0, std::numeric_limits<unsigned>::max()));
  if (!c.args.atEnd()) {
    const SourceLocation where = c.args.here();
    const double texels = c.requiredNumber("the texels along a strand's length");
    if (!(texels >= 1 && texels <= 4096))
      c.fail(where, "the texels per length must be from 1 to 4096");
    fur(c).texelsPerLength = static_cast<float>(texels);
  }
}

// `droplet: u v r rho [surface]` (docs/fur.md).
void droplet(ViewLine& c) {
  Droplet d;
  d.where = c.labelAt();
  const SourceLocation uAt = c.args.here();
  const double u = c.requiredNumber("the droplet's u");
  const SourceLocation vAt = c.args.here();
  const double v = c.requiredNumber("the droplet's v");
  if (!(u >= 0 && u <= 1))
    c.fail(uAt, "the droplet's u must be in [0, 1] (the fur surface's parametrization)");
  if (!(v >= 0 && v <= 1))
    c.fail(vAt, "the droplet's v must be in [0, 1] (the fur surface's parametrization)");
  const SourceLocation rAt = c.args.here();
  const double r = c.requiredNumber("the droplet's radius");
  if (!(r > 0 && r <= 1)) c.fail(rAt, "the droplet's radius must be in (0, 1]");
  const SourceLocation rhoAt = c.args.here();
  const double rho = c.requiredNumber("the droplet's wetness");
  if (!(rho >= 0 && rho <= 1)) c.fail(rhoAt, "the droplet's wetness must be in [0, 1]");
  if (!c.args.atEnd())
    d.surface =
        static_cast<int>(c.requiredInteger("the fur surface (1-based, 0: all)", 0, 1 << 30));
  d.centre = glm::vec2(static_cast<float>(u), static_cast<float>(v));
  d.radius = static_cast<float>(r);
  d.wetness = static_cast<float>(rho);
  fur(c).droplets.push_back(d);
}

const ViewLineCommand kLines[] = {
    {"fur layers:",
     [](ViewLine& c) {
       fur(c).layers =
           static_cast<int>(c.requiredInteger("the number of layers", 1, kMaxFurLayers));
     }},
    {"fur texture:", &furTexture},
    {"wetness mask:",
     [](ViewLine& c) {
       fur(c).wetnessMaskSize =
           static_cast<int>(c.requiredInteger("the mask size", 8, kMaxFurTextureSize));
     }},
    {"droplet:", &droplet},
    {"fur force:",
     [](ViewLine& c) {
       glm::vec3 force;
       for (int i = 0; i < 3; ++i) {
         const SourceLocation where = c.args.here();
         const double value = c.requiredNumber("the force's x, y and z");
         if (!std::isfinite(value) || std::abs(value) > 1e6)
           c.fail(where, "a fur force component must be finite, at most 1e6");
         force[i] = static_cast<float>(value);
       }
       fur(c).force = force;
     }},
};

}  // namespace

std::span<const ViewLineCommand> furViewLines() {
  return kLines;
}

}  // namespace hirsute
