// Derivation with cpfg's semantics: parallel rewriting in file order, contexts with
// ignore/consider and branch skipping, conditions and blocks, stochastic choice, decomposition
// after each step, the cut, sub-L-systems, Start/StartEach/EndEach/End; and the homomorphism
// applied when the string is handed to a sink.
#pragma once

#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <unordered_set>
#include <vector>

#include "hirsute/lsys/branch_index.h"
#include "hirsute/lsys/diagnostic.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/module_sink.h"
#include "hirsute/lsys/module_string.h"
#include "hirsute/lsys/program.h"
#include "hirsute/lsys/progress.h"
#include "hirsute/lsys/random_streams.h"

namespace hirsute {

struct DerivationOptions {
  std::optional<int> steps;              // overrides `derivation length:`
  std::size_t maxModules = 100'000'000;  // a longer string is an error
  std::size_t maxStringBytes = 0;        // 0: a share of the machine's memory
  Progress* progress = nullptr;          // shows `deriving: step k/n` (null: nothing)
  // Threads that rewrite the parts of a long step at once, when the program's productions
  // rewrite every module independently (parallel_rewriting.h); 0: one a processor core, 1: the
  // step on the calling thread alone. The string, warnings and errors are those of one thread.
  int threads = 0;
  // A step is split when its string has at least parallelMinimumModules modules and the last
  // step of such a string took at least parallelMinimumCost nanoseconds of one thread's time a
  // module: a step that mostly copies modules gains nothing from threads and spends memory on the
  // parts. Steps in parts that take as long a module as one thread did make the next step run
  // alone, to measure it again, and after three in a row every step. Tests set both to 0 to split
  // every step that may be.
  std::size_t parallelMinimumModules = 16384;
  double parallelMinimumCost = 150;
};

class Derivation {
 public:
  Derivation(const Program& program, Evaluator& evaluator, Diagnostics& diagnostics,
             DerivationOptions options = {});
  ~Derivation();
  Derivation(const Derivation&) = delete;
  Derivation& operator=(const Derivation&) = delete;

  // Runs define:, Start: and builds the axiom. Called once before the first step.
  void start();
  // Performs one derivation step; returns false when the derivation has ended (all steps done
  // or stop() called), without changing the string.
  bool step();
  // Steps until the end; calls `afterStep` (if given) after every step.
  template <typename AfterStep>
  void run(AfterStep afterStep) {
    while (step()) afterStep(*this);
  }
  void run() {
    while (step()) {
    }
  }

  // Runs every step like run(), but hands the last step's string to `sink` while it is being
  // produced instead of keeping it, so that the largest string never exists whole: for writing
  // the final string only. Streams when nothing after the step needs the string (no
  // homomorphism to apply, no decomposition, no sub-L-systems) and returns true; string() is
  // then empty and emit() must not be called. Otherwise it returns false with the string kept,
  // to emit as usual. A derivation that has taken steps already runs on without streaming.
  bool runStreamingLastStep(ModuleSink& sink, bool applyHomomorphism);
  // The modules the streamed step handed to its sink.
  std::size_t streamedModules() const { return streamed_; }

  // The turtle's query pass, run before each rewriting when the program has query modules; it
  // interprets the string (emit) and writes positions and orientations into it.
  void setQueryPass(std::function<void(Derivation&)> pass) { queryPass_ = std::move(pass); }
  ModuleString& mutableString() {
    branches_.clear();
    return current_;
  }

  const Program& program() const { return program_; }
  int stepsDone() const { return stepsDone_; }
  // Steps whose string was rewritten in parts on several threads (DerivationOptions::threads).
  int stepsRewrittenInParts() const { return stepsInParts_; }
  int totalSteps() const { return totalSteps_; }
  const ModuleString& string() const { return current_; }

  // Hands every module of the current string to `sink`, after the main L-system's
  // homomorphism when `applyHomomorphism` (recursively, with contexts in the string).
  void emit(ModuleSink& sink, bool applyHomomorphism);

 private:
  struct Match {
    const Production* production = nullptr;
    std::size_t end = 0;  // position after the strict predecessor
    double* frame = nullptr;
  };

