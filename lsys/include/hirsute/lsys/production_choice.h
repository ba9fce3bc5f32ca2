// Production choice with cpfg's semantics: at a module, the first production in file order whose
// strict predecessor, contexts and condition hold (pre-condition blocks run as they are tested);
// in a stochastic L-system, one of all those that hold, drawn by their weights from cpfg's
// drand48 stream, which advances once for every module of the string. ChoiceTables holds what
// choice decides from a module's symbol (and its left neighbour's) alone, for the rewriting loop
// to apply without asking.
#pragma once

#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hirsute/lsys/context_matching.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/module_string.h"
#include "hirsute/lsys/program.h"
#include "hirsute/lsys/random_streams.h"

namespace hirsute {

// An L-system's rule sets by number: 0 productions, 1 decomposition, 2 homomorphism.
inline const RuleSet& ruleSet(const Lsystem& l, int set) {
  return set == 0 ? l.productions : set == 1 ? l.decomposition : l.homomorphism;
}

// Whether a module `m` of p's first strict module's parameter count fails p's guard, and so its
// condition (Production::guard).
inline bool guardRefuses(const Production& p, ModuleRef m) {
  for (const ParameterTest& test : p.guard) {
    if (!test.holds(m.parameter(test.parameter))) return true;
  }
  return false;
}

// One frame of variables for every production of every rule set, kept between uses as cpfg
// keeps a production's variables (a block may read what the last module left).
class ProductionFrames {
 public:
  explicit ProductionFrames(const Program& program);
  double* of(int lsystem, int set, std::size_t production) {
    return frames_.data() + offsets_[static_cast<std::size_t>(lsystem * 3 + set)][production];
  }

 private:
  std::vector<std::vector<std::size_t>> offsets_;  // by L-system and set, then production
  std::vector<double> frames_;
};

// A production chosen at a module.
struct Match {
  const Production* production = nullptr;
  std::size_t end = 0;      // position after the strict predecessor
  double* frame = nullptr;  // its variables, the predecessor's and contexts' parameters bound
};

// Chooses the production of an L-system's productions (rule set 0) to apply at a module.
class ProductionChoice {
 public:
  ProductionChoice(const Program& program, Evaluator& evaluator, ProductionFrames& frames,
                   const ContextMatcher& matcher);

  // Finds the production to apply at `at` in `s`, running pre-condition blocks and conditions;
  // false when none applies. `neighbours`: the rewriting pass's left neighbours, asked only when
  // a production has a left context and they are enabled.
  bool choose(int lsystem, const ModuleString& s, std::size_t at, LeftNeighbours& neighbours,
              Match& match);
  // The stochastic stream's next number, drawn for a module whose choice the rewriting loop
  // makes itself (ChoiceTables::drawnTable), as choose() would have drawn it.
  double draw() { return stream_.next(); }
  // n draws whose numbers nobody reads (modules no production can rewrite), at the cost of one.
  void skipDraws(std::uint64_t n) { stream_.skip(n); }
  // The production of `ids` (one strict module each, without context, block or condition, of
  // the parameter count of `m`) that choose() takes for `m` with `draw`: each bound to `m` and
  // weighed in file order, as choose() binds and weighs them.
  std::uint32_t weigh(const std::vector<std::uint32_t>& ids, ModuleRef m, double draw);

 private:
  // A stochastic production's weight (`: w`) in its frame.
  double weightOf(const Production& p, double* frame);

  const Program& program_;
  Evaluator& evaluator_;
  ProductionFrames& frames_;
  const ContextMatcher& matcher_;
  Rand48 stream_;                  // cpfg's drand48 stream for stochastic productions
  std::vector<Match> candidates_;  // reused: no allocation per module
  std::vector<double> weights_;    // the candidates' weights, beside candidates_
};

// What production choice decides in the main L-system from a module's symbol, and its left
// neighbour's, alone: tables that the rewriting loop reads to copy or replace a module without
// calling choose().
struct ChoiceTables {
  // `plainSuccessors`: fill plainSuccessor and the context tables (a program of one L-system,
  // not stochastic, where a module's choice depends on nothing before it in the step).
  ChoiceTables(const Program& program, bool plainSuccessors);

