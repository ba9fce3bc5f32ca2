// The feathers' lines of the view file (view_lines.h; docs/feathers.md): gathered by
// organViewLines().
#include <cmath>
#include <limits>
#include <string>

#include "hirsute/interpreter/feather_attributes.h"
#include "hirsute/interpreter/view_lines.h"

namespace hirsute {
namespace {

using view_text::inQuotes;

const ViewLineCommand kLines[] = {
    {"feather:",
     [](ViewLine& c) {
       const SourceLocation where = c.args.here();
       const std::string file = c.resolve(c.requiredWord("a feather type file (.fea)"), where);
       if (c.view.featherTypes.size() >= static_cast<std::size_t>(kMaxFeatherTypes)) {
         c.fail(where, "at most " + std::to_string(kMaxFeatherTypes) + " feather types per model");
       }
       c.view.featherTypes.push_back(FeatherTypeDeclaration{file, where});
     }},
    {"feather follicles:",
     [](ViewLine& c) {
       const SourceLocation where = c.args.here();
       const std::string_view word = c.requiredWord("diffusion or hexagonal");
       if (word != "diffusion" && word != "hexagonal")
         c.fail(where, "expected diffusion or hexagonal, found " + inQuotes(word));
       c.view.follicleLayout =
           word == "hexagonal" ? FollicleLayout::Hexagonal : FollicleLayout::Diffusion;
     }},
};

}  // namespace

std::span<const ViewLineCommand> featherViewLines() {
  return kLines;
}

}  // namespace hirsute
