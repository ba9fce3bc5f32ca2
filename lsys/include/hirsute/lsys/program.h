// A compiled `.l` file: what the derivation runs. Built by compileProgram() from the syntax tree;
// immutable afterwards, so one Program can be derived many times.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/lsys/ast.h"
#include "hirsute/lsys/code.h"
#include "hirsute/core/diagnostic.h"

namespace hirsute {

// A module of a predecessor or context: its symbol, parameter count, and the frame slots its
// formal parameters are bound to.
struct ModulePattern {
  char symbol = 0;
  std::uint8_t parameterCount = 0;
  std::vector<int> slots;  // one per parameter
};

// A successor module: symbol and parameter count; values come from the successor's code.
struct SuccessorModule {
  char symbol = 0;
  std::uint8_t parameterCount = 0;
};

// A parameter of an axiom or successor module as the file writes it: where it begins and, when
// it is a constant expression (numbers, operators and math functions), its value, known before
// the derivation (the organ tables check such values: interpreter/organ_modules.h).
struct ModuleArgument {
  SourceLocation where;
  std::optional<double> constant;
};

// A test of one parameter of a production's first strict module against a constant, taken
// from its condition: `parameter comparison constant`, with the comparison one of Equal …
// GreaterEqual. See Production::guard.
struct ParameterTest {
  std::uint8_t parameter = 0;
  // The comparison's outcomes: bit 1 when the parameter is less than the constant, bit 2 when
  // equal, bit 4 when greater, bit 0 when unordered (a NaN); Equal is 0b00100, Less 0b00010.
  std::uint8_t holdsWhen = 0;
  double constant = 0;

  bool holds(double value) const {
    const unsigned outcome = (value < constant) | (value == constant) << 1 | (value > constant) << 2;
    return (holdsWhen >> outcome) & 1;
  }
};

inline std::uint8_t comparisonOutcomes(ast::BinaryOp comparison) {
  constexpr std::uint8_t kUnordered = 1, kLess = 2, kEqual = 4, kGreater = 16;
  switch (comparison) {
    case ast::BinaryOp::Equal: return kEqual;
    case ast::BinaryOp::NotEqual: return kUnordered | kLess | kGreater;
    case ast::BinaryOp::Less: return kLess;
    case ast::BinaryOp::LessEqual: return kLess | kEqual;
    case ast::BinaryOp::Greater: return kGreater;
    case ast::BinaryOp::GreaterEqual: return kEqual | kGreater;
    default: return 0;
  }
}

struct Production {
  SourceLocation where;
  std::vector<ModulePattern> left;   // in string order
  std::vector<ModulePattern> strict;
  std::vector<ModulePattern> right;
  Code before;                       // pre-condition statements
  Code condition;                    // empty: always true
  Code after;                        // post-condition statements
  std::vector<SuccessorModule> successor;
  Code successorValues;              // pushes every successor parameter, left to right
  std::vector<ModuleArgument> successorArguments;  // every successor parameter, left to right
  // The successor already encoded as module-string bytes, with the byte offset of each
  // parameter's float: emitting it is one copy and a float store per parameter.
  std::vector<std::uint8_t> successorBytes;
  std::vector<std::uint32_t> parameterOffsets;
  Code probability;                  // empty: weight 1
  bool callsSubLsystem = false;      // the successor has a `?(id…)` module: its id is checked
  int frameSize = 0;                 // formal parameters and local variables
  std::vector<std::string> slotNames;
  // Conjuncts of the condition that compare a parameter of the first strict module with a
  // constant, when the production has no pre-condition block and its condition can neither
  // have an effect nor fail (no call, array element, division or modulo): a module that fails
  // one of them is refused before its contexts are searched and its parameters bound, with the
  // result the condition would give. Empty: nothing to test early.
  std::vector<ParameterTest> guard;
  bool hasContext() const { return !left.empty() || !right.empty(); }
};

struct RuleSet {
  std::vector<Production> productions;
  // Productions by the first symbol of their strict predecessor, in file order.
  std::array<std::vector<std::uint32_t>, 128> bySymbol;
  int maximumDepth = 1;
  bool warnings = true;
  bool present = false;
  bool hasSeed = false;
  double seed = 0;
};

struct Lsystem {
  SourceLocation where;
  std::string label;
  double id = 0;                  // atof(label), as cpfg numbers sub-L-systems
  int derivationLength = 0;
  bool hasDerivationLength = false;
  bool stochastic = false;        // `seed:` given
  double seed = 0;
  std::array<bool, 128> ignored{};  // symbols skipped in context matching
  bool ring = false;
  Code define;                    // array initializers
  Code start, startEach, endEach, end;
  std::vector<SuccessorModule> axiom;
  Code axiomValues;
  std::vector<ModuleArgument> axiomArguments;  // every axiom parameter, left to right
  SourceLocation axiomWhere;
  RuleSet productions, decomposition, homomorphism;
};

struct ArrayDefinition {
  std::string name;
  std::vector<int> dimensions;
  SourceLocation where;
};

// cpfg: @L("format", …), @S("command") and @I("file", …) take a string literal as their first
// argument (cpfg-features.md, string literals; cpfg-manual.txt §6.10). The module string holds
// numbers only, so that parameter is the string's id in Program::strings: a small integer, exact
// in float32. Which modules carry one is fixed by this convention, not marked in the string:
// `symbol` is the module after a bare `@`.
inline bool takesStringArgument(char symbol) {
  return symbol == 'L' || symbol == 'S' || symbol == 'I';
}

// String ids stay below 2^24 so that a float parameter holds them exactly.
inline constexpr std::size_t kMaxStrings = std::size_t{1} << 24;

class NativeCode;  // native_code.h

struct Program {
  std::vector<Lsystem> lsystems;  // [0] is the main L-system
  std::vector<std::string> sharedNames;  // L-system and global variables, by slot
  int stepSlot = 0;                      // the hidden global Q (current step)
  int lengthSlot = 0;                    // the hidden global Z (derivation length)
  std::vector<ArrayDefinition> arrays;
  std::vector<std::string> strings;      // string literals, by id (see takesStringArgument)
  std::vector<SourceLocation> locations; // by Instruction::where
  int maxStack = 0;
  // The machine code of the codes compileNativeCode compiled (native_code.h): shared by copies.
  std::shared_ptr<const NativeCode> nativeCode;
  bool usesQueries = false;              // ?P ?H ?L ?U modules appear
  bool usesEnvironment = false;          // ?E modules appear

  int lsystemIndex(double id) const;     // -1 when absent
};

// Compiles a parsed file. Throws DiagnosticError; warnings go to `diagnostics`.
Program compileProgram(const ast::File& file, Diagnostics& diagnostics);

}  // namespace hirsute
