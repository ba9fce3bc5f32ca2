// The tree's broad phase against every pair tested directly: random boxes of many sizes (some
// huge, some unbounded or NaN) in groups that pair only as told, searched again after the boxes
// move (the tree refitted, not rebuilt), and on several threads.
#include "hirsute/hairs/dynamics/box_tree.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

std::vector<Box> randomBoxes(std::mt19937& random, int count) {
  std::uniform_real_distribution<double> place(-2, 2);
  std::lognormal_distribution<double> size(-3, 1.2);
  std::vector<Box> boxes;
  for (int i = 0; i < count; ++i) {
    const Vector3d low(place(random), place(random), place(random));
    const Vector3d extent(size(random), size(random), size(random));
    boxes.push_back({low, low + extent});
  }
  boxes[7].max = Vector3d(3, 3, 3);
  boxes[7].min = Vector3d(-3, -3, -3);
  boxes[11].max.x() = std::numeric_limits<double>::infinity();
  boxes[12].min.x() = -std::numeric_limits<double>::infinity();
  boxes[13].min.y() = std::numeric_limits<double>::quiet_NaN();
  return boxes;
}

std::vector<std::pair<int, int>> everyPair(const std::vector<Box>& boxes, const BoxGroups& groups,
                                           const std::function<bool(int, int)>& wanted) {
  std::vector<std::pair<int, int>> expected;
  for (int a = 0; a < static_cast<int>(boxes.size()); ++a)
    for (int b = a + 1; b < static_cast<int>(boxes.size()); ++b) {
      const int g = groups.of[a], h = groups.of[b];
      const bool paired = ((groups.pairsWith[g] >> h) & 1) &&
                          (((groups.moving >> g) & 1) || ((groups.moving >> h) & 1));
      if (paired && boxes[a].overlaps(boxes[b]) && wanted(a, b)) expected.emplace_back(a, b);
    }
  return expected;
}

TEST(BoxTree, FindsEveryOverlappingPairOfGroupsThatPairOnceSortedAfterMovesAndOnThreads) {
  std::mt19937 random(12);
  std::vector<Box> boxes = randomBoxes(random, 1500);
  BoxGroups groups;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) groups.of.push_back(i % 4);
  // Groups 0 and 1 move; 0 meets 0 and 2, 1 meets 3 and 1; 2 and 3 are still, and 2 would meet
  // 3 (never: two still groups do not pair).
  groups.pairsWith = {0b0101, 0b1010, 0b1001, 0b0110};
  groups.moving = 0b0011;
  const auto wanted = [](int a, int b) { return (a + b) % 5 != 0; };
  WorkerPool pool(3);
  BoxTree alone, threaded(&pool);
  std::normal_distribution<double> move(0, 0.05);
  for (int search = 0; search < 3; ++search) {
    const auto expected = everyPair(boxes, groups, wanted);
    ASSERT_GT(expected.size(), 200u);
    EXPECT_EQ(alone.overlappingPairs(boxes, groups, wanted), expected) << "search " << search;
    EXPECT_EQ(threaded.overlappingPairs(boxes, groups, wanted), expected) << "search " << search;
    // Moved boxes: the tree is refitted, its shape kept.
    for (Box& box : boxes) {
      const Vector3d by(move(random), move(random), move(random));
      box.min += by;
      box.max += by;
    }
    boxes[13].min.y() = search == 0 ? 0.0 : std::numeric_limits<double>::quiet_NaN();
  }
  EXPECT_EQ(alone.builds(), 4u);  // the four groups' trees, once
  EXPECT_EQ(alone.refits(), 2u);
}

// The kept list, filtered while the boxes stay within the slack and made anew when one leaves
// it or the version changes, finds what a search finds.
TEST(BoxTree, TheKeptListFindsWhatASearchFinds) {
  std::mt19937 random(21);
  std::vector<Box> boxes = randomBoxes(random, 1200);
  BoxGroups groups;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) groups.of.push_back(i % 3);
  groups.pairsWith = {0b011, 0b101, 0b010};
  groups.moving = 0b011;
  const auto wanted = [](int a, int b) { return (a * b) % 7 != 3; };
  WorkerPool pool(2);
  BoxTree tree(&pool);
  std::normal_distribution<double> move(0, 0.001);
  for (int search = 0; search < 12; ++search) {
    const int version = search / 5;  // what `lasting` holds changes with it
    const auto lasting = [version](int a, int b) { return (a + b + version) % 11 != 0; };
    const auto both = [&](int a, int b) { return lasting(a, b) && wanted(a, b); };
    EXPECT_EQ(tree.coherentPairs(boxes, groups, 0.01, version, lasting, wanted),
              everyPair(boxes, groups, both))
        << "search " << search;
    for (Box& box : boxes) {
      const Vector3d by(move(random), move(random), move(random));
      box.min += by;
      box.max += by;
    }
  }
  // Made again when a box left its slack (the moves, 0.001 a search in each coordinate, add up
  // to 0.01 for some of the boxes) and when the version changed, filtered the other times.
  EXPECT_GT(tree.listSearches(), 2u);
  EXPECT_GT(tree.listFilters(), 2u);
  EXPECT_EQ(tree.listSearches() + tree.listFilters(), 12u);
}

TEST(BoxTree, TwoGroupsFindWhatTheGridFinds) {
  std::mt19937 random(5);
  const std::vector<Box> boxes = randomBoxes(random, 1200);
  std::vector<char> moving;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) moving.push_back(i % 3 != 0);
  const auto all = [](int, int) { return true; };
  BoxTree tree;
  const auto pairs = tree.overlappingPairs(boxes, moving, all);
  EXPECT_GT(pairs.size(), 200u);
  EXPECT_EQ(pairs, overlappingPairs(boxes, moving, all));
}

}  // namespace
}  // namespace hirsute::dynamics
