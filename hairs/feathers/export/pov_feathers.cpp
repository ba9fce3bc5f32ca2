// Feathers in the POV-Ray scene (DESIGN.md, "Feathers"; docs/export.md, "Feathers"): built at the
// level of detail of their size in the scene's image (--width, --height), as the GL renderer
// builds them (feather_buffers.h), one level finer, the shafts one opaque mesh2, the barbs another
// whose vertices carry their colour and a transparency that fades to the barb tips (and, on
// strips, to their edges), interpolated across each triangle as POV-Ray does for a face with three
// texture indices. Polyline barbs become thin ribbons facing the feather's front, since POV-Ray
// has no lines. A textured type's barbs take its texture's colour at each vertex, times the
// type's colour, as GL's barb shader does (at a still's detail the barbs sample it densely).
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "hirsute/hairs/feathers/feather_writer.h"
#include "hirsute/interpreter/feather_part.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/view/feather_buffers.h"

namespace hirsute {
namespace {

constexpr float kRibbonShare = 0.3f;  // a polyline barb's ribbon: this share of the spacing
constexpr char kLitFinish[] = "ambient 0.2 diffuse 0.7";

}  // namespace

void FeatherWriter::writePov(const Scene& scene, PovWriter& pov) const {
  using Shade = PovWriter::Shade;
  if (scene.organ<FeatherPart>().feathers.empty()) return;
  // A still is looked at closer than a preview: one level finer than the camera asks for.
  std::vector<std::uint8_t> levels = featherDetailLevels(scene, pov.camera());
  for (std::uint8_t& level : levels) level = static_cast<std::uint8_t>(std::min(level + 1, 7));
  FeatherBuffers b = buildFeatherBuffers(scene, levels);

  // Polyline barbs as ribbons: each segment (i, j) a quad across the barb in the vane plane.
  std::vector<std::uint32_t> triangles;
  std::vector<glm::vec3> positions = b.barbPositions;
  std::vector<glm::vec4> colours = texturedBarbColours(scene, b);
  for (const FeatherBuffers::Part& part : b.parts) {
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      const auto begin = b.vaneIndices.begin() + vane.first;
      if (vane.primitiveSize == 3) {
        triangles.insert(triangles.end(), begin, begin + vane.count);
        continue;
      }
      for (std::uint32_t k = 0; k + 1 < vane.count; k += 2) {
        const std::uint32_t i = begin[k], j = begin[k + 1];
        const glm::vec3 along = positions[j] - positions[i];
        glm::vec3 across = glm::cross(along, glm::cross(part.left, along));
        const float length = glm::length(across);
        if (!(length > 0)) continue;
        across *= kRibbonShare * 0.5f * glm::length(along) / length;
        const auto base = static_cast<std::uint32_t>(positions.size());
        for (std::uint32_t v : {i, j}) {
          positions.push_back(positions[v] + across);
          positions.push_back(positions[v] - across);
          colours.push_back(colours[v]);
          colours.push_back(colours[v]);
        }
        triangles.insert(triangles.end(), {base, base + 1, base + 2, base + 2, base + 1, base + 3});
      }
    }
  }

  if (!b.shaftIndices.empty()) {
    std::vector<Shade> shades;
    shades.reserve(b.shaftColors.size());
    for (const glm::vec3& c : b.shaftColors) shades.push_back(PovWriter::shadeOf(c, 1));
    pov.writeShadedMesh("feather shafts", b.shaftPositions, shades, b.shaftIndices, kLitFinish);
  }
  if (!triangles.empty()) {
    std::vector<Shade> shades;
    shades.reserve(colours.size());
    for (const glm::vec4& c : colours) shades.push_back(PovWriter::shadeOf(glm::vec3(c), c.a));
    pov.writeShadedMesh("feather barbs", positions, shades, triangles, kLitFinish);
  }
  pov.count("feathers", scene.organ<FeatherPart>().feathers.size());
}

}  // namespace hirsute
