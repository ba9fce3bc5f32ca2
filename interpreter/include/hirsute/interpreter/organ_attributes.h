// What every organ's attribute record shares (docs/design.md,
// "Organs"): the value form of its modules, and the indices by which the
// turtle carries the records. Each organ keeps its records in its part of the Scene; the turtle
// state holds an index into each, copied on write, so `[` and `]` save and restore them
// and generalized-cylinder segments record them at their two ends.
#pragma once

#include <array>
#include <cstddef>

namespace hirsute {

// One attribute of an organ module in the value form `v[,rng[,fun[,loc]]]` (Fuhrer et al. 2004,
// Table 1): value ± a uniform offset up to `range` per instance, times function `function` of
// the model's function set evaluated at the girth position s in [0, 1] (0: none).
struct OrganValue {
  float value = 0;
  float range = 0;
  int function = 0;

  bool operator==(const OrganValue&) const = default;
};

// The most organ types with attribute records (organModuleTables(), organ_modules.cpp, checks
// its list against it): the turtle carries one index for each, in every state and at both ends
// of every cylinder segment, so the room is kept small. One more organ raises it.
inline constexpr std::size_t kMaxOrganTypes = 4;

// The place in organModuleTables() of the organ whose modules are @`letter`…: its index in
// OrganAttributeIndices. Throws std::logic_error when no table has that letter.
std::size_t organSlot(char letter);

// The organs' attribute records where the turtle is: per organ, an index into the records of its
// part of the Scene (-1: the organ's defaults, switched off), reached by the record's type,
// which names its organ's letter (Record::kOrgan).
class OrganAttributeIndices {
 public:
  template <class Record>
  int& of() {
    return indices_[slot<Record>()];
  }
  template <class Record>
  int of() const {
    return indices_[slot<Record>()];
  }
  // Whether no organ has a record here.
  bool none() const { return *this == OrganAttributeIndices{}; }

  bool operator==(const OrganAttributeIndices&) const = default;

 private:
  template <class Record>
  static std::size_t slot() {
    static const std::size_t found = organSlot(Record::kOrgan);
    return found;
  }

  std::array<int, kMaxOrganTypes> indices_ = [] {
    std::array<int, kMaxOrganTypes> none{};
    none.fill(-1);
    return none;
  }();
};

}  // namespace hirsute
