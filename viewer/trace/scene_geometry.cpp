#include "hirsute/viewer/trace/scene_geometry.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "hirsute/viewer/trace/organ_tracer.h"

namespace hirsute::trace {

void addSceneGeometry(const Scene& scene, const Camera& camera, TraceScene& out) {
  const float pixelWorld = camera.pixelSize();
  for (const TriangleMesh& mesh : scene.meshes) {
    const bool normals = mesh.normals.size() == mesh.positions.size();
    const TriangleBuffers b = out.addTriangles(mesh.positions.size(), mesh.triangleCount(),
                                               out.surfaceMaterial(scene, mesh.material),
                                               normals, false);
    if (!b.positions) continue;
    std::copy(mesh.positions.begin(), mesh.positions.end(), b.positions);
    if (normals) std::copy(mesh.normals.begin(), mesh.normals.end(), b.normals);
    std::copy_n(mesh.indices.begin(), 3 * mesh.triangleCount(), b.indices);
  }
  // Lines as tubes: polygon-style widths are world units, pixel-style ones pixels.
  const float unit = scene.lineStyle == LineStyle::Polygon ? 1.0f : pixelWorld;
  std::vector<std::vector<const LineSegment*>> byMaterial;
  for (const LineSegment& line : scene.lines) {
    const auto m = static_cast<std::size_t>(std::max(0, line.material));
    if (m >= byMaterial.size()) byMaterial.resize(m + 1);
    byMaterial[m].push_back(&line);
  }
  for (std::size_t m = 0; m < byMaterial.size(); ++m) {
    const auto& lines = byMaterial[m];
    if (lines.empty()) continue;
    const CurveBuffers b = out.addCurves(CurveShape::Round, 2 * lines.size(), lines.size(),
                                         out.surfaceMaterial(scene, static_cast<int>(m)), false);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      b.vertices[2 * i] = glm::vec4(lines[i]->from, 0.5f * unit * lines[i]->widthFrom);
      b.vertices[2 * i + 1] = glm::vec4(lines[i]->to, 0.5f * unit * lines[i]->widthTo);
      b.segments[i] = static_cast<std::uint32_t>(2 * i);
    }
  }
  std::vector<std::vector<glm::vec4>> spheres;
  for (const Sphere& s : scene.spheres) {
    const auto m = static_cast<std::size_t>(std::max(0, s.material));
    if (m >= spheres.size()) spheres.resize(m + 1);
    spheres[m].emplace_back(s.center, s.radius);
  }
  for (std::size_t m = 0; m < spheres.size(); ++m) {
    out.addSpheres(spheres[m], out.surfaceMaterial(scene, static_cast<int>(m)));
  }
  std::vector<std::vector<glm::vec4>> discs;
  std::vector<std::vector<glm::vec3>> discNormals;
  for (const Disc& d : scene.discs) {
    const auto m = static_cast<std::size_t>(std::max(0, d.material));
    if (m >= discs.size()) {
      discs.resize(m + 1);
      discNormals.resize(m + 1);
    }
    discs[m].emplace_back(d.center, d.radius);
    discNormals[m].push_back(d.normal);
  }
  for (std::size_t m = 0; m < discs.size(); ++m) {
    out.addDiscs(discs[m], discNormals[m], out.surfaceMaterial(scene, static_cast<int>(m)));
  }
  for (const OrganTracer* organ : organTracers()) organ->addTo(scene, camera, out);
}

}  // namespace hirsute::trace
