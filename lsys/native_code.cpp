#include "hirsute/lsys/native_code.h"

#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <vector>

#include "hirsute/lsys/builtins.h"
#include "hirsute/lsys/power.h"
#include "hirsute/lsys/program.h"

#if defined(__x86_64__) && defined(HIRSUTE_HAVE_XBYAK)
#define HIRSUTE_NATIVE_CODE 1
#include <xbyak/xbyak.h>
#endif

namespace hirsute {

namespace {

// The operations the machine code calls, computed as the evaluator computes them.
constexpr double kDegree = M_PI / 180.0;
double callPower(double a, double b) {
  return power(a, b);
}
// The exponent of x^2 and x^3, hidden from the compiler: it would turn the std::pow(x, 2.0) that
// power() falls back on into x*x, which is not always libm's pow (the evaluator's exponent is a
// value, and so is cpfg's).
double exponent(double y) {
  asm("" : "+x"(y));
  return y;
}
// The exponents written most: one argument less to pass.
double callSquare(double a) {
  return power(a, exponent(2.0));
}
double callCube(double a) {
  return power(a, exponent(3.0));
}
// With fused multiply-adds, where the processor has them: the same values, sooner.
[[gnu::target("fma")]] double callPowerFused(double a, double b) {
  return powerFused(a, b);
}
[[gnu::target("fma")]] double callSquareFused(double a) {
  return powerFused(a, exponent(2.0));
}
[[gnu::target("fma")]] double callCubeFused(double a) {
  return powerFused(a, exponent(3.0));
}
struct PowerCalls {
  double (*power)(double, double);
  double (*square)(double);
  double (*cube)(double);
};
PowerCalls powerCalls() {
  if (__builtin_cpu_supports("fma")) return {&callPowerFused, &callSquareFused, &callCubeFused};
  return {&callPower, &callSquare, &callCube};
}
double callSin(double a) {
  return std::sin(a * kDegree);
}
double callCos(double a) {
  return std::cos(a * kDegree);
}
double callExp(double a) {
  return std::exp(a);
}
double callLog(double a) {
  return std::log(a);
}
double callMath(int id, const double* arguments, int count) {
  return applyMathBuiltin(static_cast<Builtin>(id), arguments, count);
}

bool inRange(Op op, Op first, Op last) {
  return op >= first && op <= last;
}

// How an instruction changes the number of values on the stack.
int stackEffect(const Instruction& in) {
  const Op op = in.op;
  switch (op) {
    case Op::Constant:
    case Op::LoadLocal:
    case Op::LoadShared:
      return 1;
    case Op::StoreLocal:
    case Op::StoreShared:
    case Op::Pop:
    case Op::JumpIfFalse:
      return -1;
    case Op::Negate:
    case Op::Not:
    case Op::Truth:
    case Op::Jump:
    case Op::LoopBack:
    case Op::End:
      return 0;
    case Op::Call:
      return 1 - in.count;
    default:
      break;
  }
  if (inRange(op, Op::Add, Op::GreaterEqual)) return -1;
  if (inRange(op, Op::AddLocal, Op::GreaterEqualConstant)) return 0;
  if (inRange(op, Op::CallSin, Op::CallLog)) return 0;
  if (inRange(op, Op::LocalAddLocal, Op::LocalPowerConstant)) return 1;
  if (inRange(op, Op::UnlessEqualLocal, Op::UnlessGreaterEqualConstant)) return -1;
  return 0;
}

// The number of values on the stack before each instruction, -1 where none reaches it; empty
// when two ways reach an instruction with different numbers, or a value would be popped that is
// not there (the code is then left to the evaluator).
std::vector<int> depths(const Code& code) {
  const std::size_t n = code.instructions.size();
  std::vector<int> depth(n, -1);
  std::vector<std::size_t> work{0};
  depth[0] = 0;
  const auto reach = [&](std::int32_t target, int d) {
    if (target < 0 || static_cast<std::size_t>(target) >= n) return false;
    int& known = depth[static_cast<std::size_t>(target)];
    if (known == -1) {
      known = d;
      work.push_back(static_cast<std::size_t>(target));
      return true;
    }
    return known == d;
  };
  while (!work.empty()) {
    const std::size_t i = work.back();
    work.pop_back();
    const Instruction& in = code.instructions[i];
    if (in.op == Op::End) continue;
    const int after = depth[i] + stackEffect(in);
    const int popped = in.op == Op::Call ? in.count : stackEffect(in) < 0 ? 1 : 0;
    const bool binary = inRange(in.op, Op::Add, Op::GreaterEqual);
    if (depth[i] < popped + (binary ? 1 : 0) || after < 0) return {};
    if (depth[i] == 0 && (inRange(in.op, Op::Negate, Op::Truth) ||
                          inRange(in.op, Op::AddLocal, Op::GreaterEqualConstant) ||
                          inRange(in.op, Op::CallSin, Op::CallLog))) {
      return {};
    }
    const std::int32_t target = jumpTarget(in);
    if (target >= 0 && !reach(target, after)) return {};
    if (fallsThrough(in.op) && !reach(static_cast<std::int32_t>(i + 1), after)) return {};
  }
  return depth;
}

}  // namespace

bool compilable(const Code& code) {
  for (const Instruction& in : code.instructions) {
    switch (in.op) {
      case Op::LoadElement:
      case Op::StoreElement:
      case Op::Modulo:
      case Op::Scan:
        return false;
      case Op::Call:
        if (!isMathBuiltin(static_cast<Builtin>(in.operand))) return false;
        break;
      default:
        break;
    }
  }
  return true;
}

#ifdef HIRSUTE_NATIVE_CODE

namespace {

using namespace Xbyak;
using namespace Xbyak::util;

// Registers while a code runs: the frame, constants, shared variables and stack pointers, the
// loop counter and the NativeFrame; the top value in xmm0 (the evaluator's register), the values
// under it in memory, the k-th from the bottom at stack[k].
class Generator : public CodeGenerator {
 public:
  Generator() : CodeGenerator(4096, AutoGrow) {}

