// The backlit halo of the hairy-plants paper (Fig. 1 and Fig. 5; docs/trace.md, "The halo"): a
// shoot of the Nankin cherry, with its hairs' sizes and densities and its light behind it,
// traced small with and without its hairs. Just outside the bare silhouette the hairs must glow
// brightly over the band their length reaches, not only in a rim a pixel wide.
#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "hirsute/viewer/view/png_image.h"
#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kShoot =
    fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "trace" / "backlit-shoot";

std::vector<float> greyLevels(const fs::path& file, int& width, int& height) {
  const hirsute::RgbaImage image = hirsute::readPng(file);
  width = image.width;
  height = image.height;
  std::vector<float> out;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::u8vec4 p = image.pixel(x, y);
      out.push_back((static_cast<float>(p.r) + p.g + p.b) / 3);
    }
  }
  return out;
}

std::vector<float> traced(const fs::path& folder, const std::string& view, bool hairs) {
  const fs::path png = folder / (view + (hairs ? "" : "-bare") + ".png");
  std::vector<std::string> args = {"render",
                                   (kShoot / "shoot.l").string(),
                                   (kShoot / view).string(),
                                   "--trace",
                                   "--spp",
                                   "8",
                                   "--size",
                                   "160x120",
                                   "-o",
                                   png.string()};
  if (!hairs) args.push_back("--no-hairs");
  const RunResult run = runHirsute(args);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  int width = 0, height = 0;
  std::vector<float> levels = greyLevels(png, width, height);
  EXPECT_EQ(width, 160);
  EXPECT_EQ(height, 120);
  return levels;
}

// The mean gain of grey level with hairs over bare, at each chessboard distance (1 to 5 pixels)
// from the bare plant.
std::vector<float> gainByDistance(const std::vector<float>& hairs, const std::vector<float>& bare) {
  constexpr int kWidth = 160, kHeight = 120;
  std::map<int, int> counts;
  for (float v : bare) ++counts[static_cast<int>(v + 0.5f)];
  const int background =
      std::max_element(counts.begin(), counts.end(), [](const auto& a, const auto& b) {
        return a.second < b.second;
      })->first;
  std::vector<int> distance(bare.size(), -1);
  std::deque<int> queue;
  for (std::size_t i = 0; i < bare.size(); ++i) {
    if (std::abs(bare[i] - static_cast<float>(background)) > 3) {
      distance[i] = 0;
      queue.push_back(static_cast<int>(i));
    }
  }
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = i % kWidth + dx, y = i / kWidth + dy;
        if (x < 0 || y < 0 || x >= kWidth || y >= kHeight || distance[y * kWidth + x] >= 0)
          continue;
        distance[y * kWidth + x] = distance[i] + 1;
        queue.push_back(y * kWidth + x);
      }
    }
  }
  std::vector<float> sum(6, 0.0f), count(6, 0.0f);
  for (std::size_t i = 0; i < bare.size(); ++i) {
    if (distance[i] < 1 || distance[i] > 5) continue;
    sum[distance[i]] += hairs[i] - bare[i];
    count[distance[i]] += 1;
  }
  for (int d = 1; d <= 5; ++d) sum[d] /= std::max(count[d], 1.0f);
  return sum;
}

TEST(BacklitHalo, HairsGlowOverTheBandTheirLengthReachesBeyondTheSilhouette) {
  if (kAddressSanitizer)
    GTEST_SKIP() << "three traced pictures of 50 000 hairs: the release build's";
  TemporaryFolder folder;
  const std::vector<float> bare = traced(folder.path(), "shoot.v", false);
  const std::vector<float> gain = gainByDistance(traced(folder.path(), "shoot.v", true), bare);
  // The hairs are 0.5 to 0.6 mm long, about 4 pixels here: the band 1 to 3 pixels out glows
  // some 60 levels over the bare picture's background (a measured 61, 66, 48).
  const float band = (gain[1] + gain[2] + gain[3]) / 3;
  EXPECT_GT(band, 35) << gain[1] << " " << gain[2] << " " << gain[3];
  // Not a rim: three pixels out the glow is still more than half what it is next to the plant.
  EXPECT_GT(gain[3], 0.5f * gain[1]) << gain[1] << " " << gain[3];
  // Beyond the hairs' reach there is nothing to glow.
  EXPECT_LT(gain[5], 10) << gain[5];
  // The forward scattering of the fibre model makes it: Kajiya and Goldman's hairs, which pass
  // light on only as a broad diffuse lobe, glow far less (a measured 22, 24, 15).
  const std::vector<float> kajiya =
      gainByDistance(traced(folder.path(), "shoot-kajiya.v", true), bare);
  EXPECT_GT(band, 1.6f * (kajiya[1] + kajiya[2] + kajiya[3]) / 3)
      << kajiya[1] << " " << kajiya[2] << " " << kajiya[3];
}

}  // namespace
