// Matching a production's predecessor against the string, with cpfg's semantics: the strict
// predecessor module by module, then the right context before the left one, passing over the
// L-system's ignored modules, skipping complete branches beside the module (through the string's
// BranchIndex), stepping out of the branch a left context starts in, and wrapping around a ring
// L-system. LeftNeighbours carries the left context's search forward through the string, so that
// the rewriting pass finds each module's left neighbour without searching backwards.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hirsute/lsys/branch_index.h"
#include "hirsute/lsys/module_string.h"
#include "hirsute/lsys/program.h"

namespace hirsute {

// Binds the parameters of `m`, matched by `pattern`, to their slots in `frame`.
inline void bindParameters(const ModulePattern& pattern, ModuleRef m, double* frame) {
  for (std::size_t i = 0; i < pattern.slots.size(); ++i) frame[pattern.slots[i]] = m.parameter(i);
}

// Whether `p`'s strict predecessor is the modules of `s` from `at` on; if so, their parameters
// are bound in `frame` and `end` is the position after them.
bool matchStrict(const Production& p, const ModuleString& s, std::size_t at, std::size_t& end,
                 double* frame);

// The rewriting pass's left neighbours: for every position, the module a left context is compared
// with, carried forward in one pass instead of searched backwards per module. Only for the main
// L-system of a program without sub-L-systems, not a ring, whose brackets are not ignored and
// some of whose productions have a left context (enabled); otherwise the search goes backwards.
struct LeftNeighbours {
  // How the search passes a symbol (kinds): over it (an ignored module), stopping at it (a
  // module a context may compare with), into a branch, out of one.
  static constexpr std::uint8_t kPassedOver = 0, kModule = 1, kOpen = 2, kClose = 3;

  bool enabled = false;
  std::size_t trackedTo = 0;              // modules before this are accounted for
  std::size_t last = BranchIndex::kNone;  // the neighbour of position trackedTo
  // `last` at each enclosing `[`: open[0, depth); the vector is longer, so that a `[` stores
  // without a test of its own.
  std::vector<std::size_t> open;
  std::size_t depth = 0;
  std::array<std::uint8_t, 128> kinds{};  // by symbol

  // Back to the string's start; `enabled` says whether `program` uses the neighbours.
  void reset(const Program& program);

  // The module a left context's last pattern is compared with, as the backward search would
  // find it (ignored modules passed over, a complete branch to the left skipped, a `[` stepped
  // out of), found by carrying that search's answer forward through the string; kNone for none.
  // `at` may not be before the position of the last call.
  std::size_t before(const ModuleString& s, std::size_t at) {
    const std::uint8_t* const bytes = s.bytes();
    for (std::size_t q = trackedTo; q < at;) {
      const std::uint8_t b = bytes[q];
      pass(q, kinds[b & 0x7f], last, depth, open);
      q += (b & 0x80) ? 3 + 4 * static_cast<std::size_t>(bytes[q + 1]) : 1;
    }
    if (at > trackedTo) trackedTo = at;
    return last;
  }

  // Accounts for the module at q, of kind `kind`, as the search passes it: `last` becomes the
  // neighbour of the module after it. Without branches on the kind, which follow no pattern in
  // a branching string; static, so that a loop may keep `last` and `depth` in registers.
  static void pass(std::size_t q, std::uint8_t kind, std::size_t& last, std::size_t& depth,
                   std::vector<std::size_t>& open) {
    if (kind == kModule) {
      last = q;
    } else if (kind == kOpen) {
      if (depth == open.size()) [[unlikely]]
        open.resize(2 * open.size() + 32);
      open[depth++] = last;  // inside the branch the parent's module is to the left
    } else if (kind == kClose) {
      // Past the branch, the module before its `[` is; an unpaired `]` stops every search.
      last = depth != 0 ? open[--depth] : BranchIndex::kNone;
    }
  }
};

// Whether some context of `program` searches the string's branches: a right context, a left
// context of more than one module, or a left context that LeftNeighbours do not answer. Only
// then do the parts of a step need the string's branch index.
bool contextsSearchBranches(const Program& program);

// The contexts of productions in a string, searching its branches through the index of one
// string (the derivation's), which it builds on first use after the string changed.
class ContextMatcher {
 public:
  // The caller knows no left neighbour: matchContexts searches for it.
  static constexpr std::size_t kUnknownNeighbour = BranchIndex::kNone - 1;

  // `indexed`: the string whose brackets are indexed; it must outlive the matcher.
  explicit ContextMatcher(const ModuleString& indexed) : indexed_(&indexed) {}

  // The indexed string changed: its index is built again when next needed.
  void stringChanged() { branches_.clear(); }
  // Builds the index now, for the matchers that read it (readIndexOf).
  void buildIndex() const { branchesOf(*indexed_); }
  // A part of a step, on a thread of its own, searches the branches of `owner`'s string through
  // owner's index when it was built, and never builds it: the other parts may be reading it.
  void readIndexOf(const ContextMatcher& owner) { owner_ = &owner; }

  // Whether `p`'s contexts hold around its strict predecessor [at, end) in `s`, binding their
  // parameters in `frame`; cpfg tests the right context before the left one. `leftNeighbour`:
  // where the left context's last module is, when the caller knows (LeftNeighbours).
  bool matchContexts(const Production& p, const Lsystem& l, const ModuleString& s, std::size_t at,
                     std::size_t end, double* frame,
                     std::size_t leftNeighbour = kUnknownNeighbour) const;

 private:
  bool matchRight(const std::vector<ModulePattern>& patterns, const Lsystem& l,
                  const ModuleString& s, std::size_t from, double* frame) const;
  bool matchLeft(const std::vector<ModulePattern>& patterns, const Lsystem& l,
                 const ModuleString& s, std::size_t before, double* frame,
                 std::size_t neighbour) const;
  // The brackets of `s` (the indexed string), indexed on first use after it changed.
  const BranchIndex& branchesOf(const ModuleString& s) const;
  // The index to search `s` with: its owner's, when `s` is the owner's indexed string and the
  // index may be used here; null otherwise.
  const BranchIndex* indexFor(const ModuleString& s) const;
  // The position after the `]` matching the `[` at `at`, or the end of the string.
  std::size_t afterBranch(const ModuleString& s, std::size_t at) const;
  // The `[` that opens the `]` at `at`, or BranchIndex::kNone.
  std::size_t branchOpening(const ModuleString& s, std::size_t at) const;

  const ModuleString* indexed_;
  const ContextMatcher* owner_ = nullptr;
  mutable BranchIndex branches_;  // of *indexed_; cleared whenever it changes
};

}  // namespace hirsute
