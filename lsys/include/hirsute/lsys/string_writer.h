// Writes module strings as text: cpfg's `-str` format, or one line without wrapping.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "hirsute/lsys/module_sink.h"

namespace hirsute {

enum class StringFormat {
  Cpfg,     // cpfg's -str: `%g` parameters, a newline once a line reaches 70 counted characters
  Compact,  // the same modules on one line
};

// The longest `%g` text of a float ("-1.17549e-38"), with room to spare.
inline constexpr std::size_t kMaxParameterText = 15;

// Streams modules to a FILE through a buffer; nothing is built as one big text.
class StringWriter : public ModuleSink {
 public:
  StringWriter(std::FILE* out, StringFormat format);
  ~StringWriter() override;
  StringWriter(const StringWriter&) = delete;
  StringWriter& operator=(const StringWriter&) = delete;

  // The program's string table: the first parameter of @L, @S and @I is then written as the
  // quoted string it names (`@L("x=%g",2)`, takesStringArgument in program.h); without one it
  // stays a number, as every other parameter. `strings` must outlive the writer.
  void setStrings(const std::vector<std::string>* strings) { strings_ = strings; }

  void module(char symbol, const float* parameters, std::size_t count) override;
  // Read the parameters straight from the string's bytes.
  void module(ModuleRef m) override;
  void modules(const ModuleString& s, std::size_t from, std::size_t to) override;
  // Ends the string (a final newline) and flushes; returns false on a write error.
  bool finish();

 private:
  // Room for the longest module: symbol, parentheses, numbers and commas, a newline.
  static constexpr std::size_t roomFor(std::size_t count) {
    return 4 + count * (kMaxParameterText + 1);
  }
  char* reserve(std::size_t n) {
    if (used_ + n > sizeof buffer_) flush();
    return buffer_ + used_;
  }
  template <typename ParameterAt>
  char* writeModule(char* p, bool cpfg, int& lineCount, char symbol, std::size_t count,
                    ParameterAt parameterAt);
  // The string a module's first parameter names when the module carries one (it follows a bare
  // `@` and takesStringArgument); null otherwise.
  const std::string* stringArgument(bool afterAt, char symbol, std::size_t count, float first) const;
  // Writes a module whose first parameter is `text`, quoted, through the buffer.
  template <typename ParameterAt>
  void writeStringModule(int& lineCount, char symbol, const std::string& text, std::size_t count,
                         ParameterAt parameterAt);
  void put(const char* text, std::size_t n) {
    std::memcpy(reserve(n), text, n);
    used_ += n;
  }
  void flush();
  // Writes `%g` of `value` at `out` (which has kMaxParameterText + 1 bytes of room); returns the
  // length. May write past the length within that room.
  std::size_t formatNumber(float value, char* out);

  std::FILE* out_;
  StringFormat format_;
  char buffer_[1 << 16];
  std::size_t used_ = 0;
  // cpfg's count for the line being written; 0 exactly when the line is empty (a compact line
  // counts 1 once it has a module).
  int lineCount_ = 0;
  bool failed_ = false;
  const std::vector<std::string>* strings_ = nullptr;
  bool afterAt_ = false;  // the last module written was a bare `@`
  // A small cache of formatted values: strings repeat the same few numbers. An entry is 24
  // bytes, so its text is copied with one fixed-size move. Entries start out as 0.0f, "0".
  struct CacheEntry {
    std::uint32_t bits = 0;
    std::uint8_t length = 1;
    char text[kMaxParameterText + 4] = {'0'};
  };
  static_assert(sizeof(CacheEntry) == 24);
  CacheEntry cache_[2048];
};

// `%g` of a float as cpfg prints it (the float promoted to double).
std::string formatParameter(float value);
// The same into `out`, which must have room for kMaxParameterText + 1 bytes; returns the length
// (no terminating zero). Exact: byte-identical to printf's `%g` of the value as a double.
std::size_t formatParameter(float value, char* out);

}  // namespace hirsute
