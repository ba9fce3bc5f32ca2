#include "hirsute/lsys/branch_index.h"

#include <algorithm>

namespace hirsute {

void BranchIndex::build(const ModuleString& s) {
  built_ = true;
  positions_.clear();
  partners_.clear();
  usable_ = s.byteSize() < kUnpaired;
  if (!usable_) return;
  std::vector<std::uint32_t> open;  // indices into positions_ of `[` not yet closed
  const std::uint8_t* const bytes = s.bytes();
  const std::size_t end = s.end();
  for (std::size_t p = 0; p < end;) {
    const std::uint8_t b = bytes[p];
    // The symbol decides, with parameters or without, as everywhere in context matching.
    const std::uint8_t symbol = b & 0x7f;
    if (symbol == '[') {
      open.push_back(static_cast<std::uint32_t>(positions_.size()));
      positions_.push_back(static_cast<std::uint32_t>(p));
      partners_.push_back(kUnpaired);
    } else if (symbol == ']') {
      std::uint32_t partner = kUnpaired;
      if (!open.empty()) {
        const std::uint32_t opening = open.back();
        open.pop_back();
        partner = positions_[opening];
        partners_[opening] = static_cast<std::uint32_t>(p);
      }
      positions_.push_back(static_cast<std::uint32_t>(p));
      partners_.push_back(partner);
    }
    p += (b & 0x80) ? 3 + 4 * static_cast<std::size_t>(bytes[p + 1]) : 1;
  }
}

std::size_t BranchIndex::partner(std::size_t position) const {
  const auto at = std::lower_bound(positions_.begin(), positions_.end(), position);
  if (at == positions_.end() || *at != position) return kNone;
  const std::uint32_t partner = partners_[static_cast<std::size_t>(at - positions_.begin())];
  return partner == kUnpaired ? kNone : partner;
}

}  // namespace hirsute
