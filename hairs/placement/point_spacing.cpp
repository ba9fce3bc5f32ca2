#include "hirsute/hairs/placement/point_spacing.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hirsute {

TorusPoint toroidalOffset(const TorusPoint& a, const TorusPoint& b) {
  auto wrap = [](double d) { return d - std::round(d); };
  return {wrap(b.u - a.u), wrap(b.v - a.v)};
}

std::vector<double> nearestNeighbourDistances(std::span<const TorusPoint> points) {
  const std::size_t n = points.size();
  std::vector<double> distances(n, 0.0);
  if (n < 2) return distances;
  // About two points per bucket; rings of buckets are searched outwards until the ring's inner
  // edge is farther than the best distance found.
  const int buckets = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(n) / 2.0)));
  std::vector<std::vector<std::size_t>> grid(static_cast<std::size_t>(buckets) * buckets);
  auto bucketOf = [&](double c) {
    int b = static_cast<int>(std::floor((c - std::floor(c)) * buckets));
    return std::clamp(b, 0, buckets - 1);
  };
  for (std::size_t i = 0; i < n; ++i) {
    grid[static_cast<std::size_t>(bucketOf(points[i].v)) * buckets + bucketOf(points[i].u)]
        .push_back(i);
  }
  const double cell = 1.0 / buckets;
  for (std::size_t i = 0; i < n; ++i) {
    const int bu = bucketOf(points[i].u);
    const int bv = bucketOf(points[i].v);
    double best = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring <= buckets; ++ring) {
      if (std::isfinite(best) && (ring - 1) * cell > best) break;
      for (int dv = -ring; dv <= ring; ++dv) {
        for (int du = -ring; du <= ring; ++du) {
          if (std::max(std::abs(du), std::abs(dv)) != ring) continue;
          // Small tori visit a bucket more than once; harmless for a minimum.
          const int cu = ((bu + du) % buckets + buckets) % buckets;
          const int cv = ((bv + dv) % buckets + buckets) % buckets;
          for (std::size_t j : grid[static_cast<std::size_t>(cv) * buckets + cu]) {
            if (j == i) continue;
            const TorusPoint d = toroidalOffset(points[i], points[j]);
            best = std::min(best, std::hypot(d.u, d.v));
          }
        }
      }
    }
    distances[i] = best;
  }
  return distances;
}

double relativeRadius(std::span<const TorusPoint> points) {
  const std::size_t n = points.size();
  if (n < 2) return 0.0;
  const std::vector<double> distances = nearestNeighbourDistances(points);
  const double r = *std::min_element(distances.begin(), distances.end()) / 2.0;
  const double rMax = std::sqrt(1.0 / (2.0 * std::sqrt(3.0) * static_cast<double>(n)));
  return r / rMax;
}

}  // namespace hirsute
