#include "hirsute/hairs/feathers/barb_interpolation.h"

#include <algorithm>

#include "hirsute/hairs/feathers/bezier_curve.h"

namespace hirsute {
namespace {

// (1 - t) a + t b, vertex by vertex, after elevating the shorter; exact at t = 0 and t = 1.
std::vector<glm::vec3> blendVertices(std::span<const glm::vec3> a, std::span<const glm::vec3> b,
                                     float t) {
  const std::size_t count = std::max(a.size(), b.size());
  std::vector<glm::vec3> out = elevateBezierTo(a, count);
  const std::vector<glm::vec3> other = elevateBezierTo(b, count);
  for (std::size_t i = 0; i < count; ++i) out[i] = (1 - t) * out[i] + t * other[i];
  return out;
}

}  // namespace

VaneKeyBarbs::VaneKeyBarbs(const FeatherType& type, BarbSide side)
    : side_(side), vane_(type.vane(side)) {
  for (const KeyBarb& key : type.keyBarbs) {
    if (key.side == side || key.side == BarbSide::Both) keys_.push_back(key);
  }
  std::stable_sort(keys_.begin(), keys_.end(),
                   [](const KeyBarb& a, const KeyBarb& b) { return a.position < b.position; });
}

float VaneKeyBarbs::vaneAngle(float position) const {
  return (1 - position) * vane_.baseAngle + position * vane_.tipAngle;
}

BarbCurve VaneKeyBarbs::barbAt(float position, std::size_t index,
                               const PlumulaceousBarbTable& table) const {
  const std::span<const glm::vec3> bdf1 = table.barb(index, side_);
  if (keys_.empty())
    return BarbCurve{std::vector<glm::vec3>(bdf1.begin(), bdf1.end()), vaneAngle(position)};

  // One end of the blend: its vertices (a key barb mixed with Bdf1 as much as it is
  // plumulaceous), its position and how far its angle moves the vane's.
  struct End {
    std::vector<glm::vec3> vertices;
    float position;
    float angleOffset;
  };
  const auto endOf = [&](const KeyBarb& key) {
    End end{key.vertices, key.position, 0};
    if (key.plumulaceous > 0) end.vertices = blendVertices(key.vertices, bdf1, key.plumulaceous);
    if (key.angle) end.angleOffset = *key.angle - vaneAngle(key.position);
    return end;
  };
  const auto above = std::upper_bound(keys_.begin(), keys_.end(), position,
                                      [](float x, const KeyBarb& key) { return x < key.position; });
  const End below = above == keys_.begin()
                        ? End{std::vector<glm::vec3>(bdf1.begin(), bdf1.end()), 0, 0}
                        : endOf(*(above - 1));
  // A barb at (or past) its key barb below takes it unchanged: key barbs are reproduced exactly.
  if (position <= below.position || below.position >= 1) {
    return BarbCurve{below.vertices, vaneAngle(position) + below.angleOffset};
  }
  const std::span<const glm::vec3> bdf2 = pennaceousDefaultBarb();
  const End top = above == keys_.end() ? End{std::vector<glm::vec3>(bdf2.begin(), bdf2.end()), 1, 0}
                                       : endOf(*above);
  const float t = (position - below.position) / (top.position - below.position);
  return BarbCurve{blendVertices(below.vertices, top.vertices, t),
                   vaneAngle(position) + (1 - t) * below.angleOffset + t * top.angleOffset};
}

}  // namespace hirsute
