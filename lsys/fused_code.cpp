// Superinstructions for the evaluator's stack code (code.h: fuseInstructions). Every instruction
// costs a dispatch; blocks with loops spend most of their time there (models/bench/loops.l).
#include <cstddef>
#include <optional>
#include <vector>

#include "hirsute/lsys/builtins.h"
#include "hirsute/lsys/code.h"

namespace hirsute {
namespace {

// The fused operator for `op` with its right operand in the frame or the constants.
std::optional<Op> fusedBinary(Op op, bool fromConstants) {
  if (op < Op::Add || op > Op::GreaterEqual || op == Op::Modulo) return std::nullopt;
  // Add … Power and Equal … GreaterEqual, without Modulo, in enum order.
  int index = static_cast<int>(op) - static_cast<int>(Op::Add);
  if (op > Op::Modulo) --index;
  const Op first = fromConstants ? Op::AddConstant : Op::AddLocal;
  return static_cast<Op>(static_cast<int>(first) + index);
}

std::optional<Op> fusedCall(const Instruction& in) {
  if (in.op != Op::Call || in.count != 1) return std::nullopt;
  switch (static_cast<Builtin>(in.operand)) {
    case Builtin::Sin:
      return Op::CallSin;
    case Builtin::Cos:
      return Op::CallCos;
    case Builtin::Sqrt:
      return Op::CallSqrt;
    case Builtin::Fabs:
      return Op::CallFabs;
    case Builtin::Exp:
      return Op::CallExp;
    case Builtin::Log:
      return Op::CallLog;
    default:
      return std::nullopt;
  }
}

bool isJump(Op op) {
  return op == Op::Jump || op == Op::JumpIfFalse || op == Op::LoopBack;
}

}  // namespace

Code fuseInstructions(Code code) {
  const std::vector<Instruction>& in = code.instructions;
  const std::size_t n = in.size();
  std::vector<bool> isTarget(n + 1, false);
  for (const Instruction& i : in) {
    if (isJump(i.op)) isTarget[static_cast<std::size_t>(i.operand)] = true;
  }
  std::vector<Instruction> out;
  out.reserve(n);
  std::vector<std::int32_t> newIndex(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    newIndex[i] = static_cast<std::int32_t>(out.size());
    const Instruction& here = in[i];
    if ((here.op == Op::LoadLocal || here.op == Op::Constant) && i + 1 < n && !isTarget[i + 1]) {
      if (const std::optional<Op> fused = fusedBinary(in[i + 1].op, here.op == Op::Constant)) {
        // The operator's location: it is the one that can fail (division by zero).
        out.push_back(Instruction{*fused, 0, here.operand, in[i + 1].where});
        newIndex[i + 1] = newIndex[i];
        ++i;
        continue;
      }
    }
    if (const std::optional<Op> call = fusedCall(here)) {
      out.push_back(Instruction{*call, 0, 0, here.where});
      continue;
    }
    out.push_back(here);
  }
  newIndex[n] = static_cast<std::int32_t>(out.size());
  for (Instruction& i : out) {
    if (isJump(i.op)) i.operand = newIndex[static_cast<std::size_t>(i.operand)];
  }
  code.instructions = std::move(out);
  return code;
}

}  // namespace hirsute
