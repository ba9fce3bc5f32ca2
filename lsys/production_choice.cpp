#include "hirsute/lsys/production_choice.h"

#include <algorithm>

namespace hirsute {
namespace {

// cpfg: seed48({seed, 0, 155}) for a non-zero seed; drand48's unseeded state otherwise.
Rand48 choiceStream(const Lsystem& main) {
  auto seed = main.stochastic ? static_cast<std::uint16_t>(static_cast<long long>(main.seed))
                              : std::uint16_t{0};
  return seed != 0 ? Rand48::seed48(seed, 0, 155) : Rand48(0, 0, 0);
}

// A weight written as a number (`: 3`) is read as it is, without a run of the evaluator.
bool isConstant(const Code& code) {
  return code.instructions.size() == 2 && code.instructions[0].op == Op::Constant &&
         code.instructions[1].op == Op::End;
}

}  // namespace

ProductionFrames::ProductionFrames(const Program& program) {
  std::size_t total = 0;
  for (const Lsystem& l : program.lsystems) {
    for (int set = 0; set < 3; ++set) {
      std::vector<std::size_t> offsets;
      for (const Production& p : ruleSet(l, set).productions) {
        offsets.push_back(total);
        total += static_cast<std::size_t>(p.frameSize);
      }
      offsets_.push_back(std::move(offsets));
    }
  }
  frames_.assign(total + 1, 0.0);
}

ProductionChoice::ProductionChoice(const Program& program, Evaluator& evaluator,
                                   ProductionFrames& frames, const ContextMatcher& matcher)
    : program_(program),
      evaluator_(evaluator),
      frames_(frames),
      matcher_(matcher),
      stream_(choiceStream(program.lsystems.front())) {}

double ProductionChoice::weightOf(const Production& p, double* frame) {
  if (p.probability.empty()) return 1.0;
  if (isConstant(p.probability)) {
    return p.probability.constants[static_cast<std::size_t>(p.probability.instructions[0].operand)];
  }
  return evaluator_.run(p.probability, frame);
}

bool ProductionChoice::choose(int lsystem, const ModuleString& s, std::size_t at,
                              LeftNeighbours& neighbours, Match& match) {
  const Lsystem& l = program_.lsystems[static_cast<std::size_t>(lsystem)];
  const RuleSet& rules = l.productions;
  const bool stochastic = l.stochastic;
  // cpfg draws one number per module of the string in a stochastic L-system, whether or not a
  // production applies there.
  const double draw = stochastic ? stream_.next() : 0.0;
  const auto& ids = rules.bySymbol[static_cast<unsigned char>(s.at(at).symbol())];
  if (ids.empty()) return false;
  candidates_.clear();
  // The left context's neighbour, found once for all productions.
  std::size_t neighbour = ContextMatcher::kUnknownNeighbour;
  std::vector<double>& weights = weights_;
  weights.clear();
  const std::size_t parameterCount = s.at(at).parameterCount();
  for (std::uint32_t id : ids) {
    const Production& p = rules.productions[id];
    // Cheap refusals first: the module's own parameter count, then (with the neighbour known)
    // the last module of the left context. Binding has no effect a refused production sees.
    if (p.strict.size() == 1 && p.strict[0].parameterCount != parameterCount) continue;
    if (!p.guard.empty() && p.strict[0].parameterCount == parameterCount &&
        guardRefuses(p, s.at(at)))
      continue;
    if (!p.left.empty() && neighbours.enabled) {
      if (neighbour == ContextMatcher::kUnknownNeighbour) neighbour = neighbours.before(s, at);
      if (neighbour == BranchIndex::kNone) continue;
      const ModuleRef left = s.at(neighbour);
      const ModulePattern& last = p.left.back();
      if (left.symbol() != last.symbol || left.parameterCount() != last.parameterCount) continue;
    }
    double* frame = frames_.of(lsystem, 0, id);
    std::size_t end = 0;
    if (!matchStrict(p, s, at, end, frame)) continue;
    if (p.hasContext() && !matcher_.matchContexts(p, l, s, at, end, frame, neighbour)) continue;
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

std::uint32_t ProductionChoice::weigh(const std::vector<std::uint32_t>& ids, ModuleRef m,
                                      double draw) {
  const RuleSet& rules = program_.lsystems.front().productions;
  std::vector<double>& weights = weights_;
  weights.clear();
  for (std::uint32_t id : ids) {
    const Production& p = rules.productions[id];
    double* frame = frames_.of(0, 0, id);
    bindParameters(p.strict[0], m, frame);
    weights.push_back(weightOf(p, frame));
  }
  // choose()'s sums and comparisons, in its order.
  double sum = 0;
  for (double w : weights) sum += w;
  const double r = draw * sum;
  double accumulated = 0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    accumulated += weights[i];
    if (r < accumulated) return ids[i];
  }
  return ids.back();
}

ChoiceTables::ChoiceTables(const Program& program, bool plainSuccessors) {
  for (const Lsystem& l : program.lsystems) {
    std::array<bool, 128> copied{};
    for (std::size_t c = 0; c < copied.size(); ++c) copied[c] = l.productions.bySymbol[c].empty();
    copied['%'] = copied['?'] = copied['$'] = false;
    copiedAsIs.push_back(copied);
  }
  const Lsystem& main = program.lsystems.front();
  for (std::size_t c = 0; c < 128; ++c) {
    const auto& ids = main.productions.bySymbol[c];
    if (ids.empty() || c == '%' || c == '?' || c == '$') continue;
    needsLeft[c] = std::all_of(ids.begin(), ids.end(), [&](std::uint32_t id) {
      const Production& p = main.productions.productions[id];
      return !p.left.empty() && p.strict.size() == 1;
    });
    leftOnly[c] = plainSuccessors && std::all_of(ids.begin(), ids.end(), [&](std::uint32_t id) {
                    const Production& p = main.productions.productions[id];
                    return p.left.size() == 1 && p.strict.size() == 1 && p.right.empty();
                  });
    for (std::uint32_t id : ids) {
      const Production& p = main.productions.productions[id];
      if (!p.left.empty()) {
        leftLast[c].set(static_cast<unsigned char>(p.left.back().symbol) & 0x7f);
      }
    }
  }
  quiet.assign(128 * 128, 0);
  for (std::size_t c = 0; c < 128; ++c) {
    const bool copied = copiedAsIs.front()[c];
    for (std::size_t n = 0; n < 128; ++n)
      quiet[c * 128 + n] = copied || (needsLeft[c] && (n == 0 || !leftLast[c].test(n)));
  }
  for (std::size_t c = 0; c < 128; ++c) {
    const auto& ids = main.productions.bySymbol[c];
    if (ids.empty() || c == '%' || c == '?' || c == '$') continue;
    guardedOnly[c] = std::all_of(ids.begin(), ids.end(), [&](std::uint32_t id) {
      const Production& p = main.productions.productions[id];
      return p.strict.size() == 1 && !p.guard.empty();
    });
    if (!guardedOnly[c]) continue;
    for (std::uint32_t id : ids) {
      const Production& p = main.productions.productions[id];
      GuardedProduction g;
      g.parameterCount = p.strict[0].parameterCount;
      g.tests = std::min(p.guard.size(), g.test.size());
      std::copy_n(p.guard.begin(), g.tests, g.test.begin());
      guards[c].push_back(g);
    }
  }
  plainSuccessor.fill(-1);
  for (std::size_t c = 0; plainSuccessors && c < 128; ++c) {
    if (c == '%' || c == '?' || c == '$') continue;
    for (std::uint32_t id : main.productions.bySymbol[c]) {
      const Production& p = main.productions.productions[id];
      // choose() passes over a production whose one module wants parameters.
      if (p.strict.size() == 1 && p.strict[0].parameterCount != 0) continue;
      if (p.strict.size() == 1 && !p.hasContext() && p.before.empty() && p.condition.empty() &&
          p.after.empty() && p.successorValues.empty() && !p.callsSubLsystem) {
        plainSuccessor[c] = static_cast<int>(id);
      }
      break;
    }
  }
  contextTable.fill(-1);
  for (std::size_t c = 0; plainSuccessors && c < 128; ++c) {
    if (!needsLeft[c]) continue;
    std::array<int, 128> successors;
    successors.fill(-1);
    bool any = false;
    for (std::size_t n = 0; n < 128; ++n) {
      if (!leftLast[c].test(n)) continue;
      // choose()'s order: the first production whose module and the left context's last module
      // (the neighbour n, without parameters) do not refuse it.
      for (std::uint32_t id : main.productions.bySymbol[c]) {
        const Production& p = main.productions.productions[id];
        if (p.strict[0].parameterCount != 0) continue;
        const ModulePattern& nearest = p.left.back();
        if (static_cast<unsigned char>(nearest.symbol) != n || nearest.parameterCount != 0)
          continue;
        if (p.left.size() == 1 && p.right.empty() && p.before.empty() && p.condition.empty() &&
            p.after.empty() && p.successorValues.empty() && !p.callsSubLsystem) {
          successors[n] = static_cast<int>(id);
          any = true;
        }
        break;
      }
    }
    if (!any) continue;
    contextTable[c] = static_cast<int>(contextSuccessors.size());
    contextSuccessors.push_back(successors);
  }
  drawnTable.fill(-1);
  const bool drawn = program.lsystems.size() == 1 && main.stochastic;
  for (std::size_t c = 0; drawn && c < 128; ++c) {
    const auto& ids = main.productions.bySymbol[c];
    if (ids.empty() || c == '%' || c == '?' || c == '$') continue;
    const bool plain = std::all_of(ids.begin(), ids.end(), [&](std::uint32_t id) {
      const Production& p = main.productions.productions[id];
      return p.strict.size() == 1 && !p.hasContext() && p.before.empty() && p.condition.empty();
    });
    if (!plain) continue;
    std::vector<DrawnChoice> choices;
    for (std::uint32_t id : ids) {
      const Production& p = main.productions.productions[id];
      const std::size_t count = p.strict[0].parameterCount;
      auto choice = std::find_if(choices.begin(), choices.end(),
                                 [&](const DrawnChoice& d) { return d.parameterCount == count; });
      if (choice == choices.end()) {
        choices.push_back(DrawnChoice{count, {}, {}});
        choice = choices.end() - 1;
      }
      choice->ids.push_back(id);
      if (!p.probability.empty() && !isConstant(p.probability)) choice->weighed = false;
      if (!choice->weighed) continue;
      // weightOf()'s value, added to the sum as choose() adds it.
      const double weight =
          p.probability.empty()
              ? 1.0
              : p.probability
                    .constants[static_cast<std::size_t>(p.probability.instructions[0].operand)];
      const double before = choice->accumulated.empty() ? 0.0 : choice->accumulated.back();
      choice->accumulated.push_back(before + weight);
    }
    drawnTable[c] = static_cast<int>(drawnChoices.size());
    drawnChoices.push_back(std::move(choices));
  }
}

}  // namespace hirsute
