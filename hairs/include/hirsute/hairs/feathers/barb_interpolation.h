// The barbs between key barbs (Streit & Heidrich 2002, Sec. 4.2.1): the barb at position rp along
// the rachis is the linear blend of the key barbs found immediately below (Bb, at rp_b) and
// above (Ba, at rp_a), cv_i = (1 - t) Bb.cv_i + t Ba.cv_i with t = (rp - rp_b) / (rp_a - rp_b),
// the curve with fewer control vertices degree-elevated first. Without a key barb below, the
// default Bdf1 stands at the rachis base; without one above, Bdf2 at the tip; a vane without key
// barbs is Bdf1 throughout (down).
#pragma once

#include <cstddef>
#include <glm/vec3.hpp>
#include <vector>

#include "hirsute/hairs/feathers/default_barbs.h"
#include "hirsute/hairs/feathers/feather_type.h"

namespace hirsute {

// One barb before it is placed: its control vertices in the barb frame of KeyBarb, and its
// angle to the rachis in degrees (the vane's angle at rp, interpolated linearly from base to
// tip, moved by key barbs that set their own angle).
struct BarbCurve {
  std::vector<glm::vec3> vertices;
  float angle = 0;
};

// The key barbs of one vane, sorted by position (file order among equal positions: two key barbs
// at one position are a discontinuity, and a barb exactly there takes the second).
class VaneKeyBarbs {
 public:
  VaneKeyBarbs(const FeatherType& type, BarbSide side);  // side: Left or Right

  // The barb at `position` in [0, 1]; `index` (the barb's count from the rachis base) picks its
  // Bdf1 entry in `table`.
  BarbCurve barbAt(float position, std::size_t index, const PlumulaceousBarbTable& table) const;

  BarbSide side() const { return side_; }
  const std::vector<KeyBarb>& keys() const { return keys_; }

 private:
  // The vane's own barb angle at a position.
  float vaneAngle(float position) const;

  BarbSide side_;
  Vane vane_;
  std::vector<KeyBarb> keys_;
};

}  // namespace hirsute
