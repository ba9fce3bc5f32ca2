#include "hirsute/lsys/string_writer.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace hirsute {

std::string formatParameter(float value) {
  char text[32];
  int n = std::snprintf(text, sizeof text, "%g", static_cast<double>(value));
  return std::string(text, static_cast<std::size_t>(n));
}

StringWriter::StringWriter(std::FILE* out, StringFormat format) : out_(out), format_(format) {}

StringWriter::~StringWriter() { flush(); }

void StringWriter::flush() {
  if (used_ && std::fwrite(buffer_, 1, used_, out_) != used_) failed_ = true;
  used_ = 0;
}

std::size_t StringWriter::formatNumber(float value, char* out) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  CacheEntry& entry = cache_[(bits ^ (bits >> 13) ^ (bits >> 23)) & 1023u];
  if (entry.bits != bits) {
    int n = std::snprintf(entry.text, sizeof entry.text, "%g", static_cast<double>(value));
    entry.length = static_cast<std::uint8_t>(n);
    entry.bits = bits;
  }
  std::memcpy(out, entry.text, entry.length);
  return entry.length;
}

void StringWriter::module(char symbol, const float* parameters, std::size_t count) {
  char text[16 + 24 * 128];
  std::size_t n = 0;
  text[n++] = symbol;
  int counted = 1;
  if (count) {
    text[n++] = '(';
    for (std::size_t i = 0; i < count; ++i) {
      if (i) text[n++] = ',';
      std::size_t digits = formatNumber(parameters[i], text + n);
      n += digits;
      counted += static_cast<int>(digits);
    }
    text[n++] = ')';
    counted += 2;  // cpfg counts the parentheses but not the commas
  }
  put(text, n);
  atLineStart_ = false;
  if (format_ == StringFormat::Cpfg) {
    // cpfg's -str: after a module, a newline once the line's count reaches 70.
    lineCount_ += counted;
    if (lineCount_ >= 70) {
      put("\n", 1);
      lineCount_ = 0;
      atLineStart_ = true;
    }
  }
}

bool StringWriter::finish() {
  if (!atLineStart_) put("\n", 1);
  atLineStart_ = true;
  lineCount_ = 0;
  flush();
  if (std::fflush(out_) != 0) failed_ = true;
  return !failed_;
}

}  // namespace hirsute
