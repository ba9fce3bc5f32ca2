// Feathers in the OBJ file (DESIGN.md, "Feathers"): built at a still's level of detail
// (feather_buffers.h), the shafts as triangles with their normals, the barbs as `l` polylines
// (`drawing: lines`) or as the triangles of their two strips (`drawing: strips`), under
// `o feathers`. OBJ has no per-vertex transparency: the barbs' fading is left out, and they take
// the scene's material 0 (the colour of a feather type is in its .fea file).
#include "hirsute/viewer/export/obj_writer.h"
#include "hirsute/viewer/view/feather_buffers.h"

namespace hirsute {
namespace {
constexpr int kStillLevel = 5;  // a still's detail: featherDetailLevel's 512 pixels
}  // namespace

void ObjWriter::feathers(const Scene& scene) {
  finishPolyline();
  const FeatherBuffers b =
      buildFeatherBuffers(scene, std::vector<std::uint8_t>(scene.feathers.size(), kStillLevel));
  out_.put("o feathers\n");
  currentGroup_ = "feathers";
  useMaterial(0, -1);
  auto faces = [&](std::uint64_t first, const std::vector<std::uint32_t>& indices, std::size_t from,
                   std::size_t count, bool withNormals) {
    for (std::size_t t = from; t + 3 <= from + count && t + 3 <= indices.size(); t += 3) {
      out_.put('f');
      for (int k = 0; k < 3; ++k) {
        const auto index =
            static_cast<std::int64_t>(first + indices[t + static_cast<std::size_t>(k)]);
        out_.put(' ');
        out_.putInteger(index);
        if (withNormals) {
          out_.put("//");
          out_.putInteger(index - static_cast<std::int64_t>(first) +
                          static_cast<std::int64_t>(shaftNormalBase_));
        }
      }
      out_.put('\n');
      ++stats_.faces;
    }
  };
  // Shafts: vertices and normals numbered together.
  const std::uint64_t shaftFirst = stats_.vertices + 1;
  shaftNormalBase_ = stats_.normals + 1;
  for (const glm::vec3& p : b.shaftPositions) vertex(p);
  for (const glm::vec3& n : b.shaftNormals) normal(n);
  faces(shaftFirst, b.shaftIndices, 0, b.shaftIndices.size(), true);
  // Barbs.
  const std::uint64_t barbFirst = stats_.vertices + 1;
  for (const glm::vec3& p : b.barbPositions) vertex(p);
  for (const FeatherBuffers::Part& part : b.parts) {
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      if (vane.primitiveSize == 3) {
        faces(barbFirst, b.vaneIndices, vane.first, vane.count, false);
        continue;
      }
      // Segment pairs (i, i + 1) of one barb join into one polyline.
      for (std::uint32_t k = 0; k + 1 < vane.count; k += 2) {
        const std::uint32_t i = b.vaneIndices[vane.first + k],
                            j = b.vaneIndices[vane.first + k + 1];
        if (polyline_.empty() || polyline_.back() != barbFirst + i) {
          finishPolyline();
          polyline_.push_back(barbFirst + i);
        }
        polyline_.push_back(barbFirst + j);
      }
      finishPolyline();
    }
  }
  stats_.feathers += scene.feathers.size();
}

}  // namespace hirsute
