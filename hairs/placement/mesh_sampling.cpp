// Weighted sample elimination over a triangle mesh (mesh_sampling.h).
#include "hirsute/hairs/placement/mesh_sampling.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <utility>

#include "hirsute/hairs/placement/placement_random.h"

namespace hirsute {
namespace {

// Yuksel's parameters: the weight's exponent, and the lower clamp of the distance, which keeps
// the weights from favouring the removal of points that happen to be very close pairs only.
constexpr double kAlpha = 8.0, kBeta = 0.65, kGamma = 1.5;
constexpr std::size_t kCandidatesPerPoint = 5;

// A uniform grid of cells of the neighbourhood's diameter over the candidates.
class CandidateGrid {
 public:
  CandidateGrid(const std::vector<glm::dvec3>& points, double cell) : points_(points), cell_(cell) {
    order_.resize(points.size());
    std::iota(order_.begin(), order_.end(), 0u);
    std::vector<std::uint64_t> keys(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) keys[i] = keyOf(cellOf(points[i]));
    std::sort(order_.begin(), order_.end(),
              [&](std::uint32_t a, std::uint32_t b) {
                return keys[a] < keys[b] || (keys[a] == keys[b] && a < b);
              });
    for (std::size_t i = 0; i < order_.size();) {
      std::size_t j = i;
      while (j < order_.size() && keys[order_[j]] == keys[order_[i]]) ++j;
      ranges_.emplace(keys[order_[i]], std::make_pair(static_cast<std::uint32_t>(i),
                                                      static_cast<std::uint32_t>(j)));
      i = j;
    }
  }

  // Calls visit(j, distance) for every candidate j ≠ i within `radius` of candidate i.
  template <class Visit>
  void neighbours(std::uint32_t i, double radius, Visit&& visit) const {
    const glm::ivec3 c = cellOf(points_[i]);
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const auto found = ranges_.find(keyOf(c + glm::ivec3(dx, dy, dz)));
          if (found == ranges_.end()) continue;
          for (std::uint32_t k = found->second.first; k < found->second.second; ++k) {
            const std::uint32_t j = order_[k];
            if (j == i) continue;
            const double d = glm::distance(points_[i], points_[j]);
            if (d < radius) visit(j, d);
          }
        }
      }
    }
  }

  // The key of the cell of side `cell` holding p.
  static std::uint64_t keyOf(const glm::dvec3& p, double cell) {
    return keyOf(glm::ivec3(glm::floor(p / cell)));
  }

 private:
  glm::ivec3 cellOf(const glm::dvec3& p) const {
    return glm::ivec3(glm::floor(p / cell_));
  }
  static std::uint64_t keyOf(const glm::ivec3& c) {
    const auto part = [](int v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffffu; };
    return part(c.x) | (part(c.y) << 21) | (part(c.z) << 42);
  }

  const std::vector<glm::dvec3>& points_;
  double cell_;
  std::vector<std::uint32_t> order_;
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> ranges_;
};

}  // namespace

