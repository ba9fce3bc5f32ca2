// Fur in the OBJ file (DESIGN.md, "Fur"): every strand of the fur texture on each fur surface, bent,
// curled and clumped as the shells draw it (hirsute/hairs/fur/fur_strands.h), one `l` polyline,
// under `o fur`, in the surface's material.
#include "hirsute/hairs/fur/fur_strands.h"
#include "hirsute/viewer/export/obj_writer.h"

namespace hirsute {
namespace {
constexpr int kStrandPoints = 7;  // the POV-Ray ribbons' points (pov_fur.cpp)
}  // namespace

void ObjWriter::fur(const Scene& scene) {
  finishPolyline();
  out_.put("o fur\n");
  currentGroup_ = "fur";
  for (const FurSurface& surface : scene.furSurfaces) {
    useMaterial(surface.material, -1);
    fur::forEachStrand(scene, surface, kStrandPoints, [&](const fur::FurStrandView& strand) {
      const std::uint64_t first = stats_.vertices + 1;
      for (const glm::vec3& p : strand.points) vertex(p);
      for (std::uint64_t i = 0; i < strand.points.size(); ++i) polyline_.push_back(first + i);
      finishPolyline();
      ++stats_.furStrands;
    });
  }
}

}  // namespace hirsute
