#include "hirsute/interpreter/texture_image.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <string>
#include <system_error>

#include "hirsute/core/diagnostic.h"

// stb_image's implementation lives in this file alone. Files are read here, so its stdio
// functions are left out; the dimension limit keeps a corrupt header from asking for gigabytes.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS 16384
#include <stb/stb_image.h>

namespace hirsute {
namespace {

// At most 64 Mi pixels (256 MiB of RGBA) per texture, whatever the format.
constexpr std::size_t kMaxPixels = std::size_t{1} << 26;

SourceLocation fileLocation(const std::filesystem::path& file) {
  return SourceLocation{std::make_shared<const std::string>(file.string()), 0, 0};
}

unsigned bigEndian16(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (unsigned{b[at]} << 8) | b[at + 1];
}

std::uint32_t bigEndian32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
         (std::uint32_t{b[at + 2]} << 8) | b[at + 3];
}

constexpr unsigned kSgiMagic = 474;
constexpr std::size_t kSgiHeaderBytes = 512;

bool isSgiImage(const std::vector<std::uint8_t>& bytes) {
  return bytes.size() >= kSgiHeaderBytes && bigEndian16(bytes, 0) == kSgiMagic;
}

// The SGI image format (Haeberli, "The SGI Image File Format", version 1.0): a 512-byte
// big-endian header (magic 474, storage 0 verbatim or 1 RLE, bytes per channel 1 or 2,
// dimension, xsize, ysize, zsize), then the channels as scan lines from the bottom row up,
// verbatim or run-length encoded with a table of offsets and lengths per scan line.
Texture decodeSgi(const std::vector<std::uint8_t>& bytes, const std::filesystem::path& file) {
  const auto broken = [&file](const std::string& why) {
    return DiagnosticError(fileLocation(file), "broken SGI image: " + why);
  };
  const bool rle = bytes[2] == 1;
  const unsigned bpc = bytes[3];
  const unsigned dimension = bigEndian16(bytes, 4);
  const std::size_t width = bigEndian16(bytes, 6);
  const std::size_t height = dimension == 1 ? 1 : bigEndian16(bytes, 8);
  const std::size_t channels = dimension < 3 ? 1 : bigEndian16(bytes, 10);
  if (bytes[2] > 1) throw broken("unknown storage " + std::to_string(bytes[2]));
  if (bpc != 1 && bpc != 2) throw broken(std::to_string(bpc) + " bytes per channel");
  if (dimension < 1 || dimension > 3) throw broken("dimension " + std::to_string(dimension));
  if (width == 0 || height == 0 || channels == 0) throw broken("the image is empty");
  if (width * height > kMaxPixels) throw broken("the image is too large");

  // One scan line of one channel, 8 bits per value (16-bit values keep their high byte).
  std::vector<std::uint8_t> line(width);
  const auto readLine = [&](std::size_t y, std::size_t z) {
    if (!rle) {
      const std::size_t start = kSgiHeaderBytes + (z * height + y) * width * bpc;
      if (start + width * bpc > bytes.size()) throw broken("the file ends inside the pixels");
      for (std::size_t x = 0; x < width; ++x) line[x] = bytes[start + x * bpc];
      return;
    }
    const std::size_t entry = y + z * height;
    const std::size_t tables = kSgiHeaderBytes + 2 * 4 * height * channels;
    if (tables > bytes.size()) throw broken("the file ends inside the scan-line tables");
    std::size_t at = bigEndian32(bytes, kSgiHeaderBytes + 4 * entry);
    const std::size_t length =
        bigEndian32(bytes, kSgiHeaderBytes + 4 * (height * channels + entry));
    if (at > bytes.size() || length > bytes.size() - at) {
      throw broken("a scan line lies outside the file");
    }
    const std::size_t end = at + length;
    const auto next = [&]() -> unsigned {
      if (at + bpc > end) throw broken("a run-length scan line ends early");
      const unsigned value = bpc == 1 ? bytes[at] : bigEndian16(bytes, at);
      at += bpc;
      return value;
    };
    std::size_t x = 0;
    for (;;) {
      const unsigned code = next();
      const std::size_t count = code & 0x7f;
      if (count == 0) break;
      if (x + count > width) throw broken("a run-length scan line is longer than the image");
      if (code & 0x80) {
        for (std::size_t k = 0; k < count; ++k)
          line[x++] = static_cast<std::uint8_t>(next() >> (8 * (bpc - 1)));
      } else {
        const std::uint8_t value = static_cast<std::uint8_t>(next() >> (8 * (bpc - 1)));
        for (std::size_t k = 0; k < count; ++k) line[x++] = value;
      }
    }
    if (x != width) throw broken("a run-length scan line is shorter than the image");
  };

  Texture texture;
  texture.file = file.string();
  texture.width = static_cast<int>(width);
  texture.height = static_cast<int>(height);
  texture.rgba.assign(width * height * 4, 255);
  // Grey (1 channel), grey and alpha (2), RGB (3), RGBA (4 and more: the rest is ignored).
  for (std::size_t z = 0; z < std::min<std::size_t>(channels, 4); ++z) {
    for (std::size_t y = 0; y < height; ++y) {
      readLine(y, z);
      // SGI stores the bottom row first; Texture wants the top row first.
      std::uint8_t* row = texture.rgba.data() + (height - 1 - y) * width * 4;
      for (std::size_t x = 0; x < width; ++x) {
        if (channels <= 2) {
          if (z == 0) {
            row[4 * x] = row[4 * x + 1] = row[4 * x + 2] = line[x];
          } else {
            row[4 * x + 3] = line[x];
          }
        } else {
          row[4 * x + z] = line[x];
        }
      }
    }
  }
  return texture;
}

}  // namespace

