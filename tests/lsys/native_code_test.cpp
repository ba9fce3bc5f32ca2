// Machine code for the evaluator's stack code (native_code.h): every operation gives the
// evaluator's value to the last bit (NaN, infinities and signed zeros included), the same frame,
// the same values left for values(), and the same errors at the same locations; every model
// derives as the evaluator alone derives it.
#include "hirsute/lsys/native_code.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/lsys/program.h"
#include "hirsute/lsys/string_writer.h"
#include "support/model_corpus.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

constexpr int kSlots = 4;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInfinity = std::numeric_limits<double>::infinity();

#if defined(__x86_64__)
constexpr bool kCompiles = true;
#else
constexpr bool kCompiles = false;
#endif

Program programWithLocations() {
  Program program;
  program.maxStack = 16;
  auto file = std::make_shared<const std::string>("test.l");
  for (int line = 0; line < 64; ++line) program.locations.push_back(SourceLocation{file, line, 1});
  return program;
}

// Bit patterns, so that NaN equals NaN and -0 differs from 0.
std::vector<std::uint64_t> bits(const std::vector<double>& values) {
  std::vector<std::uint64_t> out;
  for (double v : values) out.push_back(std::bit_cast<std::uint64_t>(v));
  return out;
}

struct Outcome {
  std::vector<double> values;  // what values() returns, then the frame
  std::string error;
  int errorLine = -1;
};

Outcome runOn(const Program& program, const Code& code, std::vector<double> frame, int count) {
  Diagnostics diagnostics;
  std::ostringstream printed;
  EvaluationLimits limits;
  limits.maxLoopIterations = 100;
  Evaluator evaluator(program, diagnostics, nullptr, ".", printed, limits);
  frame.resize(kSlots, 0.0);
  Outcome outcome;
  try {
    const double* values = evaluator.values(code, frame.data(), static_cast<std::size_t>(count));
    const double top = evaluator.run(code, frame.data());
    outcome.values.assign(values, values + count);
    outcome.values.push_back(top);
  } catch (const DiagnosticError& e) {
    outcome.error = e.what();
    outcome.errorLine = e.diagnostic().where.line;
  }
  outcome.values.insert(outcome.values.end(), frame.begin(), frame.end());
  return outcome;
}

// Runs `code` (fused) by the evaluator and as machine code on each frame; expects it compiled
// (where the machine allows) and the same outcome to the bit. `count`: values it leaves.
void expectSameOutcomes(Code code, const std::vector<std::vector<double>>& frames, int count = 1) {
  const Program program = programWithLocations();
  code = fuseInstructions(std::move(code));
  Code native = code;
  const auto machineCode = compileNativeCodes({&native});
  ASSERT_EQ(native.native != nullptr, kCompiles);
  for (const std::vector<double>& frame : frames) {
    SCOPED_TRACE(::testing::PrintToString(frame));
    const Outcome expected = runOn(program, code, frame, count);
    const Outcome got = runOn(program, native, frame, count);
    EXPECT_EQ(bits(got.values), bits(expected.values));
    EXPECT_EQ(got.error, expected.error);
    EXPECT_EQ(got.errorLine, expected.errorLine);
  }
}

const std::vector<std::vector<double>> kFrames = {
    {1.5, 2},  {-2, 3},     {0.1, -0.7}, {1e200, 1e200},          {0, -0.0},
    {-0.0, 0}, {kNaN, 1},   {1, kNaN},   {kInfinity, -kInfinity}, {2, 2},
    {3, 0},    {-1e-310, 4}};

// Every operator the code may hold, on two locals, unfused (a, b pushed) and fused with a local
// and with a constant (the constant 2, so that x^2 takes its own path, then 3 and 0.5).
TEST(NativeCode, EveryOperatorGivesTheEvaluatorsBits) {
  for (Op op : {Op::Add, Op::Subtract, Op::Multiply, Op::Divide, Op::Power, Op::Equal, Op::NotEqual,
                Op::Less, Op::LessEqual, Op::Greater, Op::GreaterEqual}) {
    for (double constant : {2.0, 3.0, 0.5, -0.0}) {
      SCOPED_TRACE(static_cast<int>(op));
      SCOPED_TRACE(constant);
      // (a op b) then (b op constant) then (constant op a) on the stack, and a + (b op a).
      Code code;
      code.constants = {constant};
      code.instructions = {
          {Op::LoadLocal, 0, 0, 1},
          {Op::LoadLocal, 0, 1, 2},
          {op, 0, 0, 3},
          {Op::LoadLocal, 0, 1, 4},
          {Op::Constant, 0, 0, 5},
          {op, 0, 0, 6},
          {Op::Constant, 0, 0, 7},
          {Op::LoadLocal, 0, 0, 8},
          {op, 0, 0, 9},
          {Op::LoadLocal, 0, 0, 10},
          {Op::LoadLocal, 0, 1, 11},
          {Op::LoadLocal, 0, 0, 12},
          {op, 0, 0, 13},
          {Op::Add, 0, 0, 14},
      };
      expectSameOutcomes(code, kFrames, 4);
    }
  }
}

