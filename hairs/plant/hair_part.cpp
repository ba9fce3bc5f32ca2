// The plant hairs' part of the Scene (hair_part.h).
#include "hirsute/hairs/plant/hair_part.h"

namespace hirsute {

void HairPart::addBounds(Bounds& box) const {
  for (const Hair& h : hairs) {
    if (h.templateIndex >= templates.size()) continue;
    const float reach = h.length * templates[h.templateIndex].extent;
    box.add(h.root - glm::vec3(reach));
    box.add(h.root + glm::vec3(reach));
  }
}

}  // namespace hirsute
