// Compiles the syntax tree into a Program: resolves names to frame or shared slots, checks
// calls against the built-ins, evaluates the constant header items, and turns every block,
// condition and successor into stack code.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "hirsute/lsys/builtins.h"
#include "hirsute/lsys/native_code.h"
#include "hirsute/lsys/module_string.h"
#include "hirsute/lsys/program.h"

namespace hirsute {
namespace {

using NameMap = std::unordered_map<std::string, int>;

// Subscripts travel in an instruction's one-byte count; real models use one or two.
constexpr std::size_t kMaxArrayDimensions = 16;

int stackEffect(Op op, int count) {
  switch (op) {
    case Op::Constant: case Op::LoadLocal: case Op::LoadShared: return 1;
    case Op::StoreLocal: case Op::StoreShared: case Op::Pop: case Op::JumpIfFalse: return -1;
    case Op::LoadElement: return 1 - count;
    case Op::StoreElement: return -1 - count;
    case Op::Negate: case Op::Not: case Op::Truth: case Op::Jump: case Op::LoopBack: return 0;
    case Op::Call: return 1 - count;
    case Op::Scan: return count;  // pops the file id, pushes the result and `count` values
    default: return -1;           // binary operators
  }
}

// Collects the variables fscanf reads into (`&x`) anywhere in an expression.
void collectScanned(const ast::Expr* e, std::vector<std::string>& names) {
  if (!e) return;
  if (e->kind == ast::Expr::Kind::Call && e->name == "fscanf") {
    for (const auto& arg : e->operands) {
      if (arg->kind == ast::Expr::Kind::Unary && arg->unaryOp == ast::UnaryOp::AddressOf &&
          arg->operands[0]->kind == ast::Expr::Kind::Variable) {
        names.push_back(arg->operands[0]->name);
      }
    }
  }
  for (const auto& operand : e->operands) collectScanned(operand.get(), names);
}

// Collects the names assigned anywhere in a block (`x = …;` and fscanf's `&x`).
void collectAssigned(const ast::Block& block, std::vector<std::string>& names) {
  for (const auto& s : block) {
    if (s->kind == ast::Stmt::Kind::Assign) names.push_back(s->target);
    collectScanned(s->value.get(), names);
    collectAssigned(s->body, names);
    collectAssigned(s->otherwise, names);
  }
}

class Compiler {
 public:
  Compiler(Program& program, Diagnostics& diagnostics) : program_(program), diagnostics_(diagnostics) {}

  void compile(const ast::File& file);

 private:
  // ---- scopes ----
  struct Scope {
    NameMap* locals = nullptr;                   // production frame; null in header blocks
    std::vector<std::string>* slotNames = nullptr;
    const NameMap* shared = nullptr;             // this L-system's variables
    const NameMap* arrays = nullptr;             // this L-system's arrays
  };

  // ---- code building ----
  struct Builder {
    Code code;
    int depth = 0;
    void emit(Op op, int count, std::int32_t operand, std::uint32_t where) {
      // The count travels in a byte; callers bound it (arguments, subscripts, fscanf targets).
      if (count < 0 || count > 255) throw std::logic_error("instruction count out of range");
      code.instructions.push_back(Instruction{op, static_cast<std::uint8_t>(count), operand, where});
      depth += stackEffect(op, count);
      if (depth > code.maxStack) code.maxStack = depth;
    }
    int here() const { return static_cast<int>(code.instructions.size()); }
    void patch(int at, int target) { code.instructions[static_cast<std::size_t>(at)].operand = target; }
    void constant(double value, std::uint32_t where) {
      // Each value (bit for bit: -0 and 0 differ, a NaN is itself) once in the table, found by
      // hash: a block of 10^5 numbers took seconds with a search of the table.
      std::uint64_t bits = 0;
      std::memcpy(&bits, &value, sizeof value);
      const auto [at, added] = constantIndex.try_emplace(bits, static_cast<int>(code.constants.size()));
      if (added) code.constants.push_back(value);
      emit(Op::Constant, 0, at->second, where);
    }
    std::unordered_map<std::uint64_t, int> constantIndex;  // constants' bits to their index
  };

  std::uint32_t location(const SourceLocation& where) {
    program_.locations.push_back(where);
    return static_cast<std::uint32_t>(program_.locations.size() - 1);
  }

  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) {
    throw DiagnosticError(where, message);
  }

  double constantValue(const ast::Expr& e, const std::string& what);
  // The value of a constant expression; `what` names it in the error when it is not one.
  std::optional<double> foldConstant(const ast::Expr& e, const std::string* what);
  void compileExpr(const ast::Expr& e, const Scope& scope, Builder& b);
  void compileCall(const ast::Expr& e, const Scope& scope, Builder& b);
  void compileLoad(const std::string& name, const SourceLocation& where, const Scope& scope, Builder& b);
  void compileStore(const std::string& name, const SourceLocation& where, const Scope& scope, Builder& b);
  void compileBlock(const ast::Block& block, const Scope& scope, Builder& b);
  void compileStmt(const ast::Stmt& s, const Scope& scope, Builder& b);
  // Before the loop `s`: each math built-in the loop calls on arguments it never changes, computed
  // once into a slot of the frame that the loop then reads (hoisted_). Returns the calls hoisted.
  std::vector<const ast::Expr*> hoistInvariantCalls(const ast::Stmt& s, const Scope& scope, Builder& b);
  int arrayId(const std::string& name, const SourceLocation& where, const Scope& scope, std::size_t subscripts);
  Code finish(Builder& b) {
    if (b.code.maxStack > program_.maxStack) program_.maxStack = b.code.maxStack;
    return fuseInstructions(std::move(b.code));
  }
  Code compileCode(const ast::Block& block, const Scope& scope) {
    Builder b;
    compileBlock(block, scope, b);
    return finish(b);
  }
  Code compileValue(const ast::Expr* e, const Scope& scope) {
    Builder b;
    if (e) compileExpr(*e, scope, b);
    return finish(b);
  }

