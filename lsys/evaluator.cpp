#include "hirsute/lsys/evaluator.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "hirsute/lsys/builtins.h"
#include "hirsute/lsys/function_curve.h"
#include "hirsute/lsys/native_code.h"
#include "hirsute/lsys/power.h"
#include "hirsute/lsys/printf_format.h"

namespace hirsute {

namespace {
constexpr double kDegree = M_PI / 180.0;

// A value used as an index or id, truncated as C's cast would, but clamped first so that the
// cast is defined for every double (NaN reads as 0).
long long toInteger(double v) {
  return v == v ? static_cast<long long>(std::clamp(v, -9e18, 9e18)) : 0;
}

// Shapes beyond this make Cheng's beta generator overflow (2ab) and never accept a variate.
constexpr double kMaxBetaShape = 1e150;
}  // namespace

// The math built-ins, shared with the compiler's constant folding. Angles are degrees (cpfg).
double applyMathBuiltin(Builtin b, const double* a, int count) {
  switch (b) {
    case Builtin::Sin: return std::sin(a[0] * kDegree);
    case Builtin::Cos: return std::cos(a[0] * kDegree);
    case Builtin::Tan: return std::tan(a[0] * kDegree);
    case Builtin::Asin: return std::asin(a[0]) / kDegree;
    case Builtin::Acos: return std::acos(a[0]) / kDegree;
    case Builtin::Atan: return (count == 2 ? std::atan2(a[0], a[1]) : std::atan(a[0])) / kDegree;
    case Builtin::Exp: return std::exp(a[0]);
    case Builtin::Log: return std::log(a[0]);
    case Builtin::Sqrt: return std::sqrt(a[0]);
    case Builtin::Fabs: return std::fabs(a[0]);
    case Builtin::Floor: return std::floor(a[0]);
    case Builtin::Ceil: return std::ceil(a[0]);
    case Builtin::Sign: return a[0] > 0 ? 1.0 : a[0] < 0 ? -1.0 : 0.0;
    // cpfg: trunc rounds to the nearest integer.
    case Builtin::Trunc: return std::floor(a[0] + 0.5);
    default: return 0;
  }
}

Evaluator::Evaluator(const Program& program, Diagnostics& diagnostics, const ViewFunctions* functions,
                     std::filesystem::path modelFolder, std::ostream& printOut, EvaluationLimits limits)
    : program_(program),
      diagnostics_(diagnostics),
      functions_(functions),
      modelFolder_(std::move(modelFolder)),
      printOut_(printOut),
      limits_(limits),
      shared_(program.sharedNames.size(), 0.0),
      stack_(static_cast<std::size_t>(program.maxStack) + 8, 0.0) {
  for (const ArrayDefinition& def : program.arrays) {
    std::size_t cells = 1;
    for (int d : def.dimensions) cells *= static_cast<std::size_t>(d);
    ownArrays_.emplace_back(cells, 0.0);
  }
}

std::unique_ptr<Evaluator> Evaluator::fork(Diagnostics& diagnostics) const {
  // Not make_unique: the constructor that allocates no arrays is private.
  return std::unique_ptr<Evaluator>(new Evaluator(*this, diagnostics));
}

Evaluator::Evaluator(const Evaluator& parent, Diagnostics& diagnostics)
    : program_(parent.program_),
      diagnostics_(diagnostics),
      functions_(parent.functions_),
      modelFolder_(parent.modelFolder_),
      printOut_(parent.printOut_),
      limits_(parent.limits_),
      shared_(parent.shared_),
      arrays_(parent.arrays_),
      stack_(parent.stack_.size(), 0.0) {}

Evaluator::~Evaluator() {
  for (std::FILE* f : files_) {
    if (f) std::fclose(f);
  }
}

void Evaluator::fail(std::uint32_t where, const std::string& message) const {
  throw DiagnosticError(program_.locations[where], message);
}

std::size_t Evaluator::elementIndex(std::int32_t array, const double* subscripts, int count,
                                    std::uint32_t where) {
  const auto& dims = program_.arrays[static_cast<std::size_t>(array)].dimensions;
  std::size_t index = 0;
  for (int i = 0; i < count; ++i) {
    double s = subscripts[i];
    long long k = toInteger(s);
    // cpfg clamps out-of-range subscripts, with a warning.
    if (k < 0 || k >= dims[static_cast<std::size_t>(i)]) {
      diagnostics_.warn(program_.locations[where],
                        "subscript " + std::to_string(k) + " of array '" +
                            program_.arrays[static_cast<std::size_t>(array)].name + "' is out of range");
      k = std::clamp<long long>(k, 0, dims[static_cast<std::size_t>(i)] - 1);
    }
    index = index * static_cast<std::size_t>(dims[static_cast<std::size_t>(i)]) + static_cast<std::size_t>(k);
  }
  return index;
}

const double* Evaluator::values(const Code& code, double* frame, std::size_t count) {
  run(code, frame);
  (void)count;
  return stack_.data() + 1;  // run() leaves the values from stack_[1] on
}

// The hot loop: the cases that run for every module stay small so that the stack, frame and
// code pointers live in registers; arrays, modulo, fscanf and every error leave through
// out-of-line helpers. Dispatch is threaded (GCC's labels as values): each case jumps straight
// to the next instruction's case, so the branch predictor sees one indirect jump per case; the
// end is an instruction of its own (Op::End), so no case tests for it.
//
// The top value is kept in a register (`top value`, tv); the values under it are in memory:
// with d values on the stack, v[0] … v[d-1], base[k] holds v[k-1] for k = 1 … d-1 and
// top = base + d. base[0] is a slot below the bottom value that a push onto an empty stack
// writes (the register's stale value) and nothing reads.
double Evaluator::run(const Code& code, double* frame) {
  if (code.native) {
    NativeFrame native{frame, code.constants.data(), shared_.data(), stack_.data() + 1,
                       limits_.maxLoopIterations, 0.0};
    const std::int64_t status = code.native(&native);
    if (status != kNativeDone) [[unlikely]] {
      const Instruction& failed = code.instructions[static_cast<std::size_t>(status / 2)];
      if (status % 2 == 1) failLoop(failed.where);
      fail(failed.where, "division by zero");
    }
    return native.result;
  }
  if (code.instructions.empty()) return 0.0;
  // clang-format off
  static constexpr void* kCases[] = {
      &&constant, &&loadLocal, &&storeLocal, &&loadShared, &&storeShared, &&loadElement,
      &&storeElement, &&pop, &&negate, &&logicalNot, &&truth, &&add, &&subtract, &&multiply,
      &&divide, &&modulo, &&power, &&equal, &&notEqual, &&less, &&lessEqual, &&greater,
      &&greaterEqual, &&jump, &&jumpIfFalse, &&loopBack, &&call, &&scan,
      &&addLocal, &&subtractLocal, &&multiplyLocal, &&divideLocal, &&powerLocal, &&equalLocal,
      &&notEqualLocal, &&lessLocal, &&lessEqualLocal, &&greaterLocal, &&greaterEqualLocal,
      &&addConstant, &&subtractConstant, &&multiplyConstant, &&divideConstant, &&powerConstant,
      &&equalConstant, &&notEqualConstant, &&lessConstant, &&lessEqualConstant,
      &&greaterConstant, &&greaterEqualConstant,
      &&callSin, &&callCos, &&callSqrt, &&callFabs, &&callExp, &&callLog, &&done,
      &&localAddLocal, &&localSubtractLocal, &&localMultiplyLocal, &&localDivideLocal,
      &&localPowerLocal, &&localAddConstant, &&localSubtractConstant, &&localMultiplyConstant,
      &&localDivideConstant, &&localPowerConstant,
      &&unlessEqualLocal, &&unlessNotEqualLocal, &&unlessLessLocal, &&unlessLessEqualLocal,
      &&unlessGreaterLocal, &&unlessGreaterEqualLocal,
      &&unlessEqualConstant, &&unlessNotEqualConstant, &&unlessLessConstant,
      &&unlessLessEqualConstant, &&unlessGreaterConstant, &&unlessGreaterEqualConstant};
  // clang-format on
  static_assert(std::size(kCases) == static_cast<std::size_t>(Op::UnlessGreaterEqualConstant) + 1,
                "one case per Op");
  double* const base = stack_.data();
  double* top = base;
  double tv = 0;
  double* const shared = shared_.data();
  const double* const constants = code.constants.data();
  const Instruction* const first = code.instructions.data();
  const Instruction* in = first;
  std::uint64_t iterations = 0;
  const std::uint64_t maxIterations = limits_.maxLoopIterations;
#define HIRSUTE_NEXT() goto* kCases[static_cast<std::size_t>((++in)->op)]
#define HIRSUTE_GO_TO(target)                            \
  do {                                                   \
    in = first + (target);                               \
    goto* kCases[static_cast<std::size_t>(in->op)];      \
  } while (0)
#define HIRSUTE_PUSH(value) \
  do {                      \
    *top++ = tv;            \
    tv = (value);           \
  } while (0)
  // The whole stack in memory from base[1] on (for the helpers that take a stack pointer, one
  // past the top value), and back.
#define HIRSUTE_SPILL() (*top = tv, top + 1)
#define HIRSUTE_RELOAD(end) \
  do {                      \
    top = (end) - 1;        \
    tv = *top;              \
  } while (0)
  goto* kCases[static_cast<std::size_t>(in->op)];
constant: HIRSUTE_PUSH(constants[in->operand]); HIRSUTE_NEXT();
loadLocal: HIRSUTE_PUSH(frame[in->operand]); HIRSUTE_NEXT();
storeLocal: frame[in->operand] = tv; tv = *--top; HIRSUTE_NEXT();
loadShared: HIRSUTE_PUSH(shared[in->operand]); HIRSUTE_NEXT();
storeShared: shared[in->operand] = tv; tv = *--top; HIRSUTE_NEXT();
loadElement: HIRSUTE_RELOAD(this->loadElement(*in, HIRSUTE_SPILL())); HIRSUTE_NEXT();
storeElement: HIRSUTE_RELOAD(this->storeElement(*in, HIRSUTE_SPILL())); HIRSUTE_NEXT();
pop: tv = *--top; HIRSUTE_NEXT();
negate: tv = -tv; HIRSUTE_NEXT();
logicalNot: tv = tv == 0 ? 1.0 : 0.0; HIRSUTE_NEXT();
truth: tv = tv != 0 ? 1.0 : 0.0; HIRSUTE_NEXT();
  // Binary operators: the left operand is under the top value, the right one is the top value.
#define HIRSUTE_BINARY(name, expression) \
  name : {                               \
    const double a = *--top;             \
    const double b = tv;                 \
    tv = (expression);                   \
    HIRSUTE_NEXT();                      \
  }
  HIRSUTE_BINARY(add, a + b)
  HIRSUTE_BINARY(subtract, a - b)
  HIRSUTE_BINARY(multiply, a * b)
  HIRSUTE_BINARY(power, power(a, b))
  HIRSUTE_BINARY(equal, a == b)
  HIRSUTE_BINARY(notEqual, a != b)
  HIRSUTE_BINARY(less, a < b)
  HIRSUTE_BINARY(lessEqual, a <= b)
  HIRSUTE_BINARY(greater, a > b)
  HIRSUTE_BINARY(greaterEqual, a >= b)
#undef HIRSUTE_BINARY
divide:
  if (tv == 0) fail(in->where, "division by zero");
  tv = *--top / tv;
  HIRSUTE_NEXT();
modulo: tv = this->modulo(*--top, tv, in->where); HIRSUTE_NEXT();
jump: HIRSUTE_GO_TO(in->operand);
jumpIfFalse: {
  const bool no = tv == 0;
  tv = *--top;
  if (no) HIRSUTE_GO_TO(in->operand);
  HIRSUTE_NEXT();
}
loopBack:
  if (++iterations > maxIterations) failLoop(in->where);
  HIRSUTE_GO_TO(in->operand);
call: {
  double* const arguments = HIRSUTE_SPILL() - in->count;
  Builtin id = static_cast<Builtin>(in->operand);
  // The math built-ins go straight to libm; the rest need the evaluator's state.
  tv = isMathBuiltin(id) ? applyMathBuiltin(id, arguments, in->count)
                         : this->call(id, arguments, in->count, in->where);
  top = arguments;
  HIRSUTE_NEXT();
}
scan: HIRSUTE_RELOAD(this->scan(*in, HIRSUTE_SPILL())); HIRSUTE_NEXT();
  // The fused forms: the same operators with the right operand read in place.
#define HIRSUTE_FUSED(name, source, expression) \
  name : {                                      \
    const double b = source[in->operand];       \
    const double a = tv;                        \
    tv = (expression);                          \
    HIRSUTE_NEXT();                             \
  }
  HIRSUTE_FUSED(addLocal, frame, a + b)
  HIRSUTE_FUSED(subtractLocal, frame, a - b)
  HIRSUTE_FUSED(multiplyLocal, frame, a * b)
  HIRSUTE_FUSED(powerLocal, frame, power(a, b))
  HIRSUTE_FUSED(equalLocal, frame, a == b)
  HIRSUTE_FUSED(notEqualLocal, frame, a != b)
  HIRSUTE_FUSED(lessLocal, frame, a < b)
  HIRSUTE_FUSED(lessEqualLocal, frame, a <= b)
  HIRSUTE_FUSED(greaterLocal, frame, a > b)
  HIRSUTE_FUSED(greaterEqualLocal, frame, a >= b)
  HIRSUTE_FUSED(addConstant, constants, a + b)
  HIRSUTE_FUSED(subtractConstant, constants, a - b)
  HIRSUTE_FUSED(multiplyConstant, constants, a * b)
  HIRSUTE_FUSED(powerConstant, constants, power(a, b))
  HIRSUTE_FUSED(equalConstant, constants, a == b)
  HIRSUTE_FUSED(notEqualConstant, constants, a != b)
  HIRSUTE_FUSED(lessConstant, constants, a < b)
  HIRSUTE_FUSED(lessEqualConstant, constants, a <= b)
  HIRSUTE_FUSED(greaterConstant, constants, a > b)
  HIRSUTE_FUSED(greaterEqualConstant, constants, a >= b)
#undef HIRSUTE_FUSED
divideLocal : {
  const double b = frame[in->operand];
  if (b == 0) fail(in->where, "division by zero");
  tv /= b;
  HIRSUTE_NEXT();
}
divideConstant : {
  const double b = constants[in->operand];
  if (b == 0) fail(in->where, "division by zero");
  tv /= b;
  HIRSUTE_NEXT();
}
callSin: tv = std::sin(tv * kDegree); HIRSUTE_NEXT();
callCos: tv = std::cos(tv * kDegree); HIRSUTE_NEXT();
callSqrt: tv = std::sqrt(tv); HIRSUTE_NEXT();
callFabs: tv = std::fabs(tv); HIRSUTE_NEXT();
callExp: tv = std::exp(tv); HIRSUTE_NEXT();
callLog: tv = std::log(tv); HIRSUTE_NEXT();
  // A local and a local or a constant, pushed as the result of their operator.
#define HIRSUTE_PUSHED(name, source, expression) \
  name : {                                       \
    const double a = frame[in->operand];         \
    const double b = source[in->operand2];       \
    HIRSUTE_PUSH(expression);                    \
    HIRSUTE_NEXT();                              \
  }
  HIRSUTE_PUSHED(localAddLocal, frame, a + b)
  HIRSUTE_PUSHED(localSubtractLocal, frame, a - b)
  HIRSUTE_PUSHED(localMultiplyLocal, frame, a * b)
  HIRSUTE_PUSHED(localPowerLocal, frame, power(a, b))
  HIRSUTE_PUSHED(localAddConstant, constants, a + b)
  HIRSUTE_PUSHED(localSubtractConstant, constants, a - b)
  HIRSUTE_PUSHED(localMultiplyConstant, constants, a * b)
  HIRSUTE_PUSHED(localPowerConstant, constants, power(a, b))
#undef HIRSUTE_PUSHED
localDivideLocal: {
  const double b = frame[in->operand2];
  if (b == 0) fail(in->where, "division by zero");
  HIRSUTE_PUSH(frame[in->operand] / b);
  HIRSUTE_NEXT();
}
localDivideConstant: {
  const double b = constants[in->operand2];
  if (b == 0) fail(in->where, "division by zero");
  HIRSUTE_PUSH(frame[in->operand] / b);
  HIRSUTE_NEXT();
}
  // A comparison of the top value, popped, and a jump to operand2 when it is false.
#define HIRSUTE_UNLESS(name, source, expression) \
  name : {                                       \
    const double a = tv;                         \
    const double b = source[in->operand];        \
    tv = *--top;                                 \
    if (!(expression)) HIRSUTE_GO_TO(in->operand2); \
    HIRSUTE_NEXT();                              \
  }
  HIRSUTE_UNLESS(unlessEqualLocal, frame, a == b)
  HIRSUTE_UNLESS(unlessNotEqualLocal, frame, a != b)
  HIRSUTE_UNLESS(unlessLessLocal, frame, a < b)
  HIRSUTE_UNLESS(unlessLessEqualLocal, frame, a <= b)
  HIRSUTE_UNLESS(unlessGreaterLocal, frame, a > b)
  HIRSUTE_UNLESS(unlessGreaterEqualLocal, frame, a >= b)
  HIRSUTE_UNLESS(unlessEqualConstant, constants, a == b)
  HIRSUTE_UNLESS(unlessNotEqualConstant, constants, a != b)
  HIRSUTE_UNLESS(unlessLessConstant, constants, a < b)
  HIRSUTE_UNLESS(unlessLessEqualConstant, constants, a <= b)
  HIRSUTE_UNLESS(unlessGreaterConstant, constants, a > b)
  HIRSUTE_UNLESS(unlessGreaterEqualConstant, constants, a >= b)
#undef HIRSUTE_UNLESS
#undef HIRSUTE_NEXT
#undef HIRSUTE_GO_TO
#undef HIRSUTE_PUSH
#undef HIRSUTE_SPILL
#undef HIRSUTE_RELOAD
done:
  // The values in memory from base[1] on, for values().
  *top = tv;
  return top > base ? tv : 0.0;
}

double* Evaluator::loadElement(const Instruction& in, double* top) {
  top -= in.count;
  std::size_t i = elementIndex(in.operand, top, in.count, in.where);
  *top++ = (*arrays_)[static_cast<std::size_t>(in.operand)][i];
  return top;
}

double* Evaluator::storeElement(const Instruction& in, double* top) {
  double value = *--top;
  top -= in.count;
  std::size_t i = elementIndex(in.operand, top, in.count, in.where);
  (*arrays_)[static_cast<std::size_t>(in.operand)][i] = value;
  return top;
}

double Evaluator::modulo(double a, double b, std::uint32_t where) const {
  // cpfg: integer modulo of the truncated operands.
  if (!std::isfinite(a) || !std::isfinite(b) || std::fabs(a) > 9e18 || std::fabs(b) > 9e18) {
    fail(where, "modulo of a value out of the integer range");
  }
  long long ib = static_cast<long long>(b);
  if (ib == 0) fail(where, "modulo by zero");
  return static_cast<double>(static_cast<long long>(a) % ib);
}

void Evaluator::failLoop(std::uint32_t where) const {
  fail(where, "the loop ran more than " + std::to_string(limits_.maxLoopIterations) +
                  " iterations (raise --max-loop-iterations if it is meant to)");
}

double* Evaluator::scan(const Instruction& in, double* top) {
  double id = *--top;
  std::FILE* f = file(id, in.where);
  const std::string& fmt = program_.strings[static_cast<std::size_t>(in.operand)];
  // Each conversion reads one number into a double.
  std::vector<double> read;
  std::size_t pos = 0;
  int result = 0;
  bool failed = false;
  while (pos < fmt.size() && !failed) {
    char c = fmt[pos];
    if (c == '%' && pos + 1 < fmt.size() && fmt[pos + 1] != '%') {
      std::size_t end = fmt.find_first_of("eEfgGdiuxX", pos + 1);
      if (end == std::string::npos) break;
      std::string spec = "%lf";
      if (static_cast<int>(read.size()) >= in.count) break;
      double v = 0;
      if (std::fscanf(f, spec.c_str(), &v) == 1) {
        read.push_back(v);
        ++result;
      } else {
        failed = true;
      }
      pos = end + 1;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      std::fscanf(f, " ");
      ++pos;
    } else {
      int got = std::fgetc(f);
      if (got != c) {
        if (got != EOF) std::ungetc(got, f);
        failed = true;
      }
      pos += (c == '%') ? 2 : 1;
    }
  }
  *top++ = (result == 0 && std::feof(f)) ? -1.0 : result;
  // Values for targets that got nothing keep their value: push a marker-free copy.
  for (int i = in.count; i-- > 0;) *top++ = i < static_cast<int>(read.size()) ? read[static_cast<std::size_t>(i)] : 0.0;
  return top;
}

double Evaluator::call(Builtin id, const double* a, int count, std::uint32_t where) {
  switch (id) {
    case Builtin::Ran: return random_->ran(a[0]);
    case Builtin::Nran: return random_->nran(a[0], a[1]);
    case Builtin::Bran:
      if (!(a[0] <= kMaxBetaShape && a[1] <= kMaxBetaShape)) {
        fail(where, "bran: shapes above 1e150 (or infinite) have no usable beta variate");
      }
      return random_->bran(a[0], a[1]);
    case Builtin::Biran:
      // One draw per trial: a count beyond the loop limit would run as long as a runaway loop.
      if (a[0] > static_cast<double>(limits_.maxLoopIterations)) {
        fail(where, "biran: more than " + std::to_string(limits_.maxLoopIterations) +
                        " trials (raise --max-loop-iterations if it is meant to)");
      }
      return random_->biran(a[0], a[1]);
    case Builtin::Srand: random_->srand(a[0]); return 0;
    case Builtin::Func: {
      long long index = toInteger(a[0]);
      if (!functions_ || index < 1 || index > static_cast<long long>(functions_->functions.size())) {
        // cpfg: an unknown function id warns and reads as 0.
        diagnostics_.warn(program_.locations[where],
                          "func(" + std::to_string(index) + ", …): the view file declares " +
                              std::to_string(functions_ ? functions_->functions.size() : 0) +
                              " function(s) with 'function:' or 'function set:'; it reads as 0");
        return 0;
      }
      return functions_->functions[static_cast<std::size_t>(index - 1)].evaluate(a[1]);
    }
    case Builtin::CurveX: case Builtin::CurveY: case Builtin::CurveZ: case Builtin::CurveGal: {
      long long index = toInteger(a[0]);
      if (!functions_ || index < 1 || index > static_cast<long long>(functions_->curves.size())) {
        fail(where, "curve " + std::to_string(index) + " is not declared with 'curve:' in the view file");
      }
      const ContourCurve& curve = functions_->curves[static_cast<std::size_t>(index - 1)];
      if (id == Builtin::CurveGal) return curve.length();
      auto p = curve.point(a[1]);
      return p[id == Builtin::CurveX ? 0 : id == Builtin::CurveY ? 1 : 2];
    }
    case Builtin::Printf: {
      printOut_ << format(program_.strings[static_cast<std::size_t>(a[0])], a + 1, count - 1, where);
      printOut_.flush();
      return 0;
    }
    case Builtin::Fopen:
      return openFile(program_.strings[static_cast<std::size_t>(a[0])],
                      program_.strings[static_cast<std::size_t>(a[1])], where);
    case Builtin::Fclose: {
      std::FILE* f = file(a[0], where);
      std::fclose(f);
      files_[static_cast<std::size_t>(a[0]) - 1] = nullptr;
      return 0;
    }
    case Builtin::Fflush: std::fflush(file(a[0], where)); return 0;
    case Builtin::Fprintf: {
      std::string text = format(program_.strings[static_cast<std::size_t>(a[1])], a + 2, count - 2, where);
      std::FILE* f = file(a[0], where);
      if (text.size() > limits_.maxWrittenBytes - std::min(writtenBytes_, limits_.maxWrittenBytes)) {
        fail(where, "fprintf: the blocks would write more than " + std::to_string(limits_.maxWrittenBytes) +
                        " bytes to files (--max-file-bytes)");
      }
      writtenBytes_ += text.size();
      std::fwrite(text.data(), 1, text.size(), f);
      return 0;
    }
    case Builtin::Stop: stopRequested_ = true; return 0;
    case Builtin::Fscanf: return 0;  // compiled to Op::Scan
    default: return applyMathBuiltin(id, a, count);
  }
}

std::string Evaluator::format(const std::string& fmt, const double* args, int count, std::uint32_t where) {
  PrintfResult result = formatPrintf(fmt, args, count);
  if (result.missingValues) fail(where, "the format has more conversions than values");
  if (result.fieldTooWide > 0) {
    fail(where, "the format asks for a field of " + std::to_string(result.fieldTooWide) +
                    " characters; the limit is " + std::to_string(kMaxPrintfField));
  }
  return std::move(result.text);
}

double Evaluator::openFile(const std::string& name, const std::string& mode, std::uint32_t where) {
  // Files are confined to the model's folder (model_folder.h): a name beneath it, no way up,
  // no link followed out, and only regular files.
  FileAccess access{};
  if (!fileAccessOfMode(mode, access)) {
    fail(where, "fopen: mode '" + mode + "' is not one of r, w, a (with + or b)");
  }
  std::size_t open = static_cast<std::size_t>(std::count_if(files_.begin(), files_.end(), [](auto* f) { return f; }));
  if (static_cast<int>(open) >= limits_.maxOpenFiles) fail(where, "fopen: too many open files");
  ConfinedFile confined = modelFolder_.open(name, access);
  if (confined.refused) fail(where, "fopen: cannot open '" + name + "': " + confined.failure);
  if (!confined) {
    diagnostics_.warn(program_.locations[where], "fopen: cannot open '" + name + "': " + confined.failure);
    return 0;
  }
  std::FILE* f = fdopen(confined.fd.get(), mode.c_str());
  if (!f) fail(where, "fopen: cannot open '" + name + "': " + std::strerror(errno));
  confined.fd.release();
  for (std::size_t i = 0; i < files_.size(); ++i) {
    if (!files_[i]) {
      files_[i] = f;
      return static_cast<double>(i + 1);
    }
  }
  files_.push_back(f);
  return static_cast<double>(files_.size());
}

std::FILE* Evaluator::file(double id, std::uint32_t where) {
  long long i = toInteger(id);
  if (i < 1 || i > static_cast<long long>(files_.size()) || !files_[static_cast<std::size_t>(i - 1)]) {
    fail(where, "file id " + std::to_string(i) + " is not an open file (fopen returns the id)");
  }
  return files_[static_cast<std::size_t>(i - 1)];
}

}  // namespace hirsute
