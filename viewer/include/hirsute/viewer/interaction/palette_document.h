// The document of the viewer's palette and material editors (docs/viewer.md, "Editors"; vlab's
// `palette` and `medit`): a colour map (.map) or a material file (.mat) as its bytes are
// (model_resources.h reads and writes cpfg's formats), the edits a user makes to an entry, and
// the materials the renderer draws from it, so that an edit shows on the plant without deriving
// the model again.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/interpreter/model_resources.h"

namespace hirsute {

struct PaletteDocument {
  enum class Kind { ColorMap, Materials };
  Kind kind = Kind::ColorMap;
  ColorMapColors colors{};              // Kind::ColorMap
  std::vector<MaterialRecord> records;  // Kind::Materials, in the file's order
  bool operator==(const PaletteDocument&) const = default;
};

// The kind a file's extension names: .map a colour map, .mat materials; none for others.
std::optional<PaletteDocument::Kind> paletteKindOf(const std::filesystem::path& file);
// Reads a colour file; throws DiagnosticError as the model's reader does.
PaletteDocument readPaletteDocument(const std::filesystem::path& file, PaletteDocument::Kind kind);
// The file's bytes, as cpfg writes them.
std::string paletteBytes(const PaletteDocument& document);
// The 256 materials the document gives, as the model's reader makes them.
std::vector<Material> paletteMaterials(const PaletteDocument& document);
// A document holding `materials` (256 of them), for a model that has no colour file yet: the
// colours it shows, written down (a material file gets a record for every index).
PaletteDocument paletteFromMaterials(const std::vector<Material>& materials,
                                     PaletteDocument::Kind kind);

// A material's fields, as medit names them (and as the view script's `material` command does).
enum class MaterialField { Ambient, Diffuse, Specular, Emission, Shininess, Transparency };
std::optional<MaterialField> materialFieldNamed(std::string_view name);
// Fields that take a colour (three values); shininess and transparency take one.
bool isColorField(MaterialField field);

// A byte of cpfg's formats from a value 0..1 (clamped), as the editors set them.
std::uint8_t colorByte(float value);

// The entry an index shows: a colour map's colour; the last record a material file has for
// the index, or OpenGL's default material as bytes when it has none.
std::array<std::uint8_t, 3> colorAt(const PaletteDocument& document, int index);
MaterialRecord materialAt(const PaletteDocument& document, int index);

// Edits (`index` 0..255). A colour of a colour map; a field of a material, which changes the
// last record for the index, or adds a record at the end when the file has none for it
// (values 0..1; shininess 0..128).
void setColor(PaletteDocument& document, int index, const glm::vec3& rgb);
void setMaterialField(PaletteDocument& document, int index, MaterialField field,
                      const glm::vec3& values);
void setMaterial(PaletteDocument& document, int index, const MaterialRecord& record);

}  // namespace hirsute
