// The organs' drawings in the GL renderer, registered: one line an organ, in the order they are
// drawn.
#include "hirsute/hairs/feathers/feather_drawing.h"
#include "hirsute/hairs/fur/fur_drawing.h"
#include "hirsute/hairs/plant/hair_drawing.h"
#include "hirsute/viewer/gl/organ_drawing.h"

namespace hirsute {

std::span<const OrganDrawingType* const> organDrawings() {
  static const OrganDrawingType* const drawings[] = {
      &plantHairDrawing(),
      &featherDrawing(),
      &furDrawing(),
  };
  return drawings;
}

}  // namespace hirsute
