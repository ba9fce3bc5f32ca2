// The denoiser on pictures made up for it: noise falls where the picture is smooth, an edge its
// features draw stays sharp, a pixel without noise keeps its value, and one picture comes out
// on any number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hirsute/viewer/trace/denoise.h"

namespace {

using namespace hirsute::trace;

constexpr int kWidth = 48, kHeight = 32;

// A picture whose left half is `left` and right half `right`, each pixel the mean of `samples`
// samples of standard deviation `spread` about it (the variances are the true ones), its
// features the side's colour and a normal towards the eye.
NoisyImage halves(const glm::vec3& left, const glm::vec3& right, float spread, int samples,
                  unsigned seed) {
  NoisyImage image;
  image.width = kWidth;
  image.height = kHeight;
  const std::size_t pixels = kWidth * kHeight;
  std::mt19937 random(seed);
  std::normal_distribution<float> normal(0.0f, spread / std::sqrt(static_cast<float>(samples)));
  const glm::vec3 variance(spread * spread / static_cast<float>(samples));
  for (std::size_t p = 0; p < pixels; ++p) {
    const glm::vec3 truth = static_cast<int>(p % kWidth) < kWidth / 2 ? left : right;
    image.colour.push_back(truth + glm::vec3(normal(random), normal(random), normal(random)));
    image.colourVariance.push_back(variance);
    image.albedo.push_back(truth);
    image.normal.push_back(glm::vec3(0, 0, 1));
  }
  image.albedoVariance.assign(pixels, glm::vec3(0.0f));
  image.normalVariance.assign(pixels, glm::vec3(0.0f));
  return image;
}

// The RMS difference from the truth of the pixels whose column is in [from, to).
float rmsError(const std::vector<glm::vec3>& picture, const glm::vec3& truth, int from, int to) {
  double squares = 0;
  int count = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = from; x < to; ++x) {
      const glm::vec3 d = picture[static_cast<std::size_t>(y) * kWidth + x] - truth;
      squares += glm::dot(d, d) / 3;
      ++count;
    }
  }
  return static_cast<float>(std::sqrt(squares / count));
}

TEST(Denoise, NoiseFallsWhereThePictureIsSmoothAndAnEdgeStaysSharp) {
  const glm::vec3 dark(0.1f, 0.2f, 0.1f), light(0.6f, 0.5f, 0.4f);
  const NoisyImage image = halves(dark, light, 0.5f, 16, 1);
  const std::vector<glm::vec3> out = denoise(image);
  // The halves' own noise is 0.125 a channel; averaged over a window it falls several times.
  const float before = rmsError(image.colour, dark, 0, kWidth / 2);
  const float after = rmsError(out, dark, 0, kWidth / 2);
  EXPECT_NEAR(before, 0.125f, 0.02f);
  EXPECT_LT(after, before / 4) << before << " -> " << after;
  EXPECT_LT(rmsError(out, light, kWidth / 2, kWidth), before / 4);
  // The columns either side of the edge keep their side's colour: no light bleeds into the dark.
  EXPECT_LT(rmsError(out, dark, kWidth / 2 - 1, kWidth / 2), before / 2);
  EXPECT_LT(rmsError(out, light, kWidth / 2, kWidth / 2 + 1), before / 2);
  // And no bias: the filtered dark half's mean is the truth's to well within the noise.
  glm::vec3 mean(0.0f);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth / 2; ++x) mean += out[static_cast<std::size_t>(y) * kWidth + x];
  }
  mean /= static_cast<float>(kHeight * kWidth / 2);
  EXPECT_LT(glm::length(mean - dark), 0.01f);
}

TEST(Denoise, AnEdgeInTheColourAloneStaysSharpWhereItPassesTheNoise) {
  // One colour of features on both sides: only the colours' difference, far larger than the
  // noise, keeps the halves apart.
  NoisyImage image = halves(glm::vec3(0.1f), glm::vec3(0.9f), 0.2f, 16, 2);
  for (glm::vec3& a : image.albedo) a = glm::vec3(0.5f);
  const std::vector<glm::vec3> out = denoise(image);
  EXPECT_LT(rmsError(out, glm::vec3(0.1f), kWidth / 2 - 1, kWidth / 2), 0.05f);
  EXPECT_LT(rmsError(out, glm::vec3(0.9f), kWidth / 2, kWidth / 2 + 1), 0.05f);
}

TEST(Denoise, APixelWithoutNoiseKeepsItsValue) {
  // The background: every sample alike, no variance. Next to it a noisy region of the same
  // features must not bleed into it, but for the column beside it, whose noisy neighbours make
  // it a possible hole in a fuzz.
  NoisyImage image = halves(glm::vec3(0.0f), glm::vec3(0.3f), 0.4f, 8, 3);
  for (std::size_t p = 0; p < image.colour.size(); ++p) {
    if (static_cast<int>(p % kWidth) < kWidth / 2) {
      image.colour[p] = glm::vec3(0.02f, 0.03f, 0.04f);
      image.colourVariance[p] = glm::vec3(0.0f);
    }
    image.albedo[p] = glm::vec3(0.0f);
  }
  const std::vector<glm::vec3> out = denoise(image);
  for (std::size_t p = 0; p < out.size(); ++p) {
    if (static_cast<int>(p % kWidth) < kWidth / 2 - 1) {
      EXPECT_EQ(out[p], image.colour[p]) << p;
    }
  }
}

TEST(Denoise, AHoleInANoisyRegionIsFilteredWithIt) {
  // Uniform noise about 0.3 with one pixel whose samples all happened to agree on 0: it takes
  // the region's value, not its own.
  NoisyImage image = halves(glm::vec3(0.3f), glm::vec3(0.3f), 0.2f, 8, 6);
  const std::size_t hole = 16 * kWidth + 12;
  image.colour[hole] = glm::vec3(0.0f);
  image.colourVariance[hole] = glm::vec3(0.0f);
  const std::vector<glm::vec3> out = denoise(image);
  EXPECT_NEAR(out[hole].g, 0.3f, 0.1f);
}

TEST(Denoise, OnePictureOnAnyNumberOfThreads) {
  const NoisyImage image = halves(glm::vec3(0.2f), glm::vec3(0.7f), 0.3f, 4, 4);
  DenoiseOptions options;
  options.threads = 1;
  const std::vector<glm::vec3> one = denoise(image, options);
  options.threads = 3;
  EXPECT_EQ(denoise(image, options), one);
  options.threads = 8;
  EXPECT_EQ(denoise(image, options), one);
}

TEST(Denoise, BuffersOfTheWrongSizeAreRefused) {
  NoisyImage image = halves(glm::vec3(0.2f), glm::vec3(0.7f), 0.3f, 4, 5);
  image.normalVariance.pop_back();
  EXPECT_THROW(denoise(image), std::invalid_argument);
}

}  // namespace