TEST(NativeCode, UnaryOperatorsAndMathCallsGiveTheEvaluatorsBits) {
  for (Op op : {Op::Negate, Op::Not, Op::Truth}) {
    Code code;
    code.instructions = {{Op::LoadLocal, 0, 0},
                         {op, 0, 0},
                         {Op::StoreLocal, 0, 2},
                         {Op::LoadLocal, 0, 1},
                         {op, 0, 0}};
    expectSameOutcomes(code, kFrames);
  }
  for (Builtin b : {Builtin::Sin, Builtin::Cos, Builtin::Tan, Builtin::Asin, Builtin::Acos,
                    Builtin::Atan, Builtin::Exp, Builtin::Log, Builtin::Sqrt, Builtin::Fabs,
                    Builtin::Floor, Builtin::Ceil, Builtin::Sign, Builtin::Trunc}) {
    SCOPED_TRACE(static_cast<int>(b));
    Code code;
    code.constants = {3};
    // b(x) + b(y) * 3, so that a call happens with values under it.
    code.instructions = {{Op::LoadLocal, 0, 0}, {Op::Call, 1, static_cast<int>(b)},
                         {Op::LoadLocal, 0, 1}, {Op::Call, 1, static_cast<int>(b)},
                         {Op::Constant, 0, 0},  {Op::Multiply, 0, 0},
                         {Op::Add, 0, 0}};
    expectSameOutcomes(code, kFrames);
  }
  // atan with two arguments.
  Code code;
  code.instructions = {
      {Op::LoadLocal, 0, 0}, {Op::LoadLocal, 0, 1}, {Op::Call, 2, static_cast<int>(Builtin::Atan)}};
  expectSameOutcomes(code, kFrames);
}

// s = 0; i = 1; while (i <= 6) { s = s + sin(i*x)/i + cos(i*y)^2/(i*i) + sqrt(i + fabs(x*y));
// i = i + 1; } then r = s; do { r = r - (r^3 - s)/(3*r^2); j = j + 1 } while (j < 8): loops.l's
// blocks, with x, y in slots 0, 1 and s, i (then r, j) in 2, 3.
TEST(NativeCode, LoopsGiveTheEvaluatorsBits) {
  Code code;
  code.constants = {0, 1, 6, 2, 3, 8};
  code.instructions = {
      {Op::Constant, 0, 0},
      {Op::StoreLocal, 0, 2},
      {Op::Constant, 0, 1},  // 0
      {Op::StoreLocal, 0, 3},
      {Op::LoadLocal, 0, 3},
      {Op::Constant, 0, 2},  // 3
      {Op::LessEqual, 0, 0},
      {Op::JumpIfFalse, 0, 38},
      {Op::LoadLocal, 0, 2},  // 6
      {Op::LoadLocal, 0, 3},
      {Op::LoadLocal, 0, 0},
      {Op::Multiply, 0, 0},  // 9
      {Op::Call, 1, static_cast<int>(Builtin::Sin)},
      {Op::LoadLocal, 0, 3},  // 12
      {Op::Divide, 0, 0},
      {Op::Add, 0, 0},
      {Op::LoadLocal, 0, 3},  // 14
      {Op::LoadLocal, 0, 1},
      {Op::Multiply, 0, 0},  // 17
      {Op::Call, 1, static_cast<int>(Builtin::Cos)},
      {Op::Constant, 0, 3},  // 19
      {Op::Power, 0, 0},
      {Op::LoadLocal, 0, 3},
      {Op::LoadLocal, 0, 3},  // 21
      {Op::Multiply, 0, 0},
      {Op::Divide, 0, 0},
      {Op::Add, 0, 0},  // 24
      {Op::LoadLocal, 0, 3},
      {Op::LoadLocal, 0, 0},
      {Op::LoadLocal, 0, 1},  // 27
      {Op::Multiply, 0, 0},
      {Op::Call, 1, static_cast<int>(Builtin::Fabs)},  // 30
      {Op::Add, 0, 0},
      {Op::Call, 1, static_cast<int>(Builtin::Sqrt)},  // 32
      {Op::Add, 0, 0},
      {Op::StoreLocal, 0, 2},
      {Op::LoadLocal, 0, 3},  // 34
  };
  // The while's body ends with i = i + 1 and the jump back; its exit starts the do loop.
  code.instructions.push_back({Op::Constant, 0, 1});
  code.instructions.push_back({Op::Add, 0, 0});
  code.instructions.push_back({Op::StoreLocal, 0, 3});
  code.instructions.push_back({Op::LoopBack, 0, 4});
  const int exit = static_cast<int>(code.instructions.size());
  code.instructions[7].operand = exit;
  const std::vector<Instruction> doLoop = {
      {Op::LoadLocal, 0, 2},   {Op::StoreLocal, 0, 3}, {Op::Constant, 0, 0},
      {Op::StoreLocal, 0, 1},  // r = s (slot 3), j = 0 (slot 1)
      {Op::LoadLocal, 0, 3},   {Op::LoadLocal, 0, 3},  {Op::Constant, 0, 4},  // body: r - (r^3
      {Op::Power, 0, 0},       {Op::LoadLocal, 0, 2},  {Op::Subtract, 0, 0},  // - s)
      {Op::Constant, 0, 4},    {Op::LoadLocal, 0, 3},  {Op::Constant, 0, 3},  // / (3 * r^2)
      {Op::Power, 0, 0},       {Op::Multiply, 0, 0},   {Op::Divide, 0, 0},
      {Op::Subtract, 0, 0},    {Op::StoreLocal, 0, 3}, {Op::LoadLocal, 0, 1},  // j = j + 1
      {Op::Constant, 0, 1},    {Op::Add, 0, 0},        {Op::StoreLocal, 0, 1},
      {Op::LoadLocal, 0, 1},   {Op::Constant, 0, 5},   {Op::Less, 0, 0},  // while (j < 8)
      {Op::JumpIfFalse, 0, 0}, {Op::LoopBack, 0, 0},   {Op::LoadLocal, 0, 3},
  };
  for (Instruction in : doLoop) code.instructions.push_back(in);
  const int body = exit + 4;
  code.instructions[static_cast<std::size_t>(exit + 25)].operand = exit + 27;
  code.instructions[static_cast<std::size_t>(exit + 26)].operand = body;
  expectSameOutcomes(code, {{0.1, 0.2}, {2.5, 0.3}, {-1, 7}, {0, 0}, {kNaN, 1}, {1e10, -1e10}});
}

