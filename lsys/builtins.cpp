#include "hirsute/lsys/builtins.h"

namespace hirsute {
namespace {

// cpfg's built-ins (cpfg-features.md (c)); angles are degrees.
constexpr BuiltinInfo kBuiltins[] = {
    {"sin", Builtin::Sin, 1, 1, 0},       {"cos", Builtin::Cos, 1, 1, 0},
    {"tan", Builtin::Tan, 1, 1, 0},       {"asin", Builtin::Asin, 1, 1, 0},
    {"acos", Builtin::Acos, 1, 1, 0},     {"atan", Builtin::Atan, 1, 2, 0},
    {"exp", Builtin::Exp, 1, 1, 0},       {"log", Builtin::Log, 1, 1, 0},
    {"sqrt", Builtin::Sqrt, 1, 1, 0},     {"fabs", Builtin::Fabs, 1, 1, 0},
    {"floor", Builtin::Floor, 1, 1, 0},   {"ceil", Builtin::Ceil, 1, 1, 0},
    {"sign", Builtin::Sign, 1, 1, 0},     {"trunc", Builtin::Trunc, 1, 1, 0},
    {"ran", Builtin::Ran, 1, 1, 0},       {"nran", Builtin::Nran, 2, 2, 0},
    {"bran", Builtin::Bran, 2, 2, 0},     {"biran", Builtin::Biran, 2, 2, 0},
    {"srand", Builtin::Srand, 1, 1, 0},   {"func", Builtin::Func, 2, 2, 0},
    {"curveX", Builtin::CurveX, 2, 2, 0}, {"curveY", Builtin::CurveY, 2, 2, 0},
    {"curveZ", Builtin::CurveZ, 2, 2, 0}, {"curveGAL", Builtin::CurveGal, 1, 1, 0},
    {"printf", Builtin::Printf, 1, -1, 0x1},
    {"fopen", Builtin::Fopen, 2, 2, 0x3},
    {"fclose", Builtin::Fclose, 1, 1, 0},
    {"fflush", Builtin::Fflush, 1, 1, 0},
    {"fprintf", Builtin::Fprintf, 2, -1, 0x2},
    {"fscanf", Builtin::Fscanf, 2, -1, 0x2},
    {"stop", Builtin::Stop, 0, 1, 0},
};

constexpr std::string_view kUnsupported[] = {
    "atan2",     "inblob",   "vvXmin", "vvXmax", "vvYmin",
    "vvYmax",    "vvZmin",   "vvZmax", "vvScale", "SetDerivationLength",
    "GetDerivationLength", "Display", "play",
};

}  // namespace

const BuiltinInfo* findBuiltin(std::string_view name) {
  for (const BuiltinInfo& b : kBuiltins) {
    if (name == b.name) return &b;
  }
  return nullptr;
}

bool isUnsupportedBuiltin(std::string_view name) {
  for (std::string_view n : kUnsupported) {
    if (n == name) return true;
  }
  return false;
}

}  // namespace hirsute
