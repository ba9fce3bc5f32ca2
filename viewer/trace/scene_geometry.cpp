#include "hirsute/viewer/trace/scene_geometry.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "hirsute/viewer/trace/organ_tracer.h"

namespace hirsute::trace {
namespace {

// The surfaces' own coordinates at the vertices of mesh `m` (trace_scene.h, SurfacePoint): on
// a generalized cylinder u runs around its contour (edge to edge of an open one) and v along
// the tube from @Gs (0) to @Ge (1); on a `~` patch they are the patch's, on a polygon its plane
// coordinates over their extent. Vertices of no such surface get none. `aspect`: the median
// width over length of the surfaces.
std::vector<SurfacePoint> surfaceCoordinates(const Scene& scene, int m, float& aspect) {
  const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(m)];
  std::vector<SurfacePoint> points(mesh.positions.size(), SurfacePoint(0, 0, -1, 0));
  std::vector<float> aspects;
  // Each tube's extent along its axis and its widest girth.
  struct Tube {
    float start = 1e30f, end = -1e30f, girth = 0;
  };
  std::vector<Tube> tubes;
  for (const CylinderSegment& segment : scene.cylinderSegments) {
    if (segment.mesh != m || segment.rings.empty() || segment.tube < 0) continue;
    const auto t = static_cast<std::size_t>(segment.tube);
    if (t >= tubes.size()) tubes.resize(t + 1);
    for (const CylinderRing& ring : segment.rings) {
      tubes[t].start = std::min(tubes[t].start, ring.axisDistance);
      tubes[t].end = std::max(tubes[t].end, ring.axisDistance);
    }
    tubes[t].girth = std::max({tubes[t].girth, segment.girthStart, segment.girthEnd});
  }
  for (const Tube& tube : tubes) {
    if (tube.end > tube.start) aspects.push_back(tube.girth / (tube.end - tube.start));
  }
  for (const CylinderSegment& segment : scene.cylinderSegments) {
    if (segment.mesh != m || segment.sides <= 0 || segment.tube < 0) continue;
    const auto columns = static_cast<std::size_t>(segment.sides) + 1;
    if (segment.vertexCount != segment.rings.size() * columns ||
        segment.firstVertex + segment.vertexCount > points.size()) {
      continue;  // not drawn as a tube of rings
    }
    const Tube& tube = tubes[static_cast<std::size_t>(segment.tube)];
    const float length = std::max(tube.end - tube.start, 1e-9f);
    // Neighbouring tubes take the vein maps' variants in turn.
    const auto variant = static_cast<float>(segment.tube % kVeinVariants);
    for (std::size_t k = 0; k < segment.rings.size(); ++k) {
      const float v = (segment.rings[k].axisDistance - tube.start) / length;
      for (std::size_t j = 0; j < columns; ++j) {
        points[segment.firstVertex + k * columns + j] = SurfacePoint(
            static_cast<float>(j) / static_cast<float>(segment.sides), v, variant, length);
      }
    }
  }
  int surfaces = 0;
  for (const OrganSurface& surface : scene.organSurfaces) {
    if (surface.mesh != m || surface.uv.empty() ||
        surface.firstVertex + surface.uv.size() > points.size() ||
        surface.firstIndex + surface.indexCount > mesh.indices.size()) {
      continue;
    }
    glm::vec2 low(1e30f), high(-1e30f);
    for (const glm::vec2& uv : surface.uv) {
      low = glm::min(low, uv);
      high = glm::max(high, uv);
    }
    if (surface.kind == OrganSurfaceKind::BicubicPatch) {
      low = glm::vec2(0.0f);
      high = glm::vec2(1.0f);
    }
    const glm::vec2 extent = glm::max(high - low, glm::vec2(1e-9f));
    // Its length in world units: a polygon's (u, v) are world distances already; a patch's
    // scale is the mean of world over parameter length along its edges.
    float length = extent.y;
    if (surface.kind != OrganSurfaceKind::Polygon) {
      float sum = 0;
      int edges = 0;
      for (std::uint32_t i = 0; i + 1 < surface.indexCount; ++i) {
        const std::uint32_t a = mesh.indices[surface.firstIndex + i];
        const std::uint32_t b = mesh.indices[surface.firstIndex + i + 1];
        const std::size_t n = surface.uv.size();
        if (a < surface.firstVertex || b < surface.firstVertex || a - surface.firstVertex >= n ||
            b - surface.firstVertex >= n) {
          continue;
        }
        const float along = glm::distance(surface.uv[a - surface.firstVertex],
                                          surface.uv[b - surface.firstVertex]);
        if (along < 1e-6f) continue;
        sum += glm::distance(mesh.positions[a], mesh.positions[b]) / along;
        ++edges;
      }
      length = edges > 0 ? sum / static_cast<float>(edges) : 1.0f;
    }
    const auto variant = static_cast<float>(surfaces++ % kVeinVariants);
    for (std::size_t k = 0; k < surface.uv.size(); ++k) {
      const glm::vec2 uv = (surface.uv[k] - low) / extent;
      points[surface.firstVertex + k] = SurfacePoint(uv.x, uv.y, variant, length);
    }
    if (surface.kind == OrganSurfaceKind::Polygon) aspects.push_back(extent.x / extent.y);
  }
  if (aspects.empty()) {
    aspect = 0.4f;
  } else {
    std::nth_element(aspects.begin(), aspects.begin() + static_cast<std::ptrdiff_t>(aspects.size() / 2),
                     aspects.end());
    aspect = aspects[aspects.size() / 2];
  }
  return points;
}

// Which triangles of each mesh are thin surfaces (Scene::thinSurfaces, and open generalized
// cylinders): one flag a triangle, or none for a mesh without any.
std::vector<std::vector<bool>> thinTriangles(const Scene& scene) {
  std::vector<std::vector<bool>> thin(scene.meshes.size());
  auto mark = [&](int m, std::uint32_t firstIndex, std::uint32_t indexCount) {
    if (m < 0 || static_cast<std::size_t>(m) >= scene.meshes.size()) return;
    const std::size_t triangles = scene.meshes[static_cast<std::size_t>(m)].triangleCount();
    std::vector<bool>& flags = thin[static_cast<std::size_t>(m)];
    if (flags.empty()) flags.assign(triangles, false);
    const std::size_t end =
        std::min<std::size_t>((firstIndex + std::size_t{indexCount}) / 3, triangles);
    for (std::size_t t = firstIndex / 3; t < end; ++t) flags[t] = true;
  };
  for (const IndexRange& r : scene.thinSurfaces) mark(r.mesh, r.firstIndex, r.indexCount);
  for (const CylinderSegment& segment : scene.cylinderSegments) {
    if (!segment.closed) mark(segment.mesh, segment.firstIndex, segment.indexCount);
  }
  return thin;
}

}  // namespace

