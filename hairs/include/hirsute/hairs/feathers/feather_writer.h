// The feathers' writers (organ_writer.h): POV-Ray (export/pov_feathers.cpp), OBJ
// (export/obj_feathers.cpp) and the table of `export --feathers` (export/feather_csv_writer.cpp).
#pragma once

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/viewer/export/organ_writer.h"

namespace hirsute {

class FeatherWriter : public OrganWriter {
 public:
  std::size_t items(const Scene& scene) const override {
    return scene.organ<FeatherPart>().feathers.size();
  }
  // Shafts and barbs as two mesh2, the barbs' transparency fading to their tips. Counts
  // "feathers".
  void writePov(const Scene& scene, PovWriter& pov) const override;
  // `o feathers`: the shafts as faces, the barbs as `l` polylines (drawing: lines) or faces
  // (strips), in material 0. Counts "feathers".
  void writeObj(const Scene& scene, ObjWriter& obj) const override;
  // The shafts one mesh, the barbs one curve group (blender_feathers.cpp). Counts "feathers".
  void writeBlender(const Scene& scene, BlenderWriter& blender) const override;
  // Barbs are layers of transparent triangles: a ray may pass many before it is opaque, and
  // POV-Ray's default of 5 would blacken it.
  int povTraceLevel(const Scene&) const override { return 64; }
  // `--feathers FILE`: writeFeatherCsv (feather_csv_writer.h).
  std::optional<OrganTable> table() const override;
};

const OrganWriter& featherWriter();

}  // namespace hirsute