std::vector<SurfaceSample> sampleSurfaceArea(const PatchUnfolding& unfolding, std::size_t count,
                                             std::uint64_t key) {
  std::vector<SurfaceSample> kept;
  const std::size_t triangles = unfolding.triangles();
  if (count == 0 || triangles == 0) return kept;
  std::vector<double> cumulative(triangles);
  double area = 0;
  for (std::size_t t = 0; t < triangles; ++t) {
    const glm::dvec3 p0(unfolding.position(unfolding.corner(t, 0)));
    const glm::dvec3 p1(unfolding.position(unfolding.corner(t, 1)));
    const glm::dvec3 p2(unfolding.position(unfolding.corner(t, 2)));
    area += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    cumulative[t] = area;
  }
  if (!(area > 0)) return kept;

  // Uniform candidates: a triangle by its area, a point in it by the square-root rule.
  const std::size_t candidates = count * kCandidatesPerPoint;
  std::vector<SurfaceSample> samples(candidates);
  std::vector<glm::dvec3> points(candidates);
  PlacementRandom random(placementKey(key, 0x6d657368u));
  const auto draw = [&random] {
    return (static_cast<double>(random.uniform()) + static_cast<double>(random.uniform()) / 16777216.0);
  };
  for (std::size_t i = 0; i < candidates; ++i) {
    const double at = draw() * area;
    const auto t = static_cast<std::size_t>(
        std::min<std::ptrdiff_t>(std::upper_bound(cumulative.begin(), cumulative.end(), at) -
                                     cumulative.begin(),
                                 static_cast<std::ptrdiff_t>(triangles - 1)));
    const double r1 = std::sqrt(draw()), r2 = draw();
    const double b1 = r1 * (1 - r2), b2 = r1 * r2;
    samples[i] = SurfaceSample{static_cast<std::uint32_t>(t), static_cast<float>(b1),
                               static_cast<float>(b2)};
    const glm::dvec3 p0(unfolding.position(unfolding.corner(t, 0)));
    const glm::dvec3 p1(unfolding.position(unfolding.corner(t, 1)));
    const glm::dvec3 p2(unfolding.position(unfolding.corner(t, 2)));
    points[i] = p0 + b1 * (p1 - p0) + b2 * (p2 - p0);
  }
  if (count >= candidates) return samples;

  // The largest radius of `count` points on the area (hexagonal packing), its neighbourhood of
  // twice that, and the lower clamp of the distances.
  const double rMax = std::sqrt(area / (2.0 * std::sqrt(3.0) * static_cast<double>(count)));
  const double diameter = 2.0 * rMax;
  const double rMin = diameter * (1.0 - std::pow(static_cast<double>(count) /
                                                     static_cast<double>(candidates),
                                                 kGamma)) *
                      kBeta;
  const auto weight = [&](double d) {
    const double x = 1.0 - std::max(d, rMin) / diameter;  // (1 − d/2r)^8, kAlpha = 8
    const double x2 = x * x, x4 = x2 * x2;
    return x4 * x4;
  };
  static_assert(kAlpha == 8.0, "the weight is written out for an exponent of 8");
  // The candidates in the order of their cells, so that neighbours lie near in memory.
  {
    std::vector<std::uint64_t> keys(candidates);
    for (std::size_t i = 0; i < candidates; ++i) keys[i] = CandidateGrid::keyOf(points[i], diameter);
    std::vector<std::uint32_t> order(candidates);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return keys[a] < keys[b] || (keys[a] == keys[b] && a < b);
    });
    std::vector<SurfaceSample> sortedSamples(candidates);
    std::vector<glm::dvec3> sortedPoints(candidates);
    for (std::size_t k = 0; k < candidates; ++k) {
      sortedSamples[k] = samples[order[k]];
      sortedPoints[k] = points[order[k]];
    }
    samples = std::move(sortedSamples);
    points = std::move(sortedPoints);
  }
  // Each candidate's neighbours within the diameter, found once (compressed rows).
  const CandidateGrid grid(points, diameter);
  std::vector<std::uint32_t> first(candidates + 1, 0), neighbours;
  neighbours.reserve(candidates * 20);
  std::vector<double> weights(candidates, 0.0);
  for (std::uint32_t i = 0; i < candidates; ++i) {
    grid.neighbours(i, diameter, [&](std::uint32_t j, double d) {
      weights[i] += weight(d);
      neighbours.push_back(j);
    });
    first[i + 1] = static_cast<std::uint32_t>(neighbours.size());
  }
  // A max-heap of the candidates by weight that knows where each one is: weights only fall, so
  // a candidate whose weight fell sinks from where it is.
  std::vector<std::uint32_t> heap(candidates), at(candidates);
  std::iota(heap.begin(), heap.end(), 0u);
  const auto heavier = [&](std::uint32_t a, std::uint32_t b) {
    return weights[a] > weights[b] || (weights[a] == weights[b] && a < b);
  };
  std::size_t size = candidates;
  const auto place = [&](std::size_t k, std::uint32_t c) {
    heap[k] = c;
    at[c] = static_cast<std::uint32_t>(k);
  };
  const auto sink = [&](std::size_t k) {
    const std::uint32_t c = heap[k];
    for (;;) {
      std::size_t child = 2 * k + 1;
      if (child >= size) break;
      if (child + 1 < size && heavier(heap[child + 1], heap[child])) ++child;
      if (!heavier(heap[child], c)) break;
      place(k, heap[child]);
      k = child;
    }
    place(k, c);
  };
  for (std::size_t k = 0; k < size; ++k) at[heap[k]] = static_cast<std::uint32_t>(k);
  for (std::size_t k = size / 2; k-- > 0;) sink(k);
  std::vector<char> removed(candidates, 0);
  while (size > count) {
    const std::uint32_t i = heap[0];
    removed[i] = 1;
    --size;
    if (size > 0) {
      place(0, heap[size]);
      sink(0);
    }
    for (std::uint32_t n = first[i]; n < first[i + 1]; ++n) {
      const std::uint32_t j = neighbours[n];
      if (removed[j]) continue;
      weights[j] -= weight(glm::distance(points[i], points[j]));
      sink(at[j]);
    }
  }
  kept.reserve(count);
  for (std::size_t i = 0; i < candidates; ++i) {
    if (!removed[i]) kept.push_back(samples[i]);
  }
  return kept;
}

}  // namespace hirsute
