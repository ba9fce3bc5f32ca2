// Fur through `hirsute render`: a droplet changes the picture where it fell and nowhere else,
// and a droplet elsewhere changes it elsewhere (models/fur-square, docs/fur.md).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "hirsute/viewer/view/png_image.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kSquare = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "fur-square";
constexpr int kWidth = 400, kHeight = 340;

class FurRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("hirsute_fur_render_" + std::to_string(::getpid()));
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  RgbaImage render(const std::string& name, const std::string& options) {
    const fs::path png = folder_ / (name + ".png");
    const std::string command = std::string(HIRSUTE_BINARY) + " render " + (kSquare / "square.l").string() +
                                " " + (kSquare / "square.v").string() + " --size " +
                                std::to_string(kWidth) + "x" + std::to_string(kHeight) + " " +
                                options + " -o " + png.string() + " 2>/dev/null";
    const int status = std::system(command.c_str());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command;
    return readPng(png);
  }

  fs::path folder_;
};

// The pixels that differ between two pictures: how many, their centroid, and the farthest of
// them from it.
struct Change {
  int pixels = 0;
  double x = 0, y = 0, reach = 0;
};

Change changed(const RgbaImage& a, const RgbaImage& b) {
  Change c;
  std::vector<std::pair<int, int>> where;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      if (a.pixel(x, y) != b.pixel(x, y)) where.emplace_back(x, y);
    }
  }
  c.pixels = static_cast<int>(where.size());
  for (auto [x, y] : where) {
    c.x += x;
    c.y += y;
  }
  if (c.pixels == 0) return c;
  c.x /= c.pixels;
  c.y /= c.pixels;
  for (auto [x, y] : where) c.reach = std::max(c.reach, std::hypot(x - c.x, y - c.y));
  return c;
}

TEST_F(FurRenderTest, ADropletChangesThePictureWhereItFellAndNowhereElse) {
  const RgbaImage dry = render("dry", "");
  const RgbaImage again = render("again", "");
  ASSERT_EQ(dry.width, kWidth);
  EXPECT_EQ(changed(dry, again).pixels, 0) << "the same fur renders the same picture";
  const RgbaImage wet = render("wet", "--droplets 1 --droplet-radius 0.08 --droplet-seed 3");
  const RgbaImage elsewhere = render("elsewhere", "--droplets 1 --droplet-radius 0.08 --droplet-seed 8");
  const Change here = changed(dry, wet), there = changed(dry, elsewhere);
  // The square is about 300 pixels across for its 4 units: a droplet of radius 0.08 (0.32 units,
  // some 24 pixels) clumps the fur within it, the strands leaning in by less than their length
  // (0.18 units, 14 pixels) from its rim.
  for (const Change& c : {here, there}) {
    EXPECT_GT(c.pixels, 200);
    EXPECT_LT(c.reach, 60.0);
    EXPECT_LT(c.pixels, kWidth * kHeight / 20);
  }
  EXPECT_GT(std::hypot(here.x - there.x, here.y - there.y), 30.0) << "another seed, another place";
}

}  // namespace
}  // namespace hirsute
