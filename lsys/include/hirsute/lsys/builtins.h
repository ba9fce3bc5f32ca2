// The built-in functions of cpfg's block language, as the compiler resolves them.
#pragma once

#include <cstdint>
#include <string_view>

namespace hirsute {

enum class Builtin : std::uint8_t {
  Sin, Cos, Tan, Asin, Acos, Atan, Exp, Log, Sqrt, Fabs, Floor, Ceil, Sign, Trunc,
  Ran, Nran, Bran, Biran, Srand,
  Func, CurveX, CurveY, CurveZ, CurveGal,
  Printf, Fopen, Fclose, Fflush, Fprintf, Fscanf,
  Stop,
};

struct BuiltinInfo {
  const char* name;
  Builtin id;
  int minArguments;
  int maxArguments;          // -1: any number
  std::uint32_t stringMask;  // bit i set: argument i must be a string literal
};

// nullptr when `name` is not a built-in function.
const BuiltinInfo* findBuiltin(std::string_view name);

// The math built-ins, Sin … Trunc, of their arguments (angles in degrees, as cpfg's): the
// evaluator's, the compiler's constant folding's and the machine code's (evaluator.cpp).
double applyMathBuiltin(Builtin b, const double* args, int count);
inline bool isMathBuiltin(Builtin id) { return id <= Builtin::Trunc; }

// Names cpfg reserves for functions Hirsute does not provide (they get a clear error).
bool isUnsupportedBuiltin(std::string_view name);

}  // namespace hirsute