  std::size_t frameOffset(int lsystem, int set, std::size_t production) const {
    return frameOffsets_[static_cast<std::size_t>(lsystem * 3 + set)][production];
  }
  bool matchStrict(const Production& p, const ModuleString& s, std::size_t at, std::size_t& end,
                   double* frame) const;
  // The brackets of `s` (the current string), indexed on first use after it changed.
  const BranchIndex& branchesOf(const ModuleString& s) const;
  // The position after the `]` matching the `[` at `at`, or the end of the string.
  std::size_t afterBranch(const ModuleString& s, std::size_t at) const;
  // The `[` that opens the `]` at `at`, or BranchIndex::kNone.
  std::size_t branchOpening(const ModuleString& s, std::size_t at) const;
  bool matchRight(const std::vector<ModulePattern>& patterns, const Lsystem& l,
                  const ModuleString& s, std::size_t from, double* frame) const;
  // `neighbour`: where the last pattern's module is, when the caller knows (LeftNeighbours);
  // kUnknownNeighbour makes the search find it.
  static constexpr std::size_t kUnknownNeighbour = BranchIndex::kNone - 1;
  bool matchLeft(const std::vector<ModulePattern>& patterns, const Lsystem& l,
                 const ModuleString& s, std::size_t before, double* frame,
                 std::size_t neighbour = kUnknownNeighbour) const;
  bool matchContexts(const Production& p, const Lsystem& l, const ModuleString& s, std::size_t at,
                     std::size_t end, double* frame,
                     std::size_t leftNeighbour = kUnknownNeighbour) const;
  // A stochastic production's weight (`: w`) in its frame.
  double weightOf(const Production& p, double* frame);
  // Finds the production to apply at `at`, running pre-condition blocks and conditions.
  bool choose(int lsystem, int set, const ModuleString& s, std::size_t at, Match& match);
  void rewriteStep();
  // Rewrites the modules of `s` from byte `from` up to byte `to` (module starts) into next_.
  void rewriteRange(const ModuleString& s, std::size_t from, std::size_t to);
  // Rewrites the step's string in parts on several threads, each part by a helper derivation
  // of its own (its own evaluator, frames and output), and returns the number of parts; 0, with
  // nothing changed, when the step is not to be split or a part met a warning or an error (the
  // step is then rewritten on this thread, which warns and fails in order).
  std::size_t rewriteInParts();
  struct Helper;
  std::vector<std::unique_ptr<Helper>> helpers_;
  bool modulesIndependent_ = false;  // rewritesModulesIndependently(program_)
  bool anyContext_ = false;          // a production has a left or right context
  int threads_ = 1;
  int stepsInParts_ = 0;
  // Nanoseconds of rewriting a module: in the last step with a string of parallelMinimumModules
  // at least (for a step in parts, its time times the parts), and in the last such step on one
  // thread (-1: none yet).
  double stepCost_ = -1;
  double sequentialCost_ = -1;
  bool remeasure_ = false;  // the last step in parts did not pay: the next is measured alone
  int splitsUnpaid_ = 0;    // steps in parts in a row that did not pay
  bool splittingPays_ = true;
  // A helper searches the branches of the derivation it helps (its string and index).
  const Derivation* helped_ = nullptr;
  void appendValues(const Production& p, const double* values, ModuleString& out);
  ModuleString& levelBuffer(int level);
  bool ruleContextsMatch(const Production& p, const Lsystem& l, const ModuleString& s,
                         std::size_t at, std::size_t end, bool inMainString, std::size_t anchor,
                         double* frame) const;
  // Whether `p` would rewrite here (for the maximum-depth warning).
  bool wouldApply(const Production& p, const Lsystem& l, const ModuleString& s, std::size_t at,
                  std::size_t end, bool inMainString, std::size_t anchor, double* frame);
  // Applies the first matching rule of `set` (1 decomposition, 2 homomorphism) at `at` in `s`,
  // recursively to its successor; results go to `out`. `anchor` is the position in the derived
  // string whose contexts count when `s` is not that string.
  bool applyAt(int set, int lsystem, const ModuleString& s, std::size_t at, bool inMainString,
               std::size_t anchor, int level, std::size_t& end, ModuleSink& out);
  void decompose(const ModuleString& from, ModuleString& into);
  void trackSubLsystems(const ModuleString& s, std::size_t from, std::size_t to,
                        std::vector<int>& stack) const;
  void checkSize(const ModuleString& s, const SourceLocation& where);
  std::size_t skipCut(const ModuleString& s, std::size_t at) const;

