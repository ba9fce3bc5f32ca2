// cpfg's printf-style formatting of a format string with parameter values: used by printf and
// fprintf in blocks and by the turtle's @L labels (cpfg-manual.txt §6.10).
#pragma once

#include <string>

namespace hirsute {

struct PrintfResult {
  std::string text;
  // The format has more conversions than values; those conversions are copied as written.
  bool missingValues = false;
};

// Applies `format` one conversion at a time, each with the next value as a double (as cpfg
// does): %d %i %o %u %x %X %c take the value truncated to an integer, %f %e %g %a the value
// itself; length modifiers are ignored and %% is a percent sign.
PrintfResult formatPrintf(const std::string& format, const double* values, int count);

}  // namespace hirsute
