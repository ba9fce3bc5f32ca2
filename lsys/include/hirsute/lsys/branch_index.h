// The matching brackets of a module string, found in one pass, so that context matching skips a
// whole branch in one lookup instead of walking it module by module.
//
// cpfg's context search skips a branch `[…]` beside the module being rewritten (left contexts
// skip complete branches to their left, right contexts skip branches to their right). Walking
// them is linear in the branch, which makes a step quadratic when every module of a long axis
// tests a context behind large branches (models/bench/signal.l).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hirsute/lsys/module_string.h"

namespace hirsute {

class BranchIndex {
 public:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

  // Indexes every `[` and `]` of `s` (by symbol, with or without parameters). Strings of 4 GiB or
  // more are not indexed (usable() is then false).
  void build(const ModuleString& s);
  // Forgets the string: the next use must build again.
  void clear() {
    built_ = false;
    usable_ = false;
  }
  bool built() const { return built_; }
  bool usable() const { return usable_; }

  // The position of the bracket that pairs with the bracket at `position` (a `[` or `]` of the
  // indexed string): the `[` that opens a `]`, the `]` that closes a `[`; kNone when it has
  // none (an unbalanced string).
  std::size_t partner(std::size_t position) const;

 private:
  std::vector<std::uint32_t> positions_;  // every bracket's position, ascending
  std::vector<std::uint32_t> partners_;   // beside positions_: its partner, or kUnpaired
  static constexpr std::uint32_t kUnpaired = UINT32_MAX;
  bool built_ = false;
  bool usable_ = false;
};

}  // namespace hirsute
