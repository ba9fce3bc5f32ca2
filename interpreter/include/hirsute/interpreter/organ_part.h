// An organ's part of the Scene (DESIGN.md, "Organs as plug-ins"): the data its modules record and
// its stage grows, which its drawing and its writers read. Each organ declares its own type,
// derived from OrganPartOf, beside its attribute record (like fur_part.h); the Scene holds one of
// each type it has been asked for and reaches it by type, so that the Scene names no organ.
#pragma once

#include <memory>
#include <typeindex>
#include <utility>
#include <vector>

namespace hirsute {

struct Bounds;

class OrganPart {
 public:
  virtual ~OrganPart() = default;
  virtual std::unique_ptr<OrganPart> clone() const = 0;
  // Empties the part where it is (references to it stay valid).
  virtual void clear() = 0;
  // Widens `box` by what the organ draws (Scene::bounds).
  virtual void addBounds(Bounds& box) const = 0;
};

// The base of an organ's part: copies and clears it as a value.
template <class Part>
class OrganPartOf : public OrganPart {
 public:
  std::unique_ptr<OrganPart> clone() const override {
    return std::make_unique<Part>(static_cast<const Part&>(*this));
  }
  void clear() override { static_cast<Part&>(*this) = Part{}; }
};

// The organs' parts of one Scene, one of each type, in the order they were first asked for.
// Copying the Scene copies them.
class OrganParts {
 public:
  OrganParts() = default;
  OrganParts(const OrganParts& other) { *this = other; }
  OrganParts& operator=(const OrganParts& other) {
    if (this == &other) return *this;
    parts_.clear();
    parts_.reserve(other.parts_.size());
    for (const auto& [type, part] : other.parts_) parts_.emplace_back(type, part->clone());
    return *this;
  }
  OrganParts(OrganParts&&) noexcept = default;
  OrganParts& operator=(OrganParts&&) noexcept = default;

  // The part of type Part, made empty on first use.
  template <class Part>
  Part& get() {
    if (OrganPart* found = find(typeid(Part))) return static_cast<Part&>(*found);
    parts_.emplace_back(std::type_index(typeid(Part)), std::make_unique<Part>());
    return static_cast<Part&>(*parts_.back().second);
  }
  // The part of type Part, or an empty one when the scene has none (nothing is made).
  template <class Part>
  const Part& get() const {
    if (const OrganPart* found = find(typeid(Part))) return static_cast<const Part&>(*found);
    static const Part empty;
    return empty;
  }

  void clear() {
    for (auto& entry : parts_) entry.second->clear();
  }
  void addBounds(Bounds& box) const {
    for (const auto& entry : parts_) entry.second->addBounds(box);
  }

 private:
  OrganPart* find(std::type_index type) const {
    for (const auto& [t, part] : parts_) {
      if (t == type) return part.get();
    }
    return nullptr;
  }

  std::vector<std::pair<std::type_index, std::unique_ptr<OrganPart>>> parts_;
};

}  // namespace hirsute
