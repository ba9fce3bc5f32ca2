// Procedural veins for leaves and petals in the path tracer (papers/002_0e0bce38b72f21dc.txt,
// Sec. 5: the crocus's petal veins are jittered points joined by splines, the Nankin cherry's
// leaf veins are traced by particles after Rodkaew et al. 2003), used as colour and as a bump
// map (docs/trace.md, "Veins").
//
// A vein map is a height field over a surface's own (u, v): u across it from one edge to the
// other, v along it from base (0) to tip (1). It is made in the surface's proportions, so that
// veins keep their width and angles on a leaf narrower than long: `aspect` is the width over
// the length, and distances in the map are x = u·aspect, y = v.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/interpreter/view_settings.h"

namespace hirsute::trace {

class VeinMap {
 public:
  static constexpr int kAcross = 256, kAlong = 512;  // texels
  static constexpr std::size_t kMaxWork = std::size_t{16} << 20;

  // The map of `settings` for a surface of proportions `aspect` (width / length), the
  // `variant`-th of its kind (each variant is another draw of the same pattern).
  VeinMap(const VeinSettings& settings, float aspect, int variant);

  // The height at (u, v), 0 (no vein) to 1 (the middle of a main vein), bilinear; (u, v) is
  // clamped to the unit square.
  float height(glm::vec2 uv) const;
  // The height's derivatives by u and by v.
  glm::vec2 slope(glm::vec2 uv) const;

  // Texels whose height is above 1/2: the share of the surface the veins cover (for tests).
  float coverage() const;

 private:
  // A vein from a to b ((u, v) points), its width (a share of the length) going from `wa` to
  // `wb`, its height at its middle `peak`; where veins meet the higher wins.
  void stroke(glm::vec2 a, glm::vec2 b, float wa, float wb, float peak);
  void splines(const VeinSettings& settings, std::uint64_t seed);
  void particles(const VeinSettings& settings, std::uint64_t seed);
  float texel(int i, int j) const;

  float aspect_;
  std::vector<float> height_;  // kAcross × kAlong, u fastest
  // Texels the strokes have visited: past kMaxWork (the map covered hundreds of times over,
  // which the higher-wins rule has long saturated) the pattern stops, so that no count and
  // width a view file may give costs more than about a tenth of a second a map.
  std::size_t work_ = 0;
};

// How many variants a vein line has: surfaces of its colour take them in turn, so that
// neighbouring leaves do not repeat one pattern.
inline constexpr int kVeinVariants = 4;

}  // namespace hirsute::trace
