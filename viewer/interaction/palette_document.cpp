#include "hirsute/viewer/interaction/palette_document.h"

#include <algorithm>
#include <cmath>

namespace hirsute {
namespace {

constexpr int kColorsPerBank = 256;

std::array<std::uint8_t, 3> bytesOf(const glm::vec3& color) {
  return {colorByte(color.r), colorByte(color.g), colorByte(color.b)};
}

// OpenGL's default material (what Material{} is), which an index without a record keeps.
MaterialRecord defaultRecord(int index) {
  const Material gl;
  MaterialRecord record;
  record.index = static_cast<std::uint8_t>(index);
  record.ambient = bytesOf(gl.ambient);
  record.diffuse = bytesOf(gl.diffuse);
  record.specular = bytesOf(gl.specular);
  record.emission = bytesOf(gl.emission);
  return record;
}

MaterialRecord* lastRecordFor(PaletteDocument& document, int index) {
  for (auto r = document.records.rbegin(); r != document.records.rend(); ++r) {
    if (r->index == index) return &*r;
  }
  return nullptr;
}

}  // namespace

std::optional<PaletteDocument::Kind> paletteKindOf(const std::filesystem::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".map") return PaletteDocument::Kind::ColorMap;
  if (extension == ".mat") return PaletteDocument::Kind::Materials;
  return std::nullopt;
}

PaletteDocument readPaletteDocument(const std::filesystem::path& file, PaletteDocument::Kind kind) {
  PaletteDocument document;
  document.kind = kind;
  if (kind == PaletteDocument::Kind::ColorMap)
    document.colors = readColorMapFile(file);
  else
    document.records = readMaterialFile(file);
  return document;
}

std::string paletteBytes(const PaletteDocument& document) {
  return document.kind == PaletteDocument::Kind::ColorMap ? colorMapFileBytes(document.colors)
                                                          : materialFileBytes(document.records);
}

std::vector<Material> paletteMaterials(const PaletteDocument& document) {
  std::vector<Material> materials(kColorsPerBank);
  if (document.kind == PaletteDocument::Kind::ColorMap) {
    for (int i = 0; i < kColorsPerBank; ++i) materials[i] = colorMapMaterial(document.colors[i]);
  } else {
    for (const MaterialRecord& record : document.records)
      materials[record.index] = recordMaterial(record);
  }
  return materials;
}

PaletteDocument paletteFromMaterials(const std::vector<Material>& materials,
                                     PaletteDocument::Kind kind) {
  PaletteDocument document;
  document.kind = kind;
  for (int i = 0; i < kColorsPerBank; ++i) {
    const Material m = i < static_cast<int>(materials.size()) ? materials[i] : Material{};
    if (kind == PaletteDocument::Kind::ColorMap) {
      document.colors[i] = bytesOf(m.diffuse);
    } else {
      MaterialRecord record;
      record.index = static_cast<std::uint8_t>(i);
      record.transparency = colorByte(m.transparency);
      record.ambient = bytesOf(m.ambient);
      record.diffuse = bytesOf(m.diffuse);
      record.specular = bytesOf(m.specular);
      record.emission = bytesOf(m.emission);
      record.shininess =
          static_cast<std::uint8_t>(std::lround(std::clamp(m.shininess, 0.0f, 128.0f)));
      document.records.push_back(record);
    }
  }
  return document;
}

std::optional<MaterialField> materialFieldNamed(std::string_view name) {
  if (name == "ambient") return MaterialField::Ambient;
  if (name == "diffuse") return MaterialField::Diffuse;
  if (name == "specular") return MaterialField::Specular;
  if (name == "emission") return MaterialField::Emission;
  if (name == "shininess") return MaterialField::Shininess;
  if (name == "transparency") return MaterialField::Transparency;
  return std::nullopt;
}

bool isColorField(MaterialField field) {
  return field != MaterialField::Shininess && field != MaterialField::Transparency;
}

std::uint8_t colorByte(float value) {
  if (!std::isfinite(value)) value = 0;
  return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
}

std::array<std::uint8_t, 3> colorAt(const PaletteDocument& document, int index) {
  if (document.kind == PaletteDocument::Kind::ColorMap) return document.colors[index];
  return materialAt(document, index).diffuse;
}

MaterialRecord materialAt(const PaletteDocument& document, int index) {
  for (auto r = document.records.rbegin(); r != document.records.rend(); ++r) {
    if (r->index == index) return *r;
  }
  return defaultRecord(index);
}

void setColor(PaletteDocument& document, int index, const glm::vec3& rgb) {
  document.colors[index] = bytesOf(rgb);
}

void setMaterial(PaletteDocument& document, int index, const MaterialRecord& record) {
  MaterialRecord placed = record;
  placed.index = static_cast<std::uint8_t>(index);
  if (MaterialRecord* last = lastRecordFor(document, index))
    *last = placed;
  else
    document.records.push_back(placed);
}

void setMaterialField(PaletteDocument& document, int index, MaterialField field,
                      const glm::vec3& values) {
  MaterialRecord record = materialAt(document, index);
  switch (field) {
    case MaterialField::Ambient:
      record.ambient = bytesOf(values);
      break;
    case MaterialField::Diffuse:
      record.diffuse = bytesOf(values);
      break;
    case MaterialField::Specular:
      record.specular = bytesOf(values);
      break;
    case MaterialField::Emission:
      record.emission = bytesOf(values);
      break;
    case MaterialField::Shininess: {
      const float s = std::isfinite(values.x) ? std::clamp(values.x, 0.0f, 128.0f) : 0.0f;
      record.shininess = static_cast<std::uint8_t>(std::lround(s));
      break;
    }
    case MaterialField::Transparency:
      record.transparency = colorByte(values.x);
      break;
  }
  setMaterial(document, index, record);
}

}  // namespace hirsute
