// The packed module string: forward and backward walks, parameters kept as float32.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <span>
#include <string>
#include <vector>
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

// An empty string has no buffer: its (empty) range appends nothing, and the sanitizer build
// fails here if the copy is handed the null pointer (a thread's empty part of a split step).
TEST(ModuleString, AnEmptyStringsRangeAppendsNothing) {
  ModuleString empty, b;
  b.append('X');
  b.appendRange(empty, empty.begin(), empty.end(), 0);
  EXPECT_EQ(b.moduleCount(), 1u);
  EXPECT_EQ(b.end(), 1u);
}

TEST(FormatParameter, PrintsLikePrintfPercentG) {
  EXPECT_EQ(formatParameter(1.0f), "1");
  EXPECT_EQ(formatParameter(0.1f), "0.1");
  EXPECT_EQ(formatParameter(-0.0f), "-0");
  EXPECT_EQ(formatParameter(1234567.0f), "1.23457e+06");
  EXPECT_EQ(formatParameter(0.0001f), "0.0001");
  EXPECT_EQ(formatParameter(0.00001f), "1e-05");
}

std::string writeWith(StringFormat format, const std::function<void(StringWriter&)>& write) {
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* memory = open_memstream(&buffer, &size);
  {
    StringWriter writer(memory, format);
    write(writer);
    writer.finish();
  }
  std::fclose(memory);
  std::string text(buffer, size);
  std::free(buffer);
  return text;
}

// cpfg's -str: a newline after the module that brings the line's count (symbols, digits and
// parentheses, not commas) to 70 or more; a final newline. The whole-string path and the
// module-by-module path write the same text.
TEST(StringWriter, BreaksLinesAsCpfgOnEveryPath) {
  ModuleString s;
  const float values[] = {0.5f, -12.25f, 1e-7f};
  for (int i = 0; i < 200; ++i) {
    s.append('[');
    s.append('F', std::span<const float>(values, static_cast<std::size_t>(i % 4)));
    s.append(']');
  }
  std::string whole = writeWith(StringFormat::Cpfg, [&](StringWriter& w) { w.modules(s, s.begin(), s.end()); });
  std::string each = writeWith(StringFormat::Cpfg, [&](StringWriter& w) {
    for (std::size_t p = s.begin(); p < s.end(); p = s.next(p)) w.module(s.at(p));
  });
  EXPECT_EQ(whole, each);
  ASSERT_FALSE(whole.empty());
  EXPECT_EQ(whole.back(), '\n');
  std::size_t lineStart = 0;
  for (std::size_t nl = whole.find('\n'); nl != std::string::npos; nl = whole.find('\n', lineStart)) {
    std::string line = whole.substr(lineStart, nl - lineStart);
    std::size_t counted = line.size() - static_cast<std::size_t>(std::count(line.begin(), line.end(), ','));
    if (nl + 1 < whole.size()) {
      EXPECT_GE(counted, 70u) << line;
    }
    lineStart = nl + 1;
  }
  std::string compact = writeWith(StringFormat::Compact, [&](StringWriter& w) { w.modules(s, s.begin(), s.end()); });
  EXPECT_EQ(compact.find('\n'), compact.size() - 1);
  whole.erase(std::remove(whole.begin(), whole.end(), '\n'), whole.end());
  compact.pop_back();
  EXPECT_EQ(whole, compact);
  EXPECT_EQ(writeWith(StringFormat::Cpfg, [](StringWriter&) {}), "");
}

// Runs of modules without parameters are copied in pieces up to the line's end: runs of every
// length from 1 to 200 between modules with parameters, written whole, module by module, and in
// ranges that cut runs anywhere, through several fills of the writer's buffer, give one text.
TEST(StringWriter, CopiesRunsOfPlainModulesAsItWritesThemOneByOne) {
  ModuleString s;
  const float value = 2.5f;
  std::vector<std::size_t> cuts;
  for (int run = 1; run <= 200; ++run) {
    for (int k = 0; k < run * 7; ++k) s.append("F+[]-AB"[(k + run) % 7]);
    if (run % 3 == 0) cuts.push_back(s.end() - static_cast<std::size_t>(run % 5));
    s.append('K', std::span<const float>(&value, 1));
  }
  ASSERT_GT(s.byteSize(), std::size_t{1} << 17);
  for (StringFormat format : {StringFormat::Cpfg, StringFormat::Compact}) {
    const std::string each = writeWith(format, [&](StringWriter& w) {
      for (std::size_t p = s.begin(); p < s.end(); p = s.next(p)) w.module(s.at(p));
    });
    EXPECT_EQ(writeWith(format, [&](StringWriter& w) { w.modules(s, s.begin(), s.end()); }), each);
    EXPECT_EQ(writeWith(format,
                        [&](StringWriter& w) {
                          std::size_t from = s.begin();
                          for (std::size_t cut : cuts) {
                            w.modules(s, from, cut);
                            from = cut;
                          }
                          w.modules(s, from, s.end());
                        }),
              each);
  }
}

// formatParameter does not call printf; it must still agree with it byte for byte. Every
// 4093rd bit pattern (a million floats of both signs, subnormals, infinities and NaNs), and the
// values where %g changes notation or rounding carries into a new digit. (The whole float
// range was compared once, when the formatter was written.)
TEST(FormatParameter, MatchesPrintfOnSampledFloats) {
  auto printfG = [](float value) {
    char text[32];
    int n = std::snprintf(text, sizeof text, "%g", static_cast<double>(value));
    return std::string(text, static_cast<std::size_t>(n));
  };
  std::size_t mismatches = 0;
  auto check = [&](float value) {
    if (formatParameter(value) != printfG(value) && ++mismatches <= 10) {
      ADD_FAILURE() << "bits " << std::hex << std::bit_cast<std::uint32_t>(value) << ": printf "
                    << printfG(value) << ", formatParameter " << formatParameter(value);
    }
  };
  for (std::uint64_t bits = 0; bits <= 0xffffffffu; bits += 4093) {
    check(std::bit_cast<float>(static_cast<std::uint32_t>(bits)));
  }
  for (float edge : {1e-5f, 1e-4f, 999999.5f, 999999.4f, 1e6f, 9.999995e-5f, 16777215.0f, 1234565.0f,
                     1234575.0f, 0.5f, 3.4028235e38f, 1.17549435e-38f, 1e-45f}) {
    for (int step = -3; step <= 3; ++step) {
      std::uint32_t bits = std::bit_cast<std::uint32_t>(edge) + static_cast<std::uint32_t>(step);
      check(std::bit_cast<float>(bits));
      check(-std::bit_cast<float>(bits));
    }
  }
  EXPECT_EQ(mismatches, 0u);
}

}  // namespace
}  // namespace hirsute
