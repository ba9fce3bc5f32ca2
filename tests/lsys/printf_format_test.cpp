// printf and @L formats from blocks: what reaches the C library is always a whole conversion.
#include "hirsute/lsys/printf_format.h"

#include <gtest/gtest.h>

#include <string>

namespace hirsute {
namespace {

TEST(PrintfFormat, ConversionsTakeTheValuesInTurn) {
  const double values[] = {3.7, 0.25, 65};
  EXPECT_EQ(formatPrintf("%d|%5.2f|%c|%%", values, 3).text, "3| 0.25|A|%");
}

TEST(PrintfFormat, ANulByteIsNeitherAFlagNorAConversion) {
  // A string of a model may hold NUL bytes. A percent sign before one is not a conversion: the
  // text is copied as written and no value is used.
  const double values[] = {5};
  const std::string nulConversion("a%\0d", 4);
  const PrintfResult first = formatPrintf(nulConversion, values, 1);
  EXPECT_EQ(first.text, nulConversion);
  const std::string nulInFlags("%5\0f|%d", 7);
  EXPECT_EQ(formatPrintf(nulInFlags, values, 1).text, std::string("%5\0f|5", 6));
}

TEST(PrintfFormat, TooWideAFieldIsCopiedAsWritten) {
  const double values[] = {1};
  const PrintfResult r = formatPrintf("%2000000000d", values, 1);
  EXPECT_EQ(r.text, "%2000000000d");
  EXPECT_EQ(r.fieldTooWide, 2000000000);
}

}  // namespace
}  // namespace hirsute
