// The tracer's outputs for compositing: OpenEXR keeps linear radiance past 1, a 16-bit PNG keeps
// linear light to 1/65535; both leave no file when they cannot write.
#include <gtest/gtest.h>
#include <png.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <cstring>
#include <filesystem>
#include <vector>

#include "hirsute/viewer/trace/exr_image.h"
#include "hirsute/viewer/view/png_image.h"

namespace hirsute::trace {
namespace {

namespace fs = std::filesystem;

std::vector<glm::vec3> ramp(int width, int height) {
  std::vector<glm::vec3> pixels;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      pixels.emplace_back(0.001f * static_cast<float>(x), 4.0f * static_cast<float>(y),
                          x == 0 ? 1e9f : 0.5f);
    }
  }
  return pixels;
}

fs::path scratch(const char* name) {
  const fs::path folder = fs::temp_directory_path() / "hirsute_image_output_test";
  fs::create_directories(folder);
  return folder / name;
}

TEST(TracedImages, OpenExrKeepsLinearRadiancePastOne) {
  const int width = 7, height = 3;
  const std::vector<glm::vec3> pixels = ramp(width, height);
  const fs::path file = scratch("ramp.exr");
  writeExr(file, width, height, pixels);
  Imf::RgbaInputFile in(file.c_str());
  const Imath::Box2i window = in.dataWindow();
  ASSERT_EQ(window.max.x - window.min.x + 1, width);
  ASSERT_EQ(window.max.y - window.min.y + 1, height);
  Imf::Array2D<Imf::Rgba> read(height, width);
  in.setFrameBuffer(&read[0][0], 1, width);
  in.readPixels(window.min.y, window.max.y);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec3 p = pixels[static_cast<std::size_t>(y * width + x)];
      EXPECT_NEAR(float(read[y][x].r), p.r, 1e-3f * p.r + 1e-6f);
      EXPECT_NEAR(float(read[y][x].g), p.g, 1e-3f * p.g + 1e-6f);  // 8 is kept as 8
      // Past half's range: its largest value.
      EXPECT_FLOAT_EQ(float(read[y][x].b), x == 0 ? 65504.0f : 0.5f);
    }
  }
  fs::remove(file);
}

TEST(TracedImages, SixteenBitPngKeepsLinearLight) {
  const int width = 300, height = 2;
  std::vector<glm::vec3> pixels;
  for (int i = 0; i < width * height; ++i) {
    pixels.emplace_back(static_cast<float>(i) / 65535.0f, 0.25f, i % 2 ? 2.0f : -1.0f);
  }
  const fs::path file = scratch("ramp16.png");
  writeLinearPng16(file, width, height, pixels);
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_file(&image, file.c_str())) << image.message;
  image.format = PNG_FORMAT_LINEAR_RGB;
  std::vector<png_uint_16> rgb(static_cast<std::size_t>(width * height * 3));
  ASSERT_TRUE(png_image_finish_read(&image, nullptr, rgb.data(), width * 3, nullptr));
  png_image_free(&image);
  for (std::size_t i = 0; i < static_cast<std::size_t>(width * height); ++i) {
    EXPECT_EQ(rgb[3 * i], i);  // one step a pixel: nothing lost to 8 bits
    EXPECT_NEAR(rgb[3 * i + 1], 16384, 1);
    EXPECT_EQ(rgb[3 * i + 2], i % 2 ? 65535 : 0);  // clamped
  }
  fs::remove(file);
}

TEST(TracedImages, AFileThatCannotBeWrittenIsAnErrorAndLeavesNothing) {
  const fs::path file = scratch("missing-folder") / "out.exr";
  EXPECT_THROW(writeExr(file, 2, 2, std::vector<glm::vec3>(4)), std::runtime_error);
  EXPECT_THROW(writeExr(scratch("empty.exr"), 2, 2, {}), std::runtime_error);
  EXPECT_FALSE(fs::exists(scratch("empty.exr")));
  EXPECT_THROW(writeLinearPng16(file, 2, 2, std::vector<glm::vec3>(4)), std::runtime_error);
  EXPECT_FALSE(fs::exists(file.parent_path()));
}

}  // namespace
}  // namespace hirsute::trace
