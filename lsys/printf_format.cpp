#include "hirsute/lsys/printf_format.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>

#include "hirsute/core/characters.h"

namespace hirsute {
namespace {

// The larger of a conversion's field width and precision, from its flags (`%-08.3`): the
// numbers in them, at most 20 characters long.
int widestField(const std::string& flags) {
  int widest = 0, number = 0;
  for (char c : flags) {
    if (c >= '0' && c <= '9') {
      number = static_cast<int>(std::min<long long>(number * 10LL + (c - '0'), INT_MAX));
    } else {
      widest = std::max(widest, number);
      number = 0;
    }
  }
  return std::max(widest, number);
}

}  // namespace

PrintfResult formatPrintf(const std::string& fmt, const double* values, int count) {
  PrintfResult result;
  std::string& out = result.text;
  int next = 0;
  std::size_t pos = 0;
  // Wide enough for any conversion within the field limit: %.1000f of 1e308 is 1 311 characters.
  char buffer[2 * kMaxPrintfField + 64];
  while (pos < fmt.size()) {
    char c = fmt[pos];
    if (c != '%') {
      out += c;
      ++pos;
      continue;
    }
    if (pos + 1 < fmt.size() && fmt[pos + 1] == '%') {
      out += '%';
      pos += 2;
      continue;
    }
    std::size_t end = pos + 1;
    while (end < fmt.size() && isOneOf(fmt[end], "-+ #0123456789.")) ++end;
    std::string flags = fmt.substr(pos, end - pos);
    while (end < fmt.size() && isOneOf(fmt[end], "hlLqjzt")) ++end;  // length modifiers are ignored
    if (end >= fmt.size() || flags.size() > 20) {
      out += fmt.substr(pos);
      break;
    }
    const int field = widestField(flags);
    if (field > kMaxPrintfField) {
      result.fieldTooWide = std::max(result.fieldTooWide, field);
      out += fmt.substr(pos, end + 1 - pos);
      pos = end + 1;
      continue;
    }
    char conversion = fmt[end];
    if (!isOneOf(conversion, "diouxXcfFeEgGaA")) {
      out += fmt.substr(pos, end + 1 - pos);
      pos = end + 1;
      continue;
    }
    if (next >= count) {
      result.missingValues = true;
      out += fmt.substr(pos, end + 1 - pos);
      pos = end + 1;
      continue;
    }
    double v = values[next++];
    if (isOneOf(conversion, "diouxXc")) {
      long long i = std::isfinite(v) && std::fabs(v) < 9e18 ? static_cast<long long>(v) : 0;
      std::string spec = flags + "ll" + conversion;
      if (conversion == 'c') spec = flags + "c";
      if (conversion == 'c') std::snprintf(buffer, sizeof buffer, spec.c_str(), static_cast<int>(i));
      else std::snprintf(buffer, sizeof buffer, spec.c_str(), i);
    } else {
      std::string spec = flags + conversion;
      std::snprintf(buffer, sizeof buffer, spec.c_str(), v);
    }
    out += buffer;
    pos = end + 1;
  }
  return result;
}

}  // namespace hirsute
