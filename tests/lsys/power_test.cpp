// cpfg's `^` (power.h) against std::pow, bit for bit: squares and cubes of random doubles of
// every magnitude the fast path takes and beyond it, of numbers blocks compute (cosines, small
// integers and their neighbours), and the special values; other exponents go to std::pow. The
// same for powerFused, where the processor has fused multiply-adds.
#include "hirsute/lsys/power.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace hirsute {
namespace {

// Equal as bit patterns (NaNs compared as NaNs).
bool same(double a, double b) {
  return std::isnan(a) ? std::isnan(b) : std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// powerFused where the processor has fused multiply-adds, else power.
double fused(double x, double y) {
  return __builtin_cpu_supports("fma") ? powerFused(x, y) : power(x, y);
}

// The exponent, hidden from the compiler: knowing it, it would turn std::pow(x, 2.0) into x*x,
// which libm's pow is not always, and the reference would not be libm's.
double opaque(double y) {
  asm("" : "+x"(y));
  return y;
}

void expectPowOnEach(const std::vector<double>& bases, double exponent, std::size_t& fast) {
  const double y = opaque(exponent);
  for (double x : bases) {
    const double want = std::pow(x, y);
    const double got = power(x, y);
    ASSERT_TRUE(same(got, want)) << std::hexfloat << x << " ^ " << y << ": " << got << ", std::pow "
                                 << want;
    ASSERT_TRUE(same(fused(x, y), want)) << std::hexfloat << x << " ^ " << y << " (fused)";
    fast += got == x * x * (y == 3 ? x : 1);  // a rough share of the values the products gave
  }
}

TEST(Power, SquaresAndCubesOfRandomDoublesAreStdPowsToTheBit) {
  std::mt19937_64 random(20261202);
  std::uniform_real_distribution<double> mantissa(1, 2);
  std::uniform_int_distribution<int> exponent(-520, 520);
  std::vector<double> bases;
  for (int i = 0; i < 4'000'000; ++i) {
    const double x = std::ldexp(mantissa(random), exponent(random));
    bases.push_back(i % 2 ? x : -x);
  }
  std::size_t fast = 0;
  expectPowOnEach(bases, 2, fast);
  expectPowOnEach(bases, 3, fast);
  EXPECT_GT(fast, bases.size());  // most of them took the products
}

// Moderate bases take the wider bound (0.47 ulp): millions of them, among them many whose exact
// square or cube lies between 0.4 and 0.47 ulp from the nearest double, where only that bound
// takes the products' value.
TEST(Power, ModerateBasesNearTheWiderBoundAreStdPowsToTheBit) {
  std::mt19937_64 random(20261203);
  std::uniform_real_distribution<double> mantissa(1, 2);
  std::uniform_int_distribution<int> exponent(-16, 15);
  std::vector<double> bases;
  std::size_t betweenBounds = 0;
  for (int i = 0; i < 3'000'000; ++i) {
    const double x = std::ldexp(mantissa(random), exponent(random));
    bases.push_back(i % 2 ? x : -x);
    double p, e;
    power_detail::exactProduct(x, x, p, e);
    const double ulp = power_detail::ulpUnlessPowerOfTwo(p);
    betweenBounds += std::fabs(e) >= 0.4 * ulp && std::fabs(e) < 0.47 * ulp;
  }
  EXPECT_GT(betweenBounds, bases.size() / 20);
  std::size_t fast = 0;
  expectPowOnEach(bases, 2, fast);
  expectPowOnEach(bases, 3, fast);
  EXPECT_GT(fast, bases.size() * 3 / 2);
}

TEST(Power, TheValuesBlocksComputeAreStdPowsToTheBit) {
  std::vector<double> bases;
  for (int i = 0; i < 200'000; ++i) {
    bases.push_back(std::cos(i * 0.001));  // cos(...)^2
    bases.push_back(std::sqrt(1.0 + i));   // r^2, r^3 of a Newton iteration
    bases.push_back(1e-3 * i);
  }
  for (int n = -4096; n <= 4096; ++n) {
    const double x = n;
    bases.insert(bases.end(), {x, std::nextafter(x, -1e9), std::nextafter(x, 1e9), x / 1024,
                               std::ldexp(1.0, n / 8), std::nextafter(std::ldexp(1.0, n / 8), 0)});
  }
  std::size_t fast = 0;
  expectPowOnEach(bases, 2, fast);
  expectPowOnEach(bases, 3, fast);
}

TEST(Power, SpecialValuesAndOtherExponentsAreStdPows) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> bases{0.0,  -0.0, inf, -inf, nan, 1e-320, -1e-320, 1e300, -1e300,
                                  1e160, 1e200, 0x1p-460, 0x1p460, 2.5,  -2.5};
  for (double exponent : {2.0, 3.0, 0.5, -2.0, 4.0, 1.0, 0.0, 2.0000000000000004, nan, inf})
    for (double x : bases) {
      const double y = opaque(exponent);
      EXPECT_TRUE(same(power(x, y), std::pow(x, y))) << x << " ^ " << y;
      EXPECT_TRUE(same(fused(x, y), std::pow(x, y))) << x << " ^ " << y << " (fused)";
    }
}

}  // namespace
}  // namespace hirsute
