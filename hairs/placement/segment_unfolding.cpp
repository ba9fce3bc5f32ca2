// Unfolding a generalized-cylinder segment into (u, v) (Fuhrer, Jensen & Prusinkiewicz 2004,
// Sec. 3.1).
#include "hirsute/hairs/placement/segment_unfolding.h"

#include <algorithm>

namespace hirsute {

SegmentUnfolding::SegmentUnfolding(const CylinderSegment& segment, const TriangleMesh& mesh)
    : segment_(segment), mesh_(mesh) {
  // Arc-length fractions of the contour samples around each ring, and the girths.
  const std::size_t rings = segment.rings.size();
  const std::size_t perRing = this->perRing();
  const int faces = segment.sides;
  fraction_.resize(rings * perRing);
  girth_.resize(rings);
  for (std::size_t k = 0; k < rings; ++k) {
    float sum = 0;
    fraction_[k * perRing] = 0;
    for (int j = 1; j <= faces; ++j) {
      sum += glm::length(position(k, j) - position(k, j - 1));
      fraction_[k * perRing + static_cast<std::size_t>(j)] = sum;
    }
    girth_[k] = sum;
    maxGirth_ = std::max(maxGirth_, sum);
    for (int j = 1; j <= faces; ++j) {
      fraction_[k * perRing + static_cast<std::size_t>(j)] =
          sum > 0.0f ? fraction_[k * perRing + static_cast<std::size_t>(j)] / sum
                     : static_cast<float>(j) / static_cast<float>(faces);
    }
  }
}

float SegmentUnfolding::tau(std::size_t ring) const {
  return ringTau(segment_, ring);
}

FacePoint SegmentUnfolding::face(std::size_t ring, float t, float s) const {
  int lo = 0, hi = faces();  // fraction(lo) <= s < fraction(hi)
  auto boundary = [&](int j) { return (1.0f - t) * fraction(ring - 1, j) + t * fraction(ring, j); };
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (boundary(mid) <= s ? lo : hi) = mid;
  }
  const float b0 = boundary(lo), b1 = boundary(lo + 1);
  const float a = b1 > b0 ? std::clamp((s - b0) / (b1 - b0), 0.0f, 1.0f) : 0.5f;
  return FacePoint{ring, lo, a, t};
}

glm::vec3 SegmentUnfolding::at(const FacePoint& p) const {
  const float a = p.a, t = p.t;
  const float w00 = (1 - a) * (1 - t), w01 = a * (1 - t), w10 = (1 - a) * t, w11 = a * t;
  return w00 * position(p.ring - 1, p.column) + w01 * position(p.ring - 1, p.column + 1) +
         w10 * position(p.ring, p.column) + w11 * position(p.ring, p.column + 1);
}

float ringTau(const CylinderSegment& seg, std::size_t k) {
  if (seg.axisLength <= 0.0f)
    return static_cast<float>(k) / static_cast<float>(seg.rings.size() - 1);
  return std::clamp((seg.rings[k].axisDistance - seg.axisStart) / seg.axisLength, 0.0f, 1.0f);
}

}  // namespace hirsute
