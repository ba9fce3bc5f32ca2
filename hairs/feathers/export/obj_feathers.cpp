// Feathers in the OBJ file (docs/design.md, "Feathers"): built at a still's level of detail
// (feather_buffers.h), the shafts as triangles with their normals, the barbs as polylines of `l`
// segments (`drawing: lines`) or as the triangles of their two strips (`drawing: strips`), under
// `o feathers`. OBJ has no per-vertex transparency: the barbs' fading is left out. The shafts take
// the scene's material 0; each vane's barbs a material of its type's colour (the .fea file's) and
// texture (map_Kd, with the strips' texture coordinates of the type's mapping; OBJ readers give
// `l` edges none), as GL multiplies them. A blended type's cross-fade of textures is written as
// vertex colours (`v x y z r g b`) under a white material.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_writer.h"
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
  obj.useMaterial(0, -1);  // the shafts
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
  // Barbs: vertices and texture coordinates numbered together.
  const std::uint64_t barbFirst = obj.stats().vertices + 1;
  const std::uint64_t texcoordFirst = obj.stats().texcoords + 1;
  // A blended type's cross-fade of textures is in its barbs' colours: those vertices carry them.
  std::vector<bool> faded(b.barbPositions.size(), false);
  for (const FeatherBuffers::Part& part : b.parts) {
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      if (!vane.faded) continue;
      for (std::uint32_t k = 0; k < vane.count; ++k) {
        const std::uint32_t vertex = b.vaneIndices[vane.first + k];
        if (vertex < faded.size()) faded[vertex] = true;
      }
    }
  }
  for (std::size_t i = 0; i < b.barbPositions.size(); ++i) {
    if (faded[i] && i < b.barbColors.size()) {
      obj.vertex(b.barbPositions[i], glm::vec3(b.barbColors[i]));
    } else {
      obj.vertex(b.barbPositions[i]);
    }
  }
  const bool textured = b.barbTexcoords.size() == b.barbPositions.size();
  if (textured) {
    for (const glm::vec2& t : b.barbTexcoords) obj.texcoord(t);
  }
  for (const FeatherBuffers::Part& part : b.parts) {
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      if (vane.count == 0) continue;
      // The vane's material: its type's colour and texture; white under a cross-fade's vertex
      // colours.
      const std::uint32_t firstVertex = b.vaneIndices[vane.first];
      const glm::vec3 colour = !vane.faded && firstVertex < b.barbColors.size()
                                   ? glm::vec3(b.barbColors[firstVertex])
                                   : glm::vec3(1.0f);
      const int texture = textured && vane.texture >= 0 &&
                                  static_cast<std::size_t>(vane.texture) < scene.textures.size()
                              ? vane.texture
                              : -1;
      const auto byte = [](float c) {
        return static_cast<int>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255));
      };
      obj.useOrganMaterial(
          fmt::format("feather_{:02x}{:02x}{:02x}{}", byte(colour.r), byte(colour.g),
                      byte(colour.b), texture >= 0 ? fmt::format("_T{}", texture + 1) : ""),
          colour, texture);
      if (vane.primitiveSize == 3) {
        for (std::size_t t = vane.first;
             t + 3 <= vane.first + vane.count && t + 3 <= b.vaneIndices.size(); t += 3) {
          std::array<std::uint64_t, 3> vertices{}, texcoords{};
          for (std::size_t k = 0; k < 3; ++k) {
            vertices[k] = barbFirst + b.vaneIndices[t + k];
            texcoords[k] = texcoordFirst + b.vaneIndices[t + k];
          }
          obj.face(vertices, std::nullopt, texture >= 0 ? std::optional(texcoords) : std::nullopt);
        }
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