  // Generates one function; its offset from the start of the code.
  std::size_t function(const Code& code, const std::vector<int>& depth) {
    align(16);
    const std::size_t start = getSize();
    const Reg64 frame = rbx, constants = r12, shared = r13, stack = r14, counter = r15,
                context = rbp;
    push(rbx);
    push(rbp);
    push(r12);
    push(r13);
    push(r14);
    push(r15);
    sub(rsp, 8);  // 16-byte alignment at every call
    mov(context, rdi);
    mov(frame, ptr[context + offsetof(NativeFrame, frame)]);
    mov(constants, ptr[context + offsetof(NativeFrame, constants)]);
    mov(shared, ptr[context + offsetof(NativeFrame, shared)]);
    mov(stack, ptr[context + offsetof(NativeFrame, stack)]);
    xor_(counter, counter);
    Label exit, one;
    const std::size_t n = code.instructions.size();
    std::vector<Label> at(n);
    std::deque<std::pair<Label, std::int64_t>> failures;  // Labels stay where they are
    const auto slot = [&](int k) { return qword[stack + 8 * k]; };
    const auto local = [&](std::int32_t k) { return qword[frame + 8 * k]; };
    const auto constant = [&](std::int32_t k) { return qword[constants + 8 * k]; };
    const auto fail = [&](std::size_t i, int kind) -> Label& {
      failures.emplace_back(Label(), static_cast<std::int64_t>(i) * 2 + kind);
      return failures.back().first;
    };
    // A jump to `failure` when xmm `v` is zero (not when it is NaN).
    const auto failIfZero = [&](const Xmm& v, std::size_t i) {
      Label nonzero;
      xorpd(xmm7, xmm7);
      ucomisd(v, xmm7);
      jp(nonzero);
      Label& failure = fail(i, 0);
      je(failure, T_NEAR);
      L(nonzero);
    };
    // Pops the top value: the one under it comes into xmm0 (flags are kept).
    const auto popValue = [&](int d) {
      if (d >= 2) movsd(xmm0, slot(d - 2));
    };
    // Pushes: the top value goes to memory and xmm0 is free for the new one.
    const auto spill = [&](int d) {
      if (d >= 1) movsd(slot(d - 1), xmm0);
    };
    // xmm `a` = a + b, a - b or a * b (offsets 0, 1, 2 from Add; division and power have their
    // own code).
    const auto arithmetic = [&](int offset, const Xmm& a, const Operand& b) {
      switch (offset) {
        case 0:
          addsd(a, b);
          break;
        case 1:
          subsd(a, b);
          break;
        case 2:
          mulsd(a, b);
          break;
        default:
          break;
      }
    };
    // xmm `result` = the comparison's mask (all ones or zero) of xmm0 (a) and xmm `b`; `offset`:
    // Equal … GreaterEqual. a > b is b < a, a >= b is b <= a, false with a NaN as in C.
    const auto compare = [&](int offset, const Xmm& result, const Xmm& b) {
      static const std::uint8_t kPredicate[] = {0, 4, 1, 2, 1, 2};  // eq, neq, lt, le, lt, le
      if (offset >= 4) {
        movapd(result, b);
        cmpsd(result, xmm0, kPredicate[offset]);
      } else {
        movapd(result, xmm0);
        cmpsd(result, b, kPredicate[offset]);
      }
    };
    // xmm0 = xmm0 ^ b, where b is the constant `exponent` when that is known.
    static const PowerCalls powers = powerCalls();
    const auto callPowerOf = [&](const double* exponent, const Address& b) {
      if (exponent && *exponent == 2.0) {
        mov(rax, reinterpret_cast<std::uintptr_t>(powers.square));
      } else if (exponent && *exponent == 3.0) {
        mov(rax, reinterpret_cast<std::uintptr_t>(powers.cube));
      } else {
        movsd(xmm1, b);
        mov(rax, reinterpret_cast<std::uintptr_t>(powers.power));
      }
      call(rax);
    };
    // xmm0 = xmm0 OP b for Add, Subtract, Multiply, Divide and Power (offsets 0 … 4 from Add);
    // `exponent` is b's value when it is a constant.
    const auto operate = [&](int offset, const Address& b, const double* exponent, std::size_t i) {
      if (offset <= 2) {
        arithmetic(offset, xmm0, b);
      } else if (offset == 3) {
        movsd(xmm1, b);
        failIfZero(xmm1, i);
        divsd(xmm0, xmm1);
      } else {
        callPowerOf(exponent, b);
      }
    };
    const auto toOneOrZero = [&](const Xmm& mask) {
      movsd(xmm6, ptr[rip + one]);
      andpd(mask, xmm6);
    };
    for (std::size_t i = 0; i < n; ++i) {
      L(at[i]);
      const int d = depth[i];
      if (d < 0) continue;  // never reached
      const Instruction& in = code.instructions[i];
      const Op op = in.op;
      switch (op) {
        case Op::Constant:
          spill(d);
          movsd(xmm0, constant(in.operand));
          continue;
        case Op::LoadLocal:
          spill(d);
          movsd(xmm0, local(in.operand));
          continue;
        case Op::LoadShared:
          spill(d);
          movsd(xmm0, qword[shared + 8 * in.operand]);
          continue;
        case Op::StoreLocal:
          movsd(local(in.operand), xmm0);
          popValue(d);
          continue;
        case Op::StoreShared:
          movsd(qword[shared + 8 * in.operand], xmm0);
          popValue(d);
          continue;
        case Op::Pop:
          popValue(d);
          continue;
        case Op::Negate:
          movq(rax, xmm0);
          btc(rax, 63);
          movq(xmm0, rax);
          continue;
        case Op::Not:
        case Op::Truth:
          xorpd(xmm1, xmm1);
          cmpsd(xmm0, xmm1, op == Op::Not ? 0 : 4);
          toOneOrZero(xmm0);
          continue;
        case Op::Divide:
          failIfZero(xmm0, i);
          movsd(xmm1, slot(d - 2));
          divsd(xmm1, xmm0);
          movapd(xmm0, xmm1);
          continue;
        case Op::Power:
          movapd(xmm1, xmm0);
          movsd(xmm0, slot(d - 2));
          mov(rax, reinterpret_cast<std::uintptr_t>(powers.power));
          call(rax);
          continue;
        case Op::Jump:
          jmp(at[static_cast<std::size_t>(in.operand)], T_NEAR);
          continue;
        case Op::JumpIfFalse: {
          xorpd(xmm7, xmm7);
          ucomisd(xmm0, xmm7);
          popValue(d);
          Label nonzero;
          jp(nonzero);
          je(at[static_cast<std::size_t>(in.operand)], T_NEAR);
          L(nonzero);
          continue;
        }
        case Op::LoopBack:
          inc(counter);
          cmp(counter, ptr[context + offsetof(NativeFrame, maxIterations)]);
          ja(fail(i, 1), T_NEAR);
          jmp(at[static_cast<std::size_t>(in.operand)], T_NEAR);
          continue;
        case Op::Call:
          spill(d);
          mov(edi, in.operand);
          lea(rsi, ptr[stack + 8 * (d - in.count)]);
          mov(edx, in.count);
          mov(rax, reinterpret_cast<std::uintptr_t>(&callMath));
          call(rax);
          continue;
        case Op::End:
          if (d >= 1) {
            movsd(slot(d - 1), xmm0);
          } else {
            xorpd(xmm0, xmm0);
          }
          movsd(qword[context + offsetof(NativeFrame, result)], xmm0);
          mov(rax, kNativeDone);
          jmp(exit, T_NEAR);
          continue;
        default:
          break;
      }
      if (inRange(op, Op::Add, Op::Multiply)) {
        movsd(xmm1, slot(d - 2));
        arithmetic(static_cast<int>(op) - static_cast<int>(Op::Add), xmm1, xmm0);
        movapd(xmm0, xmm1);
      } else if (inRange(op, Op::Equal, Op::GreaterEqual)) {
        // a (under the top) against b (the top): the comparison of a in xmm0.
        movapd(xmm2, xmm0);
        movsd(xmm0, slot(d - 2));
        compare(static_cast<int>(op) - static_cast<int>(Op::Equal), xmm1, xmm2);
        toOneOrZero(xmm1);
        movapd(xmm0, xmm1);
      } else if (inRange(op, Op::AddLocal, Op::GreaterEqualConstant)) {
        const bool fromLocal = op <= Op::GreaterEqualLocal;
        const int offset =
            static_cast<int>(op) - static_cast<int>(fromLocal ? Op::AddLocal : Op::AddConstant);
        const Address b = fromLocal ? local(in.operand) : constant(in.operand);
        if (offset <= 4) {
          operate(offset, b,
                  fromLocal ? nullptr : &code.constants[static_cast<std::size_t>(in.operand)], i);
        } else {
          movsd(xmm2, b);
          compare(offset - 5, xmm1, xmm2);
          toOneOrZero(xmm1);
          movapd(xmm0, xmm1);
        }
      } else if (inRange(op, Op::CallSin, Op::CallLog)) {
        if (op == Op::CallFabs) {
          movq(rax, xmm0);
          btr(rax, 63);
          movq(xmm0, rax);
        } else if (op == Op::CallSqrt) {
          sqrtsd(xmm0, xmm0);  // correctly rounded, as std::sqrt
        } else {
          double (*function)(double) = nullptr;
          switch (op) {
            case Op::CallSin:
              function = &callSin;
              break;
            case Op::CallCos:
              function = &callCos;
              break;
            case Op::CallExp:
              function = &callExp;
              break;
            default:
              function = &callLog;
              break;
          }
          mov(rax, reinterpret_cast<std::uintptr_t>(function));
          call(rax);
        }
      } else if (inRange(op, Op::LocalAddLocal, Op::LocalPowerConstant)) {
        const bool fromLocal = op <= Op::LocalPowerLocal;
        const int offset = static_cast<int>(op) -
                           static_cast<int>(fromLocal ? Op::LocalAddLocal : Op::LocalAddConstant);
        const Address b = fromLocal ? local(in.operand2) : constant(in.operand2);
        spill(d);
        movsd(xmm0, local(in.operand));
        operate(offset, b,
                fromLocal ? nullptr : &code.constants[static_cast<std::size_t>(in.operand2)], i);
      } else if (inRange(op, Op::UnlessEqualLocal, Op::UnlessGreaterEqualConstant)) {
        const bool fromLocal = op <= Op::UnlessGreaterEqualLocal;
        const int offset =
            static_cast<int>(op) -
            static_cast<int>(fromLocal ? Op::UnlessEqualLocal : Op::UnlessEqualConstant);
        movsd(xmm2, fromLocal ? local(in.operand) : constant(in.operand));
        compare(offset, xmm1, xmm2);
        movq(rax, xmm1);
        popValue(d);
        test(rax, rax);
        jz(at[static_cast<std::size_t>(in.operand2)], T_NEAR);
      }
    }
    for (auto& [label, status] : failures) {
      L(label);
      mov(rax, status);
      jmp(exit, T_NEAR);
    }
    L(exit);
    add(rsp, 8);
    pop(r15);
    pop(r14);
    pop(r13);
    pop(r12);
    pop(rbp);
    pop(rbx);
    ret();
    align(8);
    L(one);
    dq(0x3ff0000000000000ull);  // 1.0
    return start;
  }
};

class GeneratedCode : public NativeCode {
 public:
  Generator generator;
};

void forEachCode(Program& program, const auto& visit) {
  for (Lsystem& l : program.lsystems) {
    for (Code* code : {&l.define, &l.start, &l.startEach, &l.endEach, &l.end, &l.axiomValues}) {
      visit(*code);
    }
    for (RuleSet* rules : {&l.productions, &l.decomposition, &l.homomorphism}) {
      for (Production& p : rules->productions) {
        for (Code* code : {&p.before, &p.condition, &p.after, &p.successorValues, &p.probability}) {
          visit(*code);
        }
      }
    }
  }
}

}  // namespace

std::shared_ptr<const NativeCode> compileNativeCodes(const std::vector<Code*>& codes) {
  for (Code* code : codes) code->native = nullptr;
  try {
    auto generated = std::make_shared<GeneratedCode>();
    std::vector<std::pair<Code*, std::size_t>> compiled;
    for (Code* code : codes) {
      if (code->empty() || !compilable(*code)) continue;
      const std::vector<int> depth = depths(*code);
      if (depth.empty()) continue;
      compiled.emplace_back(code, generated->generator.function(*code, depth));
    }
    if (compiled.empty()) return nullptr;
    generated->generator.readyRE();  // the code becomes executable and is no longer writable
    const std::uint8_t* base = generated->generator.getCode();
    for (auto& [code, offset] : compiled) {
      code->native = reinterpret_cast<NativeFunction>(const_cast<std::uint8_t*>(base + offset));
    }
    return generated;
  } catch (const Xbyak::Error&) {
    // No executable memory to be had (a hardened kernel, a limit): the evaluator runs it all.
  } catch (const std::bad_alloc&) {
  }
  for (Code* code : codes) code->native = nullptr;
  return nullptr;
}

void compileNativeCode(Program& program) {
  const char* setting = std::getenv("HIRSUTE_NATIVE_CODE");
  if (setting && std::strcmp(setting, "0") == 0) return;
  std::vector<Code*> codes;
  forEachCode(program, [&](Code& code) { codes.push_back(&code); });
  program.nativeCode = compileNativeCodes(codes);
}

void dropNativeCode(Program& program) {
  forEachCode(program, [](Code& code) { code.native = nullptr; });
  program.nativeCode.reset();
}

#else

std::shared_ptr<const NativeCode> compileNativeCodes(const std::vector<Code*>& codes) {
  for (Code* code : codes) code->native = nullptr;
  return nullptr;
}

void compileNativeCode(Program&) {}

void dropNativeCode(Program& program) {
  program.nativeCode.reset();
}

#endif

}  // namespace hirsute
