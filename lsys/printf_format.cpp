#include "hirsute/lsys/printf_format.h"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace hirsute {

PrintfResult formatPrintf(const std::string& fmt, const double* values, int count) {
  PrintfResult result;
  std::string& out = result.text;
  int next = 0;
  std::size_t pos = 0;
  char buffer[512];
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
    while (end < fmt.size() && std::strchr("-+ #0123456789.", fmt[end])) ++end;
    std::string flags = fmt.substr(pos, end - pos);
    while (end < fmt.size() && std::strchr("hlLqjzt", fmt[end])) ++end;  // length modifiers are ignored
    if (end >= fmt.size() || flags.size() > 20) {
      out += fmt.substr(pos);
      break;
    }
    char conversion = fmt[end];
    if (!std::strchr("diouxXcfFeEgGaA", conversion)) {
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
    if (std::strchr("diouxXc", conversion)) {
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
