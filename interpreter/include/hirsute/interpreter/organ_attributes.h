// What every organ's attribute record shares (docs/design.md, "Organs"): the value form of its
// modules, and the indices by which the turtle carries the records, one for each registered organ
// (however many there are). Each organ keeps its records in its part of the Scene; the turtle
// state holds an index into each, copied on write, so `[` and `]` save and restore them
// and generalized-cylinder segments record them at their two ends.
#pragma once

#include <algorithm>
#include <cstddef>

#include <boost/container/small_vector.hpp>

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
    const std::size_t at = slot<Record>();
    if (indices_.size() <= at) indices_.resize(at + 1, -1);
    return indices_[at];
  }
  template <class Record>
  int of() const {
    const std::size_t at = slot<Record>();
    return at < indices_.size() ? indices_[at] : -1;
  }
  // Whether no organ has a record here.
  bool none() const {
    return std::all_of(indices_.begin(), indices_.end(), [](int index) { return index < 0; });
  }

  // Equal when every organ has the same index (an organ past the end has none, -1).
  bool operator==(const OrganAttributeIndices& other) const {
    const std::size_t n = std::max(indices_.size(), other.indices_.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (at(i) != other.at(i)) return false;
    }
    return true;
  }

 private:
  template <class Record>
  static std::size_t slot() {
    static const std::size_t found = organSlot(Record::kOrgan);
    return found;
  }
  int at(std::size_t i) const { return i < indices_.size() ? indices_[i] : -1; }

  // Only as long as the last organ with a record: a state or segment with none holds nothing.
  // Room for four organs inside: every turtle state and both ends of every cylinder segment
  // carry one, so it is kept off the heap for the organs there are; a fifth spills over.
  boost::container::small_vector<int, 4> indices_;
};

}  // namespace hirsute
