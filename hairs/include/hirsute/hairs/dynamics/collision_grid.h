// Candidate pairs for collision detection: axis-aligned boxes (swept over a step, or around a
// state) in a hashed uniform grid (Bridson, Fedkiw & Anderson 2002, Sec. 6; the study's Sec.
// 3.3.2 proximity test). Only boxes that share a cell and overlap become candidates, so the
// exact tests run on a few pairs instead of all of them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
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
// The cell size is the upper quartile of the boxes' largest extents, so that a typical box covers
// a few cells; a box over more cells than a limit is compared with every other box instead of
// being inserted, so that a rare huge box does not flood the grid.
std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                  const std::function<bool(int, int)>& wanted);

// Kinds of boxes, so that a search looks only at the pairs of kinds that can be wanted (a
// feather's segments against each other and against the body's edges, its nodes against the
// body's triangles): box i is of group `of[i]` (0 to 7); groups g and h are paired when bit h of
// `pairsWith[g]` is set (set both ways); bit g of `moving` says group g moves. Only moving
// boxes go into the grid, and two still boxes are never paired.
struct BoxGroups {
  std::vector<std::uint8_t> of;
  std::array<std::uint8_t, 8> pairsWith{};
  std::uint8_t moving = 0;

  // The two groups of a search by `moving` flags, into `groups` (its memory reused): moving boxes
  // (group 0) pair with every box, still ones (group 1) with moving ones alone.
  static void ofMoving(const std::vector<char>& moving, BoxGroups& groups) {
    groups.of.clear();
    for (char m : moving) groups.of.push_back(m ? 0 : 1);
    groups.pairsWith = {0b11, 0b01};
    groups.moving = 1;
  }
};

// The same over groups: the cell size is the upper quartile of the largest extents of the
// moving boxes that pair with anything.
std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                  const BoxGroups& groups,
                                                  const std::function<bool(int, int)>& wanted);

// The same searches with the grid's working memory kept from one search to the next: a
// simulation searches a few times a step, and tables of that size allocated afresh each time are
// pages the kernel must fault in anew (a sixth of the 480-feather coat's time went so).
class CollisionGrid {
 public:
  std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                    const BoxGroups& groups,
                                                    const std::function<bool(int, int)>& wanted);
  std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                    const std::vector<char>& moving,
                                                    const std::function<bool(int, int)>& wanted);

 private:
  // A cell of the open-addressing table: its key and its run of box numbers in members_.
  struct Slot {
    std::uint64_t key = 0;
    std::uint32_t count = 0, first = 0;
  };
  std::vector<double> extents_;
  std::vector<int> inserted_, huge_, members_;
  std::vector<Slot> table_;
  std::vector<std::uint32_t> filled_;
  BoxGroups twoGroups_;
};

// Two groups: the boxes of `moving` (one flag per box) against each other and against the rest
// (the feathers among a body's many triangles).
std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                  const std::vector<char>& moving,
                                                  const std::function<bool(int, int)>& wanted);

}  // namespace hirsute::dynamics
