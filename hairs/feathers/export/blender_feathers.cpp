// Feathers in the scene file for Blender (blender_writer.h): built at a still's level of detail
// (feather_buffers.h), the shafts one mesh with their normals and colours, every barb one curve
// of the group "barbs", coloured at each point as GL draws it (its type's colour times its
// texture, texturedBarbColours). A barb's radius is the half width of the opaque ribbon the
// POV-Ray scene draws for it (pov_feathers.cpp): the barbs' fading carried as width.
#include <cmath>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_writer.h"
#include "hirsute/viewer/export/blender_writer.h"
#include "hirsute/viewer/view/feather_buffers.h"

namespace hirsute {
namespace {
constexpr int kStillLevel = 5;        // a still's detail: featherDetailLevel's 512 pixels
constexpr float kRibbonShare = 0.3f;  // a polyline barb's ribbon: this share of the spacing
}  // namespace

void FeatherWriter::writeBlender(const Scene& scene, BlenderWriter& blender) const {
  const FeatherBuffers b = buildFeatherBuffers(
      scene, std::vector<std::uint8_t>(scene.organ<FeatherPart>().feathers.size(), kStillLevel));
  blender.triangles("feathers", "shafts", blender.sceneMaterial(0, BlenderWriter::Shading::Surface),
                    b.shaftPositions, b.shaftNormals, {}, b.shaftColors, b.shaftIndices);
  const std::vector<glm::vec4> colours = texturedBarbColours(scene, b);
  const std::vector<glm::vec3>& p = b.barbPositions;
  blender.beginCurves(
      "feathers", "barbs",
      blender.organMaterial("barbs", glm::vec3(1.0f), BlenderWriter::Shading::Hair));
  // The barb being gathered: its points' indices and radii; a segment that does not start where
  // the last ended starts a new barb.
  std::vector<std::uint32_t> points;
  std::vector<float> radii;
  auto finish = [&] {
    if (points.size() >= 2) {
      for (std::size_t k = 0; k < points.size(); ++k)
        blender.curvePoint(p[points[k]], radii[k], glm::vec3(colours[points[k]]));
      blender.endCurve();
    }
    points.clear();
    radii.clear();
  };
  auto segment = [&](std::uint32_t i, std::uint32_t j, float ri, float rj) {
    if (i >= p.size() || j >= p.size()) return;
    if (points.empty() || points.back() != i) {
      finish();
      points.push_back(i);
      radii.push_back(ri);
    }
    points.push_back(j);
    radii.push_back(rj);
  };
  for (const FeatherBuffers::Part& part : b.parts) {
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      const auto begin = b.vaneIndices.begin() + vane.first;
      if (vane.primitiveSize == 3) {
        // A strip segment's twelve indices (feather_buffers.cpp): c0 + 1, c0, c1 + 1, c1 + 1,
        // c0, c1, …; c0 + 1 and c0 + 2 are c0's strip edges, the ribbon a/2 of them wide.
        for (std::uint32_t k = 0; k + 12 <= vane.count; k += 12) {
          const std::uint32_t c0 = begin[k + 1], c1 = begin[k + 5];
          if (c1 + 1 >= p.size() || c0 + 1 >= p.size()) continue;
          segment(c0, c1, 0.5f * colours[c0].a * glm::distance(p[c0 + 1], p[c0]),
                  0.5f * colours[c1].a * glm::distance(p[c1 + 1], p[c1]));
        }
        continue;
      }
      for (std::uint32_t k = 0; k + 1 < vane.count; k += 2) {
        const std::uint32_t i = begin[k], j = begin[k + 1];
        if (i >= p.size() || j >= p.size()) continue;
        const float half = 0.5f * kRibbonShare * glm::distance(p[i], p[j]);
        segment(i, j, half * colours[i].a, half * colours[j].a);
      }
      finish();
    }
  }
  finish();
  blender.endCurves();
  blender.count("feathers", scene.organ<FeatherPart>().feathers.size());
}

}  // namespace hirsute
