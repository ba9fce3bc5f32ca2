// The module string: a derived L-system string laid out for the derivation loop.
//
// Modules are packed into one byte buffer, walked forwards by the rewriting loop and backwards by
// left-context matching:
//   a module without parameters   one byte, the symbol (7-bit ASCII, high bit clear);
//   a module with n parameters    [0x80|symbol] [n] [n float32, unaligned] [0x80|n].
// So a plain module costs 1 byte and a one-parameter module 7 bytes, as in cpfg's own string.
// Parameters are float32 because cpfg stores them so; expressions compute in double.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace hirsute {

inline constexpr std::size_t kMaxModuleParameters = 127;

class ModuleString;

// A read-only view of one module inside a ModuleString; valid until the string changes.
class ModuleRef {
 public:
  ModuleRef() = default;
  ModuleRef(const std::uint8_t* at) : at_(at) {}

  char symbol() const { return static_cast<char>(at_[0] & 0x7f); }
  bool hasParameters() const { return (at_[0] & 0x80) != 0; }
  std::size_t parameterCount() const { return hasParameters() ? at_[1] : 0; }
  float parameter(std::size_t i) const {
    float value;
    std::memcpy(&value, at_ + 2 + 4 * i, sizeof value);
    return value;
  }
  // Bytes this module occupies.
  std::size_t size() const { return hasParameters() ? 3 + 4 * static_cast<std::size_t>(at_[1]) : 1; }
  const std::uint8_t* bytes() const { return at_; }

 private:
  const std::uint8_t* at_ = nullptr;
};

class ModuleString {
 public:
  ModuleString() = default;
  ~ModuleString();
  ModuleString(const ModuleString& other);
  ModuleString& operator=(const ModuleString& other);
  ModuleString(ModuleString&& other) noexcept;
  ModuleString& operator=(ModuleString&& other) noexcept;

  std::size_t moduleCount() const { return modules_; }
  std::size_t byteSize() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::size_t capacityBytes() const { return capacity_; }

  // Positions are byte offsets of module starts; end() is one past the last module.
  std::size_t begin() const { return 0; }
  std::size_t end() const { return size_; }
  ModuleRef at(std::size_t position) const { return ModuleRef(data_ + position); }
  std::size_t next(std::size_t position) const { return position + at(position).size(); }
  // The start of the module before `position` (position > 0).
  std::size_t previous(std::size_t position) const {
    std::uint8_t last = data_[position - 1];
    return (last & 0x80) ? position - 3 - 4 * static_cast<std::size_t>(last & 0x7f) : position - 1;
  }

  void append(char symbol) {
    reserveMore(1);
    data_[size_++] = static_cast<std::uint8_t>(symbol);
    ++modules_;
  }
  void append(char symbol, std::span<const float> parameters);
  // A module with parameters given as doubles, rounded to float32 as cpfg stores them.
  void appendRounded(char symbol, std::span<const double> parameters);
  // Copies one module verbatim (from this or another string).
  void append(ModuleRef module) {
    std::size_t n = module.size();
    reserveMore(n);
    std::memcpy(data_ + size_, module.bytes(), n);
    size_ += n;
    ++modules_;
  }
  // Copies modules [from, to) of another string verbatim.
  void appendRange(const ModuleString& source, std::size_t from, std::size_t to, std::size_t count);

  // Appends `bytes` encoded bytes holding `modules` modules and returns where to write them.
  std::uint8_t* appendEncoded(std::size_t bytes, std::size_t modules) {
    reserveMore(bytes);
    std::uint8_t* at = data_ + size_;
    size_ += bytes;
    modules_ += modules;
    return at;
  }
  const std::uint8_t* bytes() const { return data_; }
  // Overwrites parameter `i` of the module at `position` (the query pass fills ?P and the like).
  void setParameter(std::size_t position, std::size_t i, float value) {
    std::memcpy(data_ + position + 2 + 4 * i, &value, sizeof value);
  }

  void clear() {
    size_ = 0;
    modules_ = 0;
  }
  // Frees the buffer.
  void release();
  void swap(ModuleString& other) noexcept;

  // Bytes needed to store a module with `count` parameters.
  static std::size_t encodedSize(std::size_t count) { return count ? 3 + 4 * count : 1; }

  // Called when the buffer must grow past `limitBytes`; see setByteLimit.
  void setByteLimit(std::size_t limitBytes) { byteLimit_ = limitBytes; }

 private:
  void reserveMore(std::size_t extra) {
    if (size_ + extra > capacity_) grow(size_ + extra);
  }
  void grow(std::size_t needed);

  std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
  std::size_t modules_ = 0;
  std::size_t byteLimit_ = 0;  // 0: none
};

// Thrown by ModuleString when it would grow past its byte limit.
struct ModuleStringTooLarge {
  std::size_t bytes;
};

}  // namespace hirsute
