#include "hirsute/lsys/derivation.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "hirsute/lsys/string_writer.h"

namespace hirsute {
namespace {

// Deepest recursion of decomposition and homomorphism (each level is a C++ call).
// A level takes about 1.3 KB of stack in a sanitizer build; 4000 stay well inside the 8 MB of a
// main thread (10000 overflowed it). Real models nest a few hundred levels at most.
constexpr int kMaxRecursionDepth = 4000;

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

}  // namespace

// A part of a step in parts: a derivation of its own, with its own evaluator (a fork of this
// one's, reading its variables), frames and string, that searches this derivation's branch index.
class Derivation::Part : public StepPart {
 public:
  explicit Part(const Derivation& helped) : helpedEvaluator_(helped.evaluator_) {
    evaluator_ = helped.evaluator_.fork(diagnostics_);
    DerivationOptions options = helped.options_;
    options.threads = 1;
    options.progress = nullptr;
    derivation_ = std::make_unique<Derivation>(helped.program_, *evaluator_, diagnostics_, options);
    derivation_->matcher_.readIndexOf(helped.matcher_);
  }
  void prepare(int stepsDone) override {
    evaluator_->readVariablesOf(helpedEvaluator_);
    derivation_->stepsDone_ = stepsDone;
    derivation_->next_.clear();
  }
  void rewrite(const ModuleString& s, std::size_t from, std::size_t to,
               const LeftNeighbours& start) override {
    derivation_->rewriteRange(s, from, to, &start);
  }
  ModuleString& string() override { return derivation_->next_; }
  std::size_t warnings() const override {
    return diagnostics_.warnings().size() + diagnostics_.suppressed();
  }

