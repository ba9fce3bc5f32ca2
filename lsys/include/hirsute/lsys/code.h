// Compiled blocks and expressions: a compact stack code, built once by the compiler and run by
// the evaluator (evaluator.h) every time a condition, block or successor is evaluated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hirsute/lsys/diagnostic.h"

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
};
// clang-format on

struct Instruction {
  Op op;
  std::uint8_t count = 0;
  std::int32_t operand = 0;
  std::uint32_t where = 0;  // index into Program::locations
};

struct Code {
  std::vector<Instruction> instructions;
  std::vector<double> constants;
  int maxStack = 0;  // deepest stack the code needs
  bool empty() const { return instructions.empty(); }
};

// Rewrites `code` with fewer instructions and the same results, errors and locations: a load
// of a local or a constant followed by a binary operator becomes one …Local or …Constant
// instruction (unless a jump lands on the operator), and calls of sin, cos, sqrt, fabs, exp and
// log become their own instructions. Jump targets are renumbered.
Code fuseInstructions(Code code);

}  // namespace hirsute
