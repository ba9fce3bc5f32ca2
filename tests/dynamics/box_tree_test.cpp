// The tree's broad phase against every pair tested directly: random boxes of many sizes (some
// huge, some unbounded or NaN) in groups that pair only as told, searched again after the boxes
// move (the tree refitted, not rebuilt), and on several threads.
#include "hirsute/hairs/dynamics/box_tree.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <set>

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
    const int version = search / 5;  // what `tested` holds changes with it
    BoxTree::KeptList list;
    list.slack = 0.01;
    list.version = version;
    list.tested = [version](int a, int b) { return (a + b + version) % 11 != 0; };
    const auto both = [&](int a, int b) { return list.tested(a, b) && wanted(a, b); };
    EXPECT_EQ(tree.coherentPairs(boxes, groups, list, wanted), everyPair(boxes, groups, both))
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

// Boxes of parts (ten boxes a part, each box's corners its vertices): a few parts jump beyond
// the slack each search, the rest creep. The list is repaired, only the parts that jumped
// searched again, and finds what a search finds.
TEST(BoxTree, ARepairedListFindsWhatASearchFinds) {
  std::mt19937 random(33);
  std::vector<Box> boxes = randomBoxes(random, 1200);
  boxes[11].max.x() = 2;  // no unbounded boxes: their vertices would leave any grown box
  boxes[12].min.x() = -2;
  BoxGroups groups;
  std::vector<int> boxParts, vertexParts;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
    groups.of.push_back(i % 3);
    boxParts.push_back(i / 10);
    vertexParts.insert(vertexParts.end(), 2, i / 10);
  }
  groups.pairsWith = {0b011, 0b101, 0b010};
  groups.moving = 0b011;
  const auto wanted = [](int a, int b) { return (a * b) % 7 != 3; };
  // A test of the pair that does not depend on where the boxes are: whatever slack it is told
  // of, the pairs it keeps apart are left out.
  const auto apart = [](int a, int b, double) { return (31 * a + b) % 13 == 0; };
  WorkerPool pool(2);
  BoxTree tree(&pool);
  std::normal_distribution<double> creep(0, 0.0005);
  std::uniform_int_distribution<int> part(0, 119);
  for (int search = 0; search < 16; ++search) {
    std::vector<Box> vertices;
    for (const Box& box : boxes) {
      vertices.push_back({box.min, box.min});
      vertices.push_back({box.max, box.max});
    }
    BoxTree::KeptList list;
    list.slack = 0.01;
    list.tested = [](int a, int b) { return (a + b) % 11 != 0; };
    list.apart = apart;
    list.vertices = &vertices;
    list.boxParts = &boxParts;
    list.vertexParts = &vertexParts;
    const auto expected = everyPair(boxes, groups, [&](int a, int b) {
      return list.tested(a, b) && !apart(a, b, 0) && wanted(a, b);
    });
    EXPECT_EQ(tree.coherentPairs(boxes, groups, list, wanted), expected) << "search " << search;
    std::vector<char> jumps(120, 0);
    for (int k = 0; k < 3; ++k) jumps[part(random)] = 1;
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
      const Vector3d by = jumps[boxParts[i]]
                              ? Vector3d(0.05, -0.03, 0.02)
                              : Vector3d(creep(random), creep(random), creep(random));
      boxes[i].min += by;
      boxes[i].max += by;
    }
  }
  // Searched once, then repaired each time (three parts a time, far from all of the 1 200 boxes
  // that would have it made anew).
  EXPECT_EQ(tree.listSearches(), 1u);
  EXPECT_EQ(tree.listRepairs(), 15u);
}

// Points (a box round each) in parts that creep and jump, with the test of a plane: a pair
// whose projections on x are farther apart than the reach and the strays is left out. Every
// pair whose boxes overlap and whose points are within the reach along x is found, after any
// number of repairs: a part that stayed is allowed for as far as its grown boxes let it go.
TEST(BoxTree, APlaneTestOfARepairedListLosesNoNearPair) {
  std::mt19937 random(8);
  std::uniform_real_distribution<double> place(0, 1);
  constexpr int kPoints = 600, kPerPart = 6;
  constexpr double kMargin = 0.04, kReach = 0.05;
  std::vector<Vector3d> points;
  for (int i = 0; i < kPoints; ++i)
    points.emplace_back(place(random), place(random), 0.1 * place(random));
  BoxGroups groups;
  groups.of.assign(kPoints, 0);
  groups.pairsWith = {0b1};
  groups.moving = 0b1;
  std::vector<int> parts;
  for (int i = 0; i < kPoints; ++i) parts.push_back(i / kPerPart);
  BoxTree tree;
  std::normal_distribution<double> creep(0, 0.003);
  std::uniform_int_distribution<int> part(0, kPoints / kPerPart - 1);
  double largestStrays = 0;
  for (int search = 0; search < 40; ++search) {
    std::vector<Box> boxes, vertices;
    for (const Vector3d& p : points) {
      boxes.push_back({p.array() - kMargin, p.array() + kMargin});
      vertices.push_back({p, p});
    }
    BoxTree::KeptList list;
    list.slack = 0.01;
    list.tested = [](int, int) { return true; };
    list.apart = [&](int a, int b, double strays) {
      largestStrays = std::max(largestStrays, strays);
      return std::abs(points[a].x() - points[b].x()) > kReach + strays;
    };
    list.vertices = &vertices;
    list.boxParts = &parts;
    list.vertexParts = &parts;
    const auto found = tree.coherentPairs(boxes, groups, list, [](int, int) { return true; });
    const std::set<std::pair<int, int>> foundSet(found.begin(), found.end());
    for (int a = 0; a < kPoints; ++a)
      for (int b = a + 1; b < kPoints; ++b) {
        if (boxes[a].overlaps(boxes[b]) && std::abs(points[a].x() - points[b].x()) <= kReach) {
          EXPECT_TRUE(foundSet.count({a, b})) << "search " << search << ": " << a << ", " << b;
        }
      }
    std::vector<char> jumps(kPoints / kPerPart, 0);
    for (int k = 0; k < 2; ++k) jumps[part(random)] = 1;
    for (int i = 0; i < kPoints; ++i)
      points[i] += jumps[parts[i]] ? Vector3d(0.015, 0, 0)
                                   : Vector3d(creep(random), creep(random), creep(random));
  }
  EXPECT_GT(tree.listRepairs(), 5u);
  EXPECT_GT(largestStrays, 0.02);  // a part that stayed was allowed more than its slack
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
