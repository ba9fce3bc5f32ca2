// Loading everything a model's interpretation needs besides its string: the view file, the
// colour banks, and the contours, surfaces and textures the view file names.
#include "hirsute/interpreter/model_resources.h"

#include <algorithm>
#include <memory>
#include <string>
#include <system_error>

#include "hirsute/interpreter/texture_image.h"
#include "hirsute/lsys/model.h"
#include "hirsute/lsys/preprocessor.h"
#include "hirsute/lsys/view_file_lines.h"

namespace hirsute {
namespace {

constexpr std::size_t kColorsPerBank = 256;

SourceLocation fileLocation(const std::filesystem::path& file) {
  return SourceLocation{std::make_shared<const std::string>(file.string()), 0, 0};
}

// The file name as the view file wrote it, for messages.
std::string writtenName(const std::string& resolved, const std::filesystem::path& folder) {
  if (folder.empty()) return resolved;
  const std::filesystem::path relative = std::filesystem::path(resolved).lexically_relative(folder);
  return relative.empty() ? resolved : relative.string();
}

bool fileExists(const std::string& file) {
  std::error_code error;
  return std::filesystem::is_regular_file(file, error);
}

// cpfg's banks: -mN / -MN file fills colour indices 256·(N−1) … 256·N−1. Banks no file names
// keep the default palette (bank 1 of cpfg-Sedge-female is given by none of its options).
void loadPalette(ModelResources& resources, const ColorFiles& colors, Diagnostics& diagnostics) {
  int banks = 1;
  const auto checkBank = [&banks](int bank, const std::filesystem::path& file) {
    if (bank < 1 || bank > kMaxColorBanks) {
      throw DiagnosticError(fileLocation(file), "colour bank " + std::to_string(bank) +
                                                    " is outside 1 to " +
                                                    std::to_string(kMaxColorBanks));
    }
    banks = std::max(banks, bank);
  };
  for (const auto& [bank, file] : colors.colormaps) checkBank(bank, file);
  for (const auto& [bank, file] : colors.materials) checkBank(bank, file);

  const std::vector<Material> fallback = defaultPalette();
  resources.palette.clear();
  for (int bank = 0; bank < banks; ++bank) {
    resources.palette.insert(resources.palette.end(), fallback.begin(), fallback.end());
  }
  const auto place = [&resources](int bank, const std::vector<Material>& colors) {
    std::copy(colors.begin(), colors.end(),
              resources.palette.begin() + static_cast<std::ptrdiff_t>((bank - 1) * kColorsPerBank));
  };
  for (const auto& [bank, file] : colors.colormaps) place(bank, loadColorMap(file));
  for (const auto& [bank, file] : colors.materials) place(bank, loadMaterials(file));

  // cpfg draws in the mode of the last -m or -M option; ColorFiles does not keep their order.
  resources.materialMode = !colors.materials.empty();
  resources.colorMapFile = !colors.colormaps.empty();
  if (!colors.materials.empty() && !colors.colormaps.empty()) {
    diagnostics.warn(fileLocation(colors.colormaps.front().second),
                     "both colour maps and material files are given; drawing in material mode");
  }
}

void loadTextures(ModelResources& resources, Diagnostics& diagnostics) {
  for (const TextureDeclaration& declaration : resources.view.textures) {
    const std::string name = writtenName(declaration.file, resources.folder);
    if (!fileExists(declaration.file)) {
      diagnostics.warn(declaration.where, "cannot open texture image " + name + " (looked for " +
                                              declaration.file + "); it is drawn untextured");
      Texture missing;
      missing.file = declaration.file;
      resources.textures.push_back(std::move(missing));
      continue;
    }
    try {
      resources.textures.push_back(loadTexture(declaration.file));
    } catch (const DiagnosticError& error) {
      rethrowAtViewLine(declaration.where, "texture", name, error);
    }
  }
}

void loadContours(ModelResources& resources, Diagnostics& diagnostics) {
  for (const ContourDeclaration& declaration : resources.view.contours) {
    const std::string name = writtenName(declaration.file, resources.folder);
    if (!fileExists(declaration.file)) {
      // cpfg goes on without it; @#(id) then selects the circle.
      diagnostics.warn(declaration.where, "cannot open contour file " + name + " (looked for " +
                                              declaration.file + "); contour " +
                                              std::to_string(declaration.id) +
                                              " is drawn as a circle");
      continue;
    }
    try {
      resources.contours.add(declaration.id, loadContour(declaration.file));
    } catch (const DiagnosticError& error) {
      rethrowAtViewLine(declaration.where, "contour", name, error);
    }
  }
}

void loadSurfaces(ModelResources& resources, std::size_t maxMeshTriangles,
                  Diagnostics& diagnostics) {
  for (const SurfaceDeclaration& declaration : resources.view.surfaces) {
    const std::string name = writtenName(declaration.file, resources.folder);
    const std::string id(1, declaration.id);
    const bool mesh = isMeshFile(declaration.file);
    const bool sequence = mesh && isMeshSequence(declaration.file);
    if (!sequence && !fileExists(declaration.file)) {
      // A mesh is a model's own body (docs/meshes.md): without it the model is broken.
      if (mesh) {
        throw DiagnosticError(declaration.where, "cannot open mesh file '" + name +
                                                     "' (looked for " + declaration.file + ")");
      }
      // cpfg goes on without it (cpfg-Sedge names a bract.s it does not have); ~X draws nothing.
      diagnostics.warn(declaration.where, "cannot open surface file " + name + " (looked for " +
                                              declaration.file + "); ~" + id + " draws nothing");
      continue;
    }
    Surface surface;
    // A mesh's own errors and warnings name the mesh file (its line where it has lines): the
    // view file's line is where the user looks first, so it is named too.
    Diagnostics meshWarnings;
    try {
      if (sequence) {
        surface.file = declaration.file;
        surface.mesh = std::make_shared<const SurfaceMeshData>(
            loadMeshSequence(declaration.file, resources.folder, maxMeshTriangles, meshWarnings));
      } else if (mesh) {
        surface.file = declaration.file;
        surface.mesh = std::make_shared<const SurfaceMeshData>(
            loadMeshFile(declaration.file, resources.folder, maxMeshTriangles, meshWarnings));
      } else {
        surface = loadSurface(declaration.file);
      }
    } catch (const DiagnosticError& error) {
      for (const Diagnostic& warning : meshWarnings.warnings()) {
        diagnostics.warn(declaration.where, "surface file '" + name + "': " + warning.where.text() +
                                                ": " + warning.message);
      }
      rethrowAtViewLine(declaration.where, "surface", name, error);
    }
    for (const Diagnostic& warning : meshWarnings.warnings()) {
      diagnostics.warn(declaration.where, "surface file '" + name + "': " + warning.where.text() +
                                              ": " + warning.message);
    }

    surface.id = declaration.id;
    surface.viewSize = declaration.size;
    surface.flow = declaration.flow;
    if (declaration.sPrecision > 0) surface.sPrecision = declaration.sPrecision;
    if (declaration.tPrecision > 0) surface.tPrecision = declaration.tPrecision;
    surface.texture = declaration.texture;
    if (surface.texture > static_cast<int>(resources.view.textures.size())) {
      diagnostics.warn(declaration.where, "surface ~" + id + " names texture " +
                                              std::to_string(surface.texture) + " but only " +
                                              std::to_string(resources.view.textures.size()) +
                                              " are declared; it is drawn untextured");
      surface.texture = 0;
    }
    if (surface.patches.size() > static_cast<std::size_t>(kCpfgMaxPatches)) {
      diagnostics.warn(declaration.where,
                       "surface file " + name + " has " + std::to_string(surface.patches.size()) +
                           " patches; cpfg reads at most " + std::to_string(kCpfgMaxPatches) +
                           ", Hirsute draws them all");
    }
    resources.surfaces[declaration.id] = std::move(surface);
  }
}

// cpfg (manual §8.1.4): `background scene: file1, file2, …`, drawn after the string. A missing
// file is a warning, like the other files the view names.
void loadBackgroundScenes(ModelResources& resources, const PreprocessorOptions& preprocessing,
                          Diagnostics& diagnostics) {
  for (const std::string& file : resources.view.backgroundScenes) {
    if (!fileExists(file)) {
      diagnostics.warn(fileLocation(file), "cannot open background scene file " +
                                               writtenName(file, resources.folder) +
                                               "; it is not drawn");
      continue;
    }
    resources.backgroundScenes.push_back(loadBackgroundScene(file, diagnostics, preprocessing));
  }
}

}  // namespace

ModelResources loadModelResources(const std::optional<std::filesystem::path>& viewFile,
                                  const ColorFiles& colors, Diagnostics& diagnostics,
                                  std::size_t maxMeshTriangles, std::size_t maxSourceBytes,
                                  const std::string* viewText) {
  ModelResources resources;
  PreprocessorOptions preprocessing;
  preprocessing.maxOutputBytes = maxSourceBytes;
  if (viewFile) {
    resources.folder = viewFile->parent_path();
    resources.viewFile = *viewFile;
    diagnostics.addSourceFolder(ModelFolder(resources.folder));  // messages quote its lines
    // cpfg runs the view file through the C preprocessor too: #define, /* */ and // work.
    resources.view = parseViewFile(viewText != nullptr
                                       ? *viewText
                                       : preprocessViewFile(*viewFile, maxSourceBytes, diagnostics),
                                   *viewFile, diagnostics);
  }
  loadPalette(resources, colors, diagnostics);
  loadTextures(resources, diagnostics);
  loadContours(resources, diagnostics);
  loadSurfaces(resources, maxMeshTriangles, diagnostics);
  loadBackgroundScenes(resources, preprocessing, diagnostics);
  return resources;
}

}  // namespace hirsute
