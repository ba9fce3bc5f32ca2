// Compiled blocks and expressions: a compact stack code, built once by the compiler and run by
// the evaluator (evaluator.h) every time a condition, block or successor is evaluated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

// clang-format off
enum class Op : std::uint8_t {
  Constant,      // push constants[operand]
  LoadLocal,     // push frame[operand]
  StoreLocal,    // frame[operand] = pop
  LoadShared,    // push shared[operand]   (L-system and global variables)
  StoreShared,   // shared[operand] = pop
  LoadElement,   // pops `count` subscripts, pushes arrays[operand][...]
  StoreElement,  // pops value, then `count` subscripts; stores into arrays[operand]
  Pop,
  Negate, Not, Truth,
  Add, Subtract, Multiply, Divide, Modulo, Power,
  Equal, NotEqual, Less, LessEqual, Greater, GreaterEqual,
  Jump,          // pc = operand
  JumpIfFalse,   // pops; pc = operand when zero
  LoopBack,      // pc = operand, counting iterations against the loop limit
  Call,          // builtin `operand` with `count` arguments popped; pushes the result
  Scan,          // fscanf: pops the file id; pushes the count read, then values n..1 (`count` = n);
                 // string operand = the format (in the string table)
  // Made by fuseInstructions: a binary operator whose right operand is frame[operand] (…Local)
  // or constants[operand] (…Constant) instead of a pushed value; Add … GreaterEqual without
  // Modulo, in that order.
  AddLocal, SubtractLocal, MultiplyLocal, DivideLocal, PowerLocal,
  EqualLocal, NotEqualLocal, LessLocal, LessEqualLocal, GreaterLocal, GreaterEqualLocal,
  AddConstant, SubtractConstant, MultiplyConstant, DivideConstant, PowerConstant,
  EqualConstant, NotEqualConstant, LessConstant, LessEqualConstant, GreaterConstant,
  GreaterEqualConstant,
  // Calls of one-argument math built-ins, applied in place (as applyMathBuiltin computes them).
  CallSin, CallCos, CallSqrt, CallFabs, CallExp, CallLog,
  // The end of the code: fuseInstructions puts one after the last instruction of code that has
  // any, so that the evaluator tests for the end only here (a jump past the end lands on it).
  End,
  // Made by fuseInstructions: push frame[operand] op frame[operand2] (…Local) or
  // frame[operand] op constants[operand2] (…Constant); Add … Power without Modulo, in order.
  LocalAddLocal, LocalSubtractLocal, LocalMultiplyLocal, LocalDivideLocal, LocalPowerLocal,
  LocalAddConstant, LocalSubtractConstant, LocalMultiplyConstant, LocalDivideConstant,
  LocalPowerConstant,
  // Made by fuseInstructions: a comparison of the top value with frame[operand] (…Local) or
  // constants[operand] (…Constant), popped, then a jump to operand2 when it is false; Equal …
  // GreaterEqual in order.
  UnlessEqualLocal, UnlessNotEqualLocal, UnlessLessLocal, UnlessLessEqualLocal,
  UnlessGreaterLocal, UnlessGreaterEqualLocal,
  UnlessEqualConstant, UnlessNotEqualConstant, UnlessLessConstant, UnlessLessEqualConstant,
  UnlessGreaterConstant, UnlessGreaterEqualConstant,
};
// clang-format on

struct Instruction {
  Op op;
  std::uint8_t count = 0;
  std::int32_t operand = 0;
  std::uint32_t where = 0;     // index into Program::locations
  std::int32_t operand2 = 0;  // the second operand of the fused Local… and Unless… forms
};

// The machine code of a Code (native_code.h), when it has one.
struct NativeFrame;
using NativeFunction = std::int64_t (*)(NativeFrame*);

struct Code {
  std::vector<Instruction> instructions;
  std::vector<double> constants;
  int maxStack = 0;  // deepest stack the code needs
  NativeFunction native = nullptr;  // set by compileNativeCode; run instead of the instructions
  bool empty() const { return instructions.empty(); }
};

// Rewrites `code` with fewer instructions and the same results, errors and locations, and puts
// Op::End after its last instruction (code with none stays empty):
// - a load of a local or a constant followed by a binary operator becomes one …Local or
//   …Constant instruction;
// - a load of a local followed by a load of a local or a constant and an arithmetic operator
//   becomes one Local…Local or Local…Constant instruction;
// - a comparison with a local or a constant followed by JumpIfFalse becomes one Unless…;
// - calls of sin, cos, sqrt, fabs, exp and log become their own instructions.
// Nothing is fused over an instruction a jump lands on. Jump targets are renumbered.
Code fuseInstructions(Code code);

// Where an instruction may jump (Jump, JumpIfFalse, LoopBack and the Unless… forms), or -1.
inline std::int32_t jumpTarget(const Instruction& in) {
  if (in.op == Op::Jump || in.op == Op::JumpIfFalse || in.op == Op::LoopBack) return in.operand;
  if (in.op >= Op::UnlessEqualLocal && in.op <= Op::UnlessGreaterEqualConstant) return in.operand2;
  return -1;
}

// Whether the next instruction (or, after the last, the end) may come after this one: every
// instruction but Jump and LoopBack.
inline bool fallsThrough(Op op) { return op != Op::Jump && op != Op::LoopBack; }

// The frame slots an instruction reads, -1 where none: {first, second}.
struct SlotsRead {
  std::int32_t first = -1, second = -1;
};
inline SlotsRead slotsRead(const Instruction& in) {
  const Op op = in.op;
  if (op == Op::LoadLocal || (op >= Op::AddLocal && op <= Op::GreaterEqualLocal) ||
      (op >= Op::UnlessEqualLocal && op <= Op::UnlessGreaterEqualLocal) ||
      (op >= Op::LocalAddConstant && op <= Op::LocalPowerConstant)) {
    return {in.operand, -1};
  }
  if (op >= Op::LocalAddLocal && op <= Op::LocalPowerLocal) return {in.operand, in.operand2};
  return {};
}

}  // namespace hirsute
