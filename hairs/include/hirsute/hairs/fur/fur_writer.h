// The fur's writers (organ_writer.h): POV-Ray (export/pov_fur.cpp) and OBJ (export/obj_fur.cpp),
// both as explicit strands (fur_strands.h), since no format draws shells.
#pragma once

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/viewer/export/organ_writer.h"

namespace hirsute {

class FurWriter : public OrganWriter {
 public:
  // The fur surfaces (the strands are not counted ahead).
  std::size_t items(const Scene& scene) const override {
    return scene.organ<FurPart>().surfaces.size();
  }
  // Per fur surface one mesh2 of ribbons facing the camera, each vertex coloured by the shells'
  // own shading (Kajiya-Kay times the shadow factor, Eq. 6) so that the still matches the
  // preview, emitted rather than lit. Counts "fur strands".
  void writePov(const Scene& scene, PovWriter& pov) const override;
  // `o fur`: each fur strand one `l` polyline in its surface's material. Counts "fur strands".
  void writeObj(const Scene& scene, ObjWriter& obj) const override;
  // Each fur surface's strands one curve group (blender_fur.cpp). Counts "fur strands".
  void writeBlender(const Scene& scene, BlenderWriter& blender) const override;
};

const OrganWriter& furWriter();

}  // namespace hirsute
