#include "hirsute/lsys/string_writer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "hirsute/lsys/program.h"

namespace hirsute {
namespace {

using Wide = unsigned __int128;

// 5^k for k = 0..kMaxFivePower: with a float's 24-bit significand, m * 5^44 < 2^127.
constexpr int kMaxFivePower = 44;
constexpr auto kFivePowers = [] {
  struct Table {
    Wide power[kMaxFivePower + 1];
  } table{};
  table.power[0] = 1;
  for (int k = 1; k <= kMaxFivePower; ++k) table.power[k] = table.power[k - 1] * 5;
  return table;
}();

// num / 2^shift rounded to nearest, ties to even (printf's rounding in the default mode);
// `truncated` receives the quotient before rounding.
std::uint64_t roundShift(Wide num, int shift, std::uint64_t& truncated) {
  if (shift <= 0) return truncated = static_cast<std::uint64_t>(num << -shift);
  Wide q = num >> shift;
  Wide r = num - (q << shift);
  Wide half = Wide{1} << (shift - 1);
  truncated = static_cast<std::uint64_t>(q);
  if (r > half || (r == half && (q & 1))) ++q;
  return static_cast<std::uint64_t>(q);
}

// num / den rounded to nearest, ties to even.
std::uint64_t roundDivide(Wide num, Wide den, std::uint64_t& truncated) {
  Wide q = num / den;
  Wide r = num - q * den;
  truncated = static_cast<std::uint64_t>(q);
  if (2 * r > den || (2 * r == den && (q & 1))) ++q;
  return static_cast<std::uint64_t>(q);
}

// The six significant digits of m * 2^e scaled by 10^(5 - x), correctly rounded; the value
// before rounding goes to `truncated` (so a caller can tell an exponent estimate one too low).
// Requires 5 - x <= kMaxFivePower.
std::uint64_t scaledDigits(std::uint64_t m, int e, int x, std::uint64_t& truncated) {
  int k = 5 - x;
  if (k >= 0) {
    // m 2^e 10^k = (m 5^k) 2^(e+k)
    return roundShift(Wide{m} * kFivePowers.power[k], -(e + k), truncated);
  }
  // m 2^e / 10^j = m 2^(e-j) / 5^j; 5^j is odd, so only a power-of-two denominator can tie.
  int j = -k;
  if (e - j >= 0) return roundDivide(Wide{m} << (e - j), kFivePowers.power[j], truncated);
  return roundDivide(Wide{m}, kFivePowers.power[j] << (j - e), truncated);
}

std::size_t formatWithPrintf(float value, char* out) {
  char text[32];
  int n = std::snprintf(text, sizeof text, "%g", static_cast<double>(value));
  std::memcpy(out, text, static_cast<std::size_t>(n));
  return static_cast<std::size_t>(n);
}

}  // namespace

// C's `%g` (precision 6) of a float promoted to double, without printf: the float's exact value
// m 2^e is scaled to six digits with 128-bit integers and rounded to nearest with ties to even,
// which is what glibc's printf does in the default rounding mode. %g picks fixed notation for
// decimal exponents -4..5, and drops trailing zeros and a bare point. Values printf spells
// differently (infinities, NaNs) and the smallest subnormals go through printf itself. Compared
// with glibc's snprintf over all 2^32 bit patterns when it was written: no difference;
// tests/lsys/module_string_test.cpp keeps a million-pattern sample of that comparison.
// Out of line: the writer's cache answers most numbers, and its loop stays small without this.
[[gnu::noinline]] std::size_t formatParameter(float value, char* out) {
  std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
  std::uint32_t exponentBits = (bits >> 23) & 0xff;
  std::uint32_t fraction = bits & 0x7fffff;
  char* p = out;
  if (bits >> 31) *p++ = '-';
  if (exponentBits == 0xff) return formatWithPrintf(value, out);
  if (exponentBits == 0 && fraction == 0) {
    *p++ = '0';
    return static_cast<std::size_t>(p - out);
  }
  std::uint64_t m = exponentBits ? (fraction | 0x800000u) : fraction;
  int e = exponentBits ? static_cast<int>(exponentBits) - 150 : -149;
  // The value lies in [2^b, 2^(b+1)), so its decimal exponent is floor(b log10 2) or one more.
  int b = e + 63 - std::countl_zero(m);
  int x = (b * 78913) >> 18;  // floor(b log10 2) for |b| < 1650 (as in Ryu)
  if (5 - x > kMaxFivePower) return formatWithPrintf(value, out);
  std::uint64_t truncated;
  std::uint64_t digits = scaledDigits(m, e, x, truncated);
  if (truncated >= 1000000) {
    digits = scaledDigits(m, e, ++x, truncated);
  } else if (truncated < 100000) {  // not expected from the bound above; kept as a guard
    if (5 - (x - 1) > kMaxFivePower) return formatWithPrintf(value, out);
    digits = scaledDigits(m, e, --x, truncated);
  }
  if (digits == 1000000) {  // rounding carried into a seventh digit: 999999.5 -> 1.00000e+06
    digits = 100000;
    ++x;
  }
  char d[6];
  for (int i = 5; i >= 0; --i) {
    d[i] = static_cast<char>('0' + digits % 10);
    digits /= 10;
  }
  int significant = 6;
  while (significant > 1 && d[significant - 1] == '0') --significant;
  if (x < -4 || x >= 6) {
    *p++ = d[0];
    if (significant > 1) {
      *p++ = '.';
      for (int i = 1; i < significant; ++i) *p++ = d[i];
    }
    *p++ = 'e';
    *p++ = x < 0 ? '-' : '+';
    int magnitude = x < 0 ? -x : x;
    *p++ = static_cast<char>('0' + magnitude / 10);
    *p++ = static_cast<char>('0' + magnitude % 10);
  } else if (x >= 0) {
    for (int i = 0; i <= x; ++i) *p++ = d[i];
    if (significant > x + 1) {
      *p++ = '.';
      for (int i = x + 1; i < significant; ++i) *p++ = d[i];
    }
  } else {
    *p++ = '0';
    *p++ = '.';
    for (int i = -1; i > x; --i) *p++ = '0';
    for (int i = 0; i < significant; ++i) *p++ = d[i];
  }
  return static_cast<std::size_t>(p - out);
}

std::string formatParameter(float value) {
  char text[kMaxParameterText + 1];
  return std::string(text, formatParameter(value, text));
}

StringWriter::StringWriter(std::FILE* out, StringFormat format) : out_(out), format_(format) {}

StringWriter::~StringWriter() {
  flush();
}

void StringWriter::flush() {
  if (used_ && std::fwrite(buffer_, 1, used_, out_) != used_) failed_ = true;
  used_ = 0;
}

// Inline: called for every parameter written; a hit in the cache is a compare and one move.
inline std::size_t StringWriter::formatNumber(float value, char* out) {
  std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
  CacheEntry& entry = cache_[(bits ^ (bits >> 11) ^ (bits >> 23)) & (std::size(cache_) - 1)];
  if (entry.bits != bits) {
    entry.length = static_cast<std::uint8_t>(formatParameter(value, entry.text));
    entry.bits = bits;
  }
  std::memcpy(out, entry.text, 16);  // fixed size: one move; `out` has the room
  return entry.length;
}

// Writes one module at `p` (which has roomFor(count) bytes) and returns the end. The line count
// and the output pointer are the caller's locals: stores through a char pointer may alias any
// member, so members would be reloaded after every character.
template <typename ParameterAt>
inline char* StringWriter::writeModule(char* p, bool cpfg, int& lineCount, char symbol,
                                       std::size_t count, ParameterAt parameterAt) {
  *p++ = symbol;
  int counted = 1;
  if (count) {
    *p++ = '(';
    for (std::size_t i = 0; i < count; ++i) {
      if (i) *p++ = ',';
      std::size_t digits = formatNumber(parameterAt(i), p);
      p += digits;
      counted += static_cast<int>(digits);
    }
    *p++ = ')';
    counted += 2;  // cpfg counts the parentheses but not the commas
  }
  if (cpfg) {
    // cpfg's -str: after a module, a newline once the line's count reaches 70.
    lineCount += counted;
    if (lineCount >= 70) {
      *p++ = '\n';
      lineCount = 0;
    }
  } else {
    lineCount = 1;  // the line is not empty; compact lines never break
  }
  return p;
}

const std::string* StringWriter::stringArgument(bool afterAt, char symbol, std::size_t count,
                                                float first) const {
  if (!afterAt || count == 0 || strings_ == nullptr || !takesStringArgument(symbol)) return nullptr;
  // A parameter a production computed may be any number; only an id of the table is a string.
  if (!(first >= 0) || first != std::floor(first) || first >= static_cast<float>(strings_->size())) {
    return nullptr;
  }
  return &(*strings_)[static_cast<std::size_t>(first)];
}

// The string is written quoted with the lexer's escapes (\" \\ \n \t \r), so the text reads
// back as the same module: `@L("height %g",3)`. cpfg's line count takes the quoted text as it
// takes a parameter's digits.
template <typename ParameterAt>
void StringWriter::writeStringModule(int& lineCount, char symbol, const std::string& text,
                                     std::size_t count, ParameterAt parameterAt) {
  std::string out(1, symbol);
  out += "(\"";
  for (char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default: out += c;
    }
  }
  out += '"';
  int counted = 3 + static_cast<int>(out.size() - 2);  // symbol, parentheses, the quoted text
  char number[kMaxParameterText + 4];
  for (std::size_t i = 1; i < count; ++i) {
    std::size_t digits = formatNumber(parameterAt(i), number);
    out += ',';
    out.append(number, digits);
    counted += static_cast<int>(digits);
  }
  out += ')';
  if (format_ == StringFormat::Cpfg) {
    lineCount += counted;
    if (lineCount >= 70) {
      out += '\n';
      lineCount = 0;
    }
  } else {
    lineCount = 1;
  }
  if (out.size() > sizeof buffer_) {
    flush();
    if (std::fwrite(out.data(), 1, out.size(), out_) != out.size()) failed_ = true;
  } else {
    put(out.data(), out.size());
  }
}

