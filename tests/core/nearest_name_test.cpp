// The nearest name behind "did you mean …?": edits counted as a person makes them.
#include "hirsute/core/nearest_name.h"

#include <gtest/gtest.h>

namespace hirsute {
namespace {

TEST(EditDistance, CountsInsertionsRemovalsReplacementsAndSwapsOfNeighbours) {
  EXPECT_EQ(editDistance("render", "render"), 0u);
  EXPECT_EQ(editDistance("rendr", "render"), 1u);         // a letter left out
  EXPECT_EQ(editDistance("renderr", "render"), 1u);       // one too many
  EXPECT_EQ(editDistance("rander", "render"), 1u);        // one replaced
  EXPECT_EQ(editDistance("redner", "render"), 1u);        // two neighbours swapped
  EXPECT_EQ(editDistance("Axiom:", "axiom:"), 0u);        // case is no edit
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_GT(editDistance("frobnicate", "render"), 5u);
}

TEST(NearestName, FindsTheOneNameWithinReachAndNoneWhenTwoAreAsNear) {
  const std::vector<std::string> commands = {"derive", "render", "export", "view", "simulate"};
  EXPECT_EQ(nearestName("rendre", commands, 2), "render");
  EXPECT_EQ(nearestName("simulat", commands, 1), "simulate");
  EXPECT_EQ(nearestName("frobnicate", commands, 2), "");
  EXPECT_EQ(nearestName("ab", {"ac", "ad"}, 1), "");  // a tie names neither
  EXPECT_EQ(typoDistance(5), 1u);
  EXPECT_EQ(typoDistance(18), 2u);
}

}  // namespace
}  // namespace hirsute
