// Meshes as surfaces (docs/design.md, "Meshes"): a view file's `surface:` line whose file
// is a mesh (OBJ, PLY, STL, OFF, glTF/GLB, FBX, … whatever Assimp reads, chosen by the file)
// defines a surface drawn by `~X` like a cpfg `.s` surface (docs/meshes.md).
#pragma once

#include <algorithm>
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

// Where a mesh's (u, v) come from.
enum class MeshUvSource : std::uint8_t {
  File,       // the file's texture coordinates
  Conformal,  // none in the file; the mesh is a disc: CGAL's least-squares conformal map
  Planar,     // none in the file, and no disc: its x and y over their bounds (and, for the fur,
              // an atlas of conformal charts: SurfaceMeshData::atlasUv)
};

// A mesh file's triangles in its own coordinates, ready to be placed by the turtle.
struct SurfaceMeshData {
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;       // unit, one per vertex (the file's, or computed)
  std::vector<glm::vec2> uv;             // one per vertex: the file's, or the planar fallback
  std::vector<glm::vec3> colours;        // the file's vertex colours, or empty
  std::vector<std::uint32_t> indices;    // three per triangle, counter-clockwise about the normal
  bool fileUvs = false;                  // uv come from the file
  // A Planar mesh's atlas (parameteriseCharts): (u, v) per corner of `indices` in charts that
  // cover it without overlapping, and each triangle's chart. The fur grows through it, where x
  // and y would fold the top onto the bottom. Empty for the other sources.
  std::vector<glm::vec2> atlasUv;
  std::vector<std::uint32_t> atlasChart;
  MeshUvSource uvSource = MeshUvSource::File;
  glm::dvec3 boundsMin{0.0}, boundsMax{0.0};
  // A mesh sequence's frames after the first (`body.####.obj`): the positions and normals of
  // each, over the first frame's vertices, triangles and (u, v).
  std::vector<std::vector<glm::dvec3>> laterPositions, laterNormals;

  std::size_t triangles() const { return indices.size() / 3; }
  std::size_t frames() const { return 1 + laterPositions.size(); }
  // Frame k's positions and normals (from 0; past the last, the last).
  const std::vector<glm::dvec3>& positionsAt(std::size_t frame) const {
    return frame == 0 || laterPositions.empty()
               ? positions
               : laterPositions[std::min(frame, laterPositions.size()) - 1];
  }
  const std::vector<glm::dvec3>& normalsAt(std::size_t frame) const {
    return frame == 0 || laterNormals.empty()
               ? normals
               : laterNormals[std::min(frame, laterNormals.size()) - 1];
  }
};

// A mesh sequence may hold at most this many vertices over all its frames (24 bytes a position
// and as many a normal: about 1 GB).
inline constexpr std::size_t kMaxSequenceVertices = 20'000'000;

// Where a mesh file is read. Assimp trusts its files, and a malformed one can crash it, make it
// loop or take all memory: the program reads each mesh in a child process with a memory and a
// time limit (isolated_call.h), whose crash becomes an error naming the file. The same reading
// in this process is for the fuzzer (fuzz/mesh_file_fuzzer.cpp), which looks for the crashes.
// Both give the same mesh and the same diagnostics.
enum class MeshReading : std::uint8_t { ChildProcess, InProcess };

// Whether a file is read as a mesh rather than as a cpfg `.s` surface: its extension is one
// Assimp imports and is not `.s`.
bool isMeshFile(const std::filesystem::path& file);

// Reads a mesh beneath `folder` (model_folder.h): the file and every file it names (an OBJ's
// .mtl, a glTF's buffers) are opened through the folder, never outside it. Its bytes are checked
// first (mesh_file_checks.h). Node transforms are applied, polygons triangulated, identical
// vertices joined; degenerate triangles are dropped, edges shared by more than two triangles
// reported and vertex colours outside [0, 1] clamped, each as one warning. Throws
// DiagnosticError naming the file (and line and column where the format has lines, as an OBJ's
// non-finite coordinate) for an unreadable, malformed or empty mesh, a non-finite vertex or
// colour, more than `maxTriangles` triangles, or a reader that crashed, ran out of time or
// memory.
SurfaceMeshData loadMeshFile(const std::filesystem::path& file, const std::filesystem::path& folder,
                             std::size_t maxTriangles, Diagnostics& diagnostics,
                             MeshReading reading = MeshReading::ChildProcess);

// Whether a name is a mesh sequence's: a run of '#' in its file name stands for the frame number
// (`body.####.obj`: body.0001.obj, body.0002.obj, …).
inline bool isMeshSequence(const std::filesystem::path& file) {
  return file.filename().string().find('#') != std::string::npos;
}

// A mesh sequence: its frames are the files whose numbers, written with at least as many digits
// as the run of '#', are consecutive from the lowest there is; every frame has the first one's
// vertices and triangles (a sequence exported frame by frame from an animation), and its own
// positions and normals. Throws DiagnosticError naming the file of a frame that is missing,
// broken or of other vertices, for no frame at all, and past kMaxSequenceVertices.
SurfaceMeshData loadMeshSequence(const std::filesystem::path& pattern,
                                 const std::filesystem::path& folder, std::size_t maxTriangles,
                                 Diagnostics& diagnostics,
                                 MeshReading reading = MeshReading::ChildProcess);

// The mesh module (libhirsute-meshes.so, with Assimp and CGAL; loadable_module.h) defines the
// three functions above; the program's own definitions load it on first use and call these.
// Its entry point hirsuteMeshFileFunctions returns them.
struct MeshFileFunctions {
  bool (*isMeshFile)(const std::filesystem::path& file);
  SurfaceMeshData (*loadMeshFile)(const std::filesystem::path& file,
                                  const std::filesystem::path& folder, std::size_t maxTriangles,
                                  Diagnostics& diagnostics, MeshReading reading);
  SurfaceMeshData (*loadMeshSequence)(const std::filesystem::path& pattern,
                                      const std::filesystem::path& folder, std::size_t maxTriangles,
                                      Diagnostics& diagnostics, MeshReading reading);
};

}  // namespace hirsute