void StringWriter::module(char symbol, const float* parameters, std::size_t count) {
  const bool afterAt = afterAt_;
  afterAt_ = symbol == '@' && count == 0;
  if (const std::string* text = stringArgument(afterAt, symbol, count, count ? parameters[0] : 0)) {
    return writeStringModule(lineCount_, symbol, *text, count,
                             [parameters](std::size_t i) { return parameters[i]; });
  }
  char* p = reserve(roomFor(count));
  p = writeModule(p, format_ == StringFormat::Cpfg, lineCount_, symbol, count,
                  [parameters](std::size_t i) { return parameters[i]; });
  used_ = static_cast<std::size_t>(p - buffer_);
}

void StringWriter::module(ModuleRef m) {
  std::size_t count = m.parameterCount();
  const bool afterAt = afterAt_;
  afterAt_ = m.symbol() == '@' && count == 0;
  if (const std::string* text = stringArgument(afterAt, m.symbol(), count, count ? m.parameter(0) : 0)) {
    return writeStringModule(lineCount_, m.symbol(), *text, count,
                             [m](std::size_t i) { return m.parameter(i); });
  }
  char* p = reserve(roomFor(count));
  p = writeModule(p, format_ == StringFormat::Cpfg, lineCount_, m.symbol(), count,
                  [m](std::size_t i) { return m.parameter(i); });
  used_ = static_cast<std::size_t>(p - buffer_);
}

