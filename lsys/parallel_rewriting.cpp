#include "hirsute/lsys/parallel_rewriting.h"

#include <algorithm>
#include <deque>
#include <exception>
#include <optional>
#include <system_error>
#include <thread>

#include "hirsute/lsys/builtins.h"

namespace hirsute {
namespace {

// Built-ins whose result depends on their arguments alone and that touch nothing else. `func`
// warns about an unknown function id: a warning makes the parallel step give way to the
// sequential one, which warns in order.
bool isPure(Builtin id) {
  switch (id) {
    case Builtin::Ran:
    case Builtin::Nran:
    case Builtin::Bran:
    case Builtin::Biran:
    case Builtin::Srand:
    case Builtin::Printf:
    case Builtin::Fopen:
    case Builtin::Fclose:
    case Builtin::Fflush:
    case Builtin::Fprintf:
    case Builtin::Fscanf:
    case Builtin::Stop:
      return false;
    default:
      return true;
  }
}

// What in `code` can reach beyond the module being rewritten, in words; empty when nothing.
std::string sideEffectOf(const Code& code, const Program& program) {
  for (const Instruction& in : code.instructions) {
    switch (in.op) {
      case Op::StoreShared:
        return "a block writes the global variable " +
               program.sharedNames[static_cast<std::size_t>(in.operand)];
      case Op::StoreElement:
        return "a block writes the array " +
               program.arrays[static_cast<std::size_t>(in.operand)].name;
      case Op::Scan:
        return "a block reads a file";
      case Op::Call:
        if (!isPure(static_cast<Builtin>(in.operand))) {
          return "a block calls a function with effects (random numbers, files, printing or "
                 "stop)";
        }
        break;
      default:
        break;
    }
  }
  return {};
}

bool hasSymbol(const std::vector<SuccessorModule>& modules, char symbol) {
  for (const SuccessorModule& m : modules)
    if (m.symbol == symbol) return true;
  return false;
}

}  // namespace

bool readsOnlyWrittenSlots(const Code& code, std::vector<char>& written) {
  const std::size_t n = code.instructions.size();
  // The slots written on every path to each instruction (index n: the end); nullopt: no path
  // reaches it yet.
  std::vector<std::optional<std::vector<char>>> in(n + 1);
  in[0] = written;
  std::deque<std::size_t> work{0};
  const auto flow = [&](std::size_t to, const std::vector<char>& state) {
    if (to > n) to = n;
    if (!in[to]) {
      in[to] = state;
      work.push_back(to);
      return;
    }
    bool changed = false;
    for (std::size_t s = 0; s < state.size(); ++s) {
      if ((*in[to])[s] && !state[s]) {
        (*in[to])[s] = 0;
        changed = true;
      }
    }
    if (changed) work.push_back(to);
  };
  while (!work.empty()) {
    const std::size_t pc = work.front();
    work.pop_front();
    if (pc == n) continue;
    std::vector<char> state = *in[pc];
    const Instruction& instruction = code.instructions[pc];
    const SlotsRead reads = slotsRead(instruction);
    for (const std::int32_t read : {reads.first, reads.second}) {
      if (read >= 0 && (static_cast<std::size_t>(read) >= state.size() || !state[read])) return false;
    }
    if (instruction.op == Op::StoreLocal) {
      const auto slot = static_cast<std::size_t>(instruction.operand);
      if (slot >= state.size()) state.resize(slot + 1, 0);
      state[slot] = 1;
    }
    const std::int32_t target = jumpTarget(instruction);
    if (target >= 0) flow(static_cast<std::size_t>(target), state);
    if (fallsThrough(instruction.op)) flow(pc + 1, state);
  }
  // Code whose end no path reaches (it cannot end without an error) writes every slot.
  if (in[n]) written = *in[n];
  return true;
}

bool rewritesModulesIndependently(const Program& program, std::string* why) {
  const auto refuse = [&](std::string reason) {
    if (why) *why = std::move(reason);
    return false;
  };
  if (program.lsystems.size() != 1) return refuse("the file has sub-L-systems");
  const Lsystem& l = program.lsystems.front();
  if (l.stochastic) return refuse("the productions are stochastic (one random stream in order)");
  // A cut removes the rest of its branch, reaching over any boundary between parts.
  bool cuts = hasSymbol(l.axiom, '%');
  for (const RuleSet* rules : {&l.productions, &l.decomposition})
    for (const Production& p : rules->productions) cuts = cuts || hasSymbol(p.successor, '%');
  if (cuts) return refuse("the string can hold a cut (%)");
  for (const Production& p : l.productions.productions) {
    if (p.strict.size() != 1) {
      return refuse("a production's strict predecessor has more than one module");
    }
    for (const Code* code : {&p.before, &p.condition, &p.after, &p.successorValues}) {
      std::string effect = sideEffectOf(*code, program);
      if (!effect.empty()) return refuse(effect);
    }
    // The production's variables keep their values from one module to the next; every one its
    // code reads must have been written for the module at hand: bound to a parameter, or set
    // before it is read on every path.
    std::vector<char> written(static_cast<std::size_t>(p.frameSize), 0);
    for (const auto* patterns : {&p.left, &p.strict, &p.right})
      for (const ModulePattern& pattern : *patterns)
        for (int slot : pattern.slots) written[static_cast<std::size_t>(slot)] = 1;
    for (const Code* code : {&p.before, &p.condition, &p.after, &p.successorValues}) {
      if (!readsOnlyWrittenSlots(*code, written)) {
        return refuse(
            "a production's code can read a variable its module has not set (its value "
            "is the one the last module left)");
      }
    }
  }
  return true;
}

ParallelSteps::ParallelSteps(const Program& program, Settings settings, PartFactory makePart)
    : program_(program), settings_(settings), makePart_(std::move(makePart)) {
  modulesIndependent_ = rewritesModulesIndependently(program_);
  for (const Production& p : program_.lsystems.front().productions.productions)
    anyContext_ |= p.hasContext();
  threads_ = settings_.threads > 0 ? settings_.threads
                                   : static_cast<int>(std::thread::hardware_concurrency());
  threads_ = std::clamp(threads_, 1, 64);
}

ParallelSteps::~ParallelSteps() = default;

void ParallelSteps::measured(std::size_t modules, std::size_t produced, std::size_t parts,
                             double nanoseconds) {
  // A short string's step is mostly the step's own fixed costs: it tells nothing.
  if (modules < std::max<std::size_t>(settings_.minimumModules, 1)) return;
  const double cost = nanoseconds / static_cast<double>(modules);
  // A step that grows or shrinks the string by more than an eighth writes into memory no step
  // has touched, and often runs other productions than the steps after it (fourier.l's last
  // growth step turns G into Q, whose blocks cost twice as much): it is not compared with others.
  const bool steady = produced <= modules + modules / 8 && modules <= produced + produced / 8;
  if (parts == 0) {
    stepCost_ = cost;
    if (steady) {
      sequentialCost_ = cost;
      sequentialModules_ = modules;
    }
    remeasure_ = false;
    if (stepsAlone_ > 0) --stepsAlone_;
    return;
  }
  // What the step would have cost one thread, about: the next step is judged by it.
  stepCost_ = cost * static_cast<double>(parts);
  // The step in parts is judged against a steady step on one thread of about its size; without
  // one, the next step runs on one thread to measure it.
  const bool comparable = steady && sequentialCost_ > 0 &&
                          modules <= sequentialModules_ + sequentialModules_ / 8 &&
                          sequentialModules_ <= modules + modules / 8;
  if (!comparable) {
    remeasure_ = true;
    return;
  }
  if (cost > 0.9 * sequentialCost_) {
    // The parts took about as long a module as one thread did (the other cores are busy, or the
    // parts' copying outweighs their work): the next 1, 2, 4, ... 32 steps run on one thread,
    // the first of them measuring again, and splitting is tried after them.
    backOff_ = std::min(backOff_ == 0 ? 1 : 2 * backOff_, kMaxBackOff);
    stepsAlone_ = backOff_;
  } else {
    backOff_ = 0;
  }
}

bool ParallelSteps::splitsNextStep(std::size_t modules) const {
  if (!modulesIndependent_ || threads_ < 2 ||
      modules < std::max<std::size_t>(settings_.minimumModules, 1)) {
    return false;
  }
  return settings_.minimumCost <= 0 ||
         (stepsAlone_ == 0 && !remeasure_ && stepCost_ >= settings_.minimumCost);
}

std::size_t ParallelSteps::rewrite(const ModuleString& s, ModuleString& out,
                                   const ContextMatcher& matcher, int stepsDone) {
  if (!splitsNextStep(s.moduleCount())) return 0;
  const std::size_t parts = std::min(static_cast<std::size_t>(threads_), s.moduleCount());
  // The parts' boundaries: module starts about equally far apart in bytes. The way there carries
  // the left neighbours along, so that no part passes over the string before it again.
  std::vector<std::size_t> bounds{0};
  LeftNeighbours neighbours;
  neighbours.reset(program_);
  std::vector<LeftNeighbours> starts{neighbours};
  const std::uint8_t* const bytes = s.bytes();
  for (std::size_t k = 1, pos = 0; k < parts; ++k) {
    const std::size_t target = s.end() / parts * k;
    if (neighbours.enabled) {
      while (pos < target) {
        const std::uint8_t b = bytes[pos];
        LeftNeighbours::pass(pos, neighbours.kinds[b & 0x7f], neighbours.last, neighbours.depth,
                             neighbours.open);
        pos += (b & 0x80) ? 3 + 4 * static_cast<std::size_t>(bytes[pos + 1]) : 1;
      }
    } else {
      while (pos < target) pos = s.next(pos);
    }
    if (pos > bounds.back() && pos < s.end()) {
      bounds.push_back(pos);
      neighbours.trackedTo = pos;
      starts.push_back(neighbours);
    }
  }
  bounds.push_back(s.end());
  const std::size_t used = bounds.size() - 1;
  while (parts_.size() < used) parts_.push_back(makePart_());
  // Contexts that search the string's branches do it through its index: built here, read by
  // every part (a part never builds it).
  if (anyContext_ && contextsSearchBranches(program_)) matcher.buildIndex();
  std::vector<std::exception_ptr> errors(used);
  std::vector<std::size_t> warningsBefore(used);
  for (std::size_t k = 0; k < used; ++k) {
    parts_[k]->prepare(stepsDone);
    warningsBefore[k] = parts_[k]->warnings();
  }
  const auto rewritePart = [&](std::size_t k) {
    try {
      parts_[k]->rewrite(s, bounds[k], bounds[k + 1], starts[k]);
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
    whole = whole && !errors[k] && parts_[k]->warnings() == warningsBefore[k];
    modules += parts_[k]->string().moduleCount();
  }
  whole = whole && modules <= settings_.maxModules;
  out.clear();
  if (whole) {
    try {
      out.swap(parts_[0]->string());
      for (std::size_t k = 1; k < used; ++k) {
        const ModuleString& part = parts_[k]->string();
        out.appendRange(part, part.begin(), part.end(), part.moduleCount());
      }
    } catch (const ModuleStringTooLarge&) {
      whole = false;
      out.clear();
    }
  }
  // The parts' strings go: the next step's may be of another size.
  for (std::size_t k = 0; k < used; ++k) parts_[k]->string().release();
  if (!whole) return 0;
  ++stepsInParts_;
  return used;
}

}  // namespace hirsute
