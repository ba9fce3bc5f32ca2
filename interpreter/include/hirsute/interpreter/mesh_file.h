// Meshes as surfaces (DESIGN.md, "Meshes as surfaces"): a view file's `surface:` line whose file
// is a mesh (OBJ, PLY, STL, OFF, glTF/GLB, FBX, … whatever Assimp reads, chosen by the file)
// defines a surface drawn by `~X` like a cpfg `.s` surface (docs/meshes.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

// A mesh of more triangles than this is refused (`--max-mesh-triangles`).
inline constexpr std::size_t kDefaultMaxMeshTriangles = 2'000'000;

// A mesh file's triangles in its own coordinates, ready to be placed by the turtle.
struct SurfaceMeshData {
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;       // unit, one per vertex (the file's, or computed)
  std::vector<glm::vec2> uv;             // one per vertex: the file's, or the planar fallback
  std::vector<glm::vec3> colours;        // the file's vertex colours, or empty
  std::vector<std::uint32_t> indices;    // three per triangle, counter-clockwise about the normal
  bool fileUvs = false;                  // uv come from the file (else: x, y over their bounds)
  glm::dvec3 boundsMin{0.0}, boundsMax{0.0};

  std::size_t triangles() const { return indices.size() / 3; }
};

// Whether a file is read as a mesh rather than as a cpfg `.s` surface: its extension is one
// Assimp imports and is not `.s`.
bool isMeshFile(const std::filesystem::path& file);

// Reads a mesh beneath `folder` (model_folder.h): the file and every file it names (an OBJ's
// .mtl, a glTF's buffers) are opened through the folder, never outside it. Node transforms are
// applied, polygons triangulated, identical vertices joined; degenerate triangles are dropped and
// edges shared by more than two triangles reported, each as one warning. Throws DiagnosticError
// naming the file (and line and column where the format has lines, as an OBJ's non-finite
// coordinate) for an unreadable or empty mesh, a non-finite vertex, or more than
// `maxTriangles` triangles.
SurfaceMeshData loadMeshFile(const std::filesystem::path& file, const std::filesystem::path& folder,
                             std::size_t maxTriangles, Diagnostics& diagnostics);

}  // namespace hirsute
