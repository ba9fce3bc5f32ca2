#include "hirsute/lsys/derivation.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <system_error>
#include <thread>

#include "hirsute/lsys/parallel_rewriting.h"
#include "hirsute/lsys/string_writer.h"

namespace hirsute {
namespace {

// Deepest recursion of decomposition and homomorphism (each level is a C++ call).
// A level takes about 1.3 KB of stack in a sanitizer build; 4000 stay well inside the 8 MB of a
// main thread (10000 overflowed it). Real models nest a few hundred levels at most.
constexpr int kMaxRecursionDepth = 4000;

// cpfg: seed48({seed, 0, 155}) for a non-zero seed; drand48's unseeded state otherwise.
Rand48 choiceStream(const Lsystem& main) {
  auto seed = main.stochastic ? static_cast<std::uint16_t>(static_cast<long long>(main.seed))
                              : std::uint16_t{0};
  return seed != 0 ? Rand48::seed48(seed, 0, 155) : Rand48(0, 0, 0);
}

bool isSubLsystemStart(ModuleRef m) {
  return m.symbol() == '?' && m.parameterCount() > 0;
}

std::size_t defaultStringLimit() {
  long pages = sysconf(_SC_PHYS_PAGES);
  long pageSize = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || pageSize <= 0) return std::size_t{8} << 30;
  // Two strings live at once; together they may take 80% of the machine's memory.
  return static_cast<std::size_t>(pages) * static_cast<std::size_t>(pageSize) / 5 * 2;
}

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

const RuleSet& ruleSet(const Lsystem& l, int set) {
  return set == 0 ? l.productions : set == 1 ? l.decomposition : l.homomorphism;
}

// Every `?(id…)` from byte `from` on must name an L-system of the file; the error points at
// the production (or axiom) that made it, not at the step that later reads it.
void requireKnownLsystems(const Program& program, const ModuleString& s, std::size_t from,
                          const SourceLocation& where) {
  for (std::size_t q = from; q < s.end(); q = s.next(q)) {
    ModuleRef m = s.at(q);
    if (isSubLsystemStart(m) && program.lsystemIndex(m.parameter(0)) < 0) {
      throw DiagnosticError(where, "the string calls sub-L-system " +
                                       formatParameter(m.parameter(0)) +
                                       " with ?(…), but no L-system has that label");
    }
  }
}

// A weight written as a number (`: 3`) is read as it is, without a run of the evaluator.
bool isConstant(const Code& code) {
  return code.instructions.size() == 2 && code.instructions[0].op == Op::Constant &&
         code.instructions[1].op == Op::End;
}

void bind(const ModulePattern& pattern, ModuleRef m, double* frame) {
  for (std::size_t i = 0; i < pattern.slots.size(); ++i) frame[pattern.slots[i]] = m.parameter(i);
}

}  // namespace

Derivation::Derivation(const Program& program, Evaluator& evaluator, Diagnostics& diagnostics,
                       DerivationOptions options)
    : program_(program),
      evaluator_(evaluator),
      diagnostics_(diagnostics),
      options_(options),
      choice_(choiceStream(program.lsystems.front())) {
  if (options_.maxStringBytes == 0) options_.maxStringBytes = defaultStringLimit();
  current_.setByteLimit(options_.maxStringBytes);
  next_.setByteLimit(options_.maxStringBytes);
  // One frame per production, kept between uses as cpfg keeps production variables.
  std::size_t total = 0;
  for (const Lsystem& l : program_.lsystems) {
    for (int set = 0; set < 3; ++set) {
      std::vector<std::size_t> offsets;
      for (const Production& p : ruleSet(l, set).productions) {
        offsets.push_back(total);
        total += static_cast<std::size_t>(p.frameSize);
      }
      frameOffsets_.push_back(std::move(offsets));
    }
  }
  frames_.assign(total + 1, 0.0);
  for (const Lsystem& l : program_.lsystems) {
    hasDecomposition_ |= !l.decomposition.productions.empty();
    // Symbols no production starts with are copied as they are, except the cut and the
    // sub-L-system brackets, which the loop must see.
    std::array<bool, 128> copied{};
    for (std::size_t c = 0; c < copied.size(); ++c) copied[c] = l.productions.bySymbol[c].empty();
    copied['%'] = copied['?'] = copied['$'] = false;
    isCopiedAsIs_.push_back(copied);
  }
  const Lsystem& main = program_.lsystems.front();
  for (std::size_t c = 0; c < 128; ++c) {
    const auto& ids = main.productions.bySymbol[c];
    if (ids.empty() || c == '%' || c == '?' || c == '$') continue;
    needsLeft_[c] = std::all_of(ids.begin(), ids.end(), [&](std::uint32_t id) {
      const Production& p = main.productions.productions[id];
      return !p.left.empty() && p.strict.size() == 1;
    });
    for (std::uint32_t id : ids) {
      const Production& p = main.productions.productions[id];
      if (!p.left.empty()) {
        leftLast_[c].set(static_cast<unsigned char>(p.left.back().symbol) & 0x7f);
      }
    }
  }
  fusedScan_ = program_.lsystems.size() == 1 && !main.stochastic;
  plainSuccessor_.fill(-1);
  for (std::size_t c = 0; fusedScan_ && c < 128; ++c) {
    if (c == '%' || c == '?' || c == '$') continue;
    for (std::uint32_t id : main.productions.bySymbol[c]) {
      const Production& p = main.productions.productions[id];
      // choose() passes over a production whose one module wants parameters.
      if (p.strict.size() == 1 && p.strict[0].parameterCount != 0) continue;
      if (p.strict.size() == 1 && !p.hasContext() && p.before.empty() && p.condition.empty() &&
          p.after.empty() && p.successorValues.empty() && !p.callsSubLsystem) {
        plainSuccessor_[c] = static_cast<int>(id);
      }
      break;
    }
  }
  contextTable_.fill(-1);
  for (std::size_t c = 0; fusedScan_ && c < 128; ++c) {
    if (!needsLeft_[c]) continue;
    std::array<int, 128> successors;
    successors.fill(-1);
    bool any = false;
    for (std::size_t n = 0; n < 128; ++n) {
      if (!leftLast_[c].test(n)) continue;
      // choose()'s order: the first production whose module and the left context's last module
      // (the neighbour n, without parameters) do not refuse it.
      for (std::uint32_t id : main.productions.bySymbol[c]) {
        const Production& p = main.productions.productions[id];
        if (p.strict[0].parameterCount != 0) continue;
        const ModulePattern& nearest = p.left.back();
        if (static_cast<unsigned char>(nearest.symbol) != n || nearest.parameterCount != 0) continue;
        if (p.left.size() == 1 && p.right.empty() && p.before.empty() && p.condition.empty() &&
            p.after.empty() && p.successorValues.empty() && !p.callsSubLsystem) {
          successors[n] = static_cast<int>(id);
          any = true;
        }
        break;
      }
    }
    if (!any) continue;
    contextTable_[c] = static_cast<int>(contextSuccessors_.size());
    contextSuccessors_.push_back(successors);
  }
  modulesIndependent_ = rewritesModulesIndependently(program_);
  for (const Production& p : main.productions.productions) anyContext_ |= p.hasContext();
  threads_ = options_.threads > 0 ? options_.threads
                                  : static_cast<int>(std::thread::hardware_concurrency());
  threads_ = std::clamp(threads_, 1, 64);
}