  const Program& program_;
  Evaluator& evaluator_;
  Diagnostics& diagnostics_;
  DerivationOptions options_;
  ModuleString current_, next_;
  std::vector<std::vector<std::size_t>> frameOffsets_;
  std::vector<double> frames_;
  // Productions already warned about reaching the maximum depth: an exploding homomorphism meets
  // the limit once per module, and the message is built only the first time.
  std::unordered_set<const Production*> depthWarned_;
  Rand48 choice_;  // cpfg's drand48 stream for stochastic productions
  int stepsDone_ = 0;
  int totalSteps_ = 0;
  bool started_ = false;
  bool stopped_ = false;
  bool hasDecomposition_ = false;
  std::function<void(Derivation&)> queryPass_;
  std::vector<std::array<bool, 128>> isCopiedAsIs_;  // per L-system: symbols without productions
  const ModuleString* contextString_ = &current_;    // where rules find their contexts
  std::vector<int> subLsystems_;                     // the L-system stack while scanning the string
  std::vector<Match> candidates_;
  std::vector<double> weights_;            // the candidates' weights, beside candidates_
  std::deque<ModuleString> levelBuffers_;  // successors by recursion level (stable references)
  // The last step's sink while it streams (runStreamingLastStep), and the modules it has had.
  ModuleSink* stream_ = nullptr;
  std::size_t streamed_ = 0;
  void streamIfFull();
  mutable BranchIndex branches_;  // of current_; cleared whenever current_ changes
  // The rewriting pass's left neighbours: for every position, the module a left context is
  // compared with, carried forward in one pass instead of searched backwards per module.
  struct LeftNeighbours {
    bool enabled = false;
    std::size_t trackedTo = 0;              // modules before this are accounted for
    std::size_t last = BranchIndex::kNone;  // the neighbour of position trackedTo
    std::vector<std::size_t> open;          // `last` at each enclosing `[`
    void reset(const Program& program);
    std::size_t before(const ModuleString& s, const Lsystem& l, std::size_t at);
    // Accounts for the module at q, of symbol c, as the search passes it: `last` becomes the
    // neighbour of the module after it. Static, so that a loop may keep `last` in a register.
    static void pass(std::size_t q, char c, const Lsystem& l, std::size_t& last,
                     std::vector<std::size_t>& open) {
      if (l.ignored[static_cast<unsigned char>(c)]) return;
      if (c == '[') {
        open.push_back(last);  // inside the branch the parent's module is to the left
      } else if (c == ']') {
        // Past the branch, the module before its `[` is; an unpaired `]` stops every search.
        if (open.empty()) {
          last = BranchIndex::kNone;
        } else {
          last = open.back();
          open.pop_back();
        }
      } else {
        last = q;
      }
    }
  };
  LeftNeighbours leftNeighbours_;
  // A part's left neighbours where it starts, found by rewriteInParts on its way to the part's
  // boundary: rewriteRange from there starts with them instead of passing over the string again.
  LeftNeighbours partStart_;
  bool partStartKnown_ = false;
  // Whether the parts of a step search the string's branches through its index: some production
  // has a right context, a left context of more than one module, or a left context that the
  // left neighbours do not answer. Otherwise the index is not built for them.
  bool partsSearchBranches() const;
  // Symbols of the main L-system whose every production needs a left context (and one strict
  // module): such a module whose left neighbour is none of `leftLast_[symbol]`, the symbols
  // those contexts end with, cannot be rewritten and joins the run copied as it is.
  std::array<bool, 128> needsLeft_{};
  std::array<std::bitset<128>, 128> leftLast_{};
  bool leftRefuses(const ModuleString& s, const Lsystem& l, std::size_t at);
  // The one L-system's rewriting in a single scan (no sub-L-systems, not stochastic): runs
  // copied as they are, left neighbours carried along, and the modules below rewritten on the
  // spot; the loop stops where choose() must decide.
  bool fusedScan_ = false;
  // Symbols whose first production that a module without parameters can meet applies to it
  // unconditionally (one strict module without parameters, no context, no condition or block,
  // a successor without computed values): such a module is replaced by that production's
  // successor bytes without choose(). The index is into the production set, -1 for none.
  std::array<int, 128> plainSuccessor_{};
  // The same for a module without parameters whose every production needs a left context, by
  // its left neighbour's symbol (a neighbour without parameters): the production choose() would
  // apply when it is plain but for a left context of that one module, -1 when choose() must
  // decide. contextSuccessors_[contextTable_[symbol]][neighbour]; contextTable_ is -1 for a
  // symbol without such a table.
  std::array<int, 128> contextTable_{};
  std::vector<std::array<int, 128>> contextSuccessors_;
  void scanRun(const ModuleString& s, const Lsystem& l, std::size_t to, std::size_t& pos,
               std::size_t& runFrom, std::size_t& runCount);
  std::size_t ruleOutput_ = 0;  // modules decomposition or homomorphism produced in this pass
};

}  // namespace hirsute
