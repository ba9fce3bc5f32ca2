// Images as the renderer produces them; PNG files through libpng, JPEG files through stb.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/core/output_folder.h"

namespace hirsute {

class OutputGroup;

// 8-bit RGBA pixels, row 0 at the top.
struct RgbaImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;

  RgbaImage() = default;
  RgbaImage(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4) {}
  glm::u8vec4 pixel(int x, int y) const {
    const std::uint8_t* p = &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
    return {p[0], p[1], p[2], p[3]};
  }
};

// Writes an RGB PNG (the alpha channel is dropped: renders are opaque). The file appears only
// when complete: it is written under a temporary name beside `path` and renamed over it (with
// the other outputs of `group` when given, output_target.h). Throws std::runtime_error ("path:
// cannot write …") on failure, leaving no file behind.
void writePng(const std::filesystem::path& path, const RgbaImage& image,
              OutputGroup* group = nullptr);
// The same under `name`, a name the program makes up (a screenshot's), in `folder`: created there
// without following a link planted at the name (hirsute/core/output_folder.h).
void writePng(const OutputFolder& folder, const std::string& name, const RgbaImage& image);

// The formats a picture the user names (`render -o FILE`) is written in, chosen by the name's
// extension.
enum class ImageFormat { Png, Jpeg, Exr };

// The format `path`'s extension names, in any case: .png; .jpg or .jpeg; .exr. A device or FIFO
// (/dev/stdout, a pipe) whose name names none takes PNG. None for any other name.
std::optional<ImageFormat> imageFormatOf(const std::filesystem::path& path);
// The extensions imageFormatOf knows, for a message: ".png, .jpg, .jpeg".
inline constexpr const char* kImageExtensions = ".png, .jpg, .jpeg";

// Writes a baseline JPEG (quality 95, RGB), as writePng writes a PNG.
void writeJpeg(const std::filesystem::path& path, const RgbaImage& image,
               OutputGroup* group = nullptr);
// Writes a PNG or a JPEG, as `format` says (Exr: std::invalid_argument; the path tracer writes
// those, exr_image.h).
void writeImage(const std::filesystem::path& path, const RgbaImage& image, ImageFormat format,
                OutputGroup* group = nullptr);

// Writes linear RGB (`pixels`: width × height, row 0 at the top, 1 = white) as a 16-bit PNG of
// linear light (gAMA 1.0), for compositing; values are clamped to [0, 1]. Written like writePng.
void writeLinearPng16(const std::filesystem::path& path, int width, int height,
                      const std::vector<glm::vec3>& pixels, OutputGroup* group = nullptr);

// Reads any PNG as 8-bit RGBA. Throws std::runtime_error on failure.
RgbaImage readPng(const std::filesystem::path& path);

}  // namespace hirsute
