// The two random streams of a cpfg model, reproduced bit for bit.
//
// cpfg draws from two independent POSIX erand48 states: one chooses among stochastic productions
// (seeded from the `seed:` line with seed48({seed, 0, 155}) and read with drand48), the other
// feeds the block-language functions ran, nran, bran, biran and is reseeded only by srand.
// Models tuned on cpfg depend on both sequences, so both are exact copies of glibc's generator.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace hirsute {

// n steps of the generator below as one, for n < kCount:
// X_n = (multiplier[n] X + increment[n]) mod 2^48.
struct Rand48Skips {
  static constexpr std::size_t kCount = 64;
  std::array<std::uint64_t, kCount> multiplier{};
  std::array<std::uint64_t, kCount> increment{};
};
constexpr Rand48Skips rand48Skips(std::uint64_t a, std::uint64_t c, std::uint64_t mask) {
  Rand48Skips table;
  table.multiplier[0] = 1;
  for (std::size_t n = 1; n < Rand48Skips::kCount; ++n) {
    table.multiplier[n] = (a * table.multiplier[n - 1]) & mask;
    table.increment[n] = (a * table.increment[n - 1] + c) & mask;
  }
  return table;
}

// POSIX 48-bit linear congruential generator, identical to glibc's erand48:
// X' = (0x5DEECE66D·X + 0xB) mod 2^48, result X'/2^48.
class Rand48 {
 public:
  static constexpr std::uint64_t kMultiplier = 0x5DEECE66Dull;
  static constexpr std::uint64_t kIncrement = 0xB;
  static constexpr std::uint64_t kStateMask = (std::uint64_t{1} << 48) - 1;
  static constexpr std::size_t kDirectSkips = Rand48Skips::kCount;
  static constexpr Rand48Skips kSkips = rand48Skips(kMultiplier, kIncrement, kStateMask);

  // The state as erand48's xsubi: x0 holds the low 16 bits, x2 the high ones.
  Rand48(std::uint16_t x0, std::uint16_t x1, std::uint16_t x2);

  // glibc seed48: the state becomes {s0, s1, s2} and the multiplier and increment their
  // defaults (this class never changes them, so it is the same as the constructor).
  static Rand48 seed48(std::uint16_t s0, std::uint16_t s1, std::uint16_t s2);

  // Advances the state and returns it as a double in [0, 1), exactly as erand48. Inline: a
  // stochastic L-system draws once for every module of every step.
  double next() {
    state_ = (kMultiplier * state_ + kIncrement) & kStateMask;
    // glibc erand48 puts the 48 bits into the top of a double's mantissa in [1, 2) and subtracts
    // 1; that is exactly X/2^48, which a multiplication by 2^-48 computes without rounding (and
    // without ldexp's call).
    return static_cast<double>(state_) * 0x1p-48;
  }

  // Advances the state by `n` draws whose values nobody reads, as n calls of next() would: one
  // multiplication for n up to kDirectSkips, one for each set bit of n beyond.
  void skip(std::uint64_t n) {
    if (n < kDirectSkips) [[likely]] {
      state_ = (kSkips.multiplier[n] * state_ + kSkips.increment[n]) & kStateMask;
      return;
    }
    skipLong(n);
  }

  std::array<std::uint16_t, 3> state() const;

 private:
  void skipLong(std::uint64_t n);

  std::uint64_t state_;  // 48 significant bits
};

// The stream behind the block-language functions ran, nran, bran, biran and srand.
class BlockRandom {
 public:
  // cpfg: main_xsubi starts at {0x330E, 0, 0} when the program starts.
  BlockRandom();

  // srand(seed): the state becomes {0x330E, s & 0xFFFF, s >> 16} with s the seed converted to a
  // 32-bit unsigned integer, and nran forgets its saved value.
  void srand(double seed);

  // ran(x): uniform in [0, x) (in (x, 0] for negative x).
  double ran(double x);

  // nran(mean, sd): mean + sd·g, g standard normal by the polar Box–Muller method.
  double nran(double mean, double sd);

  // bran(a, b): a Beta(a, b) variate by Cheng's algorithms BB and BC.
  double bran(double a, double b);

  // biran(n, p): the number of successes among n trials of probability p.
  double biran(double n, double p);

  // The seed as srand uses it, exposed so the conversion of odd arguments is testable.
  static std::uint32_t seedBits(double seed);

 private:
  double uniform() { return generator_.next(); }
  double chengBB(double a, double b);
  double chengBC(double a, double b);

  Rand48 generator_;
  // Numerical Recipes' gasdev keeps the second deviate of each pair for the next call.
  bool hasSavedDeviate_;
  double savedDeviate_;
};

}  // namespace hirsute
