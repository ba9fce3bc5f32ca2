// An organ's part of the Scene (docs/design.md, "Organs"): the data its modules record and
// its stage grows, which its drawing and its writers read. Each organ declares its own type,
// derived from OrganPartOf, beside its attribute record (NAME_part.h); the Scene holds one of
// each type it has been asked for and reaches it by type, so that the Scene names no organ.
#pragma once

#include <memory>

#include "hirsute/interpreter/by_type.h"

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

// The organs' parts of one Scene, one of each type (by_type.h). Copying the Scene copies them.
class OrganParts : public ByType<OrganPart> {
 public:
  void clear() {
    forEach([](OrganPart& part) { part.clear(); });
  }
  void addBounds(Bounds& box) const {
    forEach([&box](const OrganPart& part) { part.addBounds(box); });
  }
};

}  // namespace hirsute