std::optional<ImageExtent> imageExtentOf(const std::vector<std::uint8_t>& bytes) {
  if (isSgiImage(bytes)) {
    const unsigned dimension = bigEndian16(bytes, 4);
    return ImageExtent{static_cast<int>(bigEndian16(bytes, 6)),
                       dimension == 1 ? 1 : static_cast<int>(bigEndian16(bytes, 8))};
  }
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) return std::nullopt;
  ImageExtent extent;
  int channels = 0;
  if (!stbi_info_from_memory(bytes.data(), static_cast<int>(bytes.size()), &extent.width,
                             &extent.height, &channels)) {
    return std::nullopt;
  }
  return extent;
}

Texture decodeTexture(const std::vector<std::uint8_t>& bytes, const std::filesystem::path& file) {
  if (isSgiImage(bytes)) return decodeSgi(bytes, file);
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw DiagnosticError(fileLocation(file), "the image file is too large");
  }
  int width = 0;
  int height = 0;
  int channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width, &height,
                            &channels, 4),
      stbi_image_free);
  if (!pixels) {
    throw DiagnosticError(fileLocation(file),
                          std::string("cannot decode the texture image (") + stbi_failure_reason() +
                              "); Hirsute reads PNG, JPEG, TGA, BMP, GIF, PSD, HDR, PNM and SGI "
                              "(.rgb) images");
  }
  if (static_cast<std::size_t>(width) * static_cast<std::size_t>(height) > kMaxPixels) {
    throw DiagnosticError(fileLocation(file), "the texture image is too large");
  }
  Texture texture;
  texture.file = file.string();
  texture.width = width;
  texture.height = height;
  texture.rgba.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(width) * height * 4);
  return texture;
}

Texture loadTexture(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::error_code error;
  if (!in || !std::filesystem::is_regular_file(file, error)) {
    throw DiagnosticError(fileLocation(file), "cannot open texture image");
  }
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in),
                                        std::istreambuf_iterator<char>()};
  return decodeTexture(bytes, file);
}

}  // namespace hirsute
