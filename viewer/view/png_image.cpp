#include "hirsute/viewer/view/png_image.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

#include "hirsute/core/output_target.h"

// stb's writer compiled into this file alone, with internal linkage, so that another library in
// the same program may include its own copy.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace hirsute {
namespace {

// libpng's simplified API (png_image_*) reports errors in the struct instead of longjmp, so no
// C frame is ever unwound by a C++ exception.
class PngStruct {
 public:
  PngStruct() {
    std::memset(&image_, 0, sizeof image_);
    image_.version = PNG_IMAGE_VERSION;
  }
  ~PngStruct() { png_image_free(&image_); }
  PngStruct(const PngStruct&) = delete;
  PngStruct& operator=(const PngStruct&) = delete;
  png_image* get() { return &image_; }
  png_image* operator->() { return &image_; }

 private:
  png_image image_;
};

std::runtime_error writeError(const std::filesystem::path& path, const std::string& why) {
  return std::runtime_error(path.string() + ": cannot write: " + why);
}

}  // namespace

namespace {

// The image into `file`, not empty; committed.
void writePngTo(OutputTarget& file, const RgbaImage& image) {
  const std::filesystem::path& path = file.target();
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i) {
    std::memcpy(&rgb[i * 3], &image.rgba[i * 4], 3);
  }

  PngStruct png;
  png->width = static_cast<png_uint_32>(image.width);
  png->height = static_cast<png_uint_32>(image.height);
  png->format = PNG_FORMAT_RGB;
  if (!png_image_write_to_stdio(png.get(), file.stream(), 0, rgb.data(), image.width * 3,
                                nullptr)) {
    throw writeError(path, png->message);
  }
  file.commit();
}

}  // namespace

void writePng(const std::filesystem::path& path, const RgbaImage& image, OutputGroup* group) {
  if (image.width <= 0 || image.height <= 0) throw writeError(path, "the image is empty");
  OutputTarget file(path, group);
  writePngTo(file, image);
}

void writePng(const OutputFolder& folder, const std::string& name, const RgbaImage& image) {
  if (image.width <= 0 || image.height <= 0)
    throw writeError(folder.pathOf(name), "the image is empty");
  OutputTarget file(folder, name);
  writePngTo(file, image);
}

std::optional<ImageFormat> imageFormatOf(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".png") return ImageFormat::Png;
  if (extension == ".jpg" || extension == ".jpeg") return ImageFormat::Jpeg;
  if (extension == ".exr") return ImageFormat::Exr;
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!error && (std::filesystem::is_character_file(status) || std::filesystem::is_fifo(status)))
    return ImageFormat::Png;
  return std::nullopt;
}

void writeJpeg(const std::filesystem::path& path, const RgbaImage& image, OutputGroup* group) {
  if (image.width <= 0 || image.height <= 0) throw writeError(path, "the image is empty");
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i)
    std::copy_n(&image.rgba[i * 4], 3, &rgb[i * 3]);
  std::vector<std::uint8_t> bytes;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* first = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), first, first + size);
  };
  constexpr int kQuality = 95;
  if (stbi_write_jpg_to_func(append, &bytes, image.width, image.height, 3, rgb.data(), kQuality) ==
      0)
    throw writeError(path, "cannot encode the image as JPEG");
  OutputTarget file(path, group);
  if (std::fwrite(bytes.data(), 1, bytes.size(), file.stream()) != bytes.size())
    throw writeError(path, std::strerror(errno));
  file.commit();
}

void writeImage(const std::filesystem::path& path, const RgbaImage& image, ImageFormat format,
                OutputGroup* group) {
  switch (format) {
    case ImageFormat::Png:
      writePng(path, image, group);
      return;
    case ImageFormat::Jpeg:
      writeJpeg(path, image, group);
      return;
    case ImageFormat::Exr:
      break;
  }
  throw std::invalid_argument(path.string() + ": an OpenEXR file holds a traced picture's light");
}

void writeLinearPng16(const std::filesystem::path& path, int width, int height,
                      const std::vector<glm::vec3>& pixels, OutputGroup* group) {
  const std::size_t count =
      static_cast<std::size_t>(std::max(width, 0)) * static_cast<std::size_t>(std::max(height, 0));
  if (count == 0 || pixels.size() != count) throw writeError(path, "the image is empty");
  std::vector<png_uint_16> rgb(count * 3);
  for (std::size_t i = 0; i < count; ++i) {
    for (int c = 0; c < 3; ++c) {
      const float v = pixels[i][c];
      // NaN reads as black.
      const float clamped = v > 0 ? std::min(v, 1.0f) : 0.0f;
      rgb[i * 3 + static_cast<std::size_t>(c)] =
          static_cast<png_uint_16>(std::lround(clamped * 65535.0f));
    }
  }
  OutputTarget file(path, group);
  PngStruct png;
  png->width = static_cast<png_uint_32>(width);
  png->height = static_cast<png_uint_32>(height);
  png->format = PNG_FORMAT_LINEAR_RGB;  // 16 bits a channel, gamma 1.0
  // The row stride counts components, not bytes.
  if (!png_image_write_to_stdio(png.get(), file.stream(), 0, rgb.data(), width * 3, nullptr)) {
    throw writeError(path, png->message);
  }
  file.commit();
}

RgbaImage readPng(const std::filesystem::path& path) {
  PngStruct png;
  if (!png_image_begin_read_from_file(png.get(), path.c_str())) {
    throw std::runtime_error(path.string() + ": cannot read: " + png->message);
  }
  png->format = PNG_FORMAT_RGBA;
  RgbaImage image(static_cast<int>(png->width), static_cast<int>(png->height));
  if (!png_image_finish_read(png.get(), nullptr, image.rgba.data(), image.width * 4, nullptr)) {
    throw std::runtime_error(path.string() + ": cannot read: " + png->message);
  }
  return image;
}

}  // namespace hirsute
