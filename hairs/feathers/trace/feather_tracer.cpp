#include "hirsute/hairs/feathers/feather_tracer.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/viewer/view/feather_buffers.h"

namespace hirsute {
namespace {

constexpr float kBarbWidthShare = 0.3f;  // a polyline barb's width: this share of its segments

class FeatherTracer : public trace::OrganTracer {
 public:
  void addTo(const Scene& scene, const Camera& camera, trace::TraceScene& out) const override {
    if (scene.organ<FeatherPart>().feathers.empty()) return;
    std::vector<std::uint8_t> levels = featherDetailLevels(scene, camera);
    for (std::uint8_t& level : levels) level = static_cast<std::uint8_t>(std::min(level + 1, 7));
    const FeatherBuffers b = buildFeatherBuffers(scene, levels);

    const std::size_t shaftVertices = b.shaftPositions.size();
    const trace::TriangleBuffers shafts =
        out.addTriangles(shaftVertices, b.shaftIndices.size() / 3,
                         out.surfaceOfColour(glm::vec3(1.0f)), true, true);
    if (shafts.positions) {
      std::copy(b.shaftPositions.begin(), b.shaftPositions.end(), shafts.positions);
      std::copy(b.shaftNormals.begin(), b.shaftNormals.end(), shafts.normals);
      std::copy(b.shaftIndices.begin(), b.shaftIndices.end(), shafts.indices);
      for (std::size_t i = 0; i < shaftVertices; ++i)
        shafts.tint[i] = glm::vec4(trace::linearColour(b.shaftColors[i]), 1);
    }

    std::vector<std::uint32_t> segments, triangles;
    for (const FeatherBuffers::Part& part : b.parts) {
      for (const FeatherBuffers::Vane& vane : part.vanes) {
        const auto begin = b.vaneIndices.begin() + vane.first;
        if (vane.primitiveSize == 3) {
          triangles.insert(triangles.end(), begin, begin + vane.count);
        } else {
          for (std::uint32_t k = 0; k + 1 < vane.count; k += 2) segments.push_back(begin[k]);
        }
      }
    }
    // A vertex's tint: its colour times its texture's there (as GL's barb shader multiplies
    // them), and its transparency.
    const std::size_t barbVertices = b.barbPositions.size();
    const std::vector<glm::vec4> colours = texturedBarbColours(scene, b);
    auto tintOf = [&](std::size_t i) {
      return glm::vec4(trace::linearColour(glm::vec3(colours[i])), colours[i].a);
    };
    if (!segments.empty()) {
      const trace::CurveBuffers curves =
          out.addCurves(trace::CurveShape::Flat, barbVertices, segments.size(),
                        out.hairOfColour(glm::vec3(1.0f), FibreOrgan::Feathers), true);
      // Each vertex as wide as a share of the longer segment beside it, and at least a pixel,
      // as GL draws a barb.
      std::vector<float> width(barbVertices, 0.0f);
      const float pixel = camera.pixelSize();
      for (std::uint32_t s : segments) {
        const float length = glm::distance(b.barbPositions[s], b.barbPositions[s + 1]);
        width[s] = std::max(width[s], length);
        width[s + 1] = std::max(width[s + 1], length);
      }
      for (std::size_t i = 0; i < barbVertices; ++i) {
        curves.vertices[i] = glm::vec4(b.barbPositions[i],
                                       0.5f * std::max(kBarbWidthShare * width[i], pixel));
        curves.tint[i] = tintOf(i);
      }
      std::copy(segments.begin(), segments.end(), curves.segments);
    }
    if (!triangles.empty()) {
      const trace::TriangleBuffers strips =
          out.addTriangles(barbVertices, triangles.size() / 3,
                           out.surfaceOfColour(glm::vec3(1.0f)), false, true);
      std::copy(b.barbPositions.begin(), b.barbPositions.end(), strips.positions);
      std::copy(triangles.begin(), triangles.end(), strips.indices);
      for (std::size_t i = 0; i < barbVertices; ++i) strips.tint[i] = tintOf(i);
    }
  }
};

}  // namespace

const trace::OrganTracer& featherTracer() {
  static const FeatherTracer tracer;
  return tracer;
}

}  // namespace hirsute