void StringWriter::modules(const ModuleString& s, std::size_t from, std::size_t to) {
  if (from >= to) return;
  const bool cpfg = format_ == StringFormat::Cpfg;
  // Strings to write only when the program has string literals: the common case keeps its loop.
  const bool strings = strings_ != nullptr && !strings_->empty();
  bool afterAt = afterAt_;
  int lineCount = lineCount_;
  char* p = buffer_ + used_;
  const std::uint8_t* at = s.at(from).bytes();
  const std::uint8_t* const end = at + (to - from);
  // cpfg's -str breaks a line once its count reaches 70; compact lines never break.
  constexpr std::size_t kLine = 70;
  while (at < end) {
    if (!(*at & 0x80) && !strings) {
      // Modules without parameters are their symbols: a run of them up to the line's end is
      // copied in one piece, each counting one, as writeModule counts them.
      const std::size_t most =
          std::min<std::size_t>(static_cast<std::size_t>(end - at),
                                cpfg ? kLine - static_cast<std::size_t>(lineCount) : kLine);
      std::size_t n = 1;
      while (n < most && !(at[n] & 0x80)) ++n;
      if (p + n + 1 > buffer_ + sizeof buffer_) {
        used_ = static_cast<std::size_t>(p - buffer_);
        flush();
        p = buffer_;
      }
      std::memcpy(p, at, n);
      p += n;
      at += n;
      if (cpfg) {
        lineCount += static_cast<int>(n);
        if (lineCount >= static_cast<int>(kLine)) {
          *p++ = '\n';
          lineCount = 0;
        }
      } else {
        lineCount = 1;
      }
      continue;
    }
    ModuleRef m(at);
    std::size_t count = m.parameterCount();
    if (strings) {
      const std::string* text = stringArgument(afterAt, m.symbol(), count, count ? m.parameter(0) : 0);
      afterAt = m.symbol() == '@' && count == 0;
      if (text != nullptr) {
        used_ = static_cast<std::size_t>(p - buffer_);
        writeStringModule(lineCount, m.symbol(), *text, count, [m](std::size_t i) { return m.parameter(i); });
        p = buffer_ + used_;
        at += m.size();
        continue;
      }
    }
    if (p + roomFor(count) > buffer_ + sizeof buffer_) {
      used_ = static_cast<std::size_t>(p - buffer_);
      flush();
      p = buffer_;
    }
    p = writeModule(p, cpfg, lineCount, m.symbol(), count,
                    [m](std::size_t i) { return m.parameter(i); });
    at += m.size();
  }
  used_ = static_cast<std::size_t>(p - buffer_);
  lineCount_ = lineCount;
  if (strings) afterAt_ = afterAt;
}

bool StringWriter::finish() {
  if (lineCount_ != 0) put("\n", 1);
  lineCount_ = 0;
  afterAt_ = false;
  flush();
  if (std::fflush(out_) != 0) failed_ = true;
  return !failed_;
}

}  // namespace hirsute
