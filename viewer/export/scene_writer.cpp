#include "hirsute/viewer/export/scene_writer.h"

#include <algorithm>
#include <cmath>

namespace hirsute {

void printScene(const Scene& scene, ScenePrinter& printer, Progress* progress, const char* stage) {
  printer.progress_ = progress;
  printer.done_ = 0;
  if (progress != nullptr) {
    const std::size_t items = scene.triangleCount() + scene.lines.size() + scene.spheres.size() +
                              scene.discs.size() + scene.labels.size() + scene.hairs.size() +
                              scene.feathers.size();
    progress->begin(stage, Progress::Unit::Percent, static_cast<double>(items));
  }
  printer.beginScene(scene);
  for (const TriangleMesh& mesh : scene.meshes) {
    if (mesh.triangleCount() == 0) continue;
    printer.mesh(mesh);
    printer.advance(static_cast<double>(mesh.triangleCount()));
  }
  for (const LineSegment& line : scene.lines) {
    printer.line(line, scene.lineStyle);
    printer.advance();
  }
  for (const Sphere& sphere : scene.spheres) {
    printer.sphere(sphere);
    printer.advance();
  }
  for (const Disc& disc : scene.discs) {
    printer.disc(disc);
    printer.advance();
  }
  for (const Label& label : scene.labels) printer.label(label);
  printer.advance(static_cast<double>(scene.labels.size()));
  if (!scene.hairs.empty()) {
    // The printer advances hair by hair if it can; after it, the count is right either way.
    const double before = printer.done_;
    printer.hairs(scene.hairTemplates, scene.hairs);
    printer.done_ = before;
    printer.advance(static_cast<double>(scene.hairs.size()));
  }
  if (!scene.feathers.empty()) printer.feathers(scene);
  printer.advance(static_cast<double>(scene.feathers.size()));
  if (!scene.furSurfaces.empty()) printer.fur(scene);
  printer.endScene();
  printer.progress_ = nullptr;
}

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
