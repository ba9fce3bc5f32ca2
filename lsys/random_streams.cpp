#include "hirsute/lsys/random_streams.h"

#include <cmath>

namespace hirsute {
namespace {

// cpfg: srand and the initial state keep 0x330E in the low word, as POSIX srand48 does.
constexpr std::uint16_t kLowSeedWord = 0x330E;

}  // namespace

Rand48::Rand48(std::uint16_t x0, std::uint16_t x1, std::uint16_t x2)
    : state_(std::uint64_t{x0} | (std::uint64_t{x1} << 16) | (std::uint64_t{x2} << 32)) {}

Rand48 Rand48::seed48(std::uint16_t s0, std::uint16_t s1, std::uint16_t s2) {
  return Rand48(s0, s1, s2);
}

void Rand48::skipLong(std::uint64_t n) {
  // Squaring the step: (m, c) applied twice is (m m, m c + c).
  std::uint64_t multiplier = kMultiplier, increment = kIncrement;
  for (; n != 0; n >>= 1) {
    if (n & 1) state_ = (multiplier * state_ + increment) & kStateMask;
    increment = (multiplier * increment + increment) & kStateMask;
    multiplier = (multiplier * multiplier) & kStateMask;
  }
}

std::array<std::uint16_t, 3> Rand48::state() const {
  return {static_cast<std::uint16_t>(state_), static_cast<std::uint16_t>(state_ >> 16),
          static_cast<std::uint16_t>(state_ >> 32)};
}

// cpfg: "the saved-value flag starts set with a saved value of 0", so the first nran before any
// srand returns exactly its mean (tools-LeafRandom's first internode is I(…,1) for nran(1,0.05)).
BlockRandom::BlockRandom()
    : generator_(kLowSeedWord, 0, 0), hasSavedDeviate_(true), savedDeviate_(0.0) {}

std::uint32_t BlockRandom::seedBits(double seed) {
  // cpfg converts the double with a C cast to unsigned. gcc on x86-64 compiles that as a
  // truncating conversion to a 64-bit integer and keeps the low 32 bits, so a negative seed wraps
  // modulo 2^32 (srand(-1) is srand(4294967295)) and so does a seed of 2^32 or more. Values
  // beyond the 64-bit range and NaN give the processor's "integer indefinite" 0x8000000000000000,
  // whose low 32 bits are 0. We define the conversion the same way so that no seed is undefined.
  constexpr double kTwoTo63 = 9223372036854775808.0;
  if (!(std::fabs(seed) < kTwoTo63)) return 0;
  return static_cast<std::uint32_t>(static_cast<std::uint64_t>(static_cast<std::int64_t>(seed)));
}

void BlockRandom::srand(double seed) {
  const std::uint32_t bits = seedBits(seed);
  generator_ = Rand48(kLowSeedWord, static_cast<std::uint16_t>(bits & 0xFFFF),
                      static_cast<std::uint16_t>(bits >> 16));
  hasSavedDeviate_ = false;
}

double BlockRandom::ran(double x) {
  return x * uniform();
}

double BlockRandom::nran(double mean, double sd) {
  // Numerical Recipes in C, 2nd ed., Sec. 7.2, gasdev: polar form of Box–Muller. Each pair of
  // uniforms in the unit disc yields two deviates; the second is returned by the next call.
  if (hasSavedDeviate_) {
    hasSavedDeviate_ = false;
    return mean + sd * savedDeviate_;
  }
  double v1 = 0.0;
  double v2 = 0.0;
  double rsq = 0.0;
  do {
    v1 = 2.0 * uniform() - 1.0;
    v2 = 2.0 * uniform() - 1.0;
    rsq = v1 * v1 + v2 * v2;
  } while (rsq >= 1.0 || rsq == 0.0);
  const double fac = std::sqrt(-2.0 * std::log(rsq) / rsq);
  savedDeviate_ = v1 * fac;
  hasSavedDeviate_ = true;
  return mean + sd * v2 * fac;
}

namespace {

// Cheng's W = a·e^V, with the overflow that ranlib's genbet guards against (w = 1e38 there)
// resolved in the limit: the delivered ratio W/(b+W) is then 1.
double chengResult(double a, double b, double v, bool aIsFirst) {
  const double w = a * std::exp(v);
  if (std::isinf(w)) return aIsFirst ? 1.0 : 0.0;
  return aIsFirst ? w / (b + w) : b / (b + w);
}

}  // namespace

// R.C.H. Cheng, "Generating beta variates with nonintegral shape parameters", Comm. ACM 21(4),
// 1978, algorithm BB (both shapes above 1). a is the smaller shape, b the larger; the variate is
// W/(b+W) when the smaller shape was the first argument and b/(b+W) otherwise.
double BlockRandom::chengBB(double a0, double b0) {
  const double a = std::fmin(a0, b0);
  const double b = std::fmax(a0, b0);
  const double alpha = a + b;
  const double beta = std::sqrt((alpha - 2.0) / (2.0 * a * b - alpha));
  const double gamma = a + 1.0 / beta;
  const double log4 = std::log(4.0);
  const double onePlusLog5 = 1.0 + std::log(5.0);
  for (;;) {
    // Step 1.
    const double u1 = uniform();
    const double u2 = uniform();
    const double v = beta * std::log(u1 / (1.0 - u1));
    const double w = a * std::exp(v);
    // Step 2.
    const double z = u1 * u1 * u2;
    const double r = gamma * v - log4;
    const double s = a + r - w;
    // Step 3: quick acceptance.
    if (s + onePlusLog5 >= 5.0 * z) return chengResult(a, b, v, a == a0);
    // Step 4: second quick acceptance.
    const double t = std::log(z);
    if (s > t) return chengResult(a, b, v, a == a0);
    // Step 5: the full test; rejection starts over.
    if (r + alpha * std::log(alpha / (b + w)) >= t) return chengResult(a, b, v, a == a0);
  }
}

// Cheng 1978, algorithm BC (the smaller shape at most 1). Here a is the larger shape and b the
// smaller, and the variate is W/(b+W) when the larger shape was the first argument.
double BlockRandom::chengBC(double a0, double b0) {
  const double a = std::fmax(a0, b0);
  const double b = std::fmin(a0, b0);
  const double alpha = a + b;
  const double beta = 1.0 / b;
  const double delta = 1.0 + a - b;
  const double k1 = delta * (0.0138889 + 0.0416667 * b) / (a * beta - 0.777778);
  const double k2 = 0.25 + (0.5 + 0.25 / delta) * b;
  const double log4 = std::log(4.0);
  for (;;) {
    // Step 1.
    const double u1 = uniform();
    const double u2 = uniform();
    double z = 0.0;
    if (u1 < 0.5) {
      // Step 2.
      const double y = u1 * u2;
      z = u1 * y;
      if (0.25 * u2 + z - y >= k1) continue;
    } else {
      // Step 3.
      z = u1 * u1 * u2;
      if (z <= 0.25) {
        const double v = beta * std::log(u1 / (1.0 - u1));
        return chengResult(a, b, v, a == a0);
      }
      // Step 4.
      if (z >= k2) continue;
    }
    // Step 5.
    const double v = beta * std::log(u1 / (1.0 - u1));
    const double w = a * std::exp(v);
    if (alpha * (std::log(alpha / (b + w)) + v) - log4 < std::log(z)) continue;
    // Step 6.
    return chengResult(a, b, v, a == a0);
  }
}

double BlockRandom::bran(double a, double b) {
  // Beta(a, b) exists only for positive shapes. Rather than loop forever or return NaN, we give
  // the limits of the distribution: all mass at 0 as a→0, at 1 as b→0; nothing is drawn.
  if (!(a > 0.0)) return 0.0;
  if (!(b > 0.0)) return 1.0;
  return std::fmin(a, b) > 1.0 ? chengBB(a, b) : chengBC(a, b);
}

double BlockRandom::biran(double n, double p) {
  // A binomial count as n Bernoulli trials on this stream: each trial is one uniform, a success
  // when it falls below p. n is truncated to a whole number of trials; n ≤ 0 (or NaN) is none.
  // The cost is one draw per trial; counts stop at 2^53, beyond which a double cannot count.
  constexpr double kMaxTrials = 9007199254740992.0;
  std::uint64_t trials = 0;
  if (n > 0.0) trials = static_cast<std::uint64_t>(std::floor(std::fmin(n, kMaxTrials)));
  std::uint64_t successes = 0;
  for (std::uint64_t i = 0; i < trials; ++i) {
    if (uniform() < p) ++successes;
  }
  return static_cast<double>(successes);
}

}  // namespace hirsute
