// The file an exporter writes: text (or bytes) through a large buffer, with a compact number
// formatter, into an OutputTarget: a regular file is written under a temporary name and renamed
// over the target on commit(), so that a reader never sees a half-written scene and a failed
// export leaves no file; a device or FIFO is written in place.
//
// POV-Ray's parse time grows with the size of the text, and a million-triangle scene is tens of
// megabytes, so numbers are not printed through iostreams: fixed-point values are rounded to an
// integer count of the last decimal and their digits written directly into the buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/core/output_target.h"

namespace hirsute {

// How many decimals a number is printed with, and whether 0.5 may be written ".5" (POV-Ray
// reads it; some OBJ readers expect the leading zero).
struct NumberFormat {
  int decimals = 4;
  bool leadingZero = true;
};

// Writes `value` rounded to `format.decimals` decimals into `out` (at least 32 bytes), with
// trailing zeros and a trailing point dropped and "-0" written "0": 2 → "2", -1.250 → "-1.25",
// 0.5 → ".5" without leadingZero. Returns the number of characters. Throws
// std::invalid_argument for a value that is not finite (no format reads NaN back).
std::size_t formatFixed(double value, NumberFormat format, char* out);

class ExportFile {
 public:
  // Opens `target` (hirsute/core/output_target.h), in `group` when given; throws
  // std::runtime_error naming the path.
  explicit ExportFile(std::filesystem::path target, OutputGroup* group = nullptr);
  // Opens `name`, a file name Hirsute derives, in `folder`: created there without following a
  // link, a FIFO or device at the name refused (output_folder.h).
  ExportFile(const OutputFolder& folder, const std::string& name, OutputGroup* group = nullptr);
  ExportFile(const ExportFile&) = delete;
  ExportFile& operator=(const ExportFile&) = delete;

  void put(char c) {
    if (used_ == buffer_.size()) flush();
    buffer_[used_++] = c;
  }
  void put(std::string_view text);
  void putBytes(const void* data, std::size_t size);
  void putInteger(std::int64_t value);
  void putFixed(double value, NumberFormat format) {
    if (buffer_.size() - used_ < kMaxNumberLength) flush();
    used_ += formatFixed(value, format, buffer_.data() + used_);
  }

  // Flushes, closes and renames the file into place; throws std::runtime_error on failure.
  // Without it, the target is left as it was.
  void commit();

  const std::filesystem::path& target() const { return file_.target(); }
  // A device, FIFO or descriptor written directly: no file may be written beside it.
  bool writesInPlace() const { return file_.writesInPlace(); }
  std::uint64_t bytesWritten() const { return flushed_ + used_; }

  static constexpr std::size_t kMaxNumberLength = 32;

 private:
  void flush();
  [[noreturn]] void fail(const char* what);

  OutputTarget file_;
  std::vector<char> buffer_;
  std::size_t used_ = 0;
  std::uint64_t flushed_ = 0;
};

}  // namespace hirsute