struct Derivation::Helper {
  Diagnostics diagnostics;
  std::unique_ptr<Evaluator> evaluator;
  std::unique_ptr<Derivation> derivation;
};

Derivation::~Derivation() = default;

// The copying part of the rewriting loop: from `pos`, modules no production can rewrite (and
// those whose left neighbour refuses every production) join the run [runFrom, pos), and a
// module with a plain successor is replaced on the spot; it stops at the first module choose()
// must decide, or at the end.
void Derivation::scanRun(const ModuleString& s, const Lsystem& l, std::size_t to,
                         std::size_t& position, std::size_t& runStart, std::size_t& runModules) {
  const std::uint8_t* const bytes = s.bytes();
  const std::size_t end = to;
  const std::array<bool, 128>& copied = isCopiedAsIs_.front();
  const bool tracking = leftNeighbours_.enabled;
  if (tracking) leftNeighbours_.before(s, l, position);  // over the modules a production consumed
  // Locals, which the compiler keeps in registers: the loop stores nothing through references.
  std::size_t pos = position, runFrom = runStart, runCount = runModules;
  std::size_t last = leftNeighbours_.last;
  std::vector<std::size_t>& open = leftNeighbours_.open;
  // The modules the run may still take before the string passes the limit.
  const auto room = [&] {
    const std::size_t used = next_.moduleCount() + streamed_;
    return options_.maxModules > used ? options_.maxModules - used : 0;
  };
  std::size_t left = room();
  while (pos < end) {
    const std::uint8_t b = bytes[pos];
    const auto c = static_cast<unsigned char>(b & 0x7f);
    // Most modules of a long string are copied as they are: that path falls through.
    if (copied[c]) [[likely]] {
      if (runCount == 0) runFrom = pos;
      ++runCount;
    } else {
      int successor = -1;
      if (!(b & 0x80) && plainSuccessor_[c] >= 0) {
        successor = plainSuccessor_[c];
      } else {
        if (!tracking || !needsLeft_[c]) break;
        if (last != BranchIndex::kNone && leftLast_[c].test(bytes[last] & 0x7f)) {
          // The neighbour may satisfy a context: a plain production for it, or choose().
          const int table = contextTable_[c];
          if (table < 0 || (b & 0x80) || (bytes[last] & 0x80)) break;
          successor = contextSuccessors_[static_cast<std::size_t>(table)][bytes[last] & 0x7f];
          if (successor < 0) break;
        }
      }
      if (successor >= 0) {
        if (runCount) {
          next_.appendRange(s, runFrom, pos, runCount);
          runCount = 0;
        }
        const Production& p = l.productions.productions[static_cast<std::size_t>(successor)];
        std::uint8_t* at = next_.appendEncoded(p.successorBytes.size(), p.successor.size());
        if (!p.successorBytes.empty())
          std::memcpy(at, p.successorBytes.data(), p.successorBytes.size());
        checkSize(next_, p.where);
        streamIfFull();
        left = room();
      } else {
        if (runCount == 0) runFrom = pos;
        ++runCount;
      }
    }
    if (tracking) LeftNeighbours::pass(pos, static_cast<char>(c), l, last, open);
    pos += (b & 0x80) ? 3 + 4 * static_cast<std::size_t>(bytes[pos + 1]) : 1;
    // The string's length is checked as each module goes out, as if it were appended.
    if (runCount > left) {
      next_.appendRange(s, runFrom, pos, runCount);
      runCount = 0;
      checkSize(next_, l.axiomWhere);
    }
  }
  position = pos;
  runStart = runFrom;
  runModules = runCount;
  if (tracking) {
    leftNeighbours_.last = last;
    leftNeighbours_.trackedTo = pos;
  }
}

