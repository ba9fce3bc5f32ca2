// The feathers' lines of the view file (view_lines.h; docs/feathers.md): gathered by
// organViewLines().
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "hirsute/hairs/feathers/feather_attributes.h"
#include "hirsute/hairs/feathers/feather_settings.h"
#include "hirsute/interpreter/view_lines.h"

namespace hirsute {
namespace {

// The settings these lines set.
FeatherSettings& feathers(ViewLine& c) {
  return c.view.organ<FeatherSettings>();
}

using view_text::inQuotes;

// A number of a `dynamics …:` line that must lie in [lo, hi].
double dynamicsNumber(ViewLine& c, const std::string& what, double lo, double hi) {
  const SourceLocation where = c.args.here();
  const double value = c.requiredNumber(what);
  if (!(value >= lo && value <= hi)) {
    char range[128];
    std::snprintf(range, sizeof range, " must be from %g to %g, found %g", lo, hi, value);
    c.fail(where, what + range);
  }
  return value;
}

glm::vec3 dynamicsVector(ViewLine& c, const std::string& what) {
  glm::vec3 v;
  for (int i = 0; i < 3; ++i)
    v[i] = static_cast<float>(dynamicsNumber(c, what + "'s x, y and z", -1e6, 1e6));
  return v;
}

// `dynamics gusts: strength scale period [seed]` (docs/dynamics.md).
void dynamicsGusts(ViewLine& c) {
  FeatherDynamicsSettings& d = feathers(c).dynamics;
  d.gustStrength = static_cast<float>(dynamicsNumber(c, "the gusts' strength", 0, 1e6));
  d.gustScale = static_cast<float>(dynamicsNumber(c, "the gusts' scale", 1e-6, 1e6));
  d.gustPeriod = static_cast<float>(dynamicsNumber(c, "the gusts' period", 1e-6, 1e6));
  if (!c.args.atEnd())
    d.gustSeed = static_cast<unsigned>(
        c.requiredInteger("the gusts' seed", 0, std::numeric_limits<unsigned>::max()));
}

const ViewLineCommand kLines[] = {
    {"feather:",
     [](ViewLine& c) {
       const SourceLocation where = c.args.here();
       const std::string file = c.resolve(c.requiredWord("a feather type file (.fea)"), where);
       if (feathers(c).types.size() >= static_cast<std::size_t>(kMaxFeatherTypes)) {
         c.fail(where, "at most " + std::to_string(kMaxFeatherTypes) + " feather types per model");
       }
       feathers(c).types.push_back(FeatherTypeDeclaration{file, where});
     }},
    {"feather follicles:",
     [](ViewLine& c) {
       const SourceLocation where = c.args.here();
       const std::string_view word = c.requiredWord("diffusion or hexagonal");
       if (word != "diffusion" && word != "hexagonal")
         c.fail(where, "expected diffusion or hexagonal, found " + inQuotes(word));
       feathers(c).follicleLayout =
           word == "hexagonal" ? FollicleLayout::Hexagonal : FollicleLayout::Diffusion;
     }},
    {"feather shingling:",
     [](ViewLine& c) {
       const SourceLocation where = c.args.here();
       const std::string_view word = c.requiredWord("on or off");
       if (word != "on" && word != "off")
         c.fail(where, "expected on or off, found " + inQuotes(word));
       feathers(c).shingling = word == "on";
     }},

    // Feather-coat dynamics (docs/dynamics.md).
    {"dynamics gravity:",
     [](ViewLine& c) { feathers(c).dynamics.gravity = dynamicsVector(c, "the gravity"); }},
    {"dynamics wind:",
     [](ViewLine& c) { feathers(c).dynamics.wind = dynamicsVector(c, "the wind"); }},
    {"dynamics gusts:", &dynamicsGusts},
    {"dynamics drag:",
     [](ViewLine& c) {
       feathers(c).dynamics.drag = static_cast<float>(dynamicsNumber(c, "the drag", 0, 1e6));
     }},
    {"dynamics springs:",
     [](ViewLine& c) {
       feathers(c).dynamics.stiffness =
           static_cast<float>(dynamicsNumber(c, "the springs' stiffness", 0, 1e9));
       feathers(c).dynamics.damping =
           static_cast<float>(dynamicsNumber(c, "the springs' damping", 0, 1e9));
     }},
    {"dynamics thickness:",
     [](ViewLine& c) {
       FeatherDynamicsSettings& d = feathers(c).dynamics;
       d.thickness = static_cast<float>(dynamicsNumber(c, "the thickness", 1e-9, 1e6));
       d.separation = static_cast<float>(
           dynamicsNumber(c, "the minimum separation", 1e-9, static_cast<double>(d.thickness)));
     }},
    {"dynamics segments:",
     [](ViewLine& c) {
       feathers(c).dynamics.segments =
           static_cast<int>(c.requiredInteger("the segments of a stem", 1, 64));
     }},
    {"dynamics substeps:",
     [](ViewLine& c) {
       feathers(c).dynamics.substeps =
           static_cast<int>(c.requiredInteger("the steps per frame", 1, 1000));
     }},
    {"dynamics vanes:",
     [](ViewLine& c) {
       const SourceLocation where = c.args.here();
       const std::string_view word = c.requiredWord("on or off");
       if (word != "on" && word != "off")
         c.fail(where, "expected on or off, found " + inQuotes(word));
       feathers(c).dynamics.vanes = word == "on";
     }},
};

}  // namespace

std::span<const ViewLineCommand> featherViewLines() {
  return kLines;
}

}  // namespace hirsute
