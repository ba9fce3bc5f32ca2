// The surfaces of a Scene as glTF 2.0 (`hirsute export --gltf FILE.gltf|FILE.glb`), for web
// viewers and game engines: its meshes with their normals, a material each of the palette's
// entries they use (base colour, alpha, emission), and the view file's camera. A .glb is one
// file; a .gltf is its JSON and, beside it, the binary buffer FILE.bin that it names.
//
// The writer gathers the scene into a GltfScene (gltf_scene.h); Assimp's exporter, in the glTF
// module loaded on first use, makes the bytes, which are written through OutputTarget (a
// temporary file renamed on commit, with the run's other outputs). Spheres and discs are
// triangle meshes, one a material (primitive_mesh.h); lines, labels and the organs (hairs, fur,
// feathers) are not written: docs/export.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>

#include "hirsute/core/output_target.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/export/gltf_scene.h"
#include "hirsute/viewer/export/primitive_mesh.h"
#include "hirsute/viewer/export/scene_writer.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute {

struct GltfOptions {
  ViewSettings view;              // the camera (cpfg's view file)
  int width = 800, height = 600;  // the picture the camera is fitted for
  OutputGroup* group = nullptr;   // the outputs the files are committed with; none: on their own
};

struct GltfExportStats {
  std::uint64_t meshes = 0, vertices = 0, triangles = 0, materials = 0;
  std::uint64_t bytes = 0;  // the file's, and the buffer file's of a .gltf
};

// Whether `target` names a binary glTF (.glb) or a text one (.gltf), in any case of letters;
// throws std::invalid_argument for any other name.
bool gltfIsBinary(const std::filesystem::path& target);

// The .gltf's buffer file: its name with .bin.
std::filesystem::path gltfBufferFile(const std::filesystem::path& target);

class GltfWriter : public ScenePrinter {
 public:
  GltfWriter(std::filesystem::path target, GltfOptions options);

  void beginScene(const Scene& scene, std::span<const OrganWriter* const> organs) override;
  void mesh(const TriangleMesh& mesh) override;
  void line(const LineSegment&, LineStyle) override {}
  void sphere(const Sphere& sphere) override;
  void disc(const Disc& disc) override;
  void label(const Label&) override {}
  void organ(const OrganWriter&, const Scene&) override {}
  void endScene() override;

  const GltfExportStats& stats() const { return stats_; }

 private:
  int material(int sceneMaterial);
  void addMesh(int sceneMaterial, std::vector<glm::vec3> positions, std::vector<glm::vec3> normals,
               std::vector<std::uint32_t> indices);

  std::filesystem::path target_;
  GltfOptions options_;
  const Scene* scene_ = nullptr;
  GltfScene gltf_;
  std::map<int, int> materials_;                  // the Scene's material → GltfScene::materials
  std::map<int, PrimitiveMesh> spheres_, discs_;  // by the Scene's material
  GltfExportStats stats_;
};

// Writes `scene` to `target` and returns the figures; shows its progress on `progress`. Throws
// std::invalid_argument for a scene glTF cannot hold (a coordinate that is not a number) or a
// name neither .gltf nor .glb, std::runtime_error when the file cannot be written or the glTF
// module (Assimp) cannot be loaded.
GltfExportStats writeGltf(const Scene& scene, const GltfOptions& options,
                          const std::filesystem::path& target, Progress* progress = nullptr);

}  // namespace hirsute