// Whether choose() would refuse the module at `at` on its left neighbour alone, as it does before
// binding or evaluating anything: every production of the symbol needs a left context, and the
// neighbour ends none of them (or there is none).
inline bool Derivation::leftRefuses(const ModuleString& s, const Lsystem& l, std::size_t at) {
  const auto c = static_cast<unsigned char>(s.at(at).symbol());
  if (!needsLeft_[c]) return false;
  const std::size_t neighbour = leftNeighbours_.before(s, l, at);
  return neighbour == BranchIndex::kNone ||
         !leftLast_[c].test(static_cast<unsigned char>(s.at(neighbour).symbol()));
}

void Derivation::start() {
  if (started_) return;
  started_ = true;
  const Lsystem& main = program_.lsystems.front();
  totalSteps_ = options_.steps ? *options_.steps : main.derivationLength;
  evaluator_.shared()[static_cast<std::size_t>(program_.lengthSlot)] = totalSteps_;
  evaluator_.shared()[static_cast<std::size_t>(program_.stepSlot)] = 0;
  for (const Lsystem& l : program_.lsystems) evaluator_.run(l.define, nullptr);
  for (const Lsystem& l : program_.lsystems) evaluator_.run(l.start, nullptr);
  // The axiom's parameters are evaluated after Start:, so they may use its variables.
  const double* v = evaluator_.values(main.axiomValues, nullptr, 0);
  std::vector<double> values(
      v, v + [&] {
        std::size_t n = 0;
        for (const SuccessorModule& m : main.axiom) n += m.parameterCount;
        return n;
      }());
  std::size_t k = 0;
  for (const SuccessorModule& m : main.axiom) {
    current_.appendRounded(m.symbol, std::span<const double>(values.data() + k, m.parameterCount));
    k += m.parameterCount;
  }
  requireKnownLsystems(program_, current_, 0, main.axiomWhere);
  branches_.clear();
  if (totalSteps_ == 0) {
    evaluator_.run(main.end, nullptr);
    stopped_ = true;
  }
}

bool Derivation::step() {
  start();
  if (stopped_ || stepsDone_ >= totalSteps_) return false;
  const Lsystem& main = program_.lsystems.front();
  // cpfg (generate.c): query modules (?P ?H ?L ?U) and the environment's ?E are served by an
  // interpretation of the string before the step counter advances and StartEach runs.
  if (queryPass_ && (program_.usesQueries || program_.usesEnvironment)) queryPass_(*this);
  evaluator_.shared()[static_cast<std::size_t>(program_.stepSlot)] = stepsDone_ + 1;
  evaluator_.run(main.startEach, nullptr);
  if (options_.progress) {
    if (stepsDone_ == 0) options_.progress->begin("deriving", Progress::Unit::Steps, totalSteps_);
    options_.progress->update(stepsDone_ + 1);  // the step under way
  }
  rewriteStep();
  if (stream_) {
    stream_->modules(next_, next_.begin(), next_.end());
    streamed_ += next_.moduleCount();
    stream_ = nullptr;
    current_.release();  // the string went to the sink; nothing keeps it
    next_.release();
  } else if (hasDecomposition_) {
    current_.clear();
    try {
      decompose(next_, current_);
    } catch (const ModuleStringTooLarge& e) {
      throw DiagnosticError(main.where, "the decomposed string needs more than " +
                                            std::to_string(e.bytes >> 20) + " MiB in step " +
                                            std::to_string(stepsDone_ + 1) +
                                            ", more than this machine allows");
    }
  } else {
    current_.swap(next_);
  }
  branches_.clear();
  next_.clear();
  ++stepsDone_;
  evaluator_.run(main.endEach, nullptr);
  if (evaluator_.stopRequested() || stepsDone_ >= totalSteps_) {
    stopped_ = true;
    evaluator_.run(main.end, nullptr);
  }
  return true;
}

bool Derivation::runStreamingLastStep(ModuleSink& sink, bool applyHomomorphism) {
  const bool fresh = !started_ || stepsDone_ == 0;
  start();
  const Lsystem& main = program_.lsystems.front();
  const bool streams = fresh && program_.lsystems.size() == 1 && !hasDecomposition_ &&
                       (!applyHomomorphism || main.homomorphism.productions.empty());
  bool streamed = false;
  while (!stopped_ && stepsDone_ < totalSteps_) {
    if (streams && stepsDone_ + 1 == totalSteps_) {
      stream_ = &sink;
      streamed = true;
    }
    step();
  }
  return streamed;
}

// While the last step streams, the new string goes out in pieces of about this size.
constexpr std::size_t kStreamChunkBytes = std::size_t{1} << 20;

// Inline: the rewriting loop calls it after every production it applies.
inline void Derivation::streamIfFull() {
  if (stream_ == nullptr || next_.byteSize() < kStreamChunkBytes) return;
  stream_->modules(next_, next_.begin(), next_.end());
  streamed_ += next_.moduleCount();
  next_.clear();
}

