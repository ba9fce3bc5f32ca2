#include "hirsute/hairs/plant/plant_hair_tracer.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace hirsute {
namespace {

// The distance of `p` from the segment from `a` to `b`.
float distanceToSegment(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 along = b - a;
  const float length2 = glm::dot(along, along);
  const float t = length2 > 0 ? std::clamp(glm::dot(p - a, along) / length2, 0.0f, 1.0f) : 0.0f;
  return glm::distance(p, a + t * along);
}

// A filled template's polygons (a scale's blade), placed with each of its hairs: flat,
// two-sided triangles of the template's colour as a surface, which pass light as a leaf of that
// colour does (docs/trace.md, "Materials"), where its outline is traced as hair.
void addFilledPolygons(const Scene& scene, const HairPart& part, std::size_t t,
                       trace::TraceScene& out) {
  const HairTemplate& hair = part.templates[t];
  if (hair.triangles.empty()) return;
  std::size_t count = 0;
  for (const Hair& h : part.hairs) {
    if (h.templateIndex == t && h.radius > 0) ++count;
  }
  if (count == 0) return;
  const std::size_t corners = hair.triangles.size() / 3 * 3;
  const trace::TriangleBuffers b =
      out.addTriangles(count * corners, count * corners / 3,
                       out.surfaceMaterial(scene, hair.material, true, false), false, false);
  if (!b.positions) return;
  std::size_t vertex = 0;
  for (const Hair& h : part.hairs) {
    if (h.templateIndex != t || !(h.radius > 0)) continue;
    const glm::quat rotation = h.rotation();
    for (std::size_t k = 0; k < corners; ++k) {
      b.positions[vertex] = h.root + h.length * (rotation * hair.triangles[k]);
      b.indices[vertex] = static_cast<std::uint32_t>(vertex);
      ++vertex;
    }
  }
}

class PlantHairTracer : public trace::OrganTracer {
 public:
  void addTo(const Scene& scene, const Camera& camera, trace::TraceScene& out) const override {
    const HairPart& part = scene.organ<HairPart>();
    if (part.hairs.empty()) return;
    // Each hair's form, from its size in the picture.
    std::vector<HairForms> forms;
    for (const HairTemplate& hair : part.templates) forms.push_back(hairFormsOf(hair));
    std::vector<std::uint8_t> formOf(part.hairs.size(), 0);
    for (std::size_t i = 0; i < part.hairs.size(); ++i) {
      const Hair& h = part.hairs[i];
      if (h.templateIndex >= forms.size()) continue;
      const float tolerance = kHairStrayPixels * camera.pixelSizeAt(h.root);
      formOf[i] = static_cast<std::uint8_t>(hairFormFor(forms[h.templateIndex], h.length, tolerance));
    }
    // Fuhrer et al. 2004, Sec. 3.2: offline, the vertices are joined by cylinders of constant
    // radius. The curves are written straight into Embree's buffers, a template at a time.
    for (std::size_t t = 0; t < part.templates.size(); ++t) {
      const HairTemplate& hair = part.templates[t];
      addFilledPolygons(scene, part, t, out);
      // Each form's kept vertices of each polyline.
      std::vector<std::vector<std::vector<std::size_t>>> kept(forms[t].stray.size());
      for (std::size_t f = 0; f < kept.size(); ++f) {
        for (const auto& polyline : hair.polylines) {
          kept[f].push_back(polyline.size() < 2 ? std::vector<std::size_t>{}
                                                : keptVertices(polyline.size(), f));
        }
      }
      std::size_t vertices = 0, segments = 0;
      for (std::size_t i = 0; i < part.hairs.size(); ++i) {
        const Hair& h = part.hairs[i];
        if (h.templateIndex != t || !(h.radius > 0)) continue;
        for (const auto& run : kept[formOf[i]]) {
          if (run.size() < 2) continue;
          vertices += run.size();
          segments += run.size() - 1;
        }
      }
      if (segments == 0) continue;
      // The template's number (from 1) chooses its `fibre:` line.
      const int material = out.hairMaterial(scene, hair.material, static_cast<int>(t) + 1);
      const trace::CurveBuffers b =
          out.addCurves(trace::CurveShape::Round, vertices, segments, material, false);
      std::uint32_t vertex = 0;
      std::size_t segment = 0;
      for (std::size_t i = 0; i < part.hairs.size(); ++i) {
        const Hair& h = part.hairs[i];
        if (h.templateIndex != t || !(h.radius > 0)) continue;
        const glm::quat rotation = h.rotation();
        const auto& runs = kept[formOf[i]];
        for (std::size_t p = 0; p < hair.polylines.size(); ++p) {
          const std::vector<std::size_t>& run = runs[p];
          if (run.size() < 2) continue;
          for (std::size_t k = 0; k < run.size(); ++k) {
            if (k + 1 < run.size()) b.segments[segment++] = vertex;
            b.vertices[vertex++] =
                glm::vec4(h.root + h.length * (rotation * hair.polylines[p][run[k]]), h.radius);
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

std::vector<std::size_t> keptVertices(std::size_t count, std::size_t form) {
  std::vector<std::size_t> kept;
  if (count == 0) return kept;
  const std::size_t stride = std::size_t{1} << std::min<std::size_t>(form, 30);
  for (std::size_t i = 0; i < count; i += stride) kept.push_back(i);
  if (kept.back() != count - 1) kept.push_back(count - 1);
  return kept;
}

HairForms hairFormsOf(const HairTemplate& hair) {
  HairForms forms;
  std::size_t longest = 0;  // segments of the longest polyline
  for (const auto& polyline : hair.polylines) {
    if (polyline.size() > 1) longest = std::max(longest, polyline.size() - 1);
  }
  forms.stray.push_back(0.0f);
  for (std::size_t form = 1; longest > 0 && (std::size_t{1} << (form - 1)) < longest; ++form) {
    float stray = 0;
    for (const auto& polyline : hair.polylines) {
      if (polyline.size() < 2) continue;
      const std::vector<std::size_t> kept = keptVertices(polyline.size(), form);
      for (std::size_t k = 0; k + 1 < kept.size(); ++k) {
        for (std::size_t i = kept[k] + 1; i < kept[k + 1]; ++i) {
          stray = std::max(stray, distanceToSegment(polyline[i], polyline[kept[k]],
                                                    polyline[kept[k + 1]]));
        }
      }
    }
    forms.stray.push_back(stray);
  }
  return forms;
}

std::size_t hairFormFor(const HairForms& forms, float length, float tolerance) {
  std::size_t form = 0;
  for (std::size_t f = 1; f < forms.stray.size(); ++f) {
    if (forms.stray[f] * length <= tolerance) form = f;
  }
  return form;
}

}  // namespace hirsute