// x^2 and x^3 with the exponent a constant (fused into one call) and a local: libm's pow to the
// bit, on bases where pow(x, 2) is not x*x (about one in a thousand; a compiler that knows the
// exponent turns pow(x, 2.0) into x*x).
TEST(NativeCode, SquaresAndCubesAreLibmsPowNotProducts) {
  volatile double two = 2;  // so that std::pow below is libm's
  std::vector<std::vector<double>> frames;
  double x = 0.5;
  while (frames.size() < 200) {
    x = std::nextafter(x * 1.0001, 1.0);
    if (x >= 1) x = 0.5;
    if (std::pow(x, two) != x * x) frames.push_back({x, 2});
  }
  frames.push_back({0x1.2e58da35b50e6p-1, 3});
  for (double exponent : {2.0, 3.0}) {
    Code code;
    code.constants = {exponent};
    code.instructions = {{Op::LoadLocal, 0, 0}, {Op::Constant, 0, 0},  {Op::Power, 0, 0},
                         {Op::LoadLocal, 0, 0}, {Op::LoadLocal, 0, 1}, {Op::Power, 0, 0},
                         {Op::StoreLocal, 0, 2}};
    expectSameOutcomes(code, frames);
  }
  const Program program = programWithLocations();
  Code code;
  code.constants = {2};
  code.instructions = {{Op::LoadLocal, 0, 0}, {Op::Constant, 0, 0}, {Op::Power, 0, 0}};
  code = fuseInstructions(code);
  const auto machineCode = compileNativeCodes({&code});
  for (const std::vector<double>& frame : frames) {
    EXPECT_EQ(runOn(program, code, frame, 1).values[0], std::pow(frame[0], two));
  }
}

// if (x) r = 1; else r = 2; with x a value, not a comparison: NaN is true, both zeros false.
TEST(NativeCode, AConditionOnAValueJumpsAsTheEvaluator) {
  Code code;
  code.constants = {1, 2};
  code.instructions = {
      {Op::LoadLocal, 0, 0},  {Op::JumpIfFalse, 0, 5}, {Op::Constant, 0, 0},
      {Op::StoreLocal, 0, 3}, {Op::Jump, 0, 7},        {Op::Constant, 0, 1},  // 5
      {Op::StoreLocal, 0, 3}, {Op::LoadLocal, 0, 3},                          // 7
  };
  expectSameOutcomes(code, kFrames);
  const Program program = programWithLocations();
  Code fused = fuseInstructions(code);
  const auto machineCode = compileNativeCodes({&fused});
  EXPECT_EQ(runOn(program, fused, {kNaN}, 1).values[0], 1);
  EXPECT_EQ(runOn(program, fused, {-0.0}, 1).values[0], 2);
}

