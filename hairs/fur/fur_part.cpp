// The fur's part of the Scene (fur_part.h).
#include "hirsute/hairs/fur/fur_part.h"

namespace hirsute {

void FurPart::addBounds(Bounds& box) const {
  for (const FurSurface& fur : surfaces) {
    const float length =
        fur.attributes >= 0 ? attributes[static_cast<std::size_t>(fur.attributes)].length : 0.0f;
    for (const glm::vec3& p : fur.positions) {
      box.add(p - glm::vec3(length));
      box.add(p + glm::vec3(length));
    }
  }
}

}  // namespace hirsute
