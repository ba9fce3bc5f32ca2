// Compiled blocks and expressions: a compact stack code, built once by the compiler and run by
// the evaluator (evaluator.h) every time a condition, block or successor is evaluated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hirsute/lsys/diagnostic.h"

namespace hirsute {

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
};

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

}  // namespace hirsute
