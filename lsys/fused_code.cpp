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

// The Local…Local or Local…Constant form of an arithmetic operator (Add … Power, not Modulo).
std::optional<Op> fusedPush(Op op, bool fromConstants) {
  if (op < Op::Add || op > Op::Power || op == Op::Modulo) return std::nullopt;
  int index = static_cast<int>(op) - static_cast<int>(Op::Add);
  if (op > Op::Modulo) --index;
  const Op first = fromConstants ? Op::LocalAddConstant : Op::LocalAddLocal;
  return static_cast<Op>(static_cast<int>(first) + index);
}

// The Unless… form of a fused comparison (EqualLocal … GreaterEqualLocal, EqualConstant …).
std::optional<Op> fusedUnless(Op op) {
  if (op >= Op::EqualLocal && op <= Op::GreaterEqualLocal) {
    return static_cast<Op>(static_cast<int>(Op::UnlessEqualLocal) + static_cast<int>(op) -
                           static_cast<int>(Op::EqualLocal));
  }
  if (op >= Op::EqualConstant && op <= Op::GreaterEqualConstant) {
    return static_cast<Op>(static_cast<int>(Op::UnlessEqualConstant) + static_cast<int>(op) -
                           static_cast<int>(Op::EqualConstant));
  }
  return std::nullopt;
}

bool isLoad(Op op) {
  return op == Op::LoadLocal || op == Op::Constant;
}

}  // namespace

Code fuseInstructions(Code code) {
  const std::vector<Instruction>& in = code.instructions;
  const std::size_t n = in.size();
  if (n == 0) return code;
  std::vector<bool> isTarget(n + 1, false);
  for (const Instruction& i : in) {
    const std::int32_t target = jumpTarget(i);
    if (target >= 0) isTarget[static_cast<std::size_t>(target)] = true;
  }
  // Whether in[i + k] exists and no jump lands on it.
  const auto follows = [&](std::size_t i, std::size_t k) {
    for (std::size_t j = 1; j <= k; ++j)
      if (i + j >= n || isTarget[i + j]) return false;
    return true;
  };
  std::vector<Instruction> out;
  out.reserve(n + 1);
  std::vector<std::int32_t> newIndex(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    newIndex[i] = static_cast<std::int32_t>(out.size());
    const Instruction& here = in[i];
    // local, local or constant, operator: one push of their result.
    if (here.op == Op::LoadLocal && follows(i, 2) && isLoad(in[i + 1].op)) {
      if (const std::optional<Op> fused = fusedPush(in[i + 2].op, in[i + 1].op == Op::Constant)) {
        out.push_back(Instruction{*fused, 0, here.operand, in[i + 2].where, in[i + 1].operand});
        newIndex[i + 1] = newIndex[i + 2] = newIndex[i];
        i += 2;
        continue;
      }
    }
    if (isLoad(here.op) && follows(i, 1)) {
      if (const std::optional<Op> fused = fusedBinary(in[i + 1].op, here.op == Op::Constant)) {
        // local or constant, comparison, JumpIfFalse: one conditional jump.
        const std::optional<Op> unless = fusedUnless(*fused);
        if (unless && follows(i, 2) && in[i + 2].op == Op::JumpIfFalse) {
          out.push_back(Instruction{*unless, 0, here.operand, in[i + 1].where, in[i + 2].operand});
          newIndex[i + 1] = newIndex[i + 2] = newIndex[i];
          i += 2;
          continue;
        }
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
  out.push_back(Instruction{Op::End, 0, 0, in.back().where});
  for (Instruction& i : out) {
    if (i.op == Op::Jump || i.op == Op::JumpIfFalse || i.op == Op::LoopBack) {
      i.operand = newIndex[static_cast<std::size_t>(i.operand)];
    } else if (jumpTarget(i) >= 0) {
      i.operand2 = newIndex[static_cast<std::size_t>(i.operand2)];
    }
  }
  code.instructions = std::move(out);
  return code;
}

}  // namespace hirsute
