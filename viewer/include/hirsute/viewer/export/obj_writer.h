// Wavefront OBJ export for Blender and MeshLab: `plant.obj` with its `plant.mtl` beside it.
// Meshes keep their normals (and texture coordinates), lines become `l` polylines, spheres and
// discs are tessellated into faces; each material used is one `newmtl` with Ka Kd Ks Ns d.
// docs/export.md describes the files.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
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
};

struct ObjExportStats {
  std::uint64_t bytes = 0, mtlBytes = 0;
  std::uint64_t vertices = 0, normals = 0, texcoords = 0, faces = 0;
  std::uint64_t lineElements = 0;  // `l` polylines (hairs' included)
  std::uint64_t hairs = 0;         // hairs written (their template has segments)
  std::uint64_t feathers = 0;      // feathers written
  std::uint64_t furStrands = 0;    // fur strands written, one `l` each
  std::size_t materials = 0;       // `newmtl` entries
};

class ObjWriter : public ScenePrinter {
 public:
  // The material library is written beside `target`, with its stem and the extension .mtl.
  explicit ObjWriter(std::filesystem::path target, ObjOptions options = {});
  ~ObjWriter() override;

  void beginScene(const Scene& scene) override;
  void mesh(const TriangleMesh& mesh) override;
  void line(const LineSegment& line, LineStyle style) override;
  void sphere(const Sphere& sphere) override;
  void disc(const Disc& disc) override;
  void label(const Label& label) override;
  // Hairs as polylines: each polyline of a hair's template, placed, one `l` element, under
  // `o hairs`, grouped by their template's material (one `usemtl` each).
  void hairs(const std::vector<HairTemplate>& templates, const std::vector<Hair>& hairs) override;
  // `o feathers`: the shafts as faces, the barbs as `l` polylines (drawing: lines) or faces
  // (strips), one material a colour (obj_feathers.cpp).
  void feathers(const Scene& scene) override;
  // `o fur`: each fur strand one `l` polyline in its surface's material (obj_fur.cpp).
  void fur(const Scene& scene) override;
  void endScene() override;

  const ObjExportStats& stats() const { return stats_; }

 private:
  void useMaterial(int material, int texture);
  void group(std::string_view name);  // `o name`, unless it is the current object
  void vertex(const glm::vec3& p);
  void normal(const glm::vec3& n);
  void finishPolyline();
  void writeMaterialLibrary();

  std::filesystem::path target_, mtlTarget_;
  ObjOptions options_;
  ExportFile out_;
  const Scene* scene_ = nullptr;
  NumberFormat position_{6, true};
  NumberFormat normal_{4, true};
  NumberFormat texcoord_{5, true};
  std::vector<std::pair<int, int>> materialsUsed_;  // (material, texture) in order of first use
  std::set<std::pair<int, int>> materialSet_;
  std::pair<int, int> current_{0, -2};
  std::string_view currentGroup_;  // a literal: "lines", "spheres", "discs", "hairs"
  int meshNumber_ = 0;
  // Unit-sphere tessellation: positions (= normals) and triangles, made once.
  std::vector<glm::vec3> spherePoints_;
  std::vector<std::uint32_t> sphereTriangles_;
  // The polyline being gathered: its vertex numbers, and where it ends.
  std::vector<std::uint64_t> polyline_;
  std::uint64_t shaftNormalBase_ = 0;  // obj_feathers.cpp: the first normal of the shafts
  glm::vec3 polylineEnd_{0.0f};
  ObjExportStats stats_;
};

// Writes `scene` to `target` and its material library beside it (and textures, see
// texture_file.h); returns the figures. Shows its progress on `progress` when given.
ObjExportStats writeObj(const Scene& scene, const std::filesystem::path& target,
                        ObjOptions options = {}, Progress* progress = nullptr);

}  // namespace hirsute
