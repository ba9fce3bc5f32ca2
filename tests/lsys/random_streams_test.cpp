// The random streams must reproduce cpfg's numbers exactly: Rand48 against glibc's own erand48,
// BlockRandom against the sequences cpfg printed for tools-LeafRandom and cpfg-WeepingBirch, and
// the distributions of nran, bran and biran statistically.
#include "hirsute/lsys/random_streams.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace hirsute {
namespace {

std::string printedAsCpfg(double value) {
  // cpfg stores parameters as float and prints them with %g.
  char text[32];
  std::snprintf(text, sizeof text, "%g", static_cast<double>(static_cast<float>(value)));
  return text;
}

TEST(Rand48Test, MatchesGlibcErand48BitForBit) {
  const std::array<std::array<std::uint16_t, 3>, 5> states = {{{0x330E, 0, 0},
                                                               {0x330E, 21, 0},
                                                               {0, 0, 0},
                                                               {0xFFFF, 0xFFFF, 0xFFFF},
                                                               {0x1234, 0xABCD, 0x00FF}}};
  for (const auto& state : states) {
    unsigned short xsubi[3] = {state[0], state[1], state[2]};
    Rand48 generator(state[0], state[1], state[2]);
    for (int i = 0; i < 1000; ++i) {
      const double expected = erand48(xsubi);
      const double actual = generator.next();
      ASSERT_EQ(expected, actual) << "state {" << state[0] << ", " << state[1] << ", " << state[2]
                                  << "}, draw " << i;
    }
    const std::array<std::uint16_t, 3> after = generator.state();
    EXPECT_EQ(after[0], xsubi[0]);
    EXPECT_EQ(after[1], xsubi[1]);
    EXPECT_EQ(after[2], xsubi[2]);
  }
}

TEST(Rand48Test, Seed48ThenNextMatchesGlibcDrand48) {
  // cpfg seeds the production-choice stream with seed48({seed, 0, 155}) and reads drand48.
  unsigned short seed[3] = {7, 0, 155};
  seed48(seed);
  Rand48 generator = Rand48::seed48(7, 0, 155);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(drand48(), generator.next()) << "draw " << i;
}

TEST(BlockRandomTest, StreamStartsAt330E) {
  unsigned short xsubi[3] = {0x330E, 0, 0};
  BlockRandom random;
  EXPECT_EQ(random.ran(1.0), erand48(xsubi));
  EXPECT_EQ(random.ran(5.0), 5.0 * erand48(xsubi));
}

TEST(BlockRandomTest, SrandSetsTheStateFromTheSeed) {
  const double seed = 70000.0;  // 0x11170: both high words are used
  unsigned short xsubi[3] = {0x330E, 0x1170, 0x0001};
  BlockRandom random;
  random.ran(1.0);
  random.srand(seed);
  for (int i = 0; i < 10; ++i) ASSERT_EQ(random.ran(1.0), erand48(xsubi));
}

TEST(BlockRandomTest, SrandMakesTheStreamReproducible) {
  BlockRandom first;
  BlockRandom second;
  second.ran(1.0);
  second.nran(0.0, 1.0);
  second.nran(0.0, 1.0);
  first.srand(21.0);
  second.srand(21.0);
  for (int i = 0; i < 100; ++i) {
    ASSERT_EQ(first.ran(3.0), second.ran(3.0));
    ASSERT_EQ(first.nran(1.0, 2.0), second.nran(1.0, 2.0));
    ASSERT_EQ(first.bran(2.0, 3.0), second.bran(2.0, 3.0));
    ASSERT_EQ(first.biran(5.0, 0.5), second.biran(5.0, 0.5));
  }
}

TEST(BlockRandomTest, SeedIsConvertedAsAnUnsignedCast) {
  EXPECT_EQ(BlockRandom::seedBits(21.0), 21u);
  EXPECT_EQ(BlockRandom::seedBits(21.9), 21u);
  EXPECT_EQ(BlockRandom::seedBits(-1.0), 0xFFFFFFFFu);
  EXPECT_EQ(BlockRandom::seedBits(-2.5), 0xFFFFFFFEu);
  EXPECT_EQ(BlockRandom::seedBits(4294967296.0 + 5.0), 5u);
  EXPECT_EQ(BlockRandom::seedBits(std::nan("")), 0u);
  EXPECT_EQ(BlockRandom::seedBits(1e300), 0u);
}

TEST(BlockRandomTest, FirstNranBeforeSrandReturnsMean) {
  BlockRandom random;
  EXPECT_EQ(random.nran(1.0, 0.05), 1.0);
  EXPECT_NE(random.nran(80.0, 4.0), 80.0);
}

TEST(BlockRandomTest, NranReproducesCpfgLeafRandom) {
  // tools-LeafRandom (no srand): each decomposition step draws I(nran(1,0.05)), then
  // +(nran(80,4)) L(nran(0.6,0.02)) -(nran(80,4)) L(nran(0.6,0.02)); cpfg printed these.
  const std::vector<std::array<const char*, 5>> expected = {
      {"1", "82.1112", "0.586096", "85.5902", "0.60756"},
      {"0.950687", "85.7776", "0.607335", "82.238", "0.559487"},
      {"0.962641", "76.3521", "0.617687", "85.4062", "0.589677"},
  };
  BlockRandom random;
  for (const auto& step : expected) {
    EXPECT_EQ(printedAsCpfg(random.nran(1.0, 0.05)), step[0]);
    EXPECT_EQ(printedAsCpfg(random.nran(80.0, 4.0)), step[1]);
    EXPECT_EQ(printedAsCpfg(random.nran(0.6, 0.02)), step[2]);
    EXPECT_EQ(printedAsCpfg(random.nran(80.0, 4.0)), step[3]);
    EXPECT_EQ(printedAsCpfg(random.nran(0.6, 0.02)), step[4]);
  }
}

TEST(BlockRandomTest, SrandForgetsTheSavedDeviate) {
  BlockRandom random;
  random.srand(5.0);
  const double first = random.nran(0.0, 1.0);  // a fresh pair; its partner is saved
  random.srand(5.0);
  EXPECT_EQ(random.nran(0.0, 1.0), first);  // the saved partner was dropped
}

TEST(BlockRandomTest, NranHasRequestedMeanAndDeviation) {
  BlockRandom random;
  random.srand(12345.0);
  constexpr int kDraws = 100000;
  double sum = 0.0;
  double sumSquares = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const double value = random.nran(3.0, 2.0);
    sum += value;
    sumSquares += value * value;
  }
  const double mean = sum / kDraws;
  const double deviation = std::sqrt(sumSquares / kDraws - mean * mean);
  EXPECT_NEAR(mean, 3.0, 0.02);  // standard error 2/sqrt(1e5) ≈ 0.0063
  EXPECT_NEAR(deviation, 2.0, 0.02);
}

