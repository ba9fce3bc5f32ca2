// A hashed uniform grid of boxes.
#include "hirsute/hairs/dynamics/collision_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

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
  BoxGroups groups;
  groups.of.assign(boxes.size(), 0);
  groups.pairsWith[0] = 1;
  groups.moving = 1;
  return overlappingPairs(boxes, groups, wanted);
}

std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                  const std::vector<char>& moving,
                                                  const std::function<bool(int, int)>& wanted) {
  return CollisionGrid().overlappingPairs(boxes, moving, wanted);
}

std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                  const BoxGroups& groups,
                                                  const std::function<bool(int, int)>& wanted) {
  return CollisionGrid().overlappingPairs(boxes, groups, wanted);
}

std::vector<std::pair<int, int>> CollisionGrid::overlappingPairs(
    const std::vector<Box>& boxes, const std::vector<char>& moving,
    const std::function<bool(int, int)>& wanted) {
  BoxGroups::ofMoving(moving, twoGroups_);
  return overlappingPairs(boxes, twoGroups_, wanted);
}

std::vector<std::pair<int, int>> CollisionGrid::overlappingPairs(
    const std::vector<Box>& boxes, const BoxGroups& groups,
    const std::function<bool(int, int)>& wanted) {
  std::vector<std::pair<int, int>> pairs;
  const auto moves = [&](int i) { return (groups.moving >> groups.of[i]) & 1; };
  const auto pairsWith = [&](int a, int b) {
    return (groups.pairsWith[groups.of[a]] >> groups.of[b]) & 1;
  };
  std::vector<double>& extents = extents_;
  extents.clear();
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    if (moves(i) && groups.pairsWith[groups.of[i]])
      extents.push_back((boxes[i].max - boxes[i].min).maxCoeff());
  if (extents.empty() || boxes.size() < 2) return pairs;
  // The upper quartile: moving points (a stem's nodes, whose boxes are their motion over a step)
  // must not shrink the cells below the segments that move with them. (Twice that made the
  // 480-feather coat's broad phase a sixth slower: fuller cells cost more than extra cells.)
  const auto quartile = extents.begin() + (3 * extents.size()) / 4;
  std::nth_element(extents.begin(), quartile, extents.end());
  const double cell = std::max(*quartile, 1e-9);
  const auto cellOf = [cell](const Eigen::Vector3d& p) -> Eigen::Array3d {
    return (p.array() / cell).floor();
  };
  // The cells a box covers, or none when it covers too many (also a non-finite box).
  const auto coveredCells = [&](const Box& box, Eigen::Array3d& lo, Eigen::Array3d& hi) {
    lo = cellOf(box.min);
    hi = cellOf(box.max);
    return (hi - lo + 1).prod() <= kMaxCellsPerBox;
  };
  const auto forEachCell = [](const Eigen::Array3d& lo, const Eigen::Array3d& hi, auto&& visit) {
    for (auto x = static_cast<std::int64_t>(lo.x()); x <= hi.x(); ++x)
      for (auto y = static_cast<std::int64_t>(lo.y()); y <= hi.y(); ++y)
        for (auto z = static_cast<std::int64_t>(lo.z()); z <= hi.z(); ++z)
          visit(cellKey(x, y, z));
  };

  // Only the moving boxes go into the grid: an open-addressing table from cell keys to runs of
  // box numbers (counted in one pass, filled in a second, so each run is in box order).
  std::vector<int>& inserted = inserted_;
  std::vector<int>& huge = huge_;
  inserted.clear();
  huge.clear();
  std::size_t cellVisits = 0;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
    if (!moves(i) || !groups.pairsWith[groups.of[i]]) continue;
    Eigen::Array3d lo, hi;
    if (!coveredCells(boxes[i], lo, hi)) {
      huge.push_back(i);
      continue;
    }
    inserted.push_back(i);
    cellVisits += static_cast<std::size_t>((hi - lo + 1).prod());
  }
  std::size_t capacity = 16;
  while (capacity < 2 * cellVisits) capacity *= 2;
  const std::size_t mask = capacity - 1;
  std::vector<Slot>& table = table_;
  table.assign(capacity, Slot{});
  const auto home = [&](std::uint64_t key) {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & mask;
  };
  // The slot of `key`, or the empty slot where it would go.
  const auto slotOf = [&](std::uint64_t key) -> Slot& {
    for (std::size_t h = home(key);; h = (h + 1) & mask)
      if (table[h].count == 0 || table[h].key == key) return table[h];
  };
  for (int i : inserted) {
    Eigen::Array3d lo, hi;
    coveredCells(boxes[i], lo, hi);
    forEachCell(lo, hi, [&](std::uint64_t key) {
      Slot& slot = slotOf(key);
      slot.key = key;
      ++slot.count;
    });
  }
  std::uint32_t total = 0;
  for (Slot& slot : table) {
    slot.first = total;
    total += slot.count;
  }
  std::vector<int>& members = members_;
  members.resize(total);
  std::vector<std::uint32_t>& filled = filled_;
  filled.assign(capacity, 0);
  for (int i : inserted) {
    Eigen::Array3d lo, hi;
    coveredCells(boxes[i], lo, hi);
    forEachCell(lo, hi, [&](std::uint64_t key) {
      Slot& slot = slotOf(key);
      members[slot.first + filled[&slot - table.data()]++] = i;
    });
  }

  // Two boxes share several cells; the pair is taken only in the cell of its overlap's lowest
  // corner, which both cover, so that it comes out once.
  const auto consider = [&](int a, int b, std::uint64_t key) {
    if (!pairsWith(a, b) || !boxes[a].overlaps(boxes[b])) return;
    const Eigen::Array3d corner = cellOf(boxes[a].min.cwiseMax(boxes[b].min));
    if (cellKey(static_cast<std::int64_t>(corner.x()), static_cast<std::int64_t>(corner.y()),
                static_cast<std::int64_t>(corner.z())) != key)
      return;
    if (a > b) std::swap(a, b);
    if (wanted(a, b)) pairs.emplace_back(a, b);
  };
  for (const Slot& slot : table)
    for (std::uint32_t m = slot.first; m < slot.first + slot.count; ++m)
      for (std::uint32_t n = m + 1; n < slot.first + slot.count; ++n)
        consider(members[m], members[n], slot.key);
  // Still boxes look up the moving ones in their cells.
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
    if (moves(i) || !groups.pairsWith[groups.of[i]]) continue;
    Eigen::Array3d lo, hi;
    if (!coveredCells(boxes[i], lo, hi)) {
      huge.push_back(i);
      continue;
    }
    forEachCell(lo, hi, [&](std::uint64_t key) {
      const Slot& slot = slotOf(key);
      for (std::uint32_t m = slot.first; m < slot.first + slot.count; ++m)
        consider(members[m], i, key);
    });
  }
  // Huge boxes against every box they may pair with, each pair once.
  std::sort(huge.begin(), huge.end());
  for (int i : huge)
    for (int j = 0; j < static_cast<int>(boxes.size()); ++j) {
      if (j == i || (!moves(i) && !moves(j)) || !pairsWith(i, j)) continue;
      if (j < i && std::binary_search(huge.begin(), huge.end(), j)) continue;
      const int a = std::min(i, j), b = std::max(i, j);
      if (boxes[a].overlaps(boxes[b]) && wanted(a, b)) pairs.emplace_back(a, b);
    }
  // The map's order is not the same from run to run; the sorted list is.
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace hirsute::dynamics
