// Organ attributes along a segment and around its girth (Fuhrer, Jensen & Prusinkiewicz 2004,
// Table 1; docs/design.md, "Placement"): the values of one side at the segment's two ends, mixed
// linearly along it (`hair interpolation: on`; without it both ends are the end's), each times
// its function of the model's function set at the girth position s.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>

#include "hirsute/hairs/placement/placement_random.h"
#include "hirsute/interpreter/organ_attributes.h"

namespace hirsute {

// The model's function set: function `index` (1-based) at x in [0, 1]. Null, or an index it
// does not know (it returns NaN), reads as no function.
using GirthFunction = std::function<double(int index, double x)>;

// fun(s) of a value: 1 without a function.
inline float girthModulation(const GirthFunction& function, int index, float s) {
  if (index <= 0 || !function) return 1.0f;
  const double y = function(index, s);
  return std::isfinite(y) ? static_cast<float>(y) : 1.0f;
}

// The largest |fun(s)| over the girth (sampled at 65 positions).
inline float maxGirthModulation(const GirthFunction& function, int index) {
  if (index <= 0 || !function) return 1.0f;
  float m = 0;
  for (int i = 0; i <= 64; ++i)
    m = std::max(m, std::abs(girthModulation(function, index, i / 64.0f)));
  return m;
}

// The OrganValue attributes of one side (a Side record of an organ) between a segment's two ends.
template <class Side>
class SegmentValues {
 public:
  using Member = OrganValue Side::*;

  SegmentValues(const Side& start, const Side& end, const GirthFunction& function)
      : start_(start), end_(end), function_(function) {}

  const Side& start() const { return start_; }
  const Side& end() const { return end_; }

  // The value at girth position s and fraction tau along the segment, before the per-instance
  // random offset: value × fun(s), each end's, mixed linearly.
  float value(Member member, float s, float tau) const {
    const OrganValue& a = start_.*member;
    const OrganValue& b = end_.*member;
    if (tau >= 1.0f || (a == b)) return b.value * girthModulation(function_, b.function, s);
    return (1.0f - tau) * a.value * girthModulation(function_, a.function, s) +
           tau * b.value * girthModulation(function_, b.function, s);
  }
  float range(Member member, float tau) const {
    return (1.0f - tau) * (start_.*member).range + tau * (end_.*member).range;
  }
  // value ± a uniform offset up to the range.
  float sample(Member member, float s, float tau, PlacementRandom& random) const {
    const float r = range(member, tau);
    return value(member, s, tau) + (r != 0.0f ? r * random.symmetric() : 0.0f);
  }
  // The largest magnitude anywhere on the segment, range included (a density's sets the tile's
  // size; points below it are thinned out).
  float peak(Member member) const {
    auto extreme = [&](const OrganValue& v) {
      return std::abs(v.value) * maxGirthModulation(function_, v.function) + v.range;
    };
    return std::max(extreme(start_.*member), extreme(end_.*member));
  }

 private:
  const Side& start_;
  const Side& end_;
  const GirthFunction& function_;
};

}  // namespace hirsute