bool Derivation::matchStrict(const Production& p, const ModuleString& s, std::size_t at,
                             std::size_t& end, double* frame) const {
  std::size_t pos = at;
  for (const ModulePattern& pattern : p.strict) {
    if (pos >= s.end()) return false;
    ModuleRef m = s.at(pos);
    if (m.symbol() != pattern.symbol || m.parameterCount() != pattern.parameterCount) return false;
    bind(pattern, m, frame);
    pos = s.next(pos);
  }
  end = pos;
  return true;
}

const BranchIndex& Derivation::branchesOf(const ModuleString& s) const {
  if (!branches_.built()) branches_.build(s);
  return branches_;
}

bool Derivation::partsSearchBranches() const {
  LeftNeighbours neighbours;
  neighbours.reset(program_);
  for (const Lsystem& l : program_.lsystems) {
    for (const RuleSet* rules : {&l.productions, &l.decomposition, &l.homomorphism}) {
      for (const Production& p : rules->productions) {
        if (!p.right.empty() || p.left.size() > 1 || (!p.left.empty() && !neighbours.enabled))
          return true;
      }
    }
  }
  return false;
}

// A part of a step (helped_) reads the index of current_ only when rewriteInParts built it, and
// never builds it: the other parts may be reading it.
std::size_t Derivation::afterBranch(const ModuleString& s, std::size_t at) const {
  const Derivation& owner = helped_ ? *helped_ : *this;
  if (&s == &owner.current_ && (!helped_ || owner.branches_.built()) &&
      owner.branchesOf(s).usable()) {
    const std::size_t close = owner.branches_.partner(at);
    return close == BranchIndex::kNone ? s.end() : s.next(close);
  }
  const std::size_t close = branchEnd(s, s.next(at));
  return close < s.end() ? s.next(close) : close;
}

std::size_t Derivation::branchOpening(const ModuleString& s, std::size_t at) const {
  const Derivation& owner = helped_ ? *helped_ : *this;
  if (&s == &owner.current_ && (!helped_ || owner.branches_.built()) &&
      owner.branchesOf(s).usable()) {
    return owner.branches_.partner(at);
  }
  int depth = 0;
  for (std::size_t r = at;; r = s.previous(r)) {
    const char d = s.at(r).symbol();
    if (d == ']') ++depth;
    if (d == '[' && --depth == 0) return r;
    if (r == 0) return BranchIndex::kNone;
  }
}

bool Derivation::matchRight(const std::vector<ModulePattern>& patterns, const Lsystem& l,
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
    bind(pattern, m, frame);
    pos = s.next(pos);
  }
  return true;
}

void Derivation::LeftNeighbours::reset(const Program& program) {
  trackedTo = 0;
  last = BranchIndex::kNone;
  open.clear();
  const Lsystem& main = program.lsystems.front();
  // Sub-L-systems have ignore sets of their own, a ring wraps around, and ignored brackets
  // would pair differently: those keep the backward search.
  enabled = program.lsystems.size() == 1 && !main.ring && !main.ignored['['] && !main.ignored[']'];
  if (enabled) {
    enabled = std::any_of(main.productions.productions.begin(), main.productions.productions.end(),
                          [](const Production& p) { return !p.left.empty(); });
  }
}

// The module a left context's last pattern is compared with, as matchLeft's backward search
// would find it (ignored modules passed over, a complete branch to the left skipped, a `[`
// stepped out of), found by carrying that search's answer forward through the string.
inline std::size_t Derivation::LeftNeighbours::before(const ModuleString& s, const Lsystem& l,
                                                      std::size_t at) {
  const std::uint8_t* const bytes = s.bytes();
  for (std::size_t q = trackedTo; q < at;) {
    const std::uint8_t b = bytes[q];
    pass(q, static_cast<char>(b & 0x7f), l, last, open);
    q += (b & 0x80) ? 3 + 4 * static_cast<std::size_t>(bytes[q + 1]) : 1;
  }
  if (at > trackedTo) trackedTo = at;
  return last;
}

bool Derivation::matchLeft(const std::vector<ModulePattern>& patterns, const Lsystem& l,
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
    bind(pattern, m, frame);
  }
  return true;
}

bool Derivation::matchContexts(const Production& p, const Lsystem& l, const ModuleString& s,
                               std::size_t at, std::size_t end, double* frame,
                               std::size_t leftNeighbour) const {
  // cpfg tests the right context before the left one.
  if (!p.right.empty() && !matchRight(p.right, l, s, end, frame)) return false;
  if (!p.left.empty() && !matchLeft(p.left, l, s, at, frame, leftNeighbour)) return false;
  return true;
}

double Derivation::weightOf(const Production& p, double* frame) {
  if (p.probability.empty()) return 1.0;
  if (isConstant(p.probability)) {
    return p.probability.constants[static_cast<std::size_t>(p.probability.instructions[0].operand)];
  }
  return evaluator_.run(p.probability, frame);
}

