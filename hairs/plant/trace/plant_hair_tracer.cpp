#include "hirsute/hairs/plant/plant_hair_tracer.h"

#include <cstdint>
#include <vector>

#include "hirsute/interpreter/hair_part.h"

namespace hirsute {
namespace {

class PlantHairTracer : public trace::OrganTracer {
 public:
  void addTo(const Scene& scene, const Camera& /*camera*/, trace::TraceScene& out) const override {
    const HairPart& part = scene.organ<HairPart>();
    if (part.hairs.empty()) return;
    // Fuhrer et al. 2004, Sec. 3.2: offline, the vertices are joined by cylinders of constant
    // radius. The curves are written straight into Embree's buffers, a template at a time.
    for (std::size_t t = 0; t < part.templates.size(); ++t) {
      const HairTemplate& hair = part.templates[t];
      std::size_t perHairVertices = 0, perHairSegments = 0;
      for (const auto& polyline : hair.polylines) {
        if (polyline.size() < 2) continue;
        perHairVertices += polyline.size();
        perHairSegments += polyline.size() - 1;
      }
      std::size_t hairs = 0;
      for (const Hair& h : part.hairs) hairs += h.templateIndex == t && h.radius > 0;
      if (hairs == 0 || perHairSegments == 0) continue;
      const trace::CurveBuffers b =
          out.addCurves(trace::CurveShape::Round, hairs * perHairVertices, hairs * perHairSegments,
                        out.hairMaterial(scene, hair.material), false);
      std::uint32_t vertex = 0;
      std::size_t segment = 0;
      for (const Hair& h : part.hairs) {
        if (h.templateIndex != t || !(h.radius > 0)) continue;
        const glm::quat rotation = h.rotation();
        for (const auto& polyline : hair.polylines) {
          if (polyline.size() < 2) continue;
          for (std::size_t i = 0; i < polyline.size(); ++i) {
            if (i + 1 < polyline.size()) b.segments[segment++] = vertex;
            b.vertices[vertex++] =
                glm::vec4(h.root + h.length * (rotation * polyline[i]), h.radius);
          }
        }
      }
    }
  }
};

}  // namespace

const trace::OrganTracer& plantHairTracer() {
  static const PlantHairTracer tracer;
  return tracer;
}

}  // namespace hirsute
