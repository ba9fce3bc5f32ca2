// The syntax tree of a `.l` file as the parser builds it. It is compiled once (compiler.h) into
// the Program the derivation runs; nothing here is evaluated directly.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute::ast {

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

enum class UnaryOp { Negate, Not, AddressOf };
// cpfg's operators; `^` is power, `<>` is a synonym of `!=`.
enum class BinaryOp { Or, And, Equal, NotEqual, Less, LessEqual, Greater, GreaterEqual, Add,
                      Subtract, Multiply, Divide, Modulo, Power };

// Deepest nesting of an expression or of blocks; deeper input is an error, so that compiling
// and freeing the tree stays within the C++ stack.
inline constexpr int kMaxNesting = 500;

struct Expr {
  enum class Kind { Number, String, Variable, Element, Unary, Binary, Conditional, Call };
  Kind kind;
  SourceLocation where;
  int depth = 1;                  // nesting of this expression
  double number = 0;              // Number
  std::string name;               // Variable, Element (array name), Call (function), String (text)
  UnaryOp unaryOp{};              // Unary
  BinaryOp binaryOp{};            // Binary
  std::vector<ExprPtr> operands;  // Unary 1, Binary 2, Conditional 3, Element subscripts, Call args
};

struct Stmt;
using StmtPtr = std::unique_ptr<Stmt>;
using Block = std::vector<StmtPtr>;

struct ArrayDeclaration {
  SourceLocation where;
  std::string name;
  std::vector<ExprPtr> dimensions;
  std::vector<ExprPtr> initializer;  // row-major; may be shorter than the array
};

struct Stmt {
  enum class Kind { Assign, AssignElement, Evaluate, If, While, DoWhile, Arrays };
  Kind kind;
  SourceLocation where;
  std::string target;              // Assign, AssignElement
  std::vector<ExprPtr> subscripts; // AssignElement
  ExprPtr value;                   // Assign, AssignElement, Evaluate; the condition of If/While/DoWhile
  Block body;                      // If (then), While, DoWhile
  Block otherwise;                 // If (else)
  std::vector<ArrayDeclaration> arrays;  // Arrays (inside `define:`)
};

// A formal parameter of a predecessor or context module: its name and where it is written.
struct Formal {
  std::string name;
  SourceLocation where;
};

// One module as written: a predecessor or context module with formal parameter names, or an
// axiom or successor module with parameter expressions.
struct Module {
  char symbol = 0;
  SourceLocation where;
  bool hasParentheses = false;
  std::vector<Formal> formals;       // predecessor and contexts
  std::vector<ExprPtr> arguments;    // axiom and successor
  std::vector<SourceLocation> argumentsWhere;  // where each argument begins (its first token)
};

// The parameter expressions of an axiom or successor module, each with where it begins.
struct ModuleArguments {
  std::vector<ExprPtr> values;
  std::vector<SourceLocation> where;
};
using ModuleList = std::vector<Module>;

struct Production {
  SourceLocation where;
  ModuleList left;    // empty: no left context
  ModuleList strict;  // never empty
  ModuleList right;   // empty: no right context
  Block before;       // pre-condition statements
  ExprPtr condition;  // null: always true (`*` or absent)
  Block after;        // post-condition statements
  ModuleList successor;  // empty: `*`
  ExprPtr probability;   // null: weight 1
};

struct RuleSet {
  std::vector<Production> productions;
  ExprPtr maximumDepth;  // null: 1
  bool warnings = true;
  ExprPtr seed;          // homomorphism only
  bool present = false;
};

struct Lsystem {
  SourceLocation where;
  std::string label;
  ExprPtr derivationLength;
  ExprPtr seed;
  std::optional<std::string> ignore;   // symbols, when `ignore:` was given
  std::optional<std::string> consider; // symbols, when `consider:` was given
  SourceLocation ignoreWhere;
  bool ring = false;
  Block define;  // array declarations
  Block start, startEach, endEach, end;
  ModuleList axiom;
  SourceLocation axiomWhere;
  bool hasAxiom = false;
  std::vector<Production> productions;
  RuleSet decomposition;
  RuleSet homomorphism;
};

struct File {
  std::vector<Lsystem> lsystems;
};

}  // namespace hirsute::ast
