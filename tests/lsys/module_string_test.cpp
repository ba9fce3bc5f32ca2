// The packed module string: forward and backward walks, parameters kept as float32.
#include <gtest/gtest.h>

#include <cmath>

#include "hirsute/lsys/module_string.h"
#include "hirsute/lsys/string_writer.h"

namespace hirsute {
namespace {

TEST(ModuleString, WalksForwardAndBackwardOverMixedModules) {
  ModuleString s;
  s.append('F');
  const float two[] = {1.5f, -2.0f};
  s.append('A', two);
  s.append('[');
  const double one[] = {0.1};
  s.appendRounded('B', one);
  ASSERT_EQ(s.moduleCount(), 4u);

  std::vector<std::size_t> forward;
  for (std::size_t p = s.begin(); p < s.end(); p = s.next(p)) forward.push_back(p);
  ASSERT_EQ(forward.size(), 4u);
  std::vector<std::size_t> backward;
  for (std::size_t p = s.end(); p > 0;) {
    p = s.previous(p);
    backward.push_back(p);
  }
  std::reverse(backward.begin(), backward.end());
  EXPECT_EQ(forward, backward);

  ModuleRef a = s.at(forward[1]);
  EXPECT_EQ(a.symbol(), 'A');
  ASSERT_EQ(a.parameterCount(), 2u);
  EXPECT_EQ(a.parameter(0), 1.5f);
  EXPECT_EQ(a.parameter(1), -2.0f);
  EXPECT_EQ(s.at(forward[2]).symbol(), '[');
  EXPECT_EQ(s.at(forward[2]).parameterCount(), 0u);
}

TEST(ModuleString, StoresParametersAsFloat32) {
  ModuleString s;
  const double tenth[] = {0.1};
  s.appendRounded('A', tenth);
  EXPECT_EQ(s.at(0).parameter(0), 0.1f);
  EXPECT_NE(static_cast<double>(s.at(0).parameter(0)), 0.1);
}

TEST(ModuleString, PlainModulesTakeOneByteAndParametricOnesThreePlusFourPerValue) {
  ModuleString s;
  s.append('F');
  const float v[] = {1, 2, 3};
  s.append('G', v);
  EXPECT_EQ(s.byteSize(), 1u + 3u + 12u);
}

TEST(ModuleString, GrowingPastTheByteLimitThrows) {
  ModuleString s;
  s.setByteLimit(10000);
  EXPECT_THROW(
      {
        for (int i = 0; i < 20000; ++i) s.append('F');
      },
      ModuleStringTooLarge);
}

TEST(ModuleString, CopiesRangesAndModulesVerbatim) {
  ModuleString a, b;
  const float v[] = {4.25f};
  a.append('X', v);
  a.append('Y');
  b.appendRange(a, 0, a.end(), a.moduleCount());
  b.append(a.at(0));
  EXPECT_EQ(b.moduleCount(), 3u);
  EXPECT_EQ(b.at(b.previous(b.end())).parameter(0), 4.25f);
}

TEST(FormatParameter, PrintsLikePrintfPercentG) {
  EXPECT_EQ(formatParameter(1.0f), "1");
  EXPECT_EQ(formatParameter(0.1f), "0.1");
  EXPECT_EQ(formatParameter(-0.0f), "-0");
  EXPECT_EQ(formatParameter(1234567.0f), "1.23457e+06");
  EXPECT_EQ(formatParameter(0.0001f), "0.0001");
  EXPECT_EQ(formatParameter(0.00001f), "1e-05");
}

}  // namespace
}  // namespace hirsute
