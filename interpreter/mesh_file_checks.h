// Cheap checks of a mesh file's bytes before Assimp reads them (docs/meshes.md, "Bad meshes").
// Assimp trusts its files: a PLY face of no corners fails an assertion, a PLY whose header
// announces more than the file holds is read past its end, a node hierarchy thousands deep
// (glTF, COLLADA) overflows its recursion, an OBJ of 200 000 groups costs minutes and
// gigabytes. What one pass over the bytes can see is refused here with the file's line and
// column; what it cannot is why Assimp runs in a child process (mesh_file.cpp).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace hirsute {

// Node hierarchies (glTF's children, COLLADA's nested elements) and JSON values may nest at
// most this deep.
inline constexpr int kMaxMeshNesting = 256;
// An OBJ may switch groups, objects or materials (`g`, `o`, `usemtl`) at most this often: Assimp
// makes a mesh of each.
inline constexpr std::size_t kMaxObjGroups = 10'000;

// Checks the bytes of `file` by their content (PLY, glTF JSON, GLB, XML) and, for a `.obj`, as an
// OBJ: structure, counts, faces of fewer than 3 corners, indices out of range, nesting, an OBJ's
// groups and non-finite coordinates, and the triangles of an OBJ or PLY against `maxTriangles`
// (counted from the file, before it is read). Throws DiagnosticError at the file (its line and
// column where it has lines).
void checkMeshFileBytes(const std::string& bytes, const std::filesystem::path& file,
                        std::size_t maxTriangles);

}  // namespace hirsute
