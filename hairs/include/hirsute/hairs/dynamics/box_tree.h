// Candidate pairs for collision detection from a bounding-volume hierarchy of axis-aligned boxes
// (one tree per group of boxes that moves), refitted from search to search and rebuilt now and
// then. It finds what collision_grid.h finds, the overlapping pairs of the groups that pair,
// each once and sorted, but its cost follows the boxes and the pairs found, not how many boxes
// crowd into a cell: a grid's cells, sized for the typical box, hold a dozen of a layered coat's
// tilted vane triangles each, and every pair of them, of every kind, was compared (two thirds of
// the time of a coat with vanes).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "hirsute/hairs/dynamics/collision_grid.h"
#include "hirsute/hairs/dynamics/worker_pool.h"

namespace hirsute::dynamics {

class BoxTree {
 public:
  // Queries spread over `pool`'s threads where one is given.
  explicit BoxTree(WorkerPool* pool = nullptr) : pool_(pool) {}

  // Pairs (i, j), i < j, of overlapping boxes of groups that pair (BoxGroups: two still boxes
  // never do) for which `wanted(i, j)` holds, sorted, each once. `wanted` may be called from
  // several threads at once. A box with a NaN coordinate overlaps nothing.
  // The trees are refitted to the new boxes when the boxes are as many as in the last search and
  // of the same groups (their shape kept: the same pairs are found, only the work differs), and
  // built anew otherwise and every `kRefitsPerBuild` searches.
  std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                    const BoxGroups& groups,
                                                    const std::function<bool(int, int)>& wanted);
  // Two groups: the boxes of `moving` (one flag per box) against each other and the rest.
  std::vector<std::pair<int, int>> overlappingPairs(const std::vector<Box>& boxes,
                                                    const std::vector<char>& moving,
                                                    const std::function<bool(int, int)>& wanted);

  // What coherentPairs keeps its list of.
  struct KeptList {
    double slack = 0;
    // Which pairs are tested at all; it may change only with `version`.
    std::function<bool(int, int)> tested;
    // Optional: whether the pair stays apart while each of its vertices stays within `strays`
    // (the two sides' allowances summed, in every coordinate) of where it is over this search
    // (a plane test). Needs `vertices`.
    std::function<bool(int, int, double strays)> apart;
    std::uint64_t version = 0;
    // The boxes of the primitives' vertices (over a step, or still): the list also counts on
    // each staying within its box of then grown by the slack.
    const std::vector<Box>* vertices = nullptr;
    // Optional: the part each box and each vertex belongs to (a stem with its vane; the body),
    // numbers from 0, a box's vertices in its own part. Where given, a part that left its slack
    // is searched again alone, against the grown boxes of the rest (the list repaired), instead
    // of the whole list made anew.
    const std::vector<int>* boxParts = nullptr;
    const std::vector<int>* vertexParts = nullptr;
  };

  // The pairs overlappingPairs(boxes, groups, ...) finds for which `list.tested` and `wanted`
  // hold, less some that `list.apart` keeps apart, from a list kept from an earlier search
  // (Verlet's neighbour lists, from molecular dynamics): that search took every box grown by
  // the slack, so while each box stays inside its grown box of then, every pair that overlaps
  // now was found then, and the list need only be filtered. It is searched anew when a box has
  // left its grown box, when the groups are not those of then, or when `version` changed
  // (`wanted` may differ from call to call). The same pairs as a search, for the cost of
  // filtering a list of somewhat more: a simulation searches several times a step, its
  // primitives moving little. Where `vertices` are given, a vertex that leaves its grown box
  // also has the list made anew, so that `apart` may count on every vertex staying within the
  // slack of where it was: a pair it keeps apart with twice the slack allowed for is left out of
  // the list. Where parts are given and few parts have left their slack, only their pairs are
  // found anew: a pair of such a part with one that stayed is kept unless `apart` keeps it apart
  // with the slack allowed for the one side and, for the other, how far its vertices may still
  // go within their grown boxes (more than the slack: they were grown where it was).
  std::vector<std::pair<int, int>> coherentPairs(const std::vector<Box>& boxes,
                                                 const BoxGroups& groups, const KeptList& list,
                                                 const std::function<bool(int, int)>& wanted);
  // How many times coherentPairs searched its list anew, repaired it (some parts searched
  // again) and filtered it as it was.
  std::uint64_t listSearches() const { return listSearches_; }
  std::uint64_t listRepairs() const { return listRepairs_; }
  std::uint64_t listFilters() const { return listFilters_; }

  WorkerPool* pool() const { return pool_; }
  std::uint64_t builds() const { return builds_; }
  std::uint64_t refits() const { return refits_; }

  static constexpr int kRefitsPerBuild = 64;

 private:
  // A node: its box and either two children (a leaf: `count` boxes from `first` of order_).
  struct Node {
    Box box;
    int first = 0, count = 0;  // count 0: children at `first` and `first + 1`
    int largest = -1;          // the largest box number under it
  };
  struct Tree {
    std::vector<int> order;      // box numbers, the leaves' runs one after the other
    std::vector<Box> leafBoxes;  // their boxes in that order
    std::vector<Node> nodes;     // a node's children come after it
  };
  // Calls visit(j) for each box j whose leaf box overlaps `box`, in the trees of the groups
  // `group` pairs with (two still groups never), leaving out the subtrees whose boxes are all
  // numbered `above` or less.
  template <class Visit>
  void forEachOverlapping(const Box& box, int group, const BoxGroups& groups, int above,
                          std::vector<int>& stack, const Visit& visit) const;
  void build(Tree& tree, const std::vector<Box>& boxes);
  static void refit(Tree& tree, const std::vector<Box>& boxes);
  // The list made anew from the grown boxes, or repaired where parts left their slack; false
  // where it cannot be repaired (then it must be made anew).
  void searchList(const std::vector<Box>& boxes, const BoxGroups& groups, const KeptList& list);
  bool repairList(const std::vector<Box>& boxes, const BoxGroups& groups, const KeptList& list);

  WorkerPool* pool_;
  std::array<Tree, 8> trees_;
  std::vector<std::uint8_t> lastGroups_;
  std::uint8_t lastMoving_ = 0;
  int sinceBuild_ = 0;
  std::uint64_t builds_ = 0, refits_ = 0;
  BoxGroups twoGroups_;
  // coherentPairs' list: the boxes grown by the slack, the pairs of them, and what they were
  // found for.
  std::vector<Box> grown_, grownVertices_;
  std::vector<std::pair<int, int>> kept_;
  std::vector<std::uint8_t> keptGroups_;
  std::array<std::uint8_t, 8> keptPairsWith_{};
  std::uint8_t keptMoving_ = 0;
  std::uint64_t keptVersion_ = 0;
  bool keptValid_ = false;
  bool treesHoldGrown_ = false;    // the trees are those of grown_ (no other search since)
  std::size_t repairedBoxes_ = 0;  // boxes searched again since the list was made anew
  std::uint64_t listSearches_ = 0, listRepairs_ = 0, listFilters_ = 0;
};

}  // namespace hirsute::dynamics
