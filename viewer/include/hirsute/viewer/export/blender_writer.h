// The scene file for Blender (`hirsute export --blender FILE`), read by the add-on
// blender/hirsute_import.py: one binary file of little-endian arrays (meshes with normals,
// texture coordinates and vertex colours; hairs, fur strands, barbs and lines as curves with a
// radius and a colour at each point) and, at its end, a JSON index that names each array's place
// with the materials, the view file's camera and lights. docs/export.md describes the layout.
//
// Meshes and curves are streamed into the file as they come; only the index and each curve
// group's sizes are held until the group ends, so a million hairs cost their file, not memory.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/export/export_file.h"
#include "hirsute/viewer/export/primitive_mesh.h"
#include "hirsute/viewer/export/scene_writer.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute {

// The file's first 8 and last 8 bytes, and the layout's version (docs/export.md).
inline constexpr char kBlenderMagic[9] = "HIRSUTEB";
inline constexpr std::uint32_t kBlenderVersion = 1;

struct BlenderOptions {
  ViewSettings view;              // camera and lights (cpfg's view file)
  bool materialMode = false;      // the background is material 0's emission, else colour 0
  int width = 800, height = 600;  // the picture the camera is fitted for
  OutputGroup* group = nullptr;   // the outputs the file is committed with; none: on its own
};

struct BlenderExportStats {
  std::uint64_t bytes = 0;
  std::uint64_t meshes = 0, triangles = 0;
  std::uint64_t curveGroups = 0, curves = 0, points = 0;
  std::map<std::string, std::uint64_t, std::less<>> organs;  // BlenderWriter::count
  std::uint64_t organ(std::string_view what) const {
    const auto found = organs.find(what);
    return found == organs.end() ? 0 : found->second;
  }
};

class BlenderWriter : public ScenePrinter {
 public:
  BlenderWriter(std::filesystem::path target, BlenderOptions options);
  ~BlenderWriter() override;

  void beginScene(const Scene& scene, std::span<const OrganWriter* const> organs) override;
  void mesh(const TriangleMesh& mesh) override;
  // Lines that continue each other in one material become one curve of the group "lines", of
  // radius half their width (pixel widths at the fitted picture's scale).
  void line(const LineSegment& line, LineStyle style) override;
  void sphere(const Sphere& sphere) override;
  void disc(const Disc& disc) override;
  void label(const Label& label) override;  // not carried: Blender's text is no plant's
  void organ(const OrganWriter& organ, const Scene& scene) override;
  void endScene() override;

  const BlenderExportStats& stats() const { return stats_; }
  const Camera& camera() const { return camera_; }
  // The world size of a pixel of the fitted picture at the point looked at.
  float worldPerPixel() const { return worldPerPixel_; }

  // What the organs' writers write with (organ_writer.h), between beginScene() and endScene().
  //
  // How a material is shaded in Blender: a surface (principled BSDF) or hair (Cycles' principled
  // hair BSDF, coloured by each curve point's colour).
  enum class Shading { Surface, Hair };
  // The index in the file of the Scene's material `material` shaded as `shading`.
  int sceneMaterial(int material, Shading shading);
  // A material an organ defines itself (a feather type's colour), by name: one name, one entry.
  int organMaterial(const std::string& name, const glm::vec3& diffuse, Shading shading);
  // A group of curves, one Blender object: `organ` ("hairs", "fur", "barbs", "lines") and
  // `name` (the template, the surface, the vane's type) name it. Points come one by one, each
  // curve ended by endCurve(); a curve of fewer than 2 points is dropped.
  void beginCurves(std::string_view organ, std::string_view name, int material);
  // `colour` in display values (0..1), written in linear light as Blender's colours are.
  void curvePoint(const glm::vec3& p, float radius, const glm::vec3& colour);
  void endCurve();
  void endCurves();
  // A triangle mesh, one Blender object. `normals`, `texcoords` and `colours` (display values)
  // are empty or one per position.
  void triangles(std::string_view organ, std::string_view name, int material,
                 std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                 std::span<const glm::vec2> texcoords, std::span<const glm::vec3> colours,
                 std::span<const std::uint32_t> indices);
  // Adds `count` to what the organs' writers wrote of `what` (BlenderExportStats::organs); the
  // index lists them under "counts".
  void count(std::string_view what, std::uint64_t count);

 private:
  struct MaterialEntry {
    std::string name;
    glm::vec3 diffuse, specular, emission;
    float shininess, alpha;
    Shading shading;
  };
  std::uint64_t put(const void* data, std::size_t bytes);  // returns the array's offset
  void flushPrimitives();

  std::filesystem::path target_;
  BlenderOptions options_;
  ExportFile out_;
  const Scene* scene_ = nullptr;
  Camera camera_;
  float worldPerPixel_ = 0;
  // The index's entries of meshes and curve groups, written as each ends.
  std::string meshEntries_, curveEntries_;
  std::vector<MaterialEntry> materials_;
  std::map<std::pair<int, int>, int> sceneMaterials_;  // (material, shading) → entry
  std::map<std::string, int, std::less<>> organMaterials_;
  // The open curve group.
  bool inGroup_ = false;
  std::string groupOrgan_, groupName_;
  int groupMaterial_ = 0;
  std::uint64_t groupOffset_ = 0, groupPoints_ = 0;
  std::vector<std::array<float, 7>> curve_;  // the curve being gathered: x y z radius r g b
  std::vector<std::uint32_t> groupSizes_;
  // The scene's lines: the curve being gathered, its material and end.
  int lineMaterial_ = -1;
  glm::vec3 lineEnd_{0.0f};
  // Spheres and discs, gathered by material into one mesh each.
  std::map<int, PrimitiveMesh> spheres_, discs_;
  BlenderExportStats stats_;
};

// Writes `scene` to `target` and returns the figures; shows its progress on `progress`.
BlenderExportStats writeBlender(const Scene& scene, const BlenderOptions& options,
                                const std::filesystem::path& target, Progress* progress = nullptr);

// What a reader finds in a file of writeBlender: the version and the JSON index (its text; the
// add-on parses it), checked against the file's size. Throws std::runtime_error naming the file
// when it is none, truncated or of another version.
struct BlenderFileIndex {
  std::uint32_t version = 0;
  std::uint64_t fileBytes = 0, indexOffset = 0;
  std::string json;
};
BlenderFileIndex readBlenderIndex(const std::filesystem::path& file);

}  // namespace hirsute
