// Machine code for the evaluator's stack code (code.h): each code of a program that uses only the
// operations below becomes one x86-64 function, and the evaluator calls it instead of running
// the code instruction by instruction. The results are those of the evaluator to the last bit
// (the same operations in the same order, the same libm calls and power.h), and so are the
// errors: a division by zero and a loop past the limit return the instruction that failed, and
// the evaluator reports it at that instruction's location.
//
// Compiled: constants, locals and global variables loaded and stored, every arithmetic,
// comparison and logical operator but %, jumps and loops, the math built-ins (sin … trunc) and
// every fused form. Left to the evaluator: arrays, %, fscanf and every built-in with effects or
// state (ran, printf, func, …), and so the codes that contain one. On other machines, or where
// memory cannot be made executable, nothing is compiled and the evaluator runs every code.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "hirsute/lsys/code.h"

namespace hirsute {

struct Program;

// What a compiled code reads and writes. `stack` holds the values under the top one as the
// evaluator's stack does (stack[k] is the k-th value from the bottom), and the values left at the
// end, for Evaluator::values().
struct NativeFrame {
  double* frame;
  const double* constants;
  double* shared;
  double* stack;
  std::uint64_t maxIterations;  // of while and do loops, per run
  double result;                // the top value at the end (0 when none)
};

// A NativeFunction (code.h) returns kNativeDone, or the failed instruction's index times two,
// plus one for the loop limit (zero for a division by zero).
inline constexpr std::int64_t kNativeDone = -1;

// The machine code of one program's codes, executable until the object is destroyed.
class NativeCode {
 public:
  virtual ~NativeCode() = default;
};

// Compiles every code of `program` that can be, setting its Code::native, and keeps the machine
// code in program.nativeCode. Does nothing when HIRSUTE_NATIVE_CODE=0 is in the environment, on
// a machine other than x86-64, or when executable memory cannot be had.
void compileNativeCode(Program& program);

// Compiles each of `codes` that can be, setting its Code::native (and clearing the others');
// the machine code lives as long as the object returned (null when none was compiled).
std::shared_ptr<const NativeCode> compileNativeCodes(const std::vector<Code*>& codes);

// Clears every Code::native of `program`: the evaluator runs all of its stack code (tests compare
// the two).
void dropNativeCode(Program& program);

// Whether `code` uses only what compileNativeCode compiles (true for the empty code).
bool compilable(const Code& code);

}  // namespace hirsute
