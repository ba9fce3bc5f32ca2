// cpfg's power operator `^`: std::pow's value to the last bit, without the call for the squares
// and cubes that blocks compute most.
//
// glibc's pow (the algorithm of its 2.28 and later) is within 0.54 ulp of the exact power: its
// exp part errs by at most 0.511 ulp and its log part adds |y log x| times 1.5 2^-68 relative,
// which the 0.54 covers up to the largest |y log x| (about 710). When the exact power lies within
// 0.4 ulp of a double p, every other double is more than 0.6 ulp from it, so pow returns p. For
// moderate bases (2^-16 < |x| < 2^16, so |y log x| < 34 and pow errs by less than 0.513 ulp) the
// same holds within 0.47 ulp. For y = 2 and y = 3 the exact power is known to far better than
// an ulp from products split into halves (Dekker's product, no fused multiply-add needed): the
// nearest double p and its distance from the exact value. Where that distance is not under the
// bound (about one time in sixteen for moderate bases), near a power of two, and outside a safe
// range of magnitudes, std::pow answers instead. tests/lsys/power_test.cpp compares the two on
// millions of arguments.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

namespace hirsute {

namespace power_detail {

// a = high + low exactly, each half with at most 26 significant bits (Veltkamp's split).
inline void split(double a, double& high, double& low) {
  const double c = 134217729.0 * a;  // 2^27 + 1
  high = c - (c - a);
  low = a - high;
}

// a b = product + error exactly (Dekker), for |a b| well inside the normal range.
inline void exactProduct(double a, double b, double& product, double& error) {
  product = a * b;
  double ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  error = ((ah * bh - product) + ah * bl + al * bh) + al * bl;
}

// The same exact product with a fused multiply-add for the error: one instruction for the six
// of the split, the same exact value. Only where the processor has it (powerFma).
inline void exactProductFused(double a, double b, double& product, double& error) {
  product = a * b;
  error = std::fma(a, b, -product);
}

// The unit in the last place of a positive normal double that is not a power of two; 0 where it
// is one (or is not normal), which no distance is below.
inline double ulpUnlessPowerOfTwo(double p) {
  const auto bits = std::bit_cast<std::uint64_t>(std::fabs(p));
  const std::uint64_t exponent = bits >> 52;
  if ((bits & ((std::uint64_t{1} << 52) - 1)) == 0 || exponent <= 53 || exponent >= 0x7ff)
    return 0;
  return std::bit_cast<double>((exponent - 52) << 52);
}

// How near the exact power must lie to a double for pow to return that double, in its ulps.
inline double roundingBound(double ax) { return ax > 0x1p-16 && ax < 0x1p16 ? 0.47 : 0.4; }

// x^y as power() below computes it, with `Product` for the exact products. Where the compiler
// may contract a sum of a product into a fused multiply-add (powerFused), s and the test's slack
// come out only nearer their exact values, which the bounds allow. Call it with an exponent the
// compiler does not know: it turns std::pow(x, 2.0) into x*x, which libm's pow is not always.
template <void (*Product)(double, double, double&, double&)>
inline double powerWith(double x, double y) {
  using namespace power_detail;
  const double ax = std::fabs(x);
  if (y == 2 && ax < 0x1p450 && ax > 0x1p-450) {
    double p, e;
    Product(x, x, p, e);  // x^2 = p + e exactly
    if (std::fabs(e) < roundingBound(ax) * ulpUnlessPowerOfTwo(p)) return p;
  } else if (y == 3 && ax < 0x1p300 && ax > 0x1p-300) {
    double p2, e2, t, et;
    Product(x, x, p2, e2);  // x^2 = p2 + e2
    Product(p2, x, t, et);  // p2 x = t + et
    // x^3 = t + et + e2 x; s carries the last two to within 2^-104 |x^3|.
    const double s = et + e2 * x;
    const double q = t + s;
    const double rest = s - (q - t);  // t + s - q, exactly (|s| is below an ulp of t)
    if (std::fabs(rest) + 0x1p-100 * std::fabs(q) < roundingBound(ax) * ulpUnlessPowerOfTwo(q)) {
      return q;
    }
  }
  return std::pow(x, y);
}

}  // namespace power_detail

// x^y, exactly as std::pow(x, y).
inline double power(double x, double y) {
  return power_detail::powerWith<power_detail::exactProduct>(x, y);
}

// The same value, the products' errors taken with fused multiply-adds (the same exact values, so
// the same result to the bit): shorter chains of dependent operations. Only for processors with
// FMA (__builtin_cpu_supports("fma")); the machine code of native_code.h calls it there.
[[gnu::target("fma")]] inline double powerFused(double x, double y) {
  return power_detail::powerWith<power_detail::exactProductFused>(x, y);
}

}  // namespace hirsute
