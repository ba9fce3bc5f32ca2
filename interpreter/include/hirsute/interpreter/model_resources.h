// Everything interpretation needs besides the string: the view file's settings, the colour map
// or materials, contours, surfaces and textures, loaded once per model.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/interpreter/contour.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/surface.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/lsys/diagnostic.h"

namespace hirsute {

// cpfg's -m[N] file.map and -M[N] file.mat options: bank N (1-based) of 256 colours each.
struct ColorFiles {
  std::vector<std::pair<int, std::filesystem::path>> colormaps;
  std::vector<std::pair<int, std::filesystem::path>> materials;
};

struct ModelResources {
  std::filesystem::path folder;      // the view file's folder; file names resolve against it
  ViewSettings view;
  std::vector<Material> palette;     // 256 per bank; index 0 of bank 1 is the background
  bool materialMode = false;         // materials (.mat) rather than a colour map (.map)
  ContourLibrary contours;
  std::map<char, Surface> surfaces;
  std::vector<Texture> textures;     // by texture id - 1
};

// Reads the view file (through the preprocessor) and every file it and `colors` name.
// Without a colour file, a default palette is used. Throws DiagnosticError (file:line).
ModelResources loadModelResources(const std::optional<std::filesystem::path>& viewFile,
                                  const ColorFiles& colors, Diagnostics& diagnostics);

// The view settings alone (used by tests and by loadModelResources).
ViewSettings parseViewFile(const std::string& preprocessedText, const std::filesystem::path& viewFile,
                           Diagnostics& diagnostics);

std::vector<Material> loadColorMap(const std::filesystem::path& file);   // 256 entries
std::vector<Material> loadMaterials(const std::filesystem::path& file);  // 256 entries
std::vector<Material> defaultPalette();

}  // namespace hirsute
