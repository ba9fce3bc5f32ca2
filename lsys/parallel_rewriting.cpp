#include "hirsute/lsys/parallel_rewriting.h"

#include <deque>
#include <optional>

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

}  // namespace hirsute
