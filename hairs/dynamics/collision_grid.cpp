// A hashed uniform grid of boxes.
#include "hirsute/hairs/dynamics/collision_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace hirsute::dynamics {
namespace {

constexpr std::int64_t kMaxCellsPerBox = 512;

// Cells are keyed by their three indices packed into one integer (21 bits each, wrapping): two
// cells that share a key only make more candidates, never fewer.
std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  constexpr std::uint64_t kMask = (1u << 21) - 1;
  return (static_cast<std::uint64_t>(x) & kMask) | ((static_cast<std::uint64_t>(y) & kMask) << 21) |
         ((static_cast<std::uint64_t>(z) & kMask) << 42);
}

}  // namespace

Box boxOf(std::initializer_list<Eigen::Vector3d> points, double margin) {
  Box box{*points.begin(), *points.begin()};
  for (const Eigen::Vector3d& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  box.min.array() -= margin;
  box.max.array() += margin;
  return box;
}

std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                  const std::function<bool(int, int)>& wanted) {
  return overlappingPairs(boxes, std::vector<char>(boxes.size(), 1), wanted);
}

std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                  const std::vector<char>& moving,
                                                  const std::function<bool(int, int)>& wanted) {
  std::vector<std::pair<int, int>> pairs;
  std::vector<double> extents;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (moving[i]) extents.push_back((boxes[i].max - boxes[i].min).maxCoeff());
  if (extents.empty() || boxes.size() < 2) return pairs;
  // The upper quartile: moving points (a stem's nodes, whose boxes are their motion over a step)
  // must not shrink the cells below the segments that move with them. (Twice that made the
  // 480-feather coat's broad phase a sixth slower: fuller cells cost more than extra cells.)
  const auto quartile = extents.begin() + (3 * extents.size()) / 4;
  std::nth_element(extents.begin(), quartile, extents.end());
  const double cell = std::max(*quartile, 1e-9);

  // Each cell's moving boxes and still ones.
  struct Cell {
    std::vector<int> moving, still;
  };
  std::unordered_map<std::uint64_t, Cell> cells;
  std::vector<int> huge;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
    const Eigen::Array3d lo = (boxes[i].min.array() / cell).floor();
    const Eigen::Array3d hi = (boxes[i].max.array() / cell).floor();
    const Eigen::Array3d span = hi - lo + 1;
    if (!(span.prod() <= kMaxCellsPerBox)) {  // also catches non-finite boxes
      huge.push_back(i);
      continue;
    }
    for (auto x = static_cast<std::int64_t>(lo.x()); x <= hi.x(); ++x)
      for (auto y = static_cast<std::int64_t>(lo.y()); y <= hi.y(); ++y)
        for (auto z = static_cast<std::int64_t>(lo.z()); z <= hi.z(); ++z) {
          Cell& c = cells[cellKey(x, y, z)];
          (moving[i] ? c.moving : c.still).push_back(i);
        }
  }
  auto consider = [&](int a, int b) {
    if (a == b || (!moving[a] && !moving[b])) return;
    if (a > b) std::swap(a, b);
    if (boxes[a].overlaps(boxes[b]) && wanted(a, b)) pairs.emplace_back(a, b);
  };
  for (const auto& [key, c] : cells) {
    for (std::size_t m = 0; m < c.moving.size(); ++m) {
      for (std::size_t n = m + 1; n < c.moving.size(); ++n) consider(c.moving[m], c.moving[n]);
      for (int other : c.still) consider(c.moving[m], other);
    }
  }
  for (int i : huge)
    for (int j = 0; j < static_cast<int>(boxes.size()); ++j) consider(i, j);
  // The map's order is not the same from run to run; the sorted list is.
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace hirsute::dynamics
