// Fur in the OBJ file (DESIGN.md, "Fur"): every strand of the fur texture on each fur surface,
// bent, curled and clumped as the shells draw it (hirsute/hairs/fur/fur_strands.h), one `l`
// polyline, under `o fur`, in the surface's material.
#include "hirsute/hairs/fur/fur_strands.h"
#include "hirsute/hairs/fur/fur_writer.h"
#include "hirsute/interpreter/fur_part.h"
#include "hirsute/viewer/export/obj_writer.h"

namespace hirsute {
namespace {
constexpr int kStrandPoints = 7;  // the POV-Ray ribbons' points (pov_fur.cpp)
}  // namespace

void FurWriter::writeObj(const Scene& scene, ObjWriter& obj) const {
  obj.group("fur");
  std::uint64_t strands = 0;
  for (const FurSurface& surface : scene.organ<FurPart>().surfaces) {
    obj.useMaterial(surface.material, -1);
    fur::forEachStrand(scene, surface, kStrandPoints, [&](const fur::FurStrandView& strand) {
      const std::uint64_t first = obj.stats().vertices + 1;
      for (const glm::vec3& p : strand.points) obj.vertex(p);
      for (std::uint64_t i = 0; i < strand.points.size(); ++i) obj.polyline().push_back(first + i);
      obj.finishPolyline();
      ++strands;
    });
  }
  obj.count("fur strands", strands);
}

const OrganWriter& furWriter() {
  static const FurWriter writer;
  return writer;
}

}  // namespace hirsute