TEST(BlockRandomTest, RanIsUniformBelowItsArgument) {
  BlockRandom random;
  double sum = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double value = random.ran(4.0);
    ASSERT_GE(value, 0.0);
    ASSERT_LT(value, 4.0);
    sum += value;
  }
  EXPECT_NEAR(sum / 100000, 2.0, 0.02);
}

TEST(BlockRandomTest, BranReproducesCpfgWeepingBirch) {
  // cpfg-WeepingBirch: Start {srand(21);}, then A(22500) splits into nl = floor(n·bran(5,16))
  // and nr = n−nl−1, printed as +(nr/n·30) and -(nl/n·30). cpfg printed +(23.192) for the first.
  BlockRandom random;
  random.srand(21.0);
  const double n = 22500.0;
  const double nl = std::floor(n * random.bran(5.0, 16.0));
  EXPECT_EQ(nl, 5105.0);
  EXPECT_EQ(printedAsCpfg((n - nl - 1.0) / n * 30.0), "23.192");
}

struct BetaCase {
  double a;
  double b;
};

class BranDistributionTest : public ::testing::TestWithParam<BetaCase> {};

TEST_P(BranDistributionTest, HasMeanAOverAPlusBAndBetaVariance) {
  const auto [a, b] = GetParam();
  BlockRandom random;
  random.srand(99.0);
  constexpr int kDraws = 100000;
  double sum = 0.0;
  double sumSquares = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const double value = random.bran(a, b);
    ASSERT_GE(value, 0.0);
    ASSERT_LE(value, 1.0);
    sum += value;
    sumSquares += value * value;
  }
  const double mean = sum / kDraws;
  const double variance = sumSquares / kDraws - mean * mean;
  const double expectedMean = a / (a + b);
  const double expectedVariance = a * b / ((a + b) * (a + b) * (a + b + 1.0));
  // Five standard errors of the mean; the variance within 3%.
  EXPECT_NEAR(mean, expectedMean, 5.0 * std::sqrt(expectedVariance / kDraws));
  EXPECT_NEAR(variance, expectedVariance, 0.03 * expectedVariance);
}