 private:
  const Evaluator& helpedEvaluator_;
  Diagnostics diagnostics_;
  std::unique_ptr<Evaluator> evaluator_;
  std::unique_ptr<Derivation> derivation_;
};

Derivation::Derivation(const Program& program, Evaluator& evaluator, Diagnostics& diagnostics,
                       DerivationOptions options)
    : program_(program),
      evaluator_(evaluator),
      diagnostics_(diagnostics),
      options_(options),
      // One frame per production, kept between uses as cpfg keeps production variables.
      frames_(program),
      choice_(program, evaluator, frames_, matcher_),
      fusedScan_(program.lsystems.size() == 1 && !program.lsystems.front().stochastic),
      drawnScan_(program.lsystems.size() == 1 && program.lsystems.front().stochastic),
      tables_(program, fusedScan_),
      parallel_(program,
                {options.threads, options.parallelMinimumModules, options.parallelMinimumCost,
                 options.maxModules},
                [this]() -> std::unique_ptr<StepPart> { return std::make_unique<Part>(*this); }) {
  if (options_.maxStringBytes == 0) options_.maxStringBytes = defaultStringLimit();
  current_.setByteLimit(options_.maxStringBytes);
  next_.setByteLimit(options_.maxStringBytes);
  for (const Lsystem& l : program_.lsystems) {
    hasDecomposition_ |= !l.decomposition.productions.empty();
  }
}

Derivation::~Derivation() = default;

// The copying part of the rewriting loop: from `pos`, modules no production can rewrite (and
// those whose left neighbour refuses every production) join the run [runFrom, pos), and a
// module with a plain successor is replaced on the spot; it stops at the first module choose()
// must decide, or at the end.
void Derivation::scanRun(const ModuleString& s, const Lsystem& l, std::size_t to,
                         std::size_t& position, std::size_t& runStart, std::size_t& runModules) {
  const std::uint8_t* const bytes = s.bytes();
  const std::size_t end = to;
  const std::array<bool, 128>& copied = tables_.copiedAsIs.front();
  const bool tracking = leftNeighbours_.enabled;
  if (tracking) leftNeighbours_.before(s, position);  // over the modules a production consumed
  // Locals, which the compiler keeps in registers: the loop stores nothing through references.
  std::size_t pos = position, runFrom = runStart, runCount = runModules;
  std::size_t last = leftNeighbours_.last, depth = leftNeighbours_.depth;
  std::vector<std::size_t>& open = leftNeighbours_.open;
  const std::array<std::uint8_t, 128>& kinds = leftNeighbours_.kinds;
  // The modules the run may still take before the string passes the limit.
  const auto room = [&] {
    const std::size_t used = next_.moduleCount() + streamed_;
    return options_.maxModules > used ? options_.maxModules - used : 0;
  };
  std::size_t left = room();
  const std::uint8_t* const quiet = tables_.quiet.data();
  while (pos < end) {
    const std::uint8_t b = bytes[pos];
    const auto c = static_cast<unsigned char>(b & 0x7f);
    if (tracking) {
      // Most modules of a long string with left contexts are copied as they are, whether or
      // not their symbol has productions: one table, the neighbour tracked without branches
      // where the compiler can.
      const unsigned neighbour = last != BranchIndex::kNone ? bytes[last] & 0x7fu : 0u;
      if (quiet[c * 128u + neighbour]) [[likely]] {
        runFrom = runCount ? runFrom : pos;
        ++runCount;
        LeftNeighbours::pass(pos, kinds[c], last, depth, open);
        pos += (b & 0x80) ? 3 + 4 * static_cast<std::size_t>(bytes[pos + 1]) : 1;
        if (runCount > left) {
          next_.appendRange(s, runFrom, pos, runCount);
          runCount = 0;
          checkSize(next_, l.axiomWhere);
        }
        continue;
      }
    }
    // Most modules of a long string are copied as they are: that path falls through.
    if (copied[c]) [[likely]] {
      if (runCount == 0) runFrom = pos;
      ++runCount;
    } else {
      int successor = -1;
      if ((b & 0x80) && tables_.guardedOnly[c] && tables_.guardsRefuse(c, bytes + pos)) {
        // No production's condition can hold: copied as it is.
      } else if (!(b & 0x80) && tables_.plainSuccessor[c] >= 0) {
        successor = tables_.plainSuccessor[c];
      } else {
        if (!tracking || !tables_.needsLeft[c]) break;
        if (last != BranchIndex::kNone && tables_.leftLast[c].test(bytes[last] & 0x7f)) {
          // The neighbour may satisfy a context: a plain production for it, the productions
          // tested here, or choose().
          const int table = tables_.contextTable[c];
          if (table >= 0 && !(b & 0x80) && !(bytes[last] & 0x80)) {
            successor =
                tables_.contextSuccessors[static_cast<std::size_t>(table)][bytes[last] & 0x7f];
          }
          if (successor < 0) {
            if (!tables_.leftOnly[c]) break;
            const int chosen = chooseByNeighbour(l, bytes + pos, bytes + last);
            if (chosen >= 0) {
              if (runCount) {
                next_.appendRange(s, runFrom, pos, runCount);
                runCount = 0;
              }
              applyChosen(l, static_cast<std::size_t>(chosen));
              left = room();
              LeftNeighbours::pass(pos, kinds[c], last, depth, open);
              pos += (b & 0x80) ? 3 + 4 * static_cast<std::size_t>(bytes[pos + 1]) : 1;
              continue;
            }
          }
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
    if (tracking) LeftNeighbours::pass(pos, kinds[c], last, depth, open);
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
    leftNeighbours_.depth = depth;
    leftNeighbours_.trackedTo = pos;
  }
}

// What the rewriting loop does after choose() chose production `id` of the main L-system for a
// module whose parameters its frame holds: the post-condition block, the successor's values.
// Out of line, so that the scan's loop stays small.
[[gnu::noinline]] void Derivation::applyChosen(const Lsystem& l, std::size_t id) {
  double* frame = frames_.of(0, 0, id);
  const Production& p = l.productions.productions[id];
  if (!p.after.empty()) evaluator_.run(p.after, frame);
  const double* values =
      p.successorValues.empty() ? nullptr : evaluator_.values(p.successorValues, frame, 0);
  appendValues(p, values, next_);
  checkSize(next_, p.where);
  streamIfFull();
}

// choose()'s test of the productions of a leftOnly symbol at `module`, whose left neighbour is
// `neighbour`, in the same order with the same bindings and code run: the first that applies.
[[gnu::noinline]] int Derivation::chooseByNeighbour(const Lsystem& l, const std::uint8_t* module,
                                                    const std::uint8_t* neighbour) {
  const ModuleRef m(module), n(neighbour);
  const std::size_t count = m.parameterCount();
  const char nearest = n.symbol();
  const std::size_t nearestCount = n.parameterCount();
  const RuleSet& rules = l.productions;
  for (std::uint32_t id : rules.bySymbol[static_cast<unsigned char>(m.symbol())]) {
    const Production& p = rules.productions[id];
    const ModulePattern& strict = p.strict[0];
    const ModulePattern& context = p.left[0];
    if (strict.parameterCount != count || context.symbol != nearest ||
        context.parameterCount != nearestCount)
      continue;
    if (guardRefuses(p, m)) continue;
    double* frame = frames_.of(0, 0, id);
    bindParameters(strict, m, frame);
    bindParameters(context, n, frame);
    if (!p.before.empty()) evaluator_.run(p.before, frame);
    if (evaluator_.isTrue(p.condition, frame)) return static_cast<int>(id);
  }
  return -1;
}

void Derivation::scanDrawn(const ModuleString& s, const Lsystem& l, std::size_t to,
                           std::size_t& position, std::size_t& runStart, std::size_t& runModules) {
  const std::uint8_t* const bytes = s.bytes();
  const std::array<bool, 128>& copied = tables_.copiedAsIs.front();
  std::size_t pos = position, runFrom = runStart, runCount = runModules;
  const auto room = [&] {
    const std::size_t used = next_.moduleCount() + streamed_;
    return options_.maxModules > used ? options_.maxModules - used : 0;
  };
  std::size_t left = room();
  std::uint64_t undrawn = 0;
  while (pos < to) {
    const std::uint8_t b = bytes[pos];
    const auto c = static_cast<unsigned char>(b & 0x7f);
    const std::size_t size = (b & 0x80) ? 3 + 4 * static_cast<std::size_t>(bytes[pos + 1]) : 1;
    const ChoiceTables::DrawnChoice* choice = nullptr;
    if (!copied[c]) {
      const int table = tables_.drawnTable[c];
      if (table < 0) break;  // choose() draws and decides
      const std::size_t count = (b & 0x80) ? bytes[pos + 1] : 0;
      for (const ChoiceTables::DrawnChoice& d :
           tables_.drawnChoices[static_cast<std::size_t>(table)])
        if (d.parameterCount == count) choice = &d;
    }
    // cpfg draws one number for every module, whether a production applies or not: the draws
    // of copied modules are counted and skipped in one go before the next number read.
    if (choice == nullptr) {
      ++undrawn;
      if (runCount == 0) runFrom = pos;
      ++runCount;
    } else {
      choice_.skipDraws(undrawn);
      undrawn = 0;
      const double draw = choice_.draw();
      if (runCount) {
        next_.appendRange(s, runFrom, pos, runCount);
        runCount = 0;
      }
      const std::uint32_t id = choice->weighed
                                   ? ChoiceTables::drawnProduction(*choice, draw)
                                   : choice_.weigh(choice->ids, ModuleRef(bytes + pos), draw);
      const Production& p = l.productions.productions[id];
      if (p.after.empty() && p.successorValues.empty() && !p.callsSubLsystem) {
        std::uint8_t* at = next_.appendEncoded(p.successorBytes.size(), p.successor.size());
        if (!p.successorBytes.empty())
          std::memcpy(at, p.successorBytes.data(), p.successorBytes.size());
      } else {
        // As after choose(): the module's parameters bound in the production's frame, its
        // post-condition block, its successor's values.
        double* frame = frames_.of(0, 0, id);
        bindParameters(p.strict[0], ModuleRef(bytes + pos), frame);
        if (!p.after.empty()) evaluator_.run(p.after, frame);
        const double* values =
            p.successorValues.empty() ? nullptr : evaluator_.values(p.successorValues, frame, 0);
        appendValues(p, values, next_);
      }
      checkSize(next_, p.where);
      streamIfFull();
      left = room();
    }
    pos += size;
    // The string's length is checked as each module goes out, as if it were appended.
    if (runCount > left) {
      next_.appendRange(s, runFrom, pos, runCount);
      runCount = 0;
      checkSize(next_, l.axiomWhere);
    }
  }
  choice_.skipDraws(undrawn);
  position = pos;
  runStart = runFrom;
  runModules = runCount;
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
  matcher_.stringChanged();
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
    if (stepsDone_ == 0) {
      options_.progress->begin("deriving", Progress::Unit::Steps, totalSteps_);
      options_.progress->withoutTimeLeft();  // a step costs as much as the string has grown
    }
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
  matcher_.stringChanged();
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
  if (inMainString) return matcher_.matchContexts(p, l, s, at, end, frame);
  // Modules a rule has produced take the contexts of the module they came from.
  const ModuleString& whole = *contextString_;
  return anchor < whole.end() &&
         matcher_.matchContexts(p, l, whole, anchor, whole.next(anchor), frame);
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
    double* frame = frames_.of(lsystem, set, id);
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
  // A streamed step goes out on this thread: its sink takes the string in order.
  const std::size_t parts =
      stream_ != nullptr ? 0 : parallel_.rewrite(current_, next_, matcher_, stepsDone_);
  if (parts == 0) rewriteRange(current_, 0, current_.end());
  parallel_.measured(
      modules, next_.moduleCount() + streamed_, parts,
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - started).count());
}

void Derivation::rewriteRange(const ModuleString& s, std::size_t from, std::size_t to,
                              const LeftNeighbours* start) {
  subLsystems_.assign(1, 0);
  leftNeighbours_.reset(program_);
  if (start && start->trackedTo == from && leftNeighbours_.enabled) leftNeighbours_ = *start;
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
      } else if (drawnScan_) {
        scanDrawn(s, l, to, pos, runFrom, runCount);
        if (pos >= to) break;
      } else if (!l.stochastic) {
        // A run of modules that no production can rewrite is copied in one piece; in the main
        // L-system, so are modules whose left neighbour no production's context ends with.
        std::size_t first = pos, count = 0;
        const std::array<bool, 128>& copied = tables_.copiedAsIs[static_cast<std::size_t>(lsystem)];
        const bool refusals = leftNeighbours_.enabled;
        while (pos < to && (copied[static_cast<unsigned char>(s.at(pos).symbol())] ||
                            (refusals && tables_.leftRefuses(s, pos, leftNeighbours_)))) {
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
      if (choice_.choose(lsystem, s, at, leftNeighbours_, match)) {
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
