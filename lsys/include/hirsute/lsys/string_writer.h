// Writes module strings as text: cpfg's `-str` format, or one line without wrapping.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "hirsute/lsys/module_sink.h"

namespace hirsute {

enum class StringFormat {
  Cpfg,     // cpfg's -str: `%g` parameters, a newline once a line reaches 70 counted characters
  Compact,  // the same modules on one line
};

// Streams modules to a FILE through a buffer; nothing is built as one big text.
class StringWriter : public ModuleSink {
 public:
  StringWriter(std::FILE* out, StringFormat format);
  ~StringWriter() override;
  StringWriter(const StringWriter&) = delete;
  StringWriter& operator=(const StringWriter&) = delete;

  using ModuleSink::module;
  void module(char symbol, const float* parameters, std::size_t count) override;
  // Ends the string (a final newline) and flushes; returns false on a write error.
  bool finish();

 private:
  void put(const char* text, std::size_t n) {
    if (used_ + n > sizeof buffer_) flush();
    std::memcpy(buffer_ + used_, text, n);
    used_ += n;
  }
  void flush();
  std::size_t formatNumber(float value, char* out);

  std::FILE* out_;
  StringFormat format_;
  char buffer_[1 << 16];
  std::size_t used_ = 0;
  int lineCount_ = 0;  // cpfg's count for the line being written
  bool failed_ = false;
  bool atLineStart_ = true;
  // A small cache of formatted values: strings repeat the same few numbers.
  struct CacheEntry {
    std::uint32_t bits = 0xffffffffu;
    std::uint8_t length = 0;
    char text[23];
  };
  CacheEntry cache_[1024];
};

// `%g` of a float as cpfg prints it (the float promoted to double).
std::string formatParameter(float value);

}  // namespace hirsute
