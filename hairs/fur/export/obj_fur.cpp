// Fur in the OBJ file (docs/design.md, "Fur"): every strand of the fur texture on each fur surface,
// bent, curled and clumped as the shells draw it (hirsute/hairs/fur/fur_strands.h), one `l`
// polyline, under `o fur`, in the surface's material.
#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_strands.h"
#include "hirsute/hairs/fur/fur_writer.h"
#include "hirsute/viewer/export/obj_writer.h"

namespace hirsute {
void FurWriter::writeObj(const Scene& scene, ObjWriter& obj) const {
  obj.group("fur");
  std::uint64_t strands = 0;
  fur::StrandBudget budget(scene.organ<FurPart>());
  const std::vector<FurSurface>& surfaces = scene.organ<FurPart>().surfaces;
  for (std::size_t index = 0; index < surfaces.size(); ++index) {
    const FurSurface& surface = surfaces[index];
    obj.useMaterial(surface.material, -1);
    const int samples = budget.charge(scene, surface, index);
    fur::forEachStrand(scene, surface, samples, [&](const fur::FurStrandView& strand) {
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
