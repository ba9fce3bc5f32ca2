#include "hirsute/interpreter/scene.h"

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

void Scene::clear() {
  meshes.clear();
  lines.clear();
  spheres.clear();
  discs.clear();
  labels.clear();
  cylinderSegments.clear();
  organSurfaces.clear();
  organs_.clear();
  meshIndex_.clear();
}

}  // namespace hirsute
