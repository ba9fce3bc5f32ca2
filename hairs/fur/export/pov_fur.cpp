// Fur in the POV-Ray scene (docs/design.md, "Fur"; docs/fur.md, "Stills"): POV-Ray has no shells:
// every strand of the fur texture on a fur surface becomes a ribbon of its own, bent, curled and
// clumped by the shells' equations (hirsute/hairs/fur/fur_strands.h), facing the camera and a
// strand thick. Each vertex carries the colour the shells' fragment shader computes there
// (Kajiya-Kay, Eq. 6, times the shadow factor) and the ribbons emit it, so that the still shows
// the preview's fur, clumps where the preview has them.
#include <algorithm>
#include <cmath>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_strand.h"
#include "hirsute/hairs/fur/fur_strands.h"
#include "hirsute/hairs/fur/fur_writer.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/view/view_lighting.h"

namespace hirsute {
namespace {

constexpr char kEmittedFinish[] = "emission 1 diffuse 0 ambient 0";

}  // namespace

void FurWriter::writePov(const Scene& scene, PovWriter& pov) const {
  using Shade = PovWriter::Shade;
  const Camera& camera = pov.camera();
  const glm::vec3 towardsEye = -camera.forward;
  const glm::vec3 light = glm::normalize(organLight(
      viewLighting(pov.options().view, pov.options().materialMode, towardsEye), towardsEye));
  const bool perspective = camera.projection == Projection::Perspective;
  fur::StrandBudget budget(scene.organ<FurPart>());
  for (std::size_t index = 0; index < scene.organ<FurPart>().surfaces.size(); ++index) {
    const FurSurface& surface = scene.organ<FurPart>().surfaces[index];
    if (surface.attributes < 0) continue;
    const FurAttributes& a =
        scene.organ<FurPart>().attributes[static_cast<std::size_t>(surface.attributes)];
    const Material material = static_cast<std::size_t>(surface.material) < scene.materials.size()
                                  ? scene.materials[static_cast<std::size_t>(surface.material)]
                                  : Material{};
    const Texture* texture = fur::colourTexture(scene, a);
    std::vector<glm::vec3> points;
    std::vector<Shade> shades;
    std::vector<std::uint32_t> faces;
    std::size_t strands = 0;
    // As many ribbon segments as the curl needs (fur_strands.h), within --max-vertices.
    const int samples = budget.charge(scene, surface, index);
    fur::forEachStrand(scene, surface, samples, [&](const fur::FurStrandView& strand) {
      const glm::vec3 colour = texture ? texture->colourAt(strand.uv) : material.diffuse;
      const auto base = static_cast<std::uint32_t>(points.size());
      const std::size_t n = strand.points.size();
      for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 p = strand.points[i];
        glm::vec3 tangent =
            strand.points[std::min(i + 1, n - 1)] - strand.points[i == 0 ? 0 : i - 1];
        tangent = glm::length(tangent) > 0 ? glm::normalize(tangent) : strand.normal;
        const glm::vec3 eye = perspective ? glm::normalize(camera.eye - p) : towardsEye;
        glm::vec3 across = glm::cross(tangent, eye);
        if (glm::length(across) < 1e-12f) across = glm::cross(tangent, camera.up);
        across = strand.radius * glm::normalize(across);
        const float h = strand.reach * static_cast<float>(i) / static_cast<float>(n - 1);
        const Shade shade = PovWriter::shadeOf(
            fur::furShade(colour, tangent, light, eye, a.specular, a.phong, a.shadow, h), 1);
        points.push_back(p - across);
        points.push_back(p + across);
        shades.push_back(shade);
        shades.push_back(shade);
      }
      for (std::uint32_t i = 0; i + 1 < n; ++i) {
        const std::uint32_t k = base + 2 * i;
        faces.insert(faces.end(), {k, k + 1, k + 3, k, k + 3, k + 2});
      }
      ++strands;
    });
    if (faces.empty()) continue;
    pov.writeShadedMesh(
        "fur surface " + std::to_string(index + 1) + ": " + std::to_string(strands) + " strands",
        points, shades, faces, kEmittedFinish);
    pov.count("fur strands", strands);
  }
}

}  // namespace hirsute