bool Derivation::choose(int lsystem, int set, const ModuleString& s, std::size_t at, Match& match) {
  const Lsystem& l = program_.lsystems[static_cast<std::size_t>(lsystem)];
  const RuleSet& rules = ruleSet(l, set);
  const bool stochastic = set == 0 && l.stochastic;
  // cpfg draws one number per module of the string in a stochastic L-system, whether or not a
  // production applies there.
  const double draw = stochastic ? choice_.next() : 0.0;
  const auto& ids = rules.bySymbol[static_cast<unsigned char>(s.at(at).symbol())];
  if (ids.empty()) return false;
  candidates_.clear();
  std::size_t neighbour = kUnknownNeighbour;  // of a left context, found once for all productions
  std::vector<double>& weights = weights_;    // reused: no allocation per module
  weights.clear();
  const std::size_t parameterCount = s.at(at).parameterCount();
  for (std::uint32_t id : ids) {
    const Production& p = rules.productions[id];
    // Cheap refusals first: the module's own parameter count, then (with the neighbour known)
    // the last module of the left context. Binding has no effect a refused production sees.
    if (p.strict.size() == 1 && p.strict[0].parameterCount != parameterCount) continue;
    if (!p.left.empty() && leftNeighbours_.enabled) {
      if (neighbour == kUnknownNeighbour) neighbour = leftNeighbours_.before(s, l, at);
      if (neighbour == BranchIndex::kNone) continue;
      const ModuleRef left = s.at(neighbour);
      const ModulePattern& last = p.left.back();
      if (left.symbol() != last.symbol || left.parameterCount() != last.parameterCount) continue;
    }
    double* frame = frames_.data() + frameOffset(lsystem, set, id);
    std::size_t end = 0;
    if (!matchStrict(p, s, at, end, frame)) continue;
    if (p.hasContext() && !matchContexts(p, l, s, at, end, frame, neighbour)) continue;
    if (!p.before.empty()) evaluator_.run(p.before, frame);
    if (!evaluator_.isTrue(p.condition, frame)) continue;
    if (!stochastic) {
      match = Match{&p, end, frame};
      return true;
    }
    candidates_.push_back(Match{&p, end, frame});
    weights.push_back(weightOf(p, frame));
  }
  if (candidates_.empty()) return false;
  double sum = 0;
  for (double w : weights) sum += w;
  double r = draw * sum;
  double accumulated = 0;
  std::size_t chosen = candidates_.size() - 1;
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    accumulated += weights[i];
    if (r < accumulated) {
      chosen = i;
      break;
    }
  }
  match = candidates_[chosen];
  return true;
}

std::size_t Derivation::skipCut(const ModuleString& s, std::size_t at) const {
  // cpfg's cut: `%` removes itself and the rest of its branch, up to the closing `]`, the `$`
  // that ends the current sub-L-system, or the end of the string.
  int depth = 0, nested = 0;
  std::size_t pos = s.next(at);
  for (; pos < s.end(); pos = s.next(pos)) {
    ModuleRef m = s.at(pos);
    char c = m.symbol();
    if (c == '[') {
      ++depth;
    } else if (c == ']') {
      if (depth == 0) break;
      --depth;
    } else if (isSubLsystemStart(m)) {
      ++nested;
    } else if (c == '$') {
      if (nested == 0 && depth == 0 && subLsystems_.size() > 1) break;
      if (nested > 0) --nested;
    }
  }
  return pos;
}

namespace {
// Out of line, so that the check before it stays small enough to inline into the loops.
[[noreturn, gnu::noinline]] void throwStringTooLong(const SourceLocation& where, std::size_t limit,
                                                    int step) {
  throw DiagnosticError(where, "the string grew past " + std::to_string(limit) +
                                   " modules in step " + std::to_string(step) +
                                   " (the limit is set with --max-modules)");
}
}  // namespace

inline void Derivation::checkSize(const ModuleString& s, const SourceLocation& where) {
  const std::size_t modules = s.moduleCount() + (&s == &next_ ? streamed_ : 0);
  if (modules > options_.maxModules) throwStringTooLong(where, options_.maxModules, stepsDone_ + 1);
}

void Derivation::appendValues(const Production& p, const double* values, ModuleString& out) {
  const std::size_t start = out.byteSize();
  std::uint8_t* at = out.appendEncoded(p.successorBytes.size(), p.successor.size());
  // An empty successor (`*`) has no bytes, and memcpy may not be given its null pointer.
  if (!p.successorBytes.empty()) std::memcpy(at, p.successorBytes.data(), p.successorBytes.size());
  for (std::size_t i = 0; i < p.parameterOffsets.size(); ++i) {
    float value = static_cast<float>(values[i]);  // cpfg stores parameters as float32
    std::memcpy(at + p.parameterOffsets[i], &value, sizeof value);
  }
  if (p.callsSubLsystem) requireKnownLsystems(program_, out, start, p.where);
}

bool Derivation::ruleContextsMatch(const Production& p, const Lsystem& l, const ModuleString& s,
                                   std::size_t at, std::size_t end, bool inMainString,
                                   std::size_t anchor, double* frame) const {
  if (inMainString) return matchContexts(p, l, s, at, end, frame);
  // Modules a rule has produced take the contexts of the module they came from.
  const ModuleString& whole = *contextString_;
  return anchor < whole.end() && matchContexts(p, l, whole, anchor, whole.next(anchor), frame);
}

bool Derivation::wouldApply(const Production& p, const Lsystem& l, const ModuleString& s,
                            std::size_t at, std::size_t end, bool inMainString, std::size_t anchor,
                            double* frame) {
  if (p.hasContext() && !ruleContextsMatch(p, l, s, at, end, inMainString, anchor, frame))
    return false;
  // A pre-condition block may have effects, so its production counts as applicable untested.
  return !p.before.empty() || evaluator_.isTrue(p.condition, frame);
}