  // Per L-system: symbols no production starts with, copied as they are, but for the cut and
  // the sub-L-system brackets, which the loop must see.
  std::vector<std::array<bool, 128>> copiedAsIs;
  // Symbols of the main L-system whose every production needs a left context (and one strict
  // module): such a module whose left neighbour is none of `leftLast[symbol]`, the symbols
  // those contexts end with, cannot be rewritten and joins the run copied as it is.
  std::array<bool, 128> needsLeft{};
  std::array<std::bitset<128>, 128> leftLast{};
  // Symbols whose first production that a module without parameters can meet applies to it
  // unconditionally (one strict module without parameters, no context, no condition or block,
  // a successor without computed values): such a module is replaced by that production's
  // successor bytes without choose(). The index is into the production set, -1 for none.
  std::array<int, 128> plainSuccessor{};
  // The same for a module without parameters whose every production needs a left context, by
  // its left neighbour's symbol (a neighbour without parameters): the production choose() would
  // apply when it is plain but for a left context of that one module, -1 when choose() must
  // decide. contextSuccessors[contextTable[symbol]][neighbour]; contextTable is -1 for a
  // symbol without such a table.
  std::array<int, 128> contextTable{};
  std::vector<std::array<int, 128>> contextSuccessors;
  // Symbols whose every production is one strict module with a left context of one module and
  // no right context: the loop, which knows the left neighbour, tests them itself as choose()
  // would (parameter counts, the neighbour, the bindings, blocks and conditions, in file order).
  std::array<bool, 128> leftOnly{};
  // Of the main L-system, by symbol * 128 + its left neighbour's symbol (0 for no neighbour):
  // whether a module is copied as it is whatever its parameters, because no production starts
  // with its symbol or because every one needs a left context that the neighbour cannot end.
  std::vector<std::uint8_t> quiet;
  // Symbols of the main L-system whose every production is one strict module with a guard
  // (Production::guard): a module with parameters that every production of its parameter count
  // refuses by its guard joins the run copied as it is, its neighbour untested. The guards of a
  // symbol's productions, up to two tests each (fewer tests refuse less, never wrongly):
  struct GuardedProduction {
    std::size_t parameterCount = 0;
    std::size_t tests = 0;
    std::array<ParameterTest, 2> test{};
  };
  std::array<bool, 128> guardedOnly{};
  std::array<std::vector<GuardedProduction>, 128> guards;
  bool guardsRefuse(unsigned char symbol, ModuleRef m) const {
    const std::size_t count = m.parameterCount();
    for (const GuardedProduction& g : guards[symbol]) {
      if (g.parameterCount != count) continue;
      bool refused = false;
      for (std::size_t i = 0; i < g.tests; ++i) refused |= !g.test[i].holds(m.parameter(g.test[i].parameter));
      if (!refused) return false;
    }
    return true;
  }

  // A stochastic program of one L-system: the productions a module of a symbol and parameter
  // count meets, when every production of the symbol is one strict module without context,
  // pre-condition block or condition. choose() would draw, keep those productions in file order
  // and take the first whose running sum of weights exceeds the draw times their sum: the loop
  // does the same, from the sums made here, added in the same order, when every weight is a
  // number (weighed), else weighing each production at the module (ProductionChoice::weigh).
  struct DrawnChoice {
    std::size_t parameterCount = 0;
    std::vector<std::uint32_t> ids;   // in file order; empty: no production applies
    std::vector<double> accumulated;  // the running sums of their weights, when weighed
    bool weighed = true;
  };
  // drawnChoices[drawnTable[symbol]], one entry a parameter count that some production wants;
  // drawnTable is -1 for a symbol choose() must decide.
  std::array<int, 128> drawnTable{};
  std::vector<std::vector<DrawnChoice>> drawnChoices;

  // The production of `choice` that a draw of `draw` takes, as choose() takes it.
  static std::uint32_t drawnProduction(const DrawnChoice& choice, double draw) {
    const std::size_t n = choice.accumulated.size();
    const double r = draw * choice.accumulated[n - 1];
    for (std::size_t i = 0; i + 1 < n; ++i)
      if (r < choice.accumulated[i]) return choice.ids[i];
    return choice.ids[n - 1];
  }

  // Whether choose() would refuse the module at `at` on its left neighbour alone, as it does
  // before binding or evaluating anything: every production of the symbol needs a left context,
  // and the neighbour ends none of them (or there is none).
  bool leftRefuses(const ModuleString& s, std::size_t at, LeftNeighbours& neighbours) const {
    const auto c = static_cast<unsigned char>(s.at(at).symbol());
    if (!needsLeft[c]) return false;
    const std::size_t neighbour = neighbours.before(s, at);
    return neighbour == BranchIndex::kNone ||
           !leftLast[c].test(static_cast<unsigned char>(s.at(neighbour).symbol()));
  }
};

}  // namespace hirsute
