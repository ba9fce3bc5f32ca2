#include "hirsute/interpreter/scene.h"

#include <algorithm>
#include <cmath>

namespace hirsute {

TriangleMesh& Scene::meshFor(int material, int texture) {
  for (const auto& [m, t, index] : meshIndex_) {
    if (m == material && t == texture) return meshes[static_cast<std::size_t>(index)];
  }
  meshes.emplace_back();
  meshes.back().material = material;
  meshes.back().texture = texture;
  meshIndex_.push_back({material, texture, static_cast<int>(meshes.size() - 1)});
  return meshes.back();
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const TriangleMesh& mesh : meshes) {
    for (const glm::vec3& p : mesh.positions) b.add(p);
  }
  for (const LineSegment& l : lines) {
    b.add(l.from);
    b.add(l.to);
  }
  for (const Sphere& s : spheres) {
    b.add(s.center - glm::vec3(s.radius));
    b.add(s.center + glm::vec3(s.radius));
  }
  for (const Disc& d : discs) {
    b.add(d.center - glm::vec3(d.radius));
    b.add(d.center + glm::vec3(d.radius));
  }
  for (const Label& l : labels) b.add(l.position);
  organs_.addBounds(b);
  return b;
}

std::size_t Scene::triangleCount() const {
  std::size_t n = 0;
  for (const TriangleMesh& mesh : meshes) n += mesh.triangleCount();
  return n;
}

std::size_t Scene::vertexCount() const {
  std::size_t n = 2 * lines.size() + spheres.size() + discs.size() + labels.size();
  for (const TriangleMesh& mesh : meshes) n += mesh.positions.size();
  return n;
}

void Scene::markThin(const TriangleMesh& mesh, std::uint32_t firstIndex) {
  const int index = static_cast<int>(&mesh - meshes.data());
  const auto end = static_cast<std::uint32_t>(mesh.indices.size());
  if (index < 0 || static_cast<std::size_t>(index) >= meshes.size() || end <= firstIndex) return;
  if (!thinSurfaces.empty()) {
    IndexRange& last = thinSurfaces.back();
    if (last.mesh == index && last.firstIndex + last.indexCount == firstIndex) {
      last.indexCount = end - last.firstIndex;
      return;
    }
  }
  thinSurfaces.push_back(IndexRange{index, firstIndex, end - firstIndex});
}

void Scene::clear() {
  meshes.clear();
  lines.clear();
  spheres.clear();
  discs.clear();
  labels.clear();
  cylinderSegments.clear();
  organSurfaces.clear();
  thinSurfaces.clear();
  organs_.clear();
  meshIndex_.clear();
}

glm::vec3 Texture::colourAt(const glm::vec2& uv) const {
  const std::size_t texels = static_cast<std::size_t>(std::max(0, width)) *
                             static_cast<std::size_t>(std::max(0, height));
  if (texels == 0 || rgba.size() < 4 * texels) return glm::vec3(0.0f);
  auto wrap = [](float t, int n) {
    if (!(std::abs(t) < 1e6f)) t = 0;  // no int holds the texel of a coordinate past this
    const int i = static_cast<int>(std::floor(t * static_cast<float>(n)));
    return ((i % n) + n) % n;
  };
  const int x = wrap(uv.x, width);
  const int y = height - 1 - wrap(uv.y, height);
  const std::uint8_t* p =
      &rgba[4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(x))];
  return glm::vec3(p[0], p[1], p[2]) / 255.0f;
}

}  // namespace hirsute
