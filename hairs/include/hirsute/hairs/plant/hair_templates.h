// Template hairs (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3.2; docs/design.md): small L-systems
// named by the view file's `hair:` lines, derived and interpreted by the plant's own turtle, kept
// once as polylines in the hair's frame.
#pragma once

#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

// Derives and interprets every `hair:` file of `resources.view`, in order, with the plant's
// view settings (angle increment, colours). Throws DiagnosticError at the template's own
// file:line:col for a broken template, at its `hair:` line for a missing one or one that draws
// nothing.
std::vector<HairTemplate> loadHairTemplates(const ModelResources& resources,
                                            Diagnostics& diagnostics);

// The template of an interpreted scene: its line segments in drawing order, chained into
// polylines, turned into the hair frame (x along the first segment). A scene without segments
// is an error at `where` (or the file, when `where` has none). Exposed for tests.
HairTemplate hairTemplateFromScene(const Scene& scene, const std::string& file,
                                   const SourceLocation& where = {});

}  // namespace hirsute
