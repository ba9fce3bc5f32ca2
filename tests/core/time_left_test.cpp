// The time a stage has left (hirsute/core/time_left.h): none before enough is known, the mean
// rate's estimate, a countdown between moves, and bursts that do not make it jump.
#include "hirsute/core/time_left.h"

#include <gtest/gtest.h>

namespace hirsute {
namespace {

TEST(TimeLeft, NothingBeforeEnoughOfTheStageIsDone) {
  TimeLeft left;
  EXPECT_FALSE(left.secondsLeft(0));
  left.add(2, 0.02);  // 2% in 2 s: too little to say
  EXPECT_FALSE(left.secondsLeft(2));
  left.add(5, 0.04);
  EXPECT_FALSE(left.secondsLeft(5));
}

TEST(TimeLeft, ASteadyStageIsGivenTheRestAtItsRate) {
  TimeLeft left;
  left.add(10, 0.25);  // a quarter in 10 s: 30 s to go
  ASSERT_TRUE(left.secondsLeft(10));
  EXPECT_DOUBLE_EQ(*left.secondsLeft(10), 30);
  left.add(20, 0.5);
  EXPECT_DOUBLE_EQ(*left.secondsLeft(20), 20);
  left.add(30, 0.75);
  EXPECT_DOUBLE_EQ(*left.secondsLeft(30), 10);
}

TEST(TimeLeft, BetweenMovesItCountsDownAndStopsAtNothing) {
  TimeLeft left;
  left.add(10, 0.25);
  left.add(14, 0.25);  // no move: the estimate is not taken again
  EXPECT_DOUBLE_EQ(*left.secondsLeft(14), 26);
  EXPECT_DOUBLE_EQ(*left.secondsLeft(25), 15);
  EXPECT_DOUBLE_EQ(*left.secondsLeft(100), 0);
}

TEST(TimeLeft, AFastBurstMovesTheEstimateHalfWay) {
  // Frames rendered two at a time, 30 s each: the estimate lands where the next burst meets it.
  TimeLeft left;
  left.add(30, 0.2);
  EXPECT_DOUBLE_EQ(*left.secondsLeft(30), 120);
  left.add(60, 0.4);
  EXPECT_DOUBLE_EQ(*left.secondsLeft(60), 90);
  // The next two took 10 s only: at the mean rate 35 s are left, counted down 80; it says 57.5.
  left.add(70, 0.6);
  EXPECT_DOUBLE_EQ(*left.secondsLeft(70), (70 * 0.4 / 0.6 + 80) / 2);
}

TEST(TimeLeft, NothingIsLeftOnceTheStageIsDone) {
  TimeLeft left;
  left.add(10, 0.5);
  left.add(20, 1.0);
  EXPECT_FALSE(left.secondsLeft(20));
}

}  // namespace
}  // namespace hirsute
