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

ColorMapColors readColorMapFile(const std::filesystem::path& file) {
  const std::vector<std::uint8_t> bytes = readBytes(file, "colour map");
  if (bytes.size() != kColorMapBytes) {
    throw DiagnosticError(fileLocation(file),
                          "a colour map has exactly 768 bytes (256 RGB colours), this file has " +
                              std::to_string(bytes.size()));
  }
  ColorMapColors colors;
  for (std::size_t i = 0; i < kColorsPerBank; ++i)
    colors[i] = {bytes[3 * i], bytes[3 * i + 1], bytes[3 * i + 2]};
  return colors;
}

std::vector<MaterialRecord> readMaterialFile(const std::filesystem::path& file) {
  const std::vector<std::uint8_t> bytes = readBytes(file, "material");
  if (bytes.empty() || bytes.size() % kMaterialRecordBytes != 0) {
    throw DiagnosticError(fileLocation(file),
                          "a material file is a sequence of 15-byte records, this file has " +
                              std::to_string(bytes.size()) + " bytes (" +
                              std::to_string(bytes.size() % kMaterialRecordBytes) +
                              " left over after the last whole record)");
  }
  std::vector<MaterialRecord> records;
  for (std::size_t offset = 0; offset < bytes.size(); offset += kMaterialRecordBytes) {
    // {u8 index; u8 transparency; u8 ambient[3]; u8 diffuse[3]; u8 emission[3];
    //  u8 specular[3]; u8 shininess}
    const std::uint8_t* b = &bytes[offset];
    MaterialRecord record;
    record.index = b[0];
    record.transparency = b[1];
    record.ambient = {b[2], b[3], b[4]};
    record.diffuse = {b[5], b[6], b[7]};
    record.emission = {b[8], b[9], b[10]};
    record.specular = {b[11], b[12], b[13]};
    record.shininess = b[14];
    records.push_back(record);
  }
  return records;
}

std::string colorMapFileBytes(const ColorMapColors& colors) {
  std::string bytes;
  bytes.reserve(kColorMapBytes);
  for (const auto& color : colors) {
    for (std::uint8_t c : color) bytes.push_back(static_cast<char>(c));
  }
  return bytes;
}

std::string materialFileBytes(const std::vector<MaterialRecord>& records) {
  std::string bytes;
  bytes.reserve(records.size() * kMaterialRecordBytes);
  auto put = [&bytes](std::uint8_t b) { bytes.push_back(static_cast<char>(b)); };
  for (const MaterialRecord& r : records) {
    put(r.index);
    put(r.transparency);
    for (const auto* field : {&r.ambient, &r.diffuse, &r.emission, &r.specular}) {
      for (std::uint8_t c : *field) put(c);
    }
    put(r.shininess);
  }
  return bytes;
}

Material colorMapMaterial(const std::array<std::uint8_t, 3>& color) {
  return flatMaterial(glm::vec3(color[0], color[1], color[2]) / 255.0f);
}

Material recordMaterial(const MaterialRecord& record) {
  auto color = [](const std::array<std::uint8_t, 3>& c) {
    return glm::vec3(c[0], c[1], c[2]) / 255.0f;
  };
  Material material;
  material.transparency = record.transparency / 255.0f;
  material.ambient = color(record.ambient);
  material.diffuse = color(record.diffuse);
  material.emission = color(record.emission);
  material.specular = color(record.specular);
  // OpenGL accepts shininess up to 128; cpfg hands larger bytes to it, which refuses them.
  material.shininess = std::min<float>(record.shininess, 128.0f);
  return material;
}

std::vector<Material> loadColorMap(const std::filesystem::path& file) {
  const ColorMapColors colors = readColorMapFile(file);
  std::vector<Material> palette;
  palette.reserve(kColorsPerBank);
  for (const auto& color : colors) palette.push_back(colorMapMaterial(color));
  return palette;
}

std::vector<Material> loadMaterials(const std::filesystem::path& file) {
  // Indices without a record keep OpenGL's default material, which Material{} is; a later record
  // for the same index replaces an earlier one.
  std::vector<Material> palette(kColorsPerBank);
  for (const MaterialRecord& record : readMaterialFile(file))
    palette[record.index] = recordMaterial(record);
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
