// The default key barbs of Streit & Heidrich 2002, Sec. 4.2.1 and 4.3.1: Bdf1, four random
// control vertices (a plumulaceous, fuzzy barb), used where no key barb lies below; Bdf2, a barb
// with a slight front-to-back curve (pennaceous), used where none lies above.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <utility>
#include <vector>

#include "hirsute/hairs/feathers/feather_type.h"

namespace hirsute {

// Sec. 4.3.1: the random vertices are a table computed once from the feather's seed and reused,
// so the same feather is the same on every frame. Barb k of a vane always reads the same entry.
class PlumulaceousBarbTable {
 public:
  static constexpr std::size_t kEntries = 256;
  static constexpr std::size_t kVertices = 4;

  explicit PlumulaceousBarbTable(std::uint64_t seed);
  // The tables of `seeds` mixed entry by entry with their weights (a blended type's,
  // FeatherType::seedBlend); one seed of weight 1 is that seed's table.
  explicit PlumulaceousBarbTable(const std::vector<std::pair<std::uint64_t, float>>& seeds);

  // Bdf1 for barb `index` (counted from the rachis base) of a vane (Left or Right). In the barb
  // frame of KeyBarb: cv0 at the origin, the chord mostly along +x, |cv0 cv3| in [0.7, 1].
  std::span<const glm::vec3> barb(std::size_t index, BarbSide side) const;

 private:
  std::vector<glm::vec3> vertices_;  // kEntries × kVertices
};

// Bdf2: straight along +x in the vane plane, bowed slightly towards the back (-z, into the bird,
// where feathers curve, Sec. 3.3) by 0.05 of its length.
std::span<const glm::vec3> pennaceousDefaultBarb();

}  // namespace hirsute
