// Feathers in the OBJ file (DESIGN.md, "Feathers"): built at a still's level of detail
// (feather_buffers.h), the shafts as triangles with their normals, the barbs as `l` polylines
// (`drawing: lines`) or as the triangles of their two strips (`drawing: strips`), under
// `o feathers`. OBJ has no per-vertex transparency: the barbs' fading is left out, and they take
// the scene's material 0 (the colour of a feather type is in its .fea file).
#include "hirsute/hairs/feathers/feather_writer.h"
#include "hirsute/interpreter/feather_part.h"
#include "hirsute/viewer/export/obj_writer.h"
#include "hirsute/viewer/view/feather_buffers.h"

namespace hirsute {
namespace {
constexpr int kStillLevel = 5;  // a still's detail: featherDetailLevel's 512 pixels
}  // namespace

void FeatherWriter::writeObj(const Scene& scene, ObjWriter& obj) const {
  const FeatherBuffers b = buildFeatherBuffers(
      scene, std::vector<std::uint8_t>(scene.organ<FeatherPart>().feathers.size(), kStillLevel));
  obj.group("feathers");
  obj.useMaterial(0, -1);
  // The faces of `indices` from `from`, `count` of them, numbered from `first`; with normals,
  // numbered alike from `normalFirst`.
  auto faces = [&obj](std::uint64_t first, const std::vector<std::uint32_t>& indices,
                      std::size_t from, std::size_t count, std::uint64_t normalFirst) {
    for (std::size_t t = from; t + 3 <= from + count && t + 3 <= indices.size(); t += 3) {
      std::array<std::uint64_t, 3> vertices{}, normals{};
      for (std::size_t k = 0; k < 3; ++k) {
        vertices[k] = first + indices[t + k];
        normals[k] = normalFirst + indices[t + k];
      }
      obj.face(vertices, normalFirst > 0 ? std::optional(normals) : std::nullopt);
    }
  };
  // Shafts: vertices and normals numbered together.
  const std::uint64_t shaftFirst = obj.stats().vertices + 1;
  const std::uint64_t shaftNormalFirst = obj.stats().normals + 1;
  for (const glm::vec3& p : b.shaftPositions) obj.vertex(p);
  for (const glm::vec3& n : b.shaftNormals) obj.normal(n);
  faces(shaftFirst, b.shaftIndices, 0, b.shaftIndices.size(), shaftNormalFirst);
  // Barbs.
  const std::uint64_t barbFirst = obj.stats().vertices + 1;
  for (const glm::vec3& p : b.barbPositions) obj.vertex(p);
  for (const FeatherBuffers::Part& part : b.parts) {
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      if (vane.primitiveSize == 3) {
        faces(barbFirst, b.vaneIndices, vane.first, vane.count, 0);
        continue;
      }
      // Segment pairs (i, i + 1) of one barb join into one polyline.
      for (std::uint32_t k = 0; k + 1 < vane.count; k += 2) {
        const std::uint32_t i = b.vaneIndices[vane.first + k],
                            j = b.vaneIndices[vane.first + k + 1];
        std::vector<std::uint64_t>& polyline = obj.polyline();
        if (polyline.empty() || polyline.back() != barbFirst + i) {
          obj.finishPolyline();
          obj.polyline().push_back(barbFirst + i);
        }
        obj.polyline().push_back(barbFirst + j);
      }
      obj.finishPolyline();
    }
  }
  obj.count("feathers", scene.organ<FeatherPart>().feathers.size());
}

}  // namespace hirsute
