// cpfg's animation file (`.a`, cpfg-manual §8.2): the settings read and the frames they give.
#include "hirsute/viewer/interaction/animation_file.h"

#include <gtest/gtest.h>

#include <string>

namespace hirsute {
namespace {

std::string fixture(const std::string& name) {
  return std::string(HIRSUTE_SOURCE_DIR) + "/tests/fixtures/viewer/" + name;
}

std::vector<int> steps(const std::vector<AnimationFrame>& frames) {
  std::vector<int> out;
  for (const AnimationFrame& f : frames) out.push_back(f.step);
  return out;
}

TEST(AnimationFileTest, CpfgsOwnFileMeansEveryStepToTheDerivationLength) {
  Diagnostics diagnostics;
  AnimationSettings a = readAnimationFile(fixture("cpfg_defaults.a"), diagnostics);
  EXPECT_EQ(a.firstFrame, 1);
  EXPECT_FALSE(a.lastFrame.has_value());  // -1
  EXPECT_EQ(a.step, 1);
  EXPECT_DOUBLE_EQ(a.swapIntervalSeconds, 0.1);
  EXPECT_TRUE(a.doubleBuffer);
  EXPECT_TRUE(diagnostics.warnings().empty());
  EXPECT_EQ(steps(animationFrames(a, 4)), (std::vector<int>{1, 2, 3, 4}));
}

TEST(AnimationFileTest, FirstLastAndStepChooseTheFrames) {
  Diagnostics diagnostics;
  AnimationSettings a = readAnimationFile(fixture("every_second.a"), diagnostics);
  EXPECT_TRUE(a.scaleBetweenFrames);
  EXPECT_DOUBLE_EQ(a.swapIntervalSeconds, 0.5);
  EXPECT_EQ(steps(animationFrames(a, 20)), (std::vector<int>{2, 4, 6, 8}));
  // Frames past the derivation length are not drawn.
  EXPECT_EQ(steps(animationFrames(a, 5)), (std::vector<int>{2, 4}));
}

TEST(AnimationFileTest, FrameIntervalsTakePrecedence) {
  Diagnostics diagnostics;
  AnimationSettings a = readAnimationFile(fixture("intervals.a"), diagnostics);
  ASSERT_EQ(a.frameIntervals.size(), 5u);
  std::vector<AnimationFrame> frames = animationFrames(a, 100);
  EXPECT_EQ(steps(frames), (std::vector<int>{1, 3, 4, 5, 10, 12, 14, 16, 19, 20, 21, 22}));
  ASSERT_TRUE(frames[8].rotateAfter.has_value());
  EXPECT_FLOAT_EQ(frames[8].rotateAfter->x, 1.5f);
  ASSERT_TRUE(frames[11].scaleAfter.has_value());
  EXPECT_FLOAT_EQ(frames[11].scaleAfter->y, 0.9f);
  EXPECT_FALSE(frames[0].rotateAfter.has_value());
}

// A step past INT_MAX once wrapped (undefined behaviour), and a range from far below 0 walked up
// to 0 a frame at a time (two billion steps); reproduced through animation_file_fuzzer.
TEST(AnimationFileTest, AStepNearIntMaxEndsAtTheLastFrame) {
  Diagnostics diagnostics;
  AnimationSettings a = readAnimationFile(fixture("huge_step.a"), diagnostics);
  EXPECT_EQ(steps(animationFrames(a, 10)), (std::vector<int>{1}));
}

TEST(AnimationFileTest, ARangeFromFarBelowZeroStartsAtItsFirstFrameFromZero) {
  Diagnostics diagnostics;
  AnimationSettings a = readAnimationFile(fixture("far_below_zero.a"), diagnostics);
  // -2000000001 + 1000000001·2 = 1; then 3 and 5; the second range gives 7 alone.
  EXPECT_EQ(steps(animationFrames(a, 100)), (std::vector<int>{1, 3, 5, 7}));
}

TEST(AnimationFileTest, BadValueNamesLineAndColumn) {
  Diagnostics diagnostics;
  try {
    readAnimationFile(fixture("bad_step.a"), diagnostics);
    FAIL() << "expected an error";
  } catch (const DiagnosticError& e) {
    EXPECT_EQ(e.diagnostic().text(),
              fixture("bad_step.a") + ":2:7: error: expected the step, an integer");
  }
}

TEST(AnimationFileTest, UnknownLabelsAreIgnoredWithAWarning) {
  Diagnostics diagnostics;
  AnimationSettings a = readAnimationFile(fixture("unknown_label.a"), diagnostics);
  EXPECT_EQ(a.lastFrame, 3);
  ASSERT_EQ(diagnostics.warnings().size(), 1u);  // lpfg's `display on request` is known
  EXPECT_EQ(diagnostics.warnings()[0].where.line, 2);
}

TEST(AnimationFileTest, WithoutAFileEveryStepIsAFrame) {
  EXPECT_EQ(steps(animationFrames(AnimationSettings(), 3)), (std::vector<int>{1, 2, 3}));
}

TEST(AnimationFileTest, TheFramesStopOnePastTheLimit) {
  const std::vector<AnimationFrame> frames = animationFrames(AnimationSettings(), 2'000'000'000);
  ASSERT_EQ(frames.size(), kMaxAnimationFrames + 1);
  EXPECT_EQ(frames.back().step, static_cast<int>(kMaxAnimationFrames) + 1);
}

}  // namespace
}  // namespace hirsute
