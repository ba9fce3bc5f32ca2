#include "hirsute/hairs/feathers/silhouette.h"

#include <algorithm>

namespace hirsute {

float silhouetteLength(std::span<const SilhouettePoint> points, float position, bool fromBelow) {
  if (points.empty()) return 0;
  // The first point above the position (at or above it when asked from below).
  const auto above =
      fromBelow
          ? std::lower_bound(points.begin(), points.end(), position,
                             [](const SilhouettePoint& p, float x) { return p.position < x; })
          : std::upper_bound(points.begin(), points.end(), position,
                             [](float x, const SilhouettePoint& p) { return x < p.position; });
  if (above == points.begin()) return points.front().length;
  if (above == points.end()) return points.back().length;
  const SilhouettePoint& a = *(above - 1);
  const SilhouettePoint& b = *above;
  if (b.position <= a.position) return fromBelow ? a.length : b.length;
  const float t = (position - a.position) / (b.position - a.position);
  return (1 - t) * a.length + t * b.length;
}

float vaneBarbLength(const Vane& vane, float position) {
  return vane.silhouette.empty() ? vane.barbLength : silhouetteLength(vane.silhouette, position);
}

}  // namespace hirsute
