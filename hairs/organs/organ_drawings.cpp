// The organs' drawings in the GL renderer, registered (organ_list.h), in the order they are drawn.
#include "hirsute/viewer/gl/organ_drawing.h"
#include "organ_list.h"

namespace hirsute {

#define HIRSUTE_DECLARE(folder, name) const OrganDrawingType& name##Drawing();
HIRSUTE_ORGANS(HIRSUTE_DECLARE)
#undef HIRSUTE_DECLARE

std::span<const OrganDrawingType* const> organDrawings() {
#define HIRSUTE_DRAWING(folder, name) &name##Drawing(),
  static const OrganDrawingType* const drawings[] = {HIRSUTE_ORGANS(HIRSUTE_DRAWING)};
#undef HIRSUTE_DRAWING
  return drawings;
}

}  // namespace hirsute
