// Candidate pairs for collision detection: axis-aligned boxes (swept over a step, or around a
// state) in a hashed uniform grid (Bridson, Fedkiw & Anderson 2002, Sec. 6; the study's Sec.
// 3.3.2 proximity test). Only boxes that share a cell and overlap become candidates, so the
// exact tests run on a few pairs instead of all of them.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <initializer_list>
#include <utility>
#include <vector>

namespace hirsute::dynamics {

struct Box {
  Eigen::Vector3d min, max;
  bool overlaps(const Box& other) const {
    return (min.array() <= other.max.array()).all() && (other.min.array() <= max.array()).all();
  }
};

// The box of the points `a` and `b` (a primitive at the two ends of a step), grown by `margin`.
Box boxOf(std::initializer_list<Eigen::Vector3d> points, double margin);

// Pairs (i, j), i < j, of overlapping boxes for which `wanted(i, j)` holds, sorted, each once.
// The cell size is twice the median of the boxes' largest extents, so that a typical box covers
// a few cells; a box over more cells than a limit is compared with every other box instead of
// being inserted, so that a rare huge box does not flood the grid.
std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                  const std::function<bool(int, int)>& wanted);

// The same where only pairs with at least one box of `moving` (one flag per box) can be wanted:
// the feathers among a body's many triangles. The cell size is twice the upper quartile of the
// moving boxes' largest extents, and pairs of two still boxes are never looked at.
std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                  const std::vector<char>& moving,
                                                  const std::function<bool(int, int)>& wanted);

}  // namespace hirsute::dynamics
