#include "hirsute/lsys/module_string.h"

#include <cstdlib>
#include <new>
#include <utility>

namespace hirsute {

ModuleString::~ModuleString() { release(); }

ModuleString::ModuleString(const ModuleString& other) { *this = other; }

ModuleString& ModuleString::operator=(const ModuleString& other) {
  if (this == &other) return *this;
  clear();
  reserveMore(other.size_);
  if (other.size_) std::memcpy(data_, other.data_, other.size_);
  size_ = other.size_;
  modules_ = other.modules_;
  byteLimit_ = other.byteLimit_;
  return *this;
}

ModuleString::ModuleString(ModuleString&& other) noexcept { swap(other); }

ModuleString& ModuleString::operator=(ModuleString&& other) noexcept {
  if (this != &other) {
    release();
    swap(other);
  }
  return *this;
}

void ModuleString::release() {
  std::free(data_);
  data_ = nullptr;
  size_ = capacity_ = modules_ = 0;
}

void ModuleString::swap(ModuleString& other) noexcept {
  std::swap(data_, other.data_);
  std::swap(size_, other.size_);
  std::swap(capacity_, other.capacity_);
  std::swap(modules_, other.modules_);
  std::swap(byteLimit_, other.byteLimit_);
}

void ModuleString::grow(std::size_t needed) {
  if (byteLimit_ && needed > byteLimit_) throw ModuleStringTooLarge{needed};
  // Growth by realloc: large blocks are moved by remapping pages, and pages not yet written are
  // never touched, so the resident size follows the string rather than the capacity.
  std::size_t capacity = capacity_ ? capacity_ + capacity_ / 2 : 4096;
  if (capacity < needed) capacity = needed;
  void* grown = std::realloc(data_, capacity);
  if (!grown) throw std::bad_alloc();
  data_ = static_cast<std::uint8_t*>(grown);
  capacity_ = capacity;
}

void ModuleString::append(char symbol, std::span<const float> parameters) {
  if (parameters.empty()) {
    append(symbol);
    return;
  }
  std::size_t n = parameters.size();
  reserveMore(encodedSize(n));
  std::uint8_t* out = data_ + size_;
  out[0] = static_cast<std::uint8_t>(symbol) | 0x80;
  out[1] = static_cast<std::uint8_t>(n);
  std::memcpy(out + 2, parameters.data(), 4 * n);
  out[2 + 4 * n] = static_cast<std::uint8_t>(0x80 | n);
  size_ += encodedSize(n);
  ++modules_;
}

void ModuleString::appendRounded(char symbol, std::span<const double> parameters) {
  if (parameters.empty()) {
    append(symbol);
    return;
  }
  std::size_t n = parameters.size();
  reserveMore(encodedSize(n));
  std::uint8_t* out = data_ + size_;
  out[0] = static_cast<std::uint8_t>(symbol) | 0x80;
  out[1] = static_cast<std::uint8_t>(n);
  for (std::size_t i = 0; i < n; ++i) {
    float value = static_cast<float>(parameters[i]);
    std::memcpy(out + 2 + 4 * i, &value, 4);
  }
  out[2 + 4 * n] = static_cast<std::uint8_t>(0x80 | n);
  size_ += encodedSize(n);
  ++modules_;
}

void ModuleString::appendRange(const ModuleString& source, std::size_t from, std::size_t to,
                               std::size_t count) {
  std::size_t n = to - from;
  // An empty range may come from an empty string, whose null buffer memcpy may not be given.
  if (n == 0) return;
  reserveMore(n);
  std::memcpy(data_ + size_, source.data_ + from, n);
  size_ += n;
  modules_ += count;
}

}  // namespace hirsute