// BB (both shapes above 1) in both argument orders, BC (a shape at most 1) in both orders.
INSTANTIATE_TEST_SUITE_P(ChengAlgorithms, BranDistributionTest,
                         ::testing::Values(BetaCase{5.0, 16.0}, BetaCase{16.0, 5.0},
                                           BetaCase{2.5, 2.5}, BetaCase{0.5, 0.7},
                                           BetaCase{3.0, 0.4}, BetaCase{0.4, 3.0},
                                           BetaCase{1.0, 1.0}));

TEST(BlockRandomTest, BranOfNonPositiveShapesGivesTheLimits) {
  BlockRandom random;
  EXPECT_EQ(random.bran(0.0, 2.0), 0.0);
  EXPECT_EQ(random.bran(2.0, -1.0), 1.0);
}

TEST(BlockRandomTest, BiranHasMeanNP) {
  BlockRandom random;
  random.srand(7.0);
  constexpr int kDraws = 20000;
  double sum = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const double count = random.biran(20.0, 0.3);
    ASSERT_EQ(count, std::floor(count));
    ASSERT_GE(count, 0.0);
    ASSERT_LE(count, 20.0);
    sum += count;
  }
  // n·p = 6, standard error sqrt(n·p·(1−p)/draws) ≈ 0.0145.
  EXPECT_NEAR(sum / kDraws, 6.0, 0.06);
}

TEST(BlockRandomTest, BiranCountsWholeTrials) {
  BlockRandom random;
  EXPECT_EQ(random.biran(7.9, 1.5), 7.0);
  EXPECT_EQ(random.biran(10.0, 0.0), 0.0);
  EXPECT_EQ(random.biran(-3.0, 0.5), 0.0);
}

}  // namespace
}  // namespace hirsute

namespace hirsute {
namespace {

// Skipping n draws leaves the state where n calls of next() leave it, for the counts the
// table serves directly, its edge and the counts skipped by squaring.
TEST(Rand48Skip, LandsWhereTheDrawsWould) {
  for (std::uint64_t n : {0ull, 1ull, 2ull, 7ull, 63ull, 64ull, 65ull, 1000ull, 123457ull}) {
    Rand48 drawn = Rand48::seed48(0x330E, 2718, 0);
    Rand48 skipped = drawn;
    for (std::uint64_t i = 0; i < n; ++i) drawn.next();
    skipped.skip(n);
    EXPECT_EQ(skipped.state(), drawn.state()) << n << " draws";
    EXPECT_EQ(skipped.next(), drawn.next()) << "the draw after " << n;
  }
}

}  // namespace
}  // namespace hirsute
