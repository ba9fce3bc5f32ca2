// Fur in the scene file for Blender (blender_writer.h): the strands of each fur surface one curve
// group, bent, curled and clumped as the shells draw them (fur_strands.h), each strand of its
// radius, coloured at its root by the fur texture (or the surface's colour).
#include <fmt/format.h>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_strands.h"
#include "hirsute/hairs/fur/fur_writer.h"
#include "hirsute/viewer/export/blender_writer.h"

namespace hirsute {

void FurWriter::writeBlender(const Scene& scene, BlenderWriter& blender) const {
  std::uint64_t strands = 0;
  const FurPart& fur = scene.organ<FurPart>();
  fur::StrandBudget budget(fur);
  for (std::size_t index = 0; index < fur.surfaces.size(); ++index) {
    const FurSurface& surface = fur.surfaces[index];
    const Material material = static_cast<std::size_t>(surface.material) < scene.materials.size()
                                  ? scene.materials[static_cast<std::size_t>(surface.material)]
                                  : Material{};
    const Texture* texture =
        surface.attributes >= 0
            ? fur::colourTexture(scene,
                                 fur.attributes[static_cast<std::size_t>(surface.attributes)])
            : nullptr;
    blender.beginCurves("fur", fmt::format("surface{}", index),
                        blender.sceneMaterial(surface.material, BlenderWriter::Shading::Hair));
    const int samples = budget.charge(scene, surface, index);
    fur::forEachStrand(scene, surface, samples, [&](const fur::FurStrandView& strand) {
      const glm::vec3 colour = texture ? texture->colourAt(strand.uv) : material.diffuse;
      for (const glm::vec3& p : strand.points) blender.curvePoint(p, strand.radius, colour);
      blender.endCurve();
      ++strands;
    });
    blender.endCurves();
    blender.advance();
  }
  blender.count("fur strands", strands);
}

}  // namespace hirsute
