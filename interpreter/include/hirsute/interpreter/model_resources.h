// Everything interpretation needs besides the string: the view file's settings, the colour map
// or materials, contours, surfaces and textures, loaded once per model.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/interpreter/background_scene.h"
#include "hirsute/interpreter/contour.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/surface.h"
#include "hirsute/interpreter/view_settings.h"

namespace hirsute {

// cpfg's -m[N] file.map and -M[N] file.mat options: bank N (1-based) of 256 colours each.
struct ColorFiles {
  std::vector<std::pair<int, std::filesystem::path>> colormaps;
  std::vector<std::pair<int, std::filesystem::path>> materials;
};

struct ModelResources {
  std::filesystem::path folder;  // the view file's folder; file names resolve against it
  std::optional<std::filesystem::path> viewFile;  // the view file itself, when there is one
  ViewSettings view;
  std::vector<Material> palette;  // 256 per bank; index 0 of bank 1 is the background
  bool materialMode = false;      // materials (.mat) rather than a colour map (.map)
  // A colour map file (.map) gives colours: its entries are the user's own, usually ramps that
  // `diffuse reflection:` shades along (the default palette's are distinct colours).
  bool colorMapFile = false;
  ContourLibrary contours;
  std::map<char, Surface> surfaces;
  // By texture id - 1. A texture whose file is missing (a warning) has no pixels (width 0) and
  // is drawn as no texture.
  std::vector<Texture> textures;
  // The view file's `background scene:` files in order; interpret() appends them to the Scene.
  std::vector<BackgroundScene> backgroundScenes;
  // The frame (from 0) of the moving meshes (mesh sequences, docs/meshes.md) that `~X` draws:
  // `hirsute simulate` sets it frame by frame; elsewhere the first.
  std::size_t meshFrame = 0;

  // The most frames of any moving mesh surface; 1 when none moves.
  std::size_t meshFrames() const {
    std::size_t frames = 1;
    for (const auto& [id, surface] : surfaces) {
      if (surface.mesh) frames = std::max(frames, surface.mesh->frames());
    }
    return frames;
  }
};

// cpfg's -m/-M banks run from 1 to 12.
inline constexpr int kMaxColorBanks = 12;

// Reads the view file (through the preprocessor) and every file it and `colors` name.
// Without a colour file, a default palette is used; a mesh surface of more than
// `maxMeshTriangles` triangles is refused; the view file and its background scenes after the
// preprocessor may be `maxSourceBytes` long each (--max-source-bytes). `viewText`, when given,
// is the view file already through the preprocessor (preprocessViewFile, model.h), as the
// model's load ran it: it is not run again. Throws DiagnosticError (file:line).
ModelResources loadModelResources(const std::optional<std::filesystem::path>& viewFile,
                                  const ColorFiles& colors, Diagnostics& diagnostics,
                                  std::size_t maxMeshTriangles = kDefaultMaxMeshTriangles,
                                  std::size_t maxSourceBytes = kDefaultMaxSourceBytes,
                                  const std::string* viewText = nullptr);

// The view settings alone (used by tests and by loadModelResources).
ViewSettings parseViewFile(const std::string& preprocessedText,
                           const std::filesystem::path& viewFile, Diagnostics& diagnostics);

// A colour map: exactly 768 bytes, 256 RGB triples; each colour becomes a Material with
// ambient = diffuse = the colour (cpfg's colour-map mode draws colours as they are; the renderer
// shows them unlit when ModelResources::materialMode is false). Throws DiagnosticError.
std::vector<Material> loadColorMap(const std::filesystem::path& file);  // 256 entries
// A material file: 15-byte records {index, transparency, ambient, diffuse, emission, specular,
// shininess}; indices without a record keep OpenGL's default material (Material{}).
// Throws DiagnosticError.
std::vector<Material> loadMaterials(const std::filesystem::path& file);  // 256 entries
// The colour files as their bytes are, for the viewer's palette and material editors
// (docs/viewer.md, "Editors"), which read and write them through here so that cpfg's binary
// formats live in this one file. A colour map: 256 RGB triples. A material file: its 15-byte
// records in the file's order (an index may come twice: the later record wins, and both are
// kept so that the file is written back as it was read).
using ColorMapColors = std::array<std::array<std::uint8_t, 3>, 256>;
struct MaterialRecord {
  std::uint8_t index = 0;
  std::uint8_t transparency = 0;
  std::array<std::uint8_t, 3> ambient{}, diffuse{}, emission{}, specular{};
  std::uint8_t shininess = 0;  // cpfg hands it to OpenGL, which accepts at most 128
  bool operator==(const MaterialRecord&) const = default;
};
// Read and checked as loadColorMap and loadMaterials check them; throw DiagnosticError.
ColorMapColors readColorMapFile(const std::filesystem::path& file);
std::vector<MaterialRecord> readMaterialFile(const std::filesystem::path& file);
// The file's bytes: what readColorMapFile and readMaterialFile read back unchanged.
std::string colorMapFileBytes(const ColorMapColors& colors);
std::string materialFileBytes(const std::vector<MaterialRecord>& records);
// What the renderer draws for an entry: a colour map's colour as ambient and diffuse, a
// record's fields (shininess at most 128).
Material colorMapMaterial(const std::array<std::uint8_t, 3>& color);
Material recordMaterial(const MaterialRecord& record);

// Colours for a model given without colour files (docs/files.md): index 0 black (background),
// 1–7 the classic red, green, yellow, blue, magenta, cyan, white, and 8–255 a hue circle with
// cpfg's default initial colour 128 at green.
std::vector<Material> defaultPalette();

}  // namespace hirsute