// Division by zero and a loop past the limit fail at the instruction's location, fused or not.
TEST(NativeCode, ErrorsAreTheEvaluatorsAtTheSameLocation) {
  Code divisions;
  divisions.constants = {0, 1};
  divisions.instructions = {
      {Op::LoadLocal, 0, 0, 1},  {Op::LoadLocal, 0, 1, 2}, {Op::Divide, 0, 0, 7},  // fused
      {Op::LoadLocal, 0, 0, 3},  {Op::Constant, 0, 0, 4},  {Op::Divide, 0, 0, 9},  // x/0
      {Op::Add, 0, 0, 5},        {Op::Constant, 0, 1, 6},  {Op::LoadLocal, 0, 1, 8},
      {Op::LoadLocal, 0, 0, 10}, {Op::Multiply, 0, 0, 11}, {Op::Divide, 0, 0, 12},  // 1/(y*x)
  };
  expectSameOutcomes(divisions, {{1, 0}, {1, 2}, {0, 2}, {-0.0, 1}, {kNaN, kNaN}});
  // while (1) { x = x + 1 }: past the limit of 100 iterations.
  Code loop;
  loop.constants = {1};
  loop.instructions = {
      {Op::Constant, 0, 0, 1}, {Op::JumpIfFalse, 0, 6, 2}, {Op::LoadLocal, 0, 0, 3},
      {Op::Constant, 0, 0, 4}, {Op::Add, 0, 0, 5},         {Op::StoreLocal, 0, 0, 6},
  };
  loop.instructions.insert(loop.instructions.begin() + 6, Instruction{Op::LoopBack, 0, 0, 13});
  loop.instructions[1].operand = 7;
  expectSameOutcomes(loop, {{0}});
}

// Code that only the evaluator runs: arrays, %, fscanf, built-ins with effects or state.
TEST(NativeCode, CodeWithArraysModuloOrEffectsIsLeftToTheEvaluator) {
  for (Instruction in : {Instruction{Op::LoadElement, 1, 0}, Instruction{Op::Modulo, 0, 0},
                         Instruction{Op::Call, 0, static_cast<int>(Builtin::Ran)},
                         Instruction{Op::Call, 1, static_cast<int>(Builtin::Printf)}}) {
    Code code;
    code.instructions = {{Op::LoadLocal, 0, 0}, {Op::LoadLocal, 0, 1}, in};
    EXPECT_FALSE(compilable(code));
    Code fused = fuseInstructions(code);
    const auto machineCode = compileNativeCodes({&fused});
    EXPECT_EQ(fused.native, nullptr);
    EXPECT_EQ(machineCode, nullptr);
  }
}

struct Derived {
  std::string text, warnings, error, printed;
  bool operator==(const Derived&) const = default;
};

Derived derive(const Model& model, std::optional<int> steps) {
  Derived out;
  Diagnostics diagnostics;
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  DerivationOptions options;
  options.steps = steps;
  options.threads = 1;
  Derivation derivation(model.program, evaluator, diagnostics, options);
  try {
    derivation.run();
  } catch (const DiagnosticError& e) {
    out.error = e.diagnostic().text();
  }
  out.text = testing::compactString(derivation, model.program);
  for (const Diagnostic& w : diagnostics.warnings()) out.warnings += w.text() + "\n";
  out.printed = printed.str();
  return out;
}

// Every model of the repository (the fixtures, models/, the benchmark kinds cut short) and, when
// present, of cpfg's conformance set: the same string, warnings, printed text and error with the
// machine code as with the evaluator alone.
TEST(NativeCode, EveryModelDerivesAsWithTheEvaluatorAlone) {
  const testing::ModelCorpus corpus(HIRSUTE_SOURCE_DIR, "native",
                                    {{"loops", 19}, {"stochastic", 12}});
  int withCode = 0;
  for (const auto& [lfile, steps] : corpus.models()) {
    SCOPED_TRACE(lfile.string());
    std::optional<Model> model;
    try {
      Diagnostics diagnostics;
      model = loadModel(lfile, testing::viewFor(lfile), diagnostics);
    } catch (const DiagnosticError&) {
      continue;
    }
    withCode += model->program.nativeCode != nullptr;
    const Derived native = derive(*model, steps);
    dropNativeCode(model->program);
    const Derived evaluated = derive(*model, steps);
    EXPECT_EQ(native.text, evaluated.text);
    EXPECT_EQ(native.warnings, evaluated.warnings);
    EXPECT_EQ(native.error, evaluated.error);
    EXPECT_EQ(native.printed, evaluated.printed);
  }
  std::printf("%zu models, %d of them with machine code\n", corpus.models().size(), withCode);
  if (kCompiles) {
    EXPECT_GT(withCode, 20);
  }
}

}  // namespace
}  // namespace hirsute
