// PNG files: what is written reads back the same, and a file appears only when complete.
#include "hirsute/viewer/view/png_image.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

namespace hirsute {
namespace {

class PngImageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ =
        std::filesystem::temp_directory_path() /
        ("hirsute_png_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(folder_);
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  std::size_t filesInFolder() const {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(folder_),
                                                  std::filesystem::directory_iterator()));
  }

  std::filesystem::path folder_;
};

RgbaImage gradient(int width, int height) {
  RgbaImage image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * width + x) * 4];
      p[0] = static_cast<std::uint8_t>(x * 255 / (width - 1));
      p[1] = static_cast<std::uint8_t>(y * 255 / (height - 1));
      p[2] = static_cast<std::uint8_t>((x + y) % 256);
      p[3] = 255;
    }
  }
  return image;
}

TEST_F(PngImageTest, WrittenImageReadsBackPixelForPixel) {
  RgbaImage image = gradient(37, 21);
  std::filesystem::path file = folder_ / "gradient.png";
  writePng(file, image);
  RgbaImage back = readPng(file);
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 21);
  EXPECT_EQ(back.rgba, image.rgba);
  EXPECT_EQ(back.pixel(36, 0), glm::u8vec4(255, 0, 36, 255));
}

TEST_F(PngImageTest, WritingLeavesOnlyTheFinishedFile) {
  std::filesystem::path file = folder_ / "plant.png";
  writePng(file, gradient(8, 8));
  writePng(file, gradient(16, 4));  // replaces it
  EXPECT_EQ(filesInFolder(), 1u);
  EXPECT_EQ(readPng(file).width, 16);
}

TEST_F(PngImageTest, FailedWriteLeavesNoFileAndSaysWhere) {
  std::filesystem::path file = folder_ / "missing" / "plant.png";
  try {
    writePng(file, gradient(4, 4));
    FAIL() << "writing into a missing folder succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(file));
  EXPECT_EQ(filesInFolder(), 0u);
}

TEST_F(PngImageTest, ReadingSomethingElseFails) {
  std::filesystem::path file = folder_ / "not.png";
  std::FILE* f = std::fopen(file.c_str(), "wb");
  std::fputs("not a picture", f);
  std::fclose(f);
  EXPECT_THROW(readPng(file), std::runtime_error);
  EXPECT_THROW(readPng(folder_ / "absent.png"), std::runtime_error);
}

}  // namespace
}  // namespace hirsute
