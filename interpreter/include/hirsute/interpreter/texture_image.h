// The images behind the view file's `texture: F: file` lines (manual §8.1.7): PNG, JPEG, TGA,
// BMP, GIF, PSD, HDR and PNM through stb_image, and SGI images (.rgb, .rgba, .bw), cpfg's other
// texture format, which enviro-CPFG-Clover uses.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include "hirsute/interpreter/scene.h"

namespace hirsute {

// Decodes an image file into 8-bit RGBA, row 0 at the top. Texture::file is `file`. Throws
// DiagnosticError (located at the file) when it cannot be read or decoded.
Texture loadTexture(const std::filesystem::path& file);

// The same from bytes in memory; `file` is used for Texture::file and in messages.
Texture decodeTexture(const std::vector<std::uint8_t>& bytes, const std::filesystem::path& file);

}  // namespace hirsute
