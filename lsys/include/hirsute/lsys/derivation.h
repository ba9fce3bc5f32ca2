// Derivation with cpfg's semantics: parallel rewriting in file order, contexts with
// ignore/consider and branch skipping, conditions and blocks, stochastic choice, decomposition
// after each step, the cut, sub-L-systems, Start/StartEach/EndEach/End; and the homomorphism
// applied when the string is handed to a sink.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <unordered_set>
#include <vector>

#include "hirsute/lsys/context_matching.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/module_sink.h"
#include "hirsute/lsys/module_string.h"
#include "hirsute/lsys/parallel_rewriting.h"
#include "hirsute/lsys/production_choice.h"
#include "hirsute/lsys/program.h"
#include "hirsute/core/progress.h"

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
  // parts. A step in parts that takes as long a module as a steady step of about its size did on
  // one thread sends the next 1, 2, 4, ... 32 such steps to one thread (ParallelSteps::measured);
  // one that pays ends that. Tests set both to 0 to split every step that may be. 60 ns: a block
  // of a few math calls a module (models/bench/fourier.l, about 140 ns) gains 1.7x on two cores;
  // steps that mostly copy and match contexts (about 4 ns a module: leaves.l, signal.l) gain too
  // little over the threads' start and the parts' copy for the measurement to tell them from
  // noise.
  std::size_t parallelMinimumModules = 16384;
  double parallelMinimumCost = 60;
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
    matcher_.stringChanged();
    return current_;
  }

  const Program& program() const { return program_; }
  int stepsDone() const { return stepsDone_; }
  // Steps whose string was rewritten in parts on several threads (DerivationOptions::threads).
  int stepsRewrittenInParts() const { return parallel_.stepsInParts(); }
  int totalSteps() const { return totalSteps_; }
  const ModuleString& string() const { return current_; }

  // Hands every module of the current string to `sink`, after the main L-system's
  // homomorphism when `applyHomomorphism` (recursively, with contexts in the string).
  void emit(ModuleSink& sink, bool applyHomomorphism);

 private:
  class Part;  // a part of a step in parts (ParallelSteps), rewritten by a derivation of its own

  void rewriteStep();
  // Rewrites the modules of `s` from byte `from` up to byte `to` (module starts) into next_;
  // `start`: the left neighbours at `from`, when a part of a step in parts starts there.
  void rewriteRange(const ModuleString& s, std::size_t from, std::size_t to,
                    const LeftNeighbours* start = nullptr);
  // The copying part of the rewriting loop (fusedScan_).
  void scanRun(const ModuleString& s, const Lsystem& l, std::size_t to, std::size_t& pos,
               std::size_t& runFrom, std::size_t& runCount);
  // For ChoiceTables::leftOnly symbols: the production choose() would apply at `module`, whose
  // left neighbour is `neighbour` (its index in the productions), or -1.
  int chooseByNeighbour(const Lsystem& l, const std::uint8_t* module,
                        const std::uint8_t* neighbour);
  // Applies production `id` of the main L-system, chosen by the scan, its frame bound.
  void applyChosen(const Lsystem& l, std::size_t id);
  // The same for a stochastic program of one L-system (drawnScan_): every module draws, as in
  // choose(), and those of tables_.drawnTable are copied or rewritten on the spot.
  void scanDrawn(const ModuleString& s, const Lsystem& l, std::size_t to, std::size_t& pos,
                 std::size_t& runFrom, std::size_t& runCount);
  void appendValues(const Production& p, const double* values, ModuleString& out);
  void checkSize(const ModuleString& s, const SourceLocation& where);
  void streamIfFull();
  std::size_t skipCut(const ModuleString& s, std::size_t at) const;
  void trackSubLsystems(const ModuleString& s, std::size_t from, std::size_t to,
                        std::vector<int>& stack) const;

  // Decomposition and the homomorphism.
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

  const Program& program_;
  Evaluator& evaluator_;
  Diagnostics& diagnostics_;
  DerivationOptions options_;
  ModuleString current_, next_;
  ContextMatcher matcher_{current_};  // searches the branches of current_
  ProductionFrames frames_;
  ProductionChoice choice_;
  // The one L-system's rewriting in a single scan (no sub-L-systems, not stochastic): runs
  // copied as they are, left neighbours carried along, and the modules below rewritten on the
  // spot from tables_; the loop stops where choice_ must decide.
  bool fusedScan_;
  bool drawnScan_;  // one stochastic L-system: scanDrawn
  ChoiceTables tables_;
  LeftNeighbours leftNeighbours_;  // of the rewriting pass
  ParallelSteps parallel_;
  // Productions already warned about reaching the maximum depth: an exploding homomorphism meets
  // the limit once per module, and the message is built only the first time.
  std::unordered_set<const Production*> depthWarned_;
  int stepsDone_ = 0;
  int totalSteps_ = 0;
  bool started_ = false;
  bool stopped_ = false;
  bool hasDecomposition_ = false;
  std::function<void(Derivation&)> queryPass_;
  const ModuleString* contextString_ = &current_;  // where rules find their contexts
  std::vector<int> subLsystems_;                   // the L-system stack while scanning the string
  std::deque<ModuleString> levelBuffers_;  // successors by recursion level (stable references)
  // The last step's sink while it streams (runStreamingLastStep), and the modules it has had.
  ModuleSink* stream_ = nullptr;
  std::size_t streamed_ = 0;
  std::size_t ruleOutput_ = 0;  // modules decomposition or homomorphism produced in this pass
};

}  // namespace hirsute
