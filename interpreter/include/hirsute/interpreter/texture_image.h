// The images behind the view file's `texture: F: file` lines (manual §8.1.7): PNG, JPEG, TGA,
// BMP, GIF, PSD, HDR and PNM through stb_image, and SGI images (.rgb, .rgba, .bw), cpfg's other
// texture format, which enviro-CPFG-Clover uses.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "hirsute/interpreter/scene.h"

namespace hirsute {

// Decodes an image file into 8-bit RGBA, row 0 at the top. Texture::file is `file`. Throws
// DiagnosticError (located at the file) when it cannot be read or decoded.
Texture loadTexture(const std::filesystem::path& file);

// The width and height an image's header states, read without decoding its pixels, so that a
// reader can refuse a picture too large for it before paying for it; nothing when the bytes are
// no image decodeTexture reads (or one whose sides stb_image refuses: over 16384 pixels).
struct ImageExtent {
  int width = 0, height = 0;
};
std::optional<ImageExtent> imageExtentOf(const std::vector<std::uint8_t>& bytes);

// The same from bytes in memory; `file` is used for Texture::file and in messages.
Texture decodeTexture(const std::vector<std::uint8_t>& bytes, const std::filesystem::path& file);

}  // namespace hirsute
