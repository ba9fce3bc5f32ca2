// The feathers' lines of the view file (view_lines.h; docs/feathers.md): gathered by
// organViewLines().
#include <cmath>
#include <limits>
#include <string>

#include "hirsute/interpreter/feather_attributes.h"
#include "hirsute/interpreter/feather_settings.h"
#include "hirsute/interpreter/view_lines.h"

namespace hirsute {
namespace {

// The settings these lines set.
FeatherSettings& feathers(ViewLine& c) {
  return c.view.organ<FeatherSettings>();
}

using view_text::inQuotes;

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
};

}  // namespace

std::span<const ViewLineCommand> featherViewLines() {
  return kLines;
}

}  // namespace hirsute