ModuleString& Derivation::levelBuffer(int level) {
  while (levelBuffers_.size() <= static_cast<std::size_t>(level)) levelBuffers_.emplace_back();
  ModuleString& buffer = levelBuffers_[static_cast<std::size_t>(level)];
  buffer.clear();
  return buffer;
}

bool Derivation::applyAt(int set, int lsystem, const ModuleString& s, std::size_t at,
                         bool inMainString, std::size_t anchor, int level, std::size_t& end,
                         ModuleSink& out) {
  const Lsystem& l = program_.lsystems[static_cast<std::size_t>(lsystem)];
  const RuleSet& rules = ruleSet(l, set);
  const auto& ids = rules.bySymbol[static_cast<unsigned char>(s.at(at).symbol())];
  for (std::uint32_t id : ids) {
    const Production& p = rules.productions[id];
    double* frame = frames_.data() + frameOffset(lsystem, set, id);
    if (!matchStrict(p, s, at, end, frame)) continue;
    if (level > rules.maximumDepth) {
      if (rules.warnings && !depthWarned_.contains(&p) &&
          wouldApply(p, l, s, at, end, inMainString, anchor, frame)) {
        depthWarned_.insert(&p);
        diagnostics_.warn(p.where, std::string(set == 1 ? "decomposition" : "homomorphism") +
                                       " reached its maximum depth (" +
                                       std::to_string(rules.maximumDepth) +
                                       ") with this production still applicable");
      }
      return false;
    }
    if (p.hasContext()) {
      // Contexts are those of the derived string, also for modules a rule has produced.
      if (!ruleContextsMatch(p, l, s, at, end, inMainString, anchor, frame)) continue;
    }
    if (!p.before.empty()) evaluator_.run(p.before, frame);
    if (!evaluator_.isTrue(p.condition, frame)) continue;
    if (!p.after.empty()) evaluator_.run(p.after, frame);
    if (level >= kMaxRecursionDepth) {
      throw DiagnosticError(
          p.where, "rules nest deeper than " + std::to_string(kMaxRecursionDepth) + " levels");
    }
    ModuleString& produced = levelBuffer(level);
    appendValues(p, evaluator_.values(p.successorValues, frame, 0), produced);
    std::size_t from = inMainString ? at : anchor;
    for (std::size_t q = 0, e = 0; q < produced.end(); q = e) {
      if (!applyAt(set, lsystem, produced, q, false, from, level + 1, e, out)) {
        e = produced.next(q);
        // Rules that double their module at every level must not run for ever.
        if (++ruleOutput_ > options_.maxModules) {
          throw DiagnosticError(p.where,
                                std::string(set == 1 ? "decomposition" : "the homomorphism") +
                                    " produced more than " + std::to_string(options_.maxModules) +
                                    " modules (the limit is set with --max-modules)");
        }
        out.module(produced.at(q));
      }
    }
    return true;
  }
  return false;
}

void Derivation::rewriteStep() {
  streamed_ = 0;
  const auto started = std::chrono::steady_clock::now();
  const std::size_t modules = current_.moduleCount();
  const std::size_t parts = rewriteInParts();
  if (parts > 0) {
    ++stepsInParts_;
  } else {
    rewriteRange(current_, 0, current_.end());
  }
  // A short string's step is mostly the step's own fixed costs: it tells nothing.
  if (modules < std::max<std::size_t>(options_.parallelMinimumModules, 1)) return;
  const double cost =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - started).count() /
      static_cast<double>(modules);
  if (parts == 0) {
    sequentialCost_ = stepCost_ = cost;
    remeasure_ = false;
    return;
  }
  // What the step would have cost one thread, about: the next step is judged by it.
  stepCost_ = cost * static_cast<double>(parts);
  if (cost > 0.9 * sequentialCost_) {
    // The parts took as long a module as one thread did (their memory grows page by page and
    // they are copied together): the next step is measured on one thread, and after three such
    // steps in a row the derivation stays on one.
    remeasure_ = true;
    if (++splitsUnpaid_ >= 3) splittingPays_ = false;
  } else {
    splitsUnpaid_ = 0;
  }
}

