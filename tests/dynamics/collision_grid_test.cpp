// The broad phase against every pair tested directly: random boxes of many sizes (some huge,
// some non-finite) in groups that pair only as told, the moving ones among still ones.
#include "hirsute/hairs/dynamics/collision_grid.h"

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
  boxes[7].max = Vector3d(3, 3, 3);  // over far more cells than a box may take
  boxes[7].min = Vector3d(-3, -3, -3);
  boxes[11].max.x() = std::numeric_limits<double>::infinity();
  return boxes;
}

TEST(CollisionGrid, GroupsFindEveryOverlappingPairTheyMayPairOnceAndNoOther) {
  std::mt19937 random(12);
  const std::vector<Box> boxes = randomBoxes(random, 1500);
  BoxGroups groups;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) groups.of.push_back(i % 4);
  // Groups 0 and 1 move; 0 meets 0 and 2, 1 meets 3; 2 and 3 are still.
  groups.pairsWith = {0b0101, 0b1000, 0b0001, 0b0010};
  groups.moving = 0b0011;
  const auto wanted = [](int a, int b) { return (a + b) % 5 != 0; };
  std::vector<std::pair<int, int>> expected;
  for (int a = 0; a < static_cast<int>(boxes.size()); ++a)
    for (int b = a + 1; b < static_cast<int>(boxes.size()); ++b) {
      const bool paired = (groups.pairsWith[groups.of[a]] >> groups.of[b]) & 1;
      if (paired && boxes[a].overlaps(boxes[b]) && wanted(a, b)) expected.emplace_back(a, b);
    }
  ASSERT_GT(expected.size(), 200u);
  EXPECT_EQ(overlappingPairs(boxes, groups, wanted), expected);
}

TEST(CollisionGrid, MovingBoxesMeetEachOtherAndStillOnesButStillOnesNeverMeet) {
  std::mt19937 random(5);
  const std::vector<Box> boxes = randomBoxes(random, 1200);
  std::vector<char> moving;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) moving.push_back(i % 3 != 0);
  const auto all = [](int, int) { return true; };
  std::vector<std::pair<int, int>> expected, everyPair;
  for (int a = 0; a < static_cast<int>(boxes.size()); ++a)
    for (int b = a + 1; b < static_cast<int>(boxes.size()); ++b) {
      if (!boxes[a].overlaps(boxes[b])) continue;
      everyPair.emplace_back(a, b);
      if (moving[a] || moving[b]) expected.emplace_back(a, b);
    }
  EXPECT_EQ(overlappingPairs(boxes, moving, all), expected);
  EXPECT_EQ(overlappingPairs(boxes, all), everyPair);
}

}  // namespace
}  // namespace hirsute::dynamics