void addSceneGeometry(const Scene& scene, const Camera& camera, TraceScene& out) {
  const float pixelWorld = camera.pixelSize();
  const std::vector<std::vector<bool>> thin = thinTriangles(scene);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const TriangleMesh& mesh = scene.meshes[m];
    const bool normals = mesh.normals.size() == mesh.positions.size();
    std::vector<SurfacePoint> surface;
    float aspect = 0;
    const bool veined = out.veinsOf(mesh.material) && mesh.triangleCount() > 0;
    if (veined) surface = surfaceCoordinates(scene, static_cast<int>(m), aspect);
    const int texture = mesh.texcoords.size() == mesh.positions.size()
                            ? out.addTexture(scene, mesh.texture)
                            : -1;
    // A mesh's solid triangles and its thin ones (leaves: they pass light) go in as two shapes
    // of their own materials, each with the mesh's vertices.
    const std::vector<bool>& flags = thin[m];
    const std::size_t thinCount =
        static_cast<std::size_t>(std::count(flags.begin(), flags.end(), true));
    for (const bool sheet : {false, true}) {
      const std::size_t count = sheet ? thinCount : mesh.triangleCount() - thinCount;
      if (count == 0) continue;
      const int material = veined ? out.veinedMaterial(scene, mesh.material, aspect, sheet)
                                  : out.surfaceMaterial(scene, mesh.material, sheet);
      const TriangleBuffers b = out.addTriangles(mesh.positions.size(), count, material, normals,
                                                 false, !surface.empty(), texture);
      if (!b.positions) continue;
      std::copy(mesh.positions.begin(), mesh.positions.end(), b.positions);
      if (normals) std::copy(mesh.normals.begin(), mesh.normals.end(), b.normals);
      if (count == mesh.triangleCount()) {
        std::copy_n(mesh.indices.begin(), 3 * count, b.indices);
      } else {
        std::size_t k = 0;
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
          if (flags[t] != sheet) continue;
          std::copy_n(mesh.indices.begin() + static_cast<std::ptrdiff_t>(3 * t), 3,
                      b.indices + 3 * k++);
        }
      }
      if (b.surface) std::copy(surface.begin(), surface.end(), b.surface);
      if (b.texcoords) std::copy(mesh.texcoords.begin(), mesh.texcoords.end(), b.texcoords);
    }
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
    // GL draws lines unlit, in their colour itself.
    const CurveBuffers b =
        out.addCurves(CurveShape::Round, 2 * lines.size(), lines.size(),
                      out.surfaceMaterial(scene, static_cast<int>(m), false, false), false);
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
