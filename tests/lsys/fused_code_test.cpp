// fuseInstructions (code.h): the fused code gives the results, frames and errors of the code as
// the compiler emits it, run instruction by instruction, and fuses what it should.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/program.h"

namespace hirsute {
namespace {

constexpr int kSlots = 4;

// A program whose codes may use up to 16 stack values; location k is line k of "test.l".
Program programWithLocations() {
  Program program;
  program.maxStack = 16;
  auto file = std::make_shared<const std::string>("test.l");
  for (int line = 0; line < 64; ++line) program.locations.push_back(SourceLocation{file, line, 1});
  return program;
}

// The code as the compiler emits it, with only the end added: nothing fused.
Code unfused(Code code) {
  code.instructions.push_back(Instruction{Op::End, 0, 0, 0});
  return code;
}

struct Outcome {
  double value = 0;
  std::vector<double> frame;
};

Outcome runOn(const Program& program, const Code& code, std::vector<double> frame) {
  Diagnostics diagnostics;
  std::ostringstream printed;
  Evaluator evaluator(program, diagnostics, nullptr, ".", printed);
  frame.resize(kSlots, 0.0);
  const double value = evaluator.run(code, frame.data());
  return {value, frame};
}

// Runs `code` unfused and fused on each frame and expects the same value and frame.
void expectSameResults(const Code& code, const std::vector<std::vector<double>>& frames) {
  const Program program = programWithLocations();
  const Code fused = fuseInstructions(code);
  for (const std::vector<double>& frame : frames) {
    const Outcome expected = runOn(program, unfused(code), frame);
    const Outcome got = runOn(program, fused, frame);
    EXPECT_EQ(got.value, expected.value);
    EXPECT_EQ(got.frame, expected.frame);
  }
}

std::vector<Op> opsOf(const Code& code) {
  std::vector<Op> ops;
  for (const Instruction& in : code.instructions) ops.push_back(in.op);
  return ops;
}

// s = 0; i = 1; while (i <= 6) { s = s + x * i / (i * i) - i ^ 2; i = i + 1; }  (x: slot 0,
// s: slot 1, i: slot 2); leaves s.
Code sumLoop() {
  Code code;
  code.constants = {0, 1, 6, 2};
  code.instructions = {
      {Op::Constant, 0, 0},   {Op::StoreLocal, 0, 1},   {Op::Constant, 0, 1},
      {Op::StoreLocal, 0, 2}, {Op::LoadLocal, 0, 2},    {Op::Constant, 0, 2},  // 4: i <= 6
      {Op::LessEqual, 0, 0},  {Op::JumpIfFalse, 0, 27}, {Op::LoadLocal, 0, 1},
      {Op::LoadLocal, 0, 0},  {Op::LoadLocal, 0, 2},    {Op::Multiply, 0, 0},
      {Op::LoadLocal, 0, 2},  {Op::LoadLocal, 0, 2},    {Op::Multiply, 0, 0},
      {Op::Divide, 0, 0},     {Op::Add, 0, 0},          {Op::LoadLocal, 0, 2},
      {Op::Constant, 0, 3},   {Op::Power, 0, 0},        {Op::Subtract, 0, 0},
      {Op::StoreLocal, 0, 1}, {Op::LoadLocal, 0, 2},    {Op::Constant, 0, 1},
      {Op::Add, 0, 0},        {Op::StoreLocal, 0, 2},   {Op::LoopBack, 0, 4},
      {Op::LoadLocal, 0, 1},  // 27
  };
  return code;
}

TEST(FusedCode, ALoopGivesTheUnfusedResults) {
  expectSameResults(sumLoop(), {{0.5}, {-3.25}, {0}, {1e300}, {-0.0}});
}

TEST(FusedCode, ALoopIsFusedIntoPushesAndAConditionalJump) {
  const Code fused = fuseInstructions(sumLoop());
  const std::vector<Op> ops = opsOf(fused);
  EXPECT_EQ(ops.back(), Op::End);
  EXPECT_NE(std::find(ops.begin(), ops.end(), Op::UnlessLessEqualConstant), ops.end());
  EXPECT_NE(std::find(ops.begin(), ops.end(), Op::LocalMultiplyLocal), ops.end());
  EXPECT_NE(std::find(ops.begin(), ops.end(), Op::LocalPowerConstant), ops.end());
  EXPECT_NE(std::find(ops.begin(), ops.end(), Op::LocalAddConstant), ops.end());
  EXPECT_EQ(std::find(ops.begin(), ops.end(), Op::JumpIfFalse), ops.end());
  // 28 instructions become 18 and the end.
  EXPECT_EQ(fused.instructions.size(), 19u);
}

// Every comparison, with a local and with a constant, as the condition of an if: a jump over
// `r = 1`; leaves r (slot 3).
TEST(FusedCode, EveryComparisonJumpsAsTheUnfusedOne) {
  for (Op compare :
       {Op::Equal, Op::NotEqual, Op::Less, Op::LessEqual, Op::Greater, Op::GreaterEqual}) {
    for (bool withConstant : {false, true}) {
      SCOPED_TRACE(static_cast<int>(compare) * 2 + withConstant);
      Code code;
      code.constants = {0, 1, 2.5};
      code.instructions = {
          {Op::Constant, 0, 0},
          {Op::StoreLocal, 0, 3},
          {Op::LoadLocal, 0, 0},
          withConstant ? Instruction{Op::Constant, 0, 2} : Instruction{Op::LoadLocal, 0, 1},
          {compare, 0, 0},
          {Op::JumpIfFalse, 0, 8},
          {Op::Constant, 0, 1},
          {Op::StoreLocal, 0, 3},
          {Op::LoadLocal, 0, 3},
      };
      const int offset = static_cast<int>(compare) - static_cast<int>(Op::Equal);
      const Op unless = withConstant ? Op::UnlessEqualConstant : Op::UnlessEqualLocal;
      EXPECT_EQ(opsOf(fuseInstructions(code))[3],
                static_cast<Op>(static_cast<int>(unless) + offset))
          << "the comparison and its jump are one instruction";
      expectSameResults(code, {{1, 2.5}, {2.5, 1}, {2.5, 2.5}, {-1, -1}, {0, -0.0}});
    }
  }
}

// Every arithmetic operator on a local and a local or a constant, as a sum of pushes.
TEST(FusedCode, EveryPushedOperatorGivesTheUnfusedValue) {
  for (Op op : {Op::Add, Op::Subtract, Op::Multiply, Op::Divide, Op::Power}) {
    for (bool withConstant : {false, true}) {
      SCOPED_TRACE(static_cast<int>(op) * 2 + withConstant);
      Code code;
      code.constants = {3, 0.5};
      code.instructions = {
          {Op::Constant, 0, 1},
          {Op::LoadLocal, 0, 0},
          withConstant ? Instruction{Op::Constant, 0, 0} : Instruction{Op::LoadLocal, 0, 1},
          {op, 0, 0},
          {Op::Add, 0, 0},
      };
      EXPECT_EQ(opsOf(fuseInstructions(code)).size(), 4u) << "constant, fused push, add, end";
      expectSameResults(code, {{1.5, 2}, {-2, 3}, {0.1, -0.7}, {1e200, 1e200}});
    }
  }
}

// A jump that lands inside a sequence keeps it apart: fused, the jump would land on nothing.
TEST(FusedCode, NothingIsFusedOverAJumpTarget) {
  // r = x > 0 ? 2 * 5 : x * 3, written so that both arms end on one Multiply.
  Code code;
  code.constants = {0, 2, 5, 3};
  code.instructions = {
      {Op::LoadLocal, 0, 0},   {Op::Constant, 0, 0},  {Op::Greater, 0, 0},
      {Op::JumpIfFalse, 0, 7}, {Op::Constant, 0, 1},  {Op::Constant, 0, 2},
      {Op::Jump, 0, 9},        {Op::LoadLocal, 0, 0}, {Op::Constant, 0, 3},  // 7
      {Op::Multiply, 0, 0},  // 9: both arms land here
      {Op::StoreLocal, 0, 3},
  };
  const std::vector<Op> ops = opsOf(fuseInstructions(code));
  EXPECT_EQ(std::count(ops.begin(), ops.end(), Op::MultiplyConstant), 0);
  EXPECT_EQ(std::count(ops.begin(), ops.end(), Op::LocalMultiplyConstant), 0);
  EXPECT_EQ(std::count(ops.begin(), ops.end(), Op::Multiply), 1);
  expectSameResults(code, {{4}, {-4}, {0}});
}

// A fused division by zero fails at the division's location, as the unfused one does.
TEST(FusedCode, AFusedDivisionByZeroFailsAtTheOperator) {
  Code code;
  code.constants = {0};
  code.instructions = {
      {Op::LoadLocal, 0, 0, 1}, {Op::LoadLocal, 0, 1, 2}, {Op::Divide, 0, 0, 7},
      {Op::LoadLocal, 0, 0, 3}, {Op::Constant, 0, 0, 4},  {Op::Divide, 0, 0, 9},
      {Op::Add, 0, 0, 5},
  };
  const Program program = programWithLocations();
  const Code fused = fuseInstructions(code);
  ASSERT_EQ(fused.instructions[0].op, Op::LocalDivideLocal);
  ASSERT_EQ(fused.instructions[1].op, Op::LocalDivideConstant);
  try {
    runOn(program, fused, {1, 0});
    FAIL() << "no error";
  } catch (const DiagnosticError& e) {
    EXPECT_NE(std::string(e.what()).find("division by zero"), std::string::npos);
    EXPECT_EQ(e.diagnostic().where.line, 7);
  }
  try {
    runOn(program, fused, {1, 2});
    FAIL() << "no error";
  } catch (const DiagnosticError& e) {
    EXPECT_EQ(e.diagnostic().where.line, 9);
  }
}

TEST(FusedCode, CodeWithNoInstructionStaysEmpty) {
  EXPECT_TRUE(fuseInstructions(Code{}).empty());
  const Program program = programWithLocations();
  EXPECT_EQ(runOn(program, Code{}, {}).value, 0.0);
}

}  // namespace
}  // namespace hirsute
