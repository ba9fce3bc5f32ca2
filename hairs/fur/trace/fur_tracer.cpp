#include "hirsute/hairs/fur/fur_tracer.h"

#include <cstdint>
#include <vector>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_strands.h"

namespace hirsute {
namespace {

class FurTracer : public trace::OrganTracer {
 public:
  void addTo(const Scene& scene, const Camera& /*camera*/, trace::TraceScene& out) const override {
    const FurPart& part = scene.organ<FurPart>();
    // Each surface's strands shade as the `fibre:` line for its colour says (one material a
    // colour).
    std::vector<std::pair<int, int>> materialOf;
    auto materialFor = [&](int colour) {
      for (const auto& [c, m] : materialOf) {
        if (c == colour) return m;
      }
      materialOf.emplace_back(colour, out.hairOfColour(glm::vec3(1.0f), FibreOrgan::Fur, colour));
      return materialOf.back().second;
    };
    fur::StrandBudget budget(part);
    for (std::size_t index = 0; index < part.surfaces.size(); ++index) {
      const FurSurface& surface = part.surfaces[index];
      if (surface.attributes < 0) continue;
      const FurAttributes& a = part.attributes[static_cast<std::size_t>(surface.attributes)];
      const glm::vec3 base =
          static_cast<std::size_t>(surface.material) < scene.materials.size()
              ? scene.materials[static_cast<std::size_t>(surface.material)].diffuse
              : Material{}.diffuse;
      const Texture* texture = fur::colourTexture(scene, a);
      const std::size_t strands = fur::countStrands(scene, surface);
      if (strands == 0) continue;
      // As the exports sample a strand: enough points to follow its curl, within --max-vertices.
      const auto points = static_cast<std::size_t>(budget.charge(scene, surface, index));
      const trace::CurveBuffers b =
          out.addCurves(trace::CurveShape::Round, strands * points, strands * (points - 1),
                        materialFor(surface.material), true);
      std::uint32_t vertex = 0;
      std::size_t segment = 0, made = 0;
      fur::forEachStrand(scene, surface, static_cast<int>(points),
                         [&](const fur::FurStrandView& strand) {
        if (made++ >= strands || strand.points.size() != points) return;
        const glm::vec3 colour = trace::linearColour(
            texture ? texture->colourAt(strand.uv) : base);
        for (std::size_t i = 0; i < strand.points.size(); ++i) {
          if (i + 1 < strand.points.size()) b.segments[segment++] = vertex;
          b.tint[vertex] = glm::vec4(colour, 1);
          b.vertices[vertex++] = glm::vec4(strand.points[i], strand.radius);
        }
      });
      // Strands the count promised and the walk did not make stay as points at the origin
      // of no width, which no ray hits.
      for (; vertex < strands * points; ++vertex) {
        b.vertices[vertex] = glm::vec4(0.0f);
        b.tint[vertex] = glm::vec4(0.0f);
      }
      for (; segment < strands * (points - 1); ++segment) b.segments[segment] = 0;
    }
  }
};

}  // namespace

const trace::OrganTracer& furTracer() {
  static const FurTracer tracer;
  return tracer;
}

}  // namespace hirsute