  void compileLsystem(const ast::Lsystem& in, Lsystem& out, NameMap& shared, NameMap& arrays);
  void compileModules(const ast::ModuleList& modules, const Scope& scope,
                      std::vector<SuccessorModule>& out, Code& values,
                      std::vector<ModuleArgument>& arguments);
  void compileRuleSet(const std::vector<ast::Production>& in, RuleSet& out, const NameMap& shared,
                      const NameMap& arrays);
  Production compileProduction(const ast::Production& in, const NameMap& shared, const NameMap& arrays);
  // Production::guard of a condition, for a production without a pre-condition block.
  // `formals`: the frame slots below it are the production's formal parameters.
  std::vector<ParameterTest> guardOf(const ast::Expr& condition, const ModulePattern& first,
                                     int formals, const NameMap& locals);
  void noteQueries(const ast::ModuleList& modules);
  // The id of `text` in Program::strings, added when new; equal literals share an id.
  int internString(const std::string& text, const SourceLocation& where);

  Program& program_;
  Diagnostics& diagnostics_;
  NameMap globals_;
  // Calls computed before the loop that holds them: the frame slot with their value.
  std::unordered_map<const ast::Expr*, int> hoisted_;
  double arrayCells_ = 0;  // elements of all arrays declared so far
};

double Compiler::constantValue(const ast::Expr& e, const std::string& what) {
  return *foldConstant(e, &what);
}

// With `what` null, an expression that is not constant, or whose value cannot be computed
// (division by zero), gives no value instead of an error: the derivation meets it as usual.
std::optional<double> Compiler::foldConstant(const ast::Expr& e, const std::string* what) {
  using K = ast::Expr::Kind;
  // The error "PROBLEM in WHAT" when a value is required; else no value.
  const auto bad = [&](const SourceLocation& where, const std::string& problem) {
    if (what) fail(where, problem + " in " + *what);
    return std::optional<double>();
  };
  switch (e.kind) {
    case K::Number:
      return e.number;
    case K::Unary: {
      const std::optional<double> v = foldConstant(*e.operands[0], what);
      if (!v) return v;
      if (e.unaryOp == ast::UnaryOp::Negate) return -*v;
      if (e.unaryOp == ast::UnaryOp::Not) return *v == 0 ? 1 : 0;
      break;
    }
    case K::Binary: {
      const std::optional<double> left = foldConstant(*e.operands[0], what);
      if (!left) return left;
      const std::optional<double> right = foldConstant(*e.operands[1], what);
      if (!right) return right;
      const double a = *left, c = *right;
      switch (e.binaryOp) {
        case ast::BinaryOp::Or: return (a != 0 || c != 0) ? 1 : 0;
        case ast::BinaryOp::And: return (a != 0 && c != 0) ? 1 : 0;
        case ast::BinaryOp::Equal: return a == c;
        case ast::BinaryOp::NotEqual: return a != c;
        case ast::BinaryOp::Less: return a < c;
        case ast::BinaryOp::LessEqual: return a <= c;
        case ast::BinaryOp::Greater: return a > c;
        case ast::BinaryOp::GreaterEqual: return a >= c;
        case ast::BinaryOp::Add: return a + c;
        case ast::BinaryOp::Subtract: return a - c;
        case ast::BinaryOp::Multiply: return a * c;
        case ast::BinaryOp::Divide:
          if (c == 0) return bad(e.where, "division by zero");
          return a / c;
        case ast::BinaryOp::Modulo: {
          if (!std::isfinite(a) || !std::isfinite(c) || std::fabs(a) > 9e18 || std::fabs(c) > 9e18) {
            return bad(e.where, "modulo of a value out of the integer range");
          }
          long long ia = static_cast<long long>(a), ic = static_cast<long long>(c);
          if (ic == 0) return bad(e.where, "modulo by zero");
          return static_cast<double>(ia % ic);
        }
        case ast::BinaryOp::Power: return std::pow(a, c);
      }
      break;
    }
    case K::Conditional: {
      const std::optional<double> condition = foldConstant(*e.operands[0], what);
      if (!condition) return condition;
      return foldConstant(*e.operands[*condition != 0 ? 1 : 2], what);
    }
    case K::Call: {
      const BuiltinInfo* info = findBuiltin(e.name);
      if (info && isMathBuiltin(info->id) && static_cast<int>(e.operands.size()) >= info->minArguments &&
          static_cast<int>(e.operands.size()) <= info->maxArguments) {
        double args[2];
        for (std::size_t i = 0; i < e.operands.size(); ++i) {
          const std::optional<double> arg = foldConstant(*e.operands[i], what);
          if (!arg) return arg;
          args[i] = *arg;
        }
        return applyMathBuiltin(info->id, args, static_cast<int>(e.operands.size()));
      }
      break;
    }
    default:
      break;
  }
  if (what) {
    // Name what is not constant: most often a name no #define gave a value (a misspelt one).
    std::string cause;
    if (e.kind == K::Variable)
      cause = "'" + e.name + "' is no constant (a name here must be one the file #defines): ";
    else if (e.kind == K::Element)
      cause = "'" + e.name + "[…]' is an array element, known only while deriving: ";
    else if (e.kind == K::Call)
      cause = "'" + e.name + "(…)' is no math function of constant arguments: ";
    fail(e.where,
         cause + *what + " must be a constant expression (numbers, operators and math functions)");
  }
  return std::nullopt;
}

int Compiler::arrayId(const std::string& name, const SourceLocation& where, const Scope& scope,
                      std::size_t subscripts) {
  auto it = scope.arrays->find(name);
  if (it == scope.arrays->end()) fail(where, "'" + name + "' is not an array (arrays are declared in define:)");
  const ArrayDefinition& def = program_.arrays[static_cast<std::size_t>(it->second)];
  if (subscripts != def.dimensions.size()) {
    fail(where, "array '" + name + "' has " + std::to_string(def.dimensions.size()) +
                    " dimension(s) but is used with " + std::to_string(subscripts) + " subscript(s)");
  }
  return it->second;
}

void Compiler::compileLoad(const std::string& name, const SourceLocation& where, const Scope& scope,
                           Builder& b) {
  std::uint32_t loc = location(where);
  if (scope.locals) {
    auto it = scope.locals->find(name);
    if (it != scope.locals->end()) return b.emit(Op::LoadLocal, 0, it->second, loc);
  }
  if (auto it = scope.shared->find(name); it != scope.shared->end()) {
    return b.emit(Op::LoadShared, 0, it->second, loc);
  }
  if (auto it = globals_.find(name); it != globals_.end()) return b.emit(Op::LoadShared, 0, it->second, loc);
  if (scope.arrays->count(name)) fail(where, "array '" + name + "' needs subscripts");
  if (findBuiltin(name)) fail(where, "'" + name + "' is a function; call it with parentheses");
  // cpfg: an undefined variable warns and reads as 0.
  diagnostics_.warn(where, "variable '" + name + "' is never assigned; it reads as 0");
  b.constant(0, loc);
}

void Compiler::compileStore(const std::string& name, const SourceLocation& where, const Scope& scope,
                            Builder& b) {
  std::uint32_t loc = location(where);
  if (scope.arrays->count(name)) fail(where, "array '" + name + "' needs subscripts");
  if (findBuiltin(name) || isUnsupportedBuiltin(name)) {
    fail(where, "'" + name + "' is a built-in function and cannot be assigned");
  }
  if (scope.locals) {
    auto it = scope.locals->find(name);
    if (it != scope.locals->end()) return b.emit(Op::StoreLocal, 0, it->second, loc);
  }
  if (auto it = scope.shared->find(name); it != scope.shared->end()) {
    return b.emit(Op::StoreShared, 0, it->second, loc);
  }
  if (auto it = globals_.find(name); it != globals_.end()) return b.emit(Op::StoreShared, 0, it->second, loc);
  fail(where, "internal: no slot for '" + name + "'");
}

void Compiler::compileExpr(const ast::Expr& e, const Scope& scope, Builder& b) {
  using K = ast::Expr::Kind;
  switch (e.kind) {
    case K::Number:
      b.constant(e.number, location(e.where));
      return;
    case K::String:
      fail(e.where,
           "a string is only allowed as the first argument of @L, @S or @I, the format of printf, "
           "fprintf or fscanf, or a name for fopen");
    case K::Variable:
      compileLoad(e.name, e.where, scope, b);
      return;
    case K::Element: {
      int id = arrayId(e.name, e.where, scope, e.operands.size());
      for (const auto& s : e.operands) compileExpr(*s, scope, b);
      b.emit(Op::LoadElement, static_cast<int>(e.operands.size()), id, location(e.where));
      return;
    }
    case K::Unary:
      if (e.unaryOp == ast::UnaryOp::AddressOf) {
        fail(e.where, "'&' is only allowed for the variables that fscanf reads into");
      }
      compileExpr(*e.operands[0], scope, b);
      b.emit(e.unaryOp == ast::UnaryOp::Negate ? Op::Negate : Op::Not, 0, 0, location(e.where));
      return;
    case K::Binary: {
      std::uint32_t loc = location(e.where);
      if (e.binaryOp == ast::BinaryOp::And || e.binaryOp == ast::BinaryOp::Or) {
        // Short-circuit; the result is 0 or 1.
        compileExpr(*e.operands[0], scope, b);
        int test = b.here();
        b.emit(Op::JumpIfFalse, 0, 0, loc);
        if (e.binaryOp == ast::BinaryOp::And) {
          compileExpr(*e.operands[1], scope, b);
          b.emit(Op::Truth, 0, 0, loc);
          int skip = b.here();
          b.emit(Op::Jump, 0, 0, loc);
          b.patch(test, b.here());
          b.depth -= 1;
          b.constant(0, loc);
          b.patch(skip, b.here());
        } else {
          b.constant(1, loc);
          int skip = b.here();
          b.emit(Op::Jump, 0, 0, loc);
          b.patch(test, b.here());
          b.depth -= 1;
          compileExpr(*e.operands[1], scope, b);
          b.emit(Op::Truth, 0, 0, loc);
          b.patch(skip, b.here());
        }
        return;
      }
      compileExpr(*e.operands[0], scope, b);
      compileExpr(*e.operands[1], scope, b);
      static const Op kOps[] = {Op::Jump, Op::Jump, Op::Equal, Op::NotEqual, Op::Less,
                                Op::LessEqual, Op::Greater, Op::GreaterEqual, Op::Add,
                                Op::Subtract, Op::Multiply, Op::Divide, Op::Modulo, Op::Power};
      b.emit(kOps[static_cast<int>(e.binaryOp)], 0, 0, loc);
      return;
    }
    case K::Conditional: {
      std::uint32_t loc = location(e.where);
      compileExpr(*e.operands[0], scope, b);
      int test = b.here();
      b.emit(Op::JumpIfFalse, 0, 0, loc);
      compileExpr(*e.operands[1], scope, b);
      int skip = b.here();
      b.emit(Op::Jump, 0, 0, loc);
      b.patch(test, b.here());
      b.depth -= 1;
      compileExpr(*e.operands[2], scope, b);
      b.patch(skip, b.here());
      return;
    }
    case K::Call:
      if (auto it = hoisted_.find(&e); it != hoisted_.end()) {
        b.emit(Op::LoadLocal, 0, it->second, location(e.where));
        return;
      }
      compileCall(e, scope, b);
      return;
  }
}

std::vector<const ast::Expr*> Compiler::hoistInvariantCalls(const ast::Stmt& loop,
                                                            const Scope& scope, Builder& b) {
  std::vector<const ast::Expr*> calls;
  if (!scope.locals || !scope.slotNames) return calls;  // header blocks have no frame
  std::vector<std::string> changed;
  collectAssigned(loop.body, changed);
  collectScanned(loop.value.get(), changed);
  // A value the loop cannot change, computed without a warning or an effect: numbers, variables
  // that exist and that it never assigns, operators, and math built-ins of such values.
  std::function<bool(const ast::Expr&)> invariant = [&](const ast::Expr& e) {
    using K = ast::Expr::Kind;
    switch (e.kind) {
      case K::Number:
        return true;
      case K::Variable:
        return std::find(changed.begin(), changed.end(), e.name) == changed.end() &&
               (scope.locals->count(e.name) || scope.shared->count(e.name) || globals_.count(e.name));
      case K::Unary:
        if (e.unaryOp == ast::UnaryOp::AddressOf) return false;
        [[fallthrough]];
      case K::Binary:
      case K::Conditional:
        return std::all_of(e.operands.begin(), e.operands.end(),
                           [&](const ast::ExprPtr& o) { return invariant(*o); });
      case K::Call: {
        const BuiltinInfo* info = findBuiltin(e.name);
        const int count = static_cast<int>(e.operands.size());
        return info && isMathBuiltin(info->id) && count >= info->minArguments &&
               count <= info->maxArguments &&
               std::all_of(e.operands.begin(), e.operands.end(),
                           [&](const ast::ExprPtr& o) { return invariant(*o); });
      }
      default:
        return false;
    }
  };
  // The outermost such calls, wherever the loop evaluates an expression.
  std::function<void(const ast::Expr*)> find = [&](const ast::Expr* e) {
    if (!e) return;
    if (e->kind == ast::Expr::Kind::Call && !hoisted_.count(e) && invariant(*e)) {
      calls.push_back(e);
      return;
    }
    for (const auto& o : e->operands) find(o.get());
  };
  std::function<void(const ast::Block&)> findIn = [&](const ast::Block& block) {
    for (const auto& st : block) {
      find(st->value.get());
      for (const auto& subscript : st->subscripts) find(subscript.get());
      findIn(st->body);
      findIn(st->otherwise);
    }
  };
  find(loop.value.get());
  findIn(loop.body);
  for (const ast::Expr* call : calls) {
    const int slot = static_cast<int>(scope.slotNames->size());
    // A name no model can write, so no variable of the model shares the slot.
    std::string name = "\x01hoisted ";
    name += std::to_string(slot);
    scope.slotNames->push_back(std::move(name));
    compileCall(*call, scope, b);
    b.emit(Op::StoreLocal, 0, slot, location(call->where));
    hoisted_.emplace(call, slot);
  }
  return calls;
}

void Compiler::compileCall(const ast::Expr& e, const Scope& scope, Builder& b) {
  const BuiltinInfo* info = findBuiltin(e.name);
  if (!info) {
    if (isUnsupportedBuiltin(e.name)) fail(e.where, "function '" + e.name + "' is not supported by Hirsute");
    fail(e.where, "unknown function '" + e.name + "'");
  }
  int count = static_cast<int>(e.operands.size());
  if (count < info->minArguments || (info->maxArguments >= 0 && count > info->maxArguments)) {
    std::string expected = info->minArguments == info->maxArguments
                               ? std::to_string(info->minArguments)
                               : info->maxArguments < 0 ? "at least " + std::to_string(info->minArguments)
                                                        : std::to_string(info->minArguments) + " or " +
                                                              std::to_string(info->maxArguments);
    fail(e.where, "function '" + e.name + "' takes " + expected + " argument(s), not " + std::to_string(count));
  }
  if (count > 250) fail(e.where, "too many arguments");
  std::uint32_t loc = location(e.where);
  auto stringId = [&](const ast::Expr& arg) {
    if (arg.kind != ast::Expr::Kind::String) {
      fail(arg.where, "function '" + e.name + "' expects a string literal here");
    }
    return internString(arg.name, arg.where);
  };
  if (info->id == Builtin::Fscanf) {
    compileExpr(*e.operands[0], scope, b);
    int format = stringId(*e.operands[1]);
    int targets = count - 2;
    b.emit(Op::Scan, targets, format, loc);
    for (int i = 0; i < targets; ++i) {
      const ast::Expr& target = *e.operands[static_cast<std::size_t>(2 + i)];
      if (target.kind != ast::Expr::Kind::Unary || target.unaryOp != ast::UnaryOp::AddressOf ||
          target.operands[0]->kind != ast::Expr::Kind::Variable) {
        fail(target.where, "fscanf reads into variables written as '&name'");
      }
      compileStore(target.operands[0]->name, target.where, scope, b);
    }
    return;
  }
  for (int i = 0; i < count; ++i) {
    const ast::Expr& arg = *e.operands[static_cast<std::size_t>(i)];
    if (info->stringMask & (1u << i)) {
      b.constant(stringId(arg), loc);
    } else {
      compileExpr(arg, scope, b);
    }
  }
  b.emit(Op::Call, count, static_cast<int>(info->id), loc);
}

void Compiler::compileBlock(const ast::Block& block, const Scope& scope, Builder& b) {
  for (const auto& s : block) compileStmt(*s, scope, b);
}

void Compiler::compileStmt(const ast::Stmt& s, const Scope& scope, Builder& b) {
  using K = ast::Stmt::Kind;
  std::uint32_t loc = location(s.where);
  switch (s.kind) {
    case K::Assign:
      compileExpr(*s.value, scope, b);
      compileStore(s.target, s.where, scope, b);
      return;
    case K::AssignElement: {
      int id = arrayId(s.target, s.where, scope, s.subscripts.size());
      for (const auto& e : s.subscripts) compileExpr(*e, scope, b);
      compileExpr(*s.value, scope, b);
      b.emit(Op::StoreElement, static_cast<int>(s.subscripts.size()), id, loc);
      return;
    }
    case K::Evaluate:
      compileExpr(*s.value, scope, b);
      b.emit(Op::Pop, 0, 0, loc);
      return;
    case K::If: {
      compileExpr(*s.value, scope, b);
      int test = b.here();
      b.emit(Op::JumpIfFalse, 0, 0, loc);
      compileBlock(s.body, scope, b);
      if (s.otherwise.empty()) {
        b.patch(test, b.here());
      } else {
        int skip = b.here();
        b.emit(Op::Jump, 0, 0, loc);
        b.patch(test, b.here());
        compileBlock(s.otherwise, scope, b);
        b.patch(skip, b.here());
      }
      return;
    }
    case K::While: {
      const std::vector<const ast::Expr*> hoisted = hoistInvariantCalls(s, scope, b);
      int top = b.here();
      compileExpr(*s.value, scope, b);
      int test = b.here();
      b.emit(Op::JumpIfFalse, 0, 0, loc);
      compileBlock(s.body, scope, b);
      b.emit(Op::LoopBack, 0, top, loc);
      b.patch(test, b.here());
      for (const ast::Expr* call : hoisted) hoisted_.erase(call);
      return;
    }
    case K::DoWhile: {
      const std::vector<const ast::Expr*> hoisted = hoistInvariantCalls(s, scope, b);
      int top = b.here();
      compileBlock(s.body, scope, b);
      compileExpr(*s.value, scope, b);
      int test = b.here();
      b.emit(Op::JumpIfFalse, 0, 0, loc);
      b.emit(Op::LoopBack, 0, top, loc);
      b.patch(test, b.here());
      for (const ast::Expr* call : hoisted) hoisted_.erase(call);
      return;
    }
    case K::Arrays:
      fail(s.where, "arrays are declared only in the define: block");
  }
}

void Compiler::noteQueries(const ast::ModuleList& modules) {
  for (std::size_t i = 0; i + 1 < modules.size(); ++i) {
    if (modules[i].symbol != '?' || modules[i].hasParentheses) continue;
    char next = modules[i + 1].symbol;
    if (next == 'P' || next == 'H' || next == 'L' || next == 'U') program_.usesQueries = true;
    if (next == 'E') program_.usesEnvironment = true;
  }
}

int Compiler::internString(const std::string& text, const SourceLocation& where) {
  auto& strings = program_.strings;
  for (std::size_t i = 0; i < strings.size(); ++i) {
    if (strings[i] == text) return static_cast<int>(i);
  }
  if (strings.size() >= kMaxStrings) fail(where, "too many string literals");
  strings.push_back(text);
  return static_cast<int>(strings.size() - 1);
}

void Compiler::compileModules(const ast::ModuleList& modules, const Scope& scope,
                              std::vector<SuccessorModule>& out, Code& values,
                              std::vector<ModuleArgument>& arguments) {
  Builder b;
  for (const ast::Module& m : modules) {
    if (m.arguments.size() > kMaxModuleParameters) {
      fail(m.where, "a module can have at most " + std::to_string(kMaxModuleParameters) + " parameters");
    }
    const std::size_t index = static_cast<std::size_t>(&m - modules.data());
    const ast::Module* before = index > 0 ? &modules[index - 1] : nullptr;
    const bool stringFirst = takesStringArgument(m.symbol) && before != nullptr &&
                             before->symbol == '@' && !before->hasParentheses;
    for (std::size_t i = 0; i < m.arguments.size(); ++i) {
      const ast::Expr& arg = *m.arguments[i];
      ModuleArgument argument{m.argumentsWhere[i], std::nullopt};
      if (i == 0 && stringFirst && arg.kind == ast::Expr::Kind::String) {
        b.constant(internString(arg.name, arg.where), location(arg.where));
      } else {
        compileExpr(arg, scope, b);
        argument.constant = foldConstant(arg, nullptr);
      }
      arguments.push_back(std::move(argument));
    }
    out.push_back(SuccessorModule{m.symbol, static_cast<std::uint8_t>(m.arguments.size())});
  }
  noteQueries(modules);
  values = finish(b);
}

namespace {

// Whether evaluating `e` can have no effect, raise no error and warn of nothing: numbers, the
// production's formal parameters (`formal`), negation, `!`, comparisons, `&&`, `||`, `+`, `-`,
// `*`, `^` and `? :`, nothing else (a variable may be unassigned, which warns).
bool pureAndSafe(const ast::Expr& e, const std::function<bool(const std::string&)>& formal) {
  using K = ast::Expr::Kind;
  switch (e.kind) {
    case K::Number:
      return true;
    case K::Variable:
      return formal(e.name);
    case K::Unary:
      if (e.unaryOp == ast::UnaryOp::AddressOf) return false;
      break;
    case K::Binary:
      if (e.binaryOp == ast::BinaryOp::Divide || e.binaryOp == ast::BinaryOp::Modulo) return false;
      break;
    case K::Conditional:
      break;
    default:
      return false;
  }
  return std::all_of(e.operands.begin(), e.operands.end(),
                     [&](const ast::ExprPtr& operand) { return pureAndSafe(*operand, formal); });
}

// The top-level operands of a chain of `&&`, left to right.
void conjuncts(const ast::Expr& e, std::vector<const ast::Expr*>& out) {
  if (e.kind == ast::Expr::Kind::Binary && e.binaryOp == ast::BinaryOp::And) {
    conjuncts(*e.operands[0], out);
    conjuncts(*e.operands[1], out);
  } else {
    out.push_back(&e);
  }
}

bool isComparison(ast::BinaryOp op) {
  return op == ast::BinaryOp::Equal || op == ast::BinaryOp::NotEqual || op == ast::BinaryOp::Less ||
         op == ast::BinaryOp::LessEqual || op == ast::BinaryOp::Greater ||
         op == ast::BinaryOp::GreaterEqual;
}

// `a op b` as `b op' a`.
ast::BinaryOp mirrored(ast::BinaryOp op) {
  switch (op) {
    case ast::BinaryOp::Less: return ast::BinaryOp::Greater;
    case ast::BinaryOp::LessEqual: return ast::BinaryOp::GreaterEqual;
    case ast::BinaryOp::Greater: return ast::BinaryOp::Less;
    case ast::BinaryOp::GreaterEqual: return ast::BinaryOp::LessEqual;
    default: return op;
  }
}

}  // namespace

std::vector<ParameterTest> Compiler::guardOf(const ast::Expr& condition, const ModulePattern& first,
                                             int formals, const NameMap& locals) {
  std::vector<ParameterTest> guard;
  const auto formal = [&](const std::string& name) {
    const auto local = locals.find(name);
    return local != locals.end() && local->second < formals;
  };
  if (!pureAndSafe(condition, formal)) return guard;
  // The parameter of `first` that a variable names, if any.
  const auto parameterNamed = [&](const ast::Expr& e) -> std::optional<std::uint8_t> {
    if (e.kind != ast::Expr::Kind::Variable) return std::nullopt;
    const auto local = locals.find(e.name);
    if (local == locals.end()) return std::nullopt;
    const auto slot = std::find(first.slots.begin(), first.slots.end(), local->second);
    if (slot == first.slots.end()) return std::nullopt;
    return static_cast<std::uint8_t>(slot - first.slots.begin());
  };
  std::vector<const ast::Expr*> terms;
  conjuncts(condition, terms);
  for (const ast::Expr* term : terms) {
    if (term->kind != ast::Expr::Kind::Binary || !isComparison(term->binaryOp)) continue;
    const ast::Expr& left = *term->operands[0];
    const ast::Expr& right = *term->operands[1];
    if (const auto parameter = parameterNamed(left)) {
      if (const auto constant = foldConstant(right, nullptr))
        guard.push_back({*parameter, comparisonOutcomes(term->binaryOp), *constant});
    } else if (const auto parameter = parameterNamed(right)) {
      if (const auto constant = foldConstant(left, nullptr))
        guard.push_back(
            {*parameter, comparisonOutcomes(mirrored(term->binaryOp)), *constant});
    }
  }
  return guard;
}

Production Compiler::compileProduction(const ast::Production& in, const NameMap& shared,
                                       const NameMap& arrays) {
  Production out;
  out.where = in.where;
  NameMap locals;
  std::vector<SourceLocation> formalsWhere;  // by slot, while only formals have slots
  auto bind = [&](const ast::ModuleList& patterns, std::vector<ModulePattern>& into) {
    for (const ast::Module& m : patterns) {
      if (m.formals.size() > kMaxModuleParameters) {
        fail(m.where, "a module can have at most " + std::to_string(kMaxModuleParameters) + " parameters");
      }
      ModulePattern p{m.symbol, static_cast<std::uint8_t>(m.formals.size()), {}};
      for (const ast::Formal& formal : m.formals) {
        const std::string& name = formal.name;
        if (findBuiltin(name)) fail(m.where, "'" + name + "' is a built-in function and cannot name a parameter");
        // A formal parameter stands for one value of the matched string; the same name twice,
        // in one module or across the contexts, would stand for two (cpfg manual §3.1).
        auto [it, added] = locals.emplace(name, static_cast<int>(out.slotNames.size()));
        if (!added) {
          const SourceLocation& first = formalsWhere[static_cast<std::size_t>(it->second)];
          fail(formal.where,
               "formal parameter '" + name + "' is named twice in the predecessor (first at " +
                   std::to_string(first.line) + ":" + std::to_string(first.column) + ")");
        }
        out.slotNames.push_back(name);
        formalsWhere.push_back(formal.where);
        p.slots.push_back(it->second);
      }
      into.push_back(std::move(p));
    }
  };
  bind(in.left, out.left);
  bind(in.strict, out.strict);
  bind(in.right, out.right);
  for (const auto& p : out.left) {
    if (p.symbol == '[' || p.symbol == ']' || p.symbol == '=') {
      fail(in.left.front().where, std::string("'") + p.symbol + "' in a left context is not supported");
    }
  }
  const int formals = static_cast<int>(out.slotNames.size());
  std::vector<std::string> assigned;
  collectAssigned(in.before, assigned);
  collectAssigned(in.after, assigned);
  for (const std::string& name : assigned) {
    if (shared.count(name) || globals_.count(name)) continue;
    auto [it, added] = locals.emplace(name, static_cast<int>(out.slotNames.size()));
    if (added) out.slotNames.push_back(name);
  }
  Scope scope{&locals, &out.slotNames, &shared, &arrays};
  out.before = compileCode(in.before, scope);
  out.condition = compileValue(in.condition.get(), scope);
  out.after = compileCode(in.after, scope);
  compileModules(in.successor, scope, out.successor, out.successorValues, out.successorArguments);
  for (const SuccessorModule& m : out.successor) out.callsSubLsystem |= m.symbol == '?' && m.parameterCount > 0;
  ModuleString encoded;
  for (const SuccessorModule& m : out.successor) {
    if (m.parameterCount == 0) {
      encoded.append(m.symbol);
      continue;
    }
    std::size_t start = encoded.byteSize();
    std::vector<float> zeros(m.parameterCount, 0.0f);
    encoded.append(m.symbol, zeros);
    for (std::size_t i = 0; i < m.parameterCount; ++i) {
      out.parameterOffsets.push_back(static_cast<std::uint32_t>(start + 2 + 4 * i));
    }
  }
  out.successorBytes.assign(encoded.bytes(), encoded.bytes() + encoded.byteSize());
  if (in.before.empty() && in.condition && !out.strict.empty())
    out.guard = guardOf(*in.condition, out.strict.front(), formals, locals);
  out.probability = compileValue(in.probability.get(), scope);
  out.frameSize = static_cast<int>(out.slotNames.size());
  return out;
}

void Compiler::compileRuleSet(const std::vector<ast::Production>& in, RuleSet& out,
                              const NameMap& shared, const NameMap& arrays) {
  for (const ast::Production& p : in) {
    out.productions.push_back(compileProduction(p, shared, arrays));
    char first = p.strict.front().symbol;
    out.bySymbol[static_cast<unsigned char>(first) & 0x7f].push_back(
        static_cast<std::uint32_t>(out.productions.size() - 1));
  }
}

void Compiler::compileLsystem(const ast::Lsystem& in, Lsystem& out, NameMap& shared, NameMap& arrays) {
  out.where = in.where;
  out.label = in.label;
  out.id = std::atof(in.label.c_str());
  if (in.derivationLength) {
    double n = constantValue(*in.derivationLength, "the derivation length");
    if (!(n >= 0) || n > 1e9) fail(in.derivationLength->where, "the derivation length must be between 0 and 10^9");
    out.derivationLength = static_cast<int>(n);
    out.hasDerivationLength = true;
  }
  if (in.seed) {
    out.stochastic = true;
    out.seed = constantValue(*in.seed, "the seed");
    // The derivation converts it to an integer (cpfg: seed48 of its low bits).
    if (!(std::fabs(out.seed) < 9e18)) fail(in.seed->where, "the seed is out of the integer range");
  }
  out.ring = in.ring;
  if (in.ignore && in.consider) {
    fail(in.ignoreWhere, "an L-system takes 'ignore:' or 'consider:', not both");
  }
  if (in.ignore) {
    for (char c : *in.ignore) {
      if (c != ' ' && c != '\t') out.ignored[static_cast<unsigned char>(c) & 0x7f] = true;
    }
  } else if (in.consider) {
    out.ignored.fill(true);
    for (char c : *in.consider) {
      if (c != ' ' && c != '\t') out.ignored[static_cast<unsigned char>(c) & 0x7f] = false;
    }
  }

  // Arrays of define:, with their constant dimensions and initial values.
  for (const auto& s : in.define) {
    if (s->kind != ast::Stmt::Kind::Arrays) fail(s->where, "define: holds only 'array' declarations");
    for (const ast::ArrayDeclaration& a : s->arrays) {
      if (arrays.count(a.name)) fail(a.where, "array '" + a.name + "' is declared twice");
      ArrayDefinition def{a.name, {}, a.where};
      if (a.dimensions.size() > kMaxArrayDimensions) {
        fail(a.where, "array '" + a.name + "' has more than " + std::to_string(kMaxArrayDimensions) + " dimensions");
      }
      double cells = 1;
      for (const auto& d : a.dimensions) {
        double n = constantValue(*d, "an array dimension");
        if (!(n >= 1) || n > 1e8) fail(d->where, "an array dimension must be between 1 and 10^8");
        def.dimensions.push_back(static_cast<int>(n));
        cells *= static_cast<int>(n);
      }
      if (cells > 1e8) fail(a.where, "array '" + a.name + "' is too large");
      arrayCells_ += cells;
      if (arrayCells_ > 1e8) fail(a.where, "the arrays together have more than 10^8 elements");
      if (static_cast<double>(a.initializer.size()) > cells) {
        fail(a.initializer[static_cast<std::size_t>(cells)]->where,
             "array '" + a.name + "' has more initial values than elements");
      }
      arrays.emplace(a.name, static_cast<int>(program_.arrays.size()));
      program_.arrays.push_back(def);
    }
  }

  // Variables assigned in the header blocks are the L-system's own.
  std::vector<std::string> names;
  for (const ast::Block* block : {&in.start, &in.startEach, &in.endEach, &in.end}) collectAssigned(*block, names);
  for (const std::string& name : names) {
    if (globals_.count(name) || shared.count(name)) continue;
    if (arrays.count(name)) continue;
    shared.emplace(name, static_cast<int>(program_.sharedNames.size()));
    program_.sharedNames.push_back(name);
  }

  Scope scope{nullptr, nullptr, &shared, &arrays};
  // The define: block's initial values are compiled as element stores run before Start:.
  {
    Builder b;
    for (const auto& s : in.define) {
      for (const ast::ArrayDeclaration& a : s->arrays) {
        int id = arrays.at(a.name);
        const auto& dims = program_.arrays[static_cast<std::size_t>(id)].dimensions;
        for (std::size_t i = 0; i < a.initializer.size(); ++i) {
          std::size_t rest = i;
          std::vector<int> index(dims.size());
          for (std::size_t d = dims.size(); d-- > 0;) {
            index[d] = static_cast<int>(rest % static_cast<std::size_t>(dims[d]));
            rest /= static_cast<std::size_t>(dims[d]);
          }
          std::uint32_t loc = location(a.initializer[i]->where);
          for (int x : index) b.constant(x, loc);
          compileExpr(*a.initializer[i], scope, b);
          b.emit(Op::StoreElement, static_cast<int>(dims.size()), id, loc);
        }
      }
    }
    out.define = finish(b);
  }
  out.start = compileCode(in.start, scope);
  out.startEach = compileCode(in.startEach, scope);
  out.endEach = compileCode(in.endEach, scope);
  out.end = compileCode(in.end, scope);
  if (!in.hasAxiom) fail(in.where, "L-system '" + in.label + "' has no 'Axiom:' line");
  out.axiomWhere = in.axiomWhere;
  compileModules(in.axiom, scope, out.axiom, out.axiomValues, out.axiomArguments);

  compileRuleSet(in.productions, out.productions, shared, arrays);
  compileRuleSet(in.decomposition.productions, out.decomposition, shared, arrays);
  compileRuleSet(in.homomorphism.productions, out.homomorphism, shared, arrays);
  for (auto [from, to] : {std::pair{&in.decomposition, &out.decomposition},
                          std::pair{&in.homomorphism, &out.homomorphism}}) {
    to->present = from->present;
    to->warnings = from->warnings;
    if (from->maximumDepth) {
      double d = constantValue(*from->maximumDepth, "the maximum depth");
      if (!(d >= 1) || d > 10000) fail(from->maximumDepth->where, "the maximum depth must be between 1 and 10000");
      to->maximumDepth = static_cast<int>(d);
    }
    if (from->seed) {
      to->hasSeed = true;
      to->seed = constantValue(*from->seed, "the homomorphism seed");
    }
  }
}

void Compiler::compile(const ast::File& file) {
  // The hidden globals of cpfg: Q is the current step, Z the derivation length.
  program_.stepSlot = 0;
  program_.lengthSlot = 1;
  program_.sharedNames = {"Q", "Z"};
  globals_ = {{"Q", 0}, {"Z", 1}};
  for (const ast::Lsystem& in : file.lsystems) {
    NameMap shared, arrays;
    program_.lsystems.emplace_back();
    compileLsystem(in, program_.lsystems.back(), shared, arrays);
  }
  for (std::size_t i = 0; i < program_.lsystems.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (program_.lsystems[i].id == program_.lsystems[j].id) {
        fail(program_.lsystems[i].where, "two L-systems have the label " + program_.lsystems[i].label);
      }
    }
  }
  if (!program_.lsystems.front().hasDerivationLength) {
    diagnostics_.warn(program_.lsystems.front().where, "no 'derivation length:'; the axiom is the result");
  }
}

}  // namespace

int Program::lsystemIndex(double id) const {
  for (std::size_t i = 0; i < lsystems.size(); ++i) {
    if (lsystems[i].id == id) return static_cast<int>(i);
  }
  return -1;
}

Program compileProgram(const ast::File& file, Diagnostics& diagnostics) {
  Program program;
  Compiler(program, diagnostics).compile(file);
  compileNativeCode(program);
  return program;
}

}  // namespace hirsute
