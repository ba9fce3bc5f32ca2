// Wavefront OBJ export for Blender and MeshLab: `plant.obj` with its `plant.mtl` beside it.
// Meshes keep their normals (and texture coordinates), lines become polylines of `l` segments,
// spheres and
// discs are tessellated into faces; each material used is one `newmtl` with Ka Kd Ks Ns d.
// docs/export.md describes the files.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/export/export_file.h"
#include "hirsute/viewer/export/scene_writer.h"

namespace hirsute {

struct ObjOptions {
  int sphereSlices = 16;  // around the axis
  int sphereStacks = 8;   // pole to pole
  int discSegments = 16;
  // The outputs this scene is committed with (output_target.h); none: on its own.
  OutputGroup* group = nullptr;
  // The folder the scene is written into under a name Hirsute made itself (the frames of
  // `simulate -o DIR`): the scene is `target`'s file name in it, created there as the side files
  // are (output_folder.h). None: `target` is the name the user typed (output_target.h), and the
  // side files go into the folder it is in.
  const OutputFolder* folder = nullptr;
  // Every vertex's position as it is written (`v`), in order: the points of a point cache of
  // the scene (point_cache.h). None: not kept.
  std::vector<glm::vec3>* positions = nullptr;
  // No `o` lines: the file is one object, whose vertices OBJ importers keep in the order written
  // (a point cache's base mesh, which the cache's points follow one for one).
  bool oneObject = false;
};

struct ObjExportStats {
  std::uint64_t bytes = 0, mtlBytes = 0;
  std::uint64_t vertices = 0, normals = 0, texcoords = 0, faces = 0;
  std::uint64_t lineElements = 0;  // `l` elements, one a segment (the organs' included)
  std::uint64_t polylines = 0;     // the chains of segments they make
  // What the organs' writers wrote, by the names they count under (ObjWriter::count).
  std::map<std::string, std::uint64_t, std::less<>> organs;
  std::uint64_t organ(std::string_view what) const {
    const auto found = organs.find(what);
    return found == organs.end() ? 0 : found->second;
  }
  std::size_t materials = 0;  // `newmtl` entries
};

class ObjWriter : public ScenePrinter {
 public:
  // The material library is written beside `target`, with its stem and the extension .mtl.
  explicit ObjWriter(std::filesystem::path target, ObjOptions options = {});
  ~ObjWriter() override;

  void beginScene(const Scene& scene, std::span<const OrganWriter* const> organs) override;
  void mesh(const TriangleMesh& mesh) override;
  void line(const LineSegment& line, LineStyle style) override;
  void sphere(const Sphere& sphere) override;
  void disc(const Disc& disc) override;
  void label(const Label& label) override;
  // Ends the polyline being gathered and hands the writer to the organ (organ_writer.h).
  void organ(const OrganWriter& organ, const Scene& scene) override;
  void endScene() override;

  const ObjExportStats& stats() const { return stats_; }

  // What the organs' writers draw with (organ_writer.h), between beginScene() and endScene().
  ExportFile& out() { return out_; }
  void useMaterial(int material, int texture);
  // A material an organ defines itself (a feather type's colour and texture, which are no entry
  // of the Scene's palette): `usemtl NAME`, and in the library Kd `diffuse` (display values) and
  // map_Kd of the Scene's texture `texture` (-1: none). One name, one material.
  void useOrganMaterial(const std::string& name, const glm::vec3& diffuse, int texture);
  // `o name`, unless it is the current object; `name` outlives the writer (a literal).
  void group(std::string_view name);
  // `v`, `vn`: numbered from 1 in the order written (stats().vertices, stats().normals).
  void vertex(const glm::vec3& p);
  // A vertex with its colour (display values, 0..1), `v x y z r g b`, the extension Blender and
  // MeshLab read as vertex colours.
  void vertex(const glm::vec3& p, const glm::vec3& colour);
  void normal(const glm::vec3& n);
  // `vt`: numbered from 1 in the order written (stats().texcoords).
  void texcoord(const glm::vec2& t);
  // A face of three vertex numbers, with the normal numbers `normals` and the texture
  // coordinate numbers `texcoords` (none: without).
  void face(const std::array<std::uint64_t, 3>& vertices,
            const std::optional<std::array<std::uint64_t, 3>>& normals = std::nullopt,
            const std::optional<std::array<std::uint64_t, 3>>& texcoords = std::nullopt);
  // The polyline being gathered: vertex numbers, written by finishPolyline() as one `l`
  // element a segment (`l 4 5`, `l 5 6`: obj_writer.cpp says why).
  std::vector<std::uint64_t>& polyline() { return polyline_; }
  void finishPolyline();
  // Adds `count` to what the organ's writers wrote of `what` (ObjExportStats::organs).
  void count(std::string_view what, std::uint64_t count);

 private:
  void putVertexPosition(const glm::vec3& p);  // `v x y z`, without the line's end
  void writeMaterialLibrary();
  void writeTextureOnce(int texture);
  // The folder of the side files (the .mtl, texture images), opened when the first is written.
  const OutputFolder& sideFolder();

  std::filesystem::path target_;
  std::string mtlName_;  // the material library's file name, beside the OBJ
  ObjOptions options_;
  ExportFile out_;
  std::optional<OutputFolder> sideFolder_;
  const Scene* scene_ = nullptr;
  NumberFormat position_{6, true};
  NumberFormat normal_{4, true};
  NumberFormat texcoord_{5, true};
  std::vector<std::pair<int, int>> materialsUsed_;  // (material, texture) in order of first use
  std::set<std::pair<int, int>> materialSet_;
  std::pair<int, int> current_{0, -2};
  std::string_view currentGroup_;  // a literal: "lines", "spheres", "discs", an organ's
  int meshNumber_ = 0;
  // Unit-sphere tessellation: positions (= normals) and triangles, made once.
  std::vector<glm::vec3> spherePoints_;
  std::vector<std::uint32_t> sphereTriangles_;
  // The polyline being gathered: its vertex numbers, and where it ends.
  std::vector<std::uint64_t> polyline_;
  struct OrganMaterial {
    std::string name;
    glm::vec3 diffuse;
    int texture;
  };
  std::vector<OrganMaterial> organMaterials_;  // in order of first use
  std::string currentOrganMaterial_;
  std::set<int> texturesWritten_;
  glm::vec3 polylineEnd_{0.0f};
  ObjExportStats stats_;
};

// Writes `scene` to `target` and its material library beside it (and textures, see
// texture_file.h); returns the figures. Shows its progress on `progress` when given.
ObjExportStats writeObj(const Scene& scene, const std::filesystem::path& target,
                        ObjOptions options = {}, Progress* progress = nullptr);

}  // namespace hirsute
