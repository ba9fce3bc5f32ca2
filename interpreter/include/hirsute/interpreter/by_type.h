// One value of each of several types that share a base, reached by their type: the organs' parts
// of a Scene (organ_part.h) and their settings in a view file (organ_settings.h), so that neither
// the Scene nor the view settings name an organ. A value is made on first use; the values keep
// the order they were first asked for in; copying copies each through Base::clone().
#pragma once

#include <memory>
#include <typeindex>
#include <utility>
#include <vector>

namespace hirsute {

template <class Base>
class ByType {
 public:
  ByType() = default;
  ByType(const ByType& other) { *this = other; }
  ByType& operator=(const ByType& other) {
    if (this == &other) return *this;
    values_.clear();
    values_.reserve(other.values_.size());
    for (const auto& [type, value] : other.values_) values_.emplace_back(type, value->clone());
    return *this;
  }
  ByType(ByType&&) noexcept = default;
  ByType& operator=(ByType&&) noexcept = default;

  // The value of type T, made with T{} on first use.
  template <class T>
  T& get() {
    if (Base* found = find(typeid(T))) return static_cast<T&>(*found);
    values_.emplace_back(std::type_index(typeid(T)), std::make_unique<T>());
    return static_cast<T&>(*values_.back().second);
  }
  // The value of type T, or T{} when there is none (nothing is made).
  template <class T>
  const T& get() const {
    if (const Base* found = find(typeid(T))) return static_cast<const T&>(*found);
    static const T empty{};
    return empty;
  }

  template <class Visit>
  void forEach(Visit&& visit) {
    for (auto& entry : values_) visit(*entry.second);
  }
  template <class Visit>
  void forEach(Visit&& visit) const {
    for (const auto& entry : values_) visit(static_cast<const Base&>(*entry.second));
  }

 private:
  Base* find(std::type_index type) const {
    for (const auto& [t, value] : values_) {
      if (t == type) return value.get();
    }
    return nullptr;
  }

  std::vector<std::pair<std::type_index, std::unique_ptr<Base>>> values_;
};

}  // namespace hirsute
