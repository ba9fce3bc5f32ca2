#include "hirsute/viewer/export/scene_writer.h"

#include <algorithm>
#include <cmath>

namespace hirsute {

bool drawnTextured(const Scene& scene, const TriangleMesh& mesh) {
  if (mesh.texture < 0 || static_cast<std::size_t>(mesh.texture) >= scene.textures.size())
    return false;
  const Texture& texture = scene.textures[static_cast<std::size_t>(mesh.texture)];
  return texture.width > 0 && texture.height > 0 &&
         texture.rgba.size() == static_cast<std::size_t>(texture.width) *
                                    static_cast<std::size_t>(texture.height) * 4 &&
         mesh.texcoords.size() == mesh.positions.size();
}

glm::vec3 VertexNormals::operator[](std::size_t vertex) {
  glm::vec3 n = mesh_.normals[vertex];
  float length = glm::length(n);
  if (length > 1e-20f && std::isfinite(length)) return n / length;
  if (faceSums_.empty()) {
    faceSums_.assign(mesh_.positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < mesh_.indices.size(); t += 3) {
      std::uint32_t a = mesh_.indices[t], b = mesh_.indices[t + 1], c = mesh_.indices[t + 2];
      glm::vec3 face = glm::cross(mesh_.positions[b] - mesh_.positions[a],
                                  mesh_.positions[c] - mesh_.positions[a]);
      faceSums_[a] += face;
      faceSums_[b] += face;
      faceSums_[c] += face;
    }
  }
  n = faceSums_[vertex];
  length = glm::length(n);
  if (length > 1e-30f && std::isfinite(length)) return n / length;
  return {0, 0, 1};  // a vertex on no face, or only on degenerate ones: its normal is never seen
}

int positionDecimals(const Bounds& bounds) {
  float size = bounds.diagonal();
  if (!(size > 0)) {
    // A single point (or nothing): resolve it relative to its distance from the origin.
    size = bounds.empty() ? 1.0f : std::max(glm::length(bounds.min), 1e-6f);
  }
  double resolution = static_cast<double>(size) * 1e-6;
  if (!std::isfinite(resolution)) return 0;
  int decimals = static_cast<int>(std::ceil(-std::log10(resolution)));
  return std::clamp(decimals, 0, 12);
}

}  // namespace hirsute
