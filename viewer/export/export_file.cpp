#include "hirsute/viewer/export/export_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace hirsute {
namespace {

constexpr std::size_t kBufferSize = 1 << 20;

constexpr double kPowersOfTen[] = {1e0, 1e1, 1e2, 1e3,  1e4,  1e5, 1e6,
                                   1e7, 1e8, 1e9, 1e10, 1e11, 1e12};
constexpr int kMaxDecimals = 12;

// Writes the decimal digits of `value` (no sign); `minDigits` pads with leading zeros.
std::size_t putDigits(std::uint64_t value, int minDigits, char* out) {
  char reversed[24];
  int n = 0;
  do {
    reversed[n++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  while (n < minDigits) reversed[n++] = '0';
  for (int i = 0; i < n; ++i) out[i] = reversed[n - 1 - i];
  return static_cast<std::size_t>(n);
}

}  // namespace

std::size_t formatFixed(double value, NumberFormat format, char* out) {
  if (!std::isfinite(value))
    throw std::invalid_argument("a coordinate or colour in the scene is not a finite number");
  int decimals =
      format.decimals < 0 ? 0 : (format.decimals > kMaxDecimals ? kMaxDecimals : format.decimals);
  double scaled = value * kPowersOfTen[decimals];
  if (std::fabs(scaled) >= 9e15) {
    // Beyond what an integer count of decimals holds exactly: nine significant digits.
    auto result = std::to_chars(out, out + ExportFile::kMaxNumberLength, value,
                                std::chars_format::general, 9);
    return static_cast<std::size_t>(result.ptr - out);
  }
  std::int64_t count = std::llround(scaled);
  if (count == 0) {
    out[0] = '0';
    return 1;
  }
  char* p = out;
  std::uint64_t magnitude;
  if (count < 0) {
    *p++ = '-';
    magnitude = static_cast<std::uint64_t>(-count);
  } else {
    magnitude = static_cast<std::uint64_t>(count);
  }
  auto unit = static_cast<std::uint64_t>(kPowersOfTen[decimals]);
  std::uint64_t whole = magnitude / unit;
  std::uint64_t fraction = magnitude % unit;
  if (whole != 0 || format.leadingZero || fraction == 0) p += putDigits(whole, 1, p);
  if (fraction != 0) {
    int digits = decimals;
    while (fraction % 10 == 0) {
      fraction /= 10;
      --digits;
    }
    *p++ = '.';
    p += putDigits(fraction, digits, p);
  }
  return static_cast<std::size_t>(p - out);
}

ExportFile::ExportFile(std::filesystem::path target, OutputGroup* group)
    : file_(std::move(target), group), buffer_(kBufferSize) {}

ExportFile::ExportFile(const OutputFolder& folder, const std::string& name, OutputGroup* group)
    : file_(folder, name, group), buffer_(kBufferSize) {}

void ExportFile::put(std::string_view text) {
  if (text.size() > buffer_.size() - used_) {
    flush();
    if (text.size() > buffer_.size()) {
      putBytes(text.data(), text.size());
      return;
    }
  }
  std::memcpy(buffer_.data() + used_, text.data(), text.size());
  used_ += text.size();
}

void ExportFile::putBytes(const void* data, std::size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    if (used_ == buffer_.size()) flush();
    std::size_t n = std::min(size, buffer_.size() - used_);
    std::memcpy(buffer_.data() + used_, bytes, n);
    used_ += n;
    bytes += n;
    size -= n;
  }
}

void ExportFile::putInteger(std::int64_t value) {
  if (buffer_.size() - used_ < kMaxNumberLength) flush();
  char* p = buffer_.data() + used_;
  std::uint64_t magnitude = static_cast<std::uint64_t>(value);
  if (value < 0) {
    *p++ = '-';
    magnitude = ~magnitude + 1;
  }
  p += putDigits(magnitude, 1, p);
  used_ = static_cast<std::size_t>(p - buffer_.data());
}

void ExportFile::flush() {
  const char* data = buffer_.data();
  std::size_t left = used_;
  while (left > 0) {
    ssize_t n = ::write(file_.descriptor(), data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write");
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  flushed_ += used_;
  used_ = 0;
}

void ExportFile::commit() {
  flush();
  file_.commit();
}

void ExportFile::fail(const char* what) {
  throw std::runtime_error(file_.target().string() + ": " + what + ": " + std::strerror(errno));
}

}  // namespace hirsute
