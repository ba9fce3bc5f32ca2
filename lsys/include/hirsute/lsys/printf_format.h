// cpfg's printf-style formatting of a format string with parameter values: used by printf and
// fprintf in blocks and by the turtle's @L labels (cpfg-manual.txt §6.10).
#pragma once

#include <string>

namespace hirsute {

// The widest field width or precision a conversion may ask for. cpfg wrote into a fixed buffer;
// a width of 2·10⁹ took seconds a label.
inline constexpr int kMaxPrintfField = 1000;

struct PrintfResult {
  std::string text;
  // The format has more conversions than values; those conversions are copied as written.
  bool missingValues = false;
  // The widest field of a conversion over kMaxPrintfField (0: none); those conversions are
  // copied as written.
  int fieldTooWide = 0;
};

// Applies `format` one conversion at a time, each with the next value as a double (as cpfg
// does): %d %i %o %u %x %X %c take the value truncated to an integer, %f %e %g %a the value
// itself; length modifiers are ignored and %% is a percent sign.
PrintfResult formatPrintf(const std::string& format, const double* values, int count);

}  // namespace hirsute
