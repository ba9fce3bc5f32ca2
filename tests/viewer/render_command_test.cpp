// `hirsute render` end to end: a shipped model through the whole pipeline into a PNG.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/viewer/view/png_image.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

class RenderCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("hirsute_render_command_" +
               std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
               std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  // Runs `hirsute render ARGS`; returns the exit code, keeps standard error.
  int render(const std::string& arguments) {
    fs::path err = folder_ / "stderr.txt";
    std::string command =
        std::string(HIRSUTE_BINARY) + " render " + arguments + " 2>" + err.string();
    int status = std::system(command.c_str());
    std::ifstream in(err);
    std::ostringstream text;
    text << in.rdbuf();
    stderr_ = text.str();
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  static std::string model(const std::string& file) {
    return std::string(HIRSUTE_SOURCE_DIR) + "/models/herb/" + file;
  }

  fs::path folder_;
  std::string stderr_;
};

// The background cpfg shows for the herb: colour 0 of the folder's colour map or material file
// (the one hirsute picks when none is named), or the default palette's black.
glm::u8vec4 herbBackground() {
  fs::path folder = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
  glm::vec3 color(0.0f);
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() == ".map") color = loadColorMap(entry.path())[0].diffuse;
    if (entry.path().extension() == ".mat") color = loadMaterials(entry.path())[0].emission;
  }
  glm::ivec3 bytes = glm::round(glm::clamp(color, 0.0f, 1.0f) * 255.0f);
  return {bytes.r, bytes.g, bytes.b, 255};
}

TEST_F(RenderCommandTest, ShippedModelRendersToPng) {
  fs::path png = folder_ / "herb.png";
  ASSERT_EQ(
      render(model("herb.l") + " " + model("herb.v") + " -o " + png.string() + " --size 320x240"),
      0)
      << stderr_;
  RgbaImage image = readPng(png);
  ASSERT_EQ(image.width, 320);
  ASSERT_EQ(image.height, 240);
  glm::u8vec4 background = herbBackground();
  auto isBackground = [&](glm::u8vec4 p) {
    return std::abs(p.r - background.r) <= 1 && std::abs(p.g - background.g) <= 1 &&
           std::abs(p.b - background.b) <= 1;
  };
  // The herb stands in the middle: its stem crosses the lower middle of the image.
  int plant = 0;
  for (int y = 120; y < 216; ++y) {
    for (int x = 140; x < 180; ++x) plant += isBackground(image.pixel(x, y)) ? 0 : 1;
  }
  EXPECT_GT(plant, 96) << "no stem in the middle of the image";
  // herb.v's `scale factor: 0.9` leaves 5% of the image's height (or width) free on either side
  // of the plant, and more in the other direction.
  for (int x = 0; x < 320; ++x) {
    EXPECT_TRUE(isBackground(image.pixel(x, 3))) << x;
    EXPECT_TRUE(isBackground(image.pixel(x, 236))) << x;
  }
  for (int y = 0; y < 240; ++y) {
    EXPECT_TRUE(isBackground(image.pixel(3, y))) << y;
    EXPECT_TRUE(isBackground(image.pixel(316, y))) << y;
  }
}

TEST_F(RenderCommandTest, StepsChangeThePicture) {
  fs::path zero = folder_ / "zero.png", full = folder_ / "full.png";
  ASSERT_EQ(render(model("herb.l") + " " + model("herb.v") + " --steps 1 -o " + zero.string() +
                   " --size 160x120 --samples 1"),
            0)
      << stderr_;
  ASSERT_EQ(render(model("herb.l") + " " + model("herb.v") + " -o " + full.string() +
                   " --size 160x120 --samples 1"),
            0)
      << stderr_;
  EXPECT_NE(readPng(zero).rgba, readPng(full).rgba);
}

TEST_F(RenderCommandTest, BadSizeIsBadInputAndWritesNothing) {
  fs::path png = folder_ / "herb.png";
  EXPECT_EQ(render(model("herb.l") + " " + model("herb.v") + " -o " + png.string() + " --size 320"),
            2);
  EXPECT_NE(stderr_.find("WIDTHxHEIGHT"), std::string::npos) << stderr_;
  EXPECT_EQ(render(model("herb.l") + " -o " + png.string() + " --size 0x10"), 2);
  EXPECT_EQ(render(model("herb.l") + " -o " + png.string() + " --size 20000x10"), 2);
  EXPECT_FALSE(fs::exists(png));
}

TEST_F(RenderCommandTest, UnwritableOutputIsAnIoError) {
  fs::path png = folder_ / "no" / "such" / "folder" / "herb.png";
  EXPECT_EQ(
      render(model("herb.l") + " " + model("herb.v") + " -o " + png.string() + " --size 64x48"), 1);
  EXPECT_NE(stderr_.find(png.string()), std::string::npos) << stderr_;
}

TEST_F(RenderCommandTest, OutputIsRequired) {
  EXPECT_EQ(render(model("herb.l") + " " + model("herb.v")), 2);
  EXPECT_NE(stderr_.find("--output"), std::string::npos) << stderr_;
}

}  // namespace
}  // namespace hirsute