std::size_t Derivation::rewriteInParts() {
  if (!modulesIndependent_ || threads_ < 2 || stream_ != nullptr ||
      current_.moduleCount() < std::max<std::size_t>(options_.parallelMinimumModules, 1)) {
    return 0;
  }
  if (options_.parallelMinimumCost > 0 &&
      (!splittingPays_ || remeasure_ || stepCost_ < options_.parallelMinimumCost)) {
    return 0;
  }
  const std::size_t parts = std::min(static_cast<std::size_t>(threads_), current_.moduleCount());
  // The parts' boundaries: module starts about equally far apart in bytes. The way there carries
  // the left neighbours along, so that no part passes over the string before it again.
  std::vector<std::size_t> bounds{0};
  LeftNeighbours neighbours;
  neighbours.reset(program_);
  std::vector<LeftNeighbours> starts{neighbours};
  const Lsystem& main = program_.lsystems.front();
  const std::uint8_t* const bytes = current_.bytes();
  for (std::size_t k = 1, pos = 0; k < parts; ++k) {
    const std::size_t target = current_.end() / parts * k;
    if (neighbours.enabled) {
      while (pos < target) {
        const std::uint8_t b = bytes[pos];
        LeftNeighbours::pass(pos, static_cast<char>(b & 0x7f), main, neighbours.last,
                             neighbours.open);
        pos += (b & 0x80) ? 3 + 4 * static_cast<std::size_t>(bytes[pos + 1]) : 1;
      }
    } else {
      while (pos < target) pos = current_.next(pos);
    }
    if (pos > bounds.back() && pos < current_.end()) {
      bounds.push_back(pos);
      neighbours.trackedTo = pos;
      starts.push_back(neighbours);
    }
  }
  bounds.push_back(current_.end());
  const std::size_t used = bounds.size() - 1;
  while (helpers_.size() < used) {
    auto helper = std::make_unique<Helper>();
    helper->evaluator = evaluator_.fork(helper->diagnostics);
    DerivationOptions options = options_;
    options.threads = 1;
    options.progress = nullptr;
    helper->derivation =
        std::make_unique<Derivation>(program_, *helper->evaluator, helper->diagnostics, options);
    helper->derivation->helped_ = this;
    helpers_.push_back(std::move(helper));
  }
  // Contexts that search the string's branches do it through its index: built here, read by
  // every part (a part never builds it).
  if (anyContext_ && partsSearchBranches()) branchesOf(current_);
  std::vector<std::exception_ptr> errors(used);
  std::vector<std::size_t> warningsBefore(used);
  for (std::size_t k = 0; k < used; ++k) {
    Helper& helper = *helpers_[k];
    helper.evaluator->readVariablesOf(evaluator_);
    helper.derivation->stepsDone_ = stepsDone_;
    helper.derivation->next_.clear();
    helper.derivation->partStart_ = starts[k];
    helper.derivation->partStartKnown_ = true;
    warningsBefore[k] = helper.diagnostics.warnings().size() + helper.diagnostics.suppressed();
  }
  const auto rewritePart = [&](std::size_t k) {
    try {
      helpers_[k]->derivation->rewriteRange(current_, bounds[k], bounds[k + 1]);
    } catch (...) {
      errors[k] = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t k = 1; k < used; ++k) {
    try {
      threads.emplace_back(rewritePart, k);
    } catch (const std::system_error&) {
      rewritePart(k);  // no thread to be had: this one does the part
    }
  }
  rewritePart(0);
  for (std::thread& thread : threads) thread.join();
  bool whole = true;
  std::size_t modules = 0;
  for (std::size_t k = 0; k < used; ++k) {
    const Helper& helper = *helpers_[k];
    whole =
        whole && !errors[k] &&
        helper.diagnostics.warnings().size() + helper.diagnostics.suppressed() == warningsBefore[k];
    modules += helper.derivation->next_.moduleCount();
  }
  whole = whole && modules <= options_.maxModules;
  next_.clear();
  if (whole) {
    try {
      next_.swap(helpers_[0]->derivation->next_);
      for (std::size_t k = 1; k < used; ++k) {
        const ModuleString& part = helpers_[k]->derivation->next_;
        next_.appendRange(part, part.begin(), part.end(), part.moduleCount());
      }
    } catch (const ModuleStringTooLarge&) {
      whole = false;
      next_.clear();
    }
  }
  // The parts' strings go: the next step's may be of another size.
  for (std::size_t k = 0; k < used; ++k) helpers_[k]->derivation->next_.release();
  return whole ? used : 0;
}

void Derivation::rewriteRange(const ModuleString& s, std::size_t from, std::size_t to) {
  subLsystems_.assign(1, 0);
  leftNeighbours_.reset(program_);
  if (partStartKnown_ && partStart_.trackedTo == from && leftNeighbours_.enabled) {
    leftNeighbours_ = partStart_;
  }
  const bool nested = program_.lsystems.size() > 1;
  std::size_t pos = from;
  // Modules that stay as they are accumulate into one run [runFrom, pos), appended in one piece
  // when a production applies, a cut skips, or the string ends.
  std::size_t runFrom = from;
  std::size_t runCount = 0;
  const auto appendRun = [&] {
    if (runCount == 0) return;
    next_.appendRange(s, runFrom, pos, runCount);
    runCount = 0;
    streamIfFull();
  };
  // A long step shows itself too (a countdown per pass of the loop, the clock read rarely).
  Progress* const progress = options_.progress;
  const double stepUnderWay = stepsDone_ + 1;
  try {
    while (pos < to) {
      if (progress) progress->tick(stepUnderWay);
      int lsystem = subLsystems_.back();
      const Lsystem& l = program_.lsystems[static_cast<std::size_t>(lsystem)];
      if (fusedScan_) {
        scanRun(s, l, to, pos, runFrom, runCount);
        if (pos >= to) break;
      } else if (!l.stochastic) {
        // A run of modules that no production can rewrite is copied in one piece; in the main
        // L-system, so are modules whose left neighbour no production's context ends with.
        std::size_t first = pos, count = 0;
        const std::array<bool, 128>& copied = isCopiedAsIs_[static_cast<std::size_t>(lsystem)];
        const bool refusals = leftNeighbours_.enabled;
        while (pos < to && (copied[static_cast<unsigned char>(s.at(pos).symbol())] ||
                            (refusals && leftRefuses(s, l, pos)))) {
          pos = s.next(pos);
          ++count;
        }
        if (count) {
          // The string's length is checked as each module goes out, as if it were appended.
          if (runCount == 0) runFrom = first;
          runCount += count;
          if (next_.moduleCount() + streamed_ + runCount > options_.maxModules) {
            appendRun();
            checkSize(next_, l.axiomWhere);
          }
          continue;
        }
        if (pos >= to) break;
      }
      const std::size_t at = pos;
      ModuleRef m = s.at(at);
      std::size_t after;
      Match match;
      if (choose(lsystem, 0, s, at, match)) {
        appendRun();
        const Production& p = *match.production;
        if (!p.after.empty()) evaluator_.run(p.after, match.frame);
        // A successor without parameters (S --> T) has no values to compute.
        const double* values = p.successorValues.empty()
                                   ? nullptr
                                   : evaluator_.values(p.successorValues, match.frame, 0);
        appendValues(p, values, next_);
        checkSize(next_, p.where);
        streamIfFull();
        after = match.end;
      } else if (m.symbol() == '%' && m.parameterCount() == 0) {
        appendRun();
        after = skipCut(s, at);
      } else {
        after = s.next(at);
        if (runCount == 0) runFrom = at;
        ++runCount;
        if (next_.moduleCount() + streamed_ + runCount > options_.maxModules) {
          pos = after;
          appendRun();
          checkSize(next_, l.axiomWhere);
        }
      }
      if (nested) trackSubLsystems(s, at, after, subLsystems_);
      pos = after;
    }
    appendRun();
  } catch (const ModuleStringTooLarge& e) {
    throw DiagnosticError(program_.lsystems.front().where,
                          "the string needs more than " + std::to_string(e.bytes >> 20) +
                              " MiB in step " + std::to_string(stepsDone_ + 1) +
                              ", more than this machine allows");
  }
}

namespace {
// Appends modules to a string: the sink decomposition writes into.
class StringSink : public ModuleSink {
 public:
  explicit StringSink(ModuleString& out) : out_(out) {}
  void module(char symbol, const float* parameters, std::size_t count) override {
    out_.append(symbol, std::span<const float>(parameters, count));
  }
  void module(ModuleRef m) override { out_.append(m); }

 private:
  ModuleString& out_;
};
}  // namespace

void Derivation::decompose(const ModuleString& from, ModuleString& into) {
  // cpfg decomposes the new string after each step: rules apply to module sequences of it,
  // recursively to their own successors, with contexts in that string.
  StringSink sink(into);
  contextString_ = &from;
  ruleOutput_ = 0;
  std::vector<int> stack(1, 0);
  for (std::size_t pos = 0, after = 0; pos < from.end(); pos = after) {
    int lsystem = stack.back();
    const Lsystem& l = program_.lsystems[static_cast<std::size_t>(lsystem)];
    bool rewritten = !l.decomposition.productions.empty() &&
                     applyAt(1, lsystem, from, pos, true, pos, 1, after, sink);
    if (!rewritten) {
      after = from.next(pos);
      into.append(from.at(pos));
    }
    checkSize(into, l.axiomWhere);
    trackSubLsystems(from, pos, after, stack);
  }
}

void Derivation::trackSubLsystems(const ModuleString& s, std::size_t from, std::size_t to,
                                  std::vector<int>& stack) const {
  // Sub-L-systems: `?(id,…)` switches to L-system `id` until its `$`.
  for (std::size_t q = from; q < to; q = s.next(q)) {
    ModuleRef m = s.at(q);
    if (isSubLsystemStart(m)) {
      int index = program_.lsystemIndex(m.parameter(0));
      if (index < 0) {
        throw DiagnosticError(program_.lsystems.front().where,
                              "the string calls sub-L-system " + formatParameter(m.parameter(0)) +
                                  " with ?(…), but no L-system has that label");
      }
      stack.push_back(index);
    } else if (m.symbol() == '$' && stack.size() > 1) {
      stack.pop_back();
    }
  }
}

void Derivation::emit(ModuleSink& sink, bool applyHomomorphism) {
  start();
  const Lsystem& main = program_.lsystems.front();
  if (program_.lsystems.size() == 1 &&
      (!applyHomomorphism || main.homomorphism.productions.empty())) {
    // Nothing to rewrite and no sub-L-systems to track: the string goes out in one piece.
    sink.modules(current_, current_.begin(), current_.end());
    return;
  }
  std::vector<int> stack(1, 0);
  std::optional<BlockRandom> ownStream;
  contextString_ = &current_;
  ruleOutput_ = 0;
  for (std::size_t pos = 0, after = 0; pos < current_.end(); pos = after) {
    int lsystem = stack.back();
    const Lsystem& l = program_.lsystems[static_cast<std::size_t>(lsystem)];
    bool rewritten = false;
    sink.beginSource(pos);
    if (applyHomomorphism && !l.homomorphism.productions.empty()) {
      if (l.homomorphism.hasSeed) {
        // The homomorphism's own random stream, restarted at every interpretation.
        if (!ownStream) {
          ownStream.emplace();
          ownStream->srand(l.homomorphism.seed);
        }
        evaluator_.useRandom(&*ownStream);
      }
      rewritten = applyAt(2, lsystem, current_, pos, true, pos, 1, after, sink);
      evaluator_.useRandom(nullptr);
    }
    if (!rewritten) {
      after = current_.next(pos);
      sink.module(current_.at(pos));
    }
    if (program_.lsystems.size() > 1) trackSubLsystems(current_, pos, after, stack);
  }
}

}  // namespace hirsute
