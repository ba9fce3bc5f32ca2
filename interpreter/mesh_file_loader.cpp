// The program's side of mesh_file.h: the functions load the mesh module (libhirsute-meshes.so,
// which links Assimp and CGAL; loadable_module.h) on first use and call its definitions, so that
// a run that reads no mesh starts without those libraries.
#include <cctype>
#include <mutex>
#include <stdexcept>
#include <string>

#include "hirsute/core/loadable_module.h"
#include "hirsute/interpreter/mesh_file.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

// The module's functions; throws std::runtime_error naming `file` when it cannot be loaded.
const MeshFileFunctions& meshModule(const fs::path& file) {
  static std::once_flag loaded;
  static const MeshFileFunctions* functions = nullptr;
  static std::string error;
  std::call_once(loaded, [] {
    using Entry = const MeshFileFunctions* (*)();
    if (void* entry = moduleEntry("libhirsute-meshes.so", "HIRSUTE_MESHES_MODULE",
                                  "hirsuteMeshFileFunctions", error))
      functions = reinterpret_cast<Entry>(entry)();
  });
  if (functions == nullptr) {
    // Not the model's fault: an error of the installation (exit code 1), not a diagnostic.
    throw std::runtime_error("cannot read the mesh " + file.string() + ": " + error +
                             " (mesh files need the mesh library and Assimp; "
                             "scripts/install-deps.sh installs them)");
  }
  return *functions;
}

}  // namespace

bool isMeshFile(const fs::path& file) {
  // A cpfg surface, or a name without an extension, is never a mesh: the module stays unloaded.
  std::string extension = file.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension.empty() || extension == ".s") return false;
  return meshModule(file).isMeshFile(file);
}

SurfaceMeshData loadMeshFile(const fs::path& file, const fs::path& folder, std::size_t maxTriangles,
                             Diagnostics& diagnostics, MeshReading reading) {
  return meshModule(file).loadMeshFile(file, folder, maxTriangles, diagnostics, reading);
}

SurfaceMeshData loadMeshSequence(const fs::path& pattern, const fs::path& folder,
                                 std::size_t maxTriangles, Diagnostics& diagnostics,
                                 MeshReading reading) {
  return meshModule(pattern).loadMeshSequence(pattern, folder, maxTriangles, diagnostics, reading);
}

}  // namespace hirsute
