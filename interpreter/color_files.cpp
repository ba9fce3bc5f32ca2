// cpfg's colour files (cpfg-features.md (e), "File formats"): colour maps (.map, -m) and
// material files (.mat, -M), and the palette used when a model names neither.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "hirsute/interpreter/model_resources.h"

namespace hirsute {
namespace {

constexpr std::size_t kColorsPerBank = 256;
constexpr std::size_t kColorMapBytes = 3 * kColorsPerBank;
constexpr std::size_t kMaterialRecordBytes = 15;

SourceLocation fileLocation(const std::filesystem::path& file) {
  return SourceLocation{std::make_shared<const std::string>(file.string()), 0, 0};
}

std::vector<std::uint8_t> readBytes(const std::filesystem::path& file, const std::string& kind) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(file, error);
  if (!std::filesystem::exists(status)) {
    throw DiagnosticError(fileLocation(file), "cannot open " + kind + " file (no such file)");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw DiagnosticError(fileLocation(file), "cannot open " + kind + " file (not a regular file)");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw DiagnosticError(fileLocation(file), "cannot open " + kind + " file");
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in),
                                   std::istreambuf_iterator<char>());
}

glm::vec3 colorAt(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
  return glm::vec3(bytes[offset], bytes[offset + 1], bytes[offset + 2]) / 255.0f;
}

// A colour of a colour map as a Material: cpfg's colour-map mode draws the colour itself, so it
// is both the ambient and the diffuse colour; nothing is specular or emitted.
Material flatMaterial(const glm::vec3& color) {
  Material material;
  material.ambient = color;
  material.diffuse = color;
  material.specular = glm::vec3(0.0f);
  material.emission = glm::vec3(0.0f);
  material.shininess = 0.0f;
  material.transparency = 0.0f;
  return material;
}

glm::vec3 fromHsv(float hueDegrees, float saturation, float value) {
  const float h = std::fmod(std::fmod(hueDegrees, 360.0f) + 360.0f, 360.0f) / 60.0f;
  const float c = value * saturation;
  const float x = c * (1.0f - std::fabs(std::fmod(h, 2.0f) - 1.0f));
  glm::vec3 rgb(0.0f);
  switch (static_cast<int>(h)) {
    case 0:
      rgb = {c, x, 0};
      break;
    case 1:
      rgb = {x, c, 0};
      break;
    case 2:
      rgb = {0, c, x};
      break;
    case 3:
      rgb = {0, x, c};
      break;
    case 4:
      rgb = {x, 0, c};
      break;
    default:
      rgb = {c, 0, x};
      break;
  }
  return rgb + glm::vec3(value - c);
}

}  // namespace

std::vector<Material> loadColorMap(const std::filesystem::path& file) {
  const std::vector<std::uint8_t> bytes = readBytes(file, "colour map");
  if (bytes.size() != kColorMapBytes) {
    throw DiagnosticError(fileLocation(file),
                          "a colour map has exactly 768 bytes (256 RGB colours), this file has " +
                              std::to_string(bytes.size()));
  }
  std::vector<Material> palette;
  palette.reserve(kColorsPerBank);
  for (std::size_t i = 0; i < kColorsPerBank; ++i)
    palette.push_back(flatMaterial(colorAt(bytes, 3 * i)));
  return palette;
}

std::vector<Material> loadMaterials(const std::filesystem::path& file) {
  const std::vector<std::uint8_t> bytes = readBytes(file, "material");
  if (bytes.empty() || bytes.size() % kMaterialRecordBytes != 0) {
    throw DiagnosticError(fileLocation(file),
                          "a material file is a sequence of 15-byte records, this file has " +
                              std::to_string(bytes.size()) + " bytes (" +
                              std::to_string(bytes.size() % kMaterialRecordBytes) +
                              " left over after the last whole record)");
  }
  // Indices without a record keep OpenGL's default material, which Material{} is.
  std::vector<Material> palette(kColorsPerBank);
  for (std::size_t offset = 0; offset < bytes.size(); offset += kMaterialRecordBytes) {
    // {u8 index; u8 transparency; u8 ambient[3]; u8 diffuse[3]; u8 emission[3];
    //  u8 specular[3]; u8 shininess}; a later record for the same index replaces an earlier one.
    Material& material = palette[bytes[offset]];
    material.transparency = bytes[offset + 1] / 255.0f;
    material.ambient = colorAt(bytes, offset + 2);
    material.diffuse = colorAt(bytes, offset + 5);
    material.emission = colorAt(bytes, offset + 8);
    material.specular = colorAt(bytes, offset + 11);
    // OpenGL accepts shininess up to 128; cpfg hands larger bytes to it, which refuses them.
    material.shininess = std::min<float>(bytes[offset + 14], 128.0f);
  }
  return palette;
}

std::vector<Material> defaultPalette() {
  std::vector<Material> palette;
  palette.reserve(kColorsPerBank);
  // Index 0 is the background.
  palette.push_back(flatMaterial(glm::vec3(0.0f)));
  // 1–7: red, green, yellow, blue, magenta, cyan, white, the order of the classic eight-colour
  // maps, so that line fractals with `initial color: 1` and small increments stay distinct.
  for (int i = 1; i <= 7; ++i) {
    palette.push_back(flatMaterial(glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1)));
  }
  // 8–255: a hue circle, with cpfg's default initial colour 128 at green, so that `;` and `,`
  // step through visibly different colours.
  for (std::size_t i = 8; i < kColorsPerBank; ++i) {
    const float hue = 120.0f + (static_cast<float>(i) - 128.0f) * 360.0f / 248.0f;
    palette.push_back(flatMaterial(fromHsv(hue, 0.65f, 0.85f)));
  }
  return palette;
}

}  // namespace hirsute
