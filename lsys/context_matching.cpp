#include "hirsute/lsys/context_matching.h"

#include <algorithm>

namespace hirsute {
namespace {

// The position of the `]` that closes the branch containing `at` (or the end of the string).
std::size_t branchEnd(const ModuleString& s, std::size_t at) {
  int depth = 0;
  for (std::size_t p = at; p < s.end(); p = s.next(p)) {
    char c = s.at(p).symbol();
    if (c == '[') {
      ++depth;
    } else if (c == ']') {
      if (depth == 0) return p;
      --depth;
    }
  }
  return s.end();
}

}  // namespace

bool matchStrict(const Production& p, const ModuleString& s, std::size_t at, std::size_t& end,
                 double* frame) {
  std::size_t pos = at;
  for (const ModulePattern& pattern : p.strict) {
    if (pos >= s.end()) return false;
    ModuleRef m = s.at(pos);
    if (m.symbol() != pattern.symbol || m.parameterCount() != pattern.parameterCount) return false;
    bindParameters(pattern, m, frame);
    pos = s.next(pos);
  }
  end = pos;
  return true;
}

void LeftNeighbours::reset(const Program& program) {
  trackedTo = 0;
  last = BranchIndex::kNone;
  depth = 0;
  const Lsystem& main = program.lsystems.front();
  for (std::size_t c = 0; c < kinds.size(); ++c) {
    kinds[c] = main.ignored[c] ? kPassedOver : c == '[' ? kOpen : c == ']' ? kClose : kModule;
  }
  // Sub-L-systems have ignore sets of their own, a ring wraps around, and ignored brackets
  // would pair differently: those keep the backward search.
  enabled = program.lsystems.size() == 1 && !main.ring && !main.ignored['['] && !main.ignored[']'];
  if (enabled) {
    enabled = std::any_of(main.productions.productions.begin(), main.productions.productions.end(),
                          [](const Production& p) { return !p.left.empty(); });
  }
}

bool contextsSearchBranches(const Program& program) {
  LeftNeighbours neighbours;
  neighbours.reset(program);
  for (const Lsystem& l : program.lsystems) {
    for (const RuleSet* rules : {&l.productions, &l.decomposition, &l.homomorphism}) {
      for (const Production& p : rules->productions) {
        if (!p.right.empty() || p.left.size() > 1 || (!p.left.empty() && !neighbours.enabled))
          return true;
      }
    }
  }
  return false;
}

const BranchIndex& ContextMatcher::branchesOf(const ModuleString& s) const {
  if (!branches_.built()) branches_.build(s);
  return branches_;
}

const BranchIndex* ContextMatcher::indexFor(const ModuleString& s) const {
  const ContextMatcher& owner = owner_ ? *owner_ : *this;
  if (&s == owner.indexed_ && (!owner_ || owner.branches_.built()) &&
      owner.branchesOf(s).usable()) {
    return &owner.branches_;
  }
  return nullptr;
}

std::size_t ContextMatcher::afterBranch(const ModuleString& s, std::size_t at) const {
  if (const BranchIndex* index = indexFor(s)) {
    const std::size_t close = index->partner(at);
    return close == BranchIndex::kNone ? s.end() : s.next(close);
  }
  const std::size_t close = branchEnd(s, s.next(at));
  return close < s.end() ? s.next(close) : close;
}

std::size_t ContextMatcher::branchOpening(const ModuleString& s, std::size_t at) const {
  if (const BranchIndex* index = indexFor(s)) return index->partner(at);
  int depth = 0;
  for (std::size_t r = at;; r = s.previous(r)) {
    const char d = s.at(r).symbol();
    if (d == ']') ++depth;
    if (d == '[' && --depth == 0) return r;
    if (r == 0) return BranchIndex::kNone;
  }
}

bool ContextMatcher::matchRight(const std::vector<ModulePattern>& patterns, const Lsystem& l,
                                const ModuleString& s, std::size_t from, double* frame) const {
  std::size_t pos = from;
  bool wrapped = false;
  for (const ModulePattern& pattern : patterns) {
    if (pattern.symbol == '=' && pattern.parameterCount == 0) {
      // cpfg's wildcard: the rest of the current branch.
      pos = branchEnd(s, pos);
      continue;
    }
    if (pattern.symbol == ']' && pattern.parameterCount == 0) {
      // The end of the current branch, whatever remains in it.
      pos = branchEnd(s, pos);
      if (pos >= s.end()) return false;
      pos = s.next(pos);
      continue;
    }
    ModuleRef m;
    for (;;) {
      if (pos >= s.end()) {
        if (!l.ring || wrapped) return false;
        wrapped = true;
        pos = 0;
        if (s.empty()) return false;
      }
      m = s.at(pos);
      char c = m.symbol();
      if (l.ignored[static_cast<unsigned char>(c)]) {
        pos = s.next(pos);
        continue;
      }
      if (c == '[' && pattern.symbol != '[') {
        pos = afterBranch(s, pos);  // branches to the right are skipped
        continue;
      }
      if (c == ']' && pattern.symbol != ']') return false;  // the branch ends
      break;
    }
    if (m.symbol() != pattern.symbol || m.parameterCount() != pattern.parameterCount) return false;
    bindParameters(pattern, m, frame);
    pos = s.next(pos);
  }
  return true;
}

bool ContextMatcher::matchLeft(const std::vector<ModulePattern>& patterns, const Lsystem& l,
                               const ModuleString& s, std::size_t before, double* frame,
                               std::size_t neighbour) const {
  std::size_t pos = before;
  bool wrapped = false;
  for (std::size_t i = patterns.size(); i-- > 0;) {
    const ModulePattern& pattern = patterns[i];
    ModuleRef m;
    if (i + 1 == patterns.size() && neighbour != kUnknownNeighbour) {
      if (neighbour == BranchIndex::kNone) return false;
      pos = neighbour;
      m = s.at(pos);
    } else {
      for (;;) {
        if (pos == 0) {
          if (!l.ring || wrapped || s.empty()) return false;
          wrapped = true;
          pos = s.end();
        }
        std::size_t q = s.previous(pos);
        m = s.at(q);
        char c = m.symbol();
        if (l.ignored[static_cast<unsigned char>(c)]) {
          pos = q;
          continue;
        }
        if (c == ']') {
          // A complete branch to the left is skipped.
          const std::size_t r = branchOpening(s, q);
          if (r == BranchIndex::kNone) return false;
          pos = r;
          continue;
        }
        if (c == '[') {
          pos = q;  // the branch's start: its left neighbour is the parent's module
          continue;
        }
        pos = q;
        break;
      }
    }
    if (m.symbol() != pattern.symbol || m.parameterCount() != pattern.parameterCount) return false;
    bindParameters(pattern, m, frame);
  }
  return true;
}

bool ContextMatcher::matchContexts(const Production& p, const Lsystem& l, const ModuleString& s,
                                   std::size_t at, std::size_t end, double* frame,
                                   std::size_t leftNeighbour) const {
  // cpfg tests the right context before the left one.
  if (!p.right.empty() && !matchRight(p.right, l, s, end, frame)) return false;
  if (!p.left.empty() && !matchLeft(p.left, l, s, at, frame, leftNeighbour)) return false;
  return true;
}

}  // namespace hirsute
