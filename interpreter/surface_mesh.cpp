#include "surface_mesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace hirsute {

namespace {

// The file's frame: columns L_f, H_f, U_f (cpfg: L_f = H_f × U_f).
glm::dmat3 fileFrame(const Surface& surface) {
  glm::dvec3 heading = surface.heading, up = surface.up;
  heading = glm::length(heading) > 0 ? glm::normalize(heading) : glm::dvec3(0, 1, 0);
  up = glm::length(up) > 0 ? glm::normalize(up) : glm::dvec3(0, 0, 1);
  return glm::dmat3(glm::cross(heading, up), heading, up);
}

// The linear part of the whole placement: file coordinates (relative to the contact point) to
// world directions.
glm::dmat3 placementMatrix(const Surface& surface, const SurfacePlacement& placement) {
  const double size =
      surface.fileSize != 0 ? surface.viewSize / surface.fileSize : surface.viewSize;
  const glm::dmat3 turtle(placement.left * placement.scale.x, placement.heading * placement.scale.y,
                          placement.up * placement.scale.z);
  return turtle * fileFrame(surface) * size;
}

std::array<double, 4> bernstein(double t) {
  const double s = 1 - t;
  return {s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t};
}

std::array<double, 4> bernsteinDerivative(double t) {
  const double s = 1 - t;
  return {-3 * s * s, 3 * s * s - 6 * t * s, 6 * t * s - 3 * t * t, 3 * t * t};
}

struct PatchSample {
  glm::dvec3 point, du, dv;
};

// Control points in 4 rows of 4: u runs along a row, v across the rows.
PatchSample evaluate(const BezierPatch& patch, double u, double v) {
  const auto bu = bernstein(u), bv = bernstein(v);
  const auto du = bernsteinDerivative(u), dv = bernsteinDerivative(v);
  PatchSample sample{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      const glm::dvec3& p = patch.points[static_cast<std::size_t>(r * 4 + c)];
      sample.point += p * (bu[c] * bv[r]);
      sample.du += p * (du[c] * bv[r]);
      sample.dv += p * (bu[c] * dv[r]);
    }
  }
  return sample;
}

}  // namespace

glm::dvec3 placeSurfacePoint(const Surface& surface, const SurfacePlacement& placement,
                             const glm::dvec3& point) {
  return placement.position + placementMatrix(surface, placement) * (point - surface.contact);
}

namespace {

// A mesh file's triangles placed like a patch's points; normals by the inverse transpose of the
// placement, so that a mesh's outside stays its outside under a mirroring scale (its triangles are
// then turned over). One organ record covers the whole mesh.
std::size_t appendMesh(Scene& scene, const Surface& surface, const SurfacePlacement& placement,
                       const SurfaceAppearance& appearance, const OrganAttributeIndices& organs) {
  const SurfaceMeshData& data = *surface.mesh;
  const glm::dmat3 m = placementMatrix(surface, placement);
  const glm::dmat3 normalMatrix =
      glm::determinant(m) != 0.0 ? glm::transpose(glm::inverse(m)) : glm::dmat3(1.0);
  TriangleMesh& mesh = scene.meshFor(appearance.material(0), appearance.texture);
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  const auto firstIndex = static_cast<std::uint32_t>(mesh.indices.size());
  const std::vector<glm::dvec3>& positions = data.positionsAt(placement.frame);
  const std::vector<glm::dvec3>& normals = data.normalsAt(placement.frame);
  for (std::size_t v = 0; v < positions.size(); ++v) {
    mesh.positions.push_back(glm::vec3(placement.position + m * (positions[v] - surface.contact)));
    const glm::dvec3 normal = normalMatrix * normals[v];
    mesh.normals.push_back(glm::dot(normal, normal) > 0 ? glm::vec3(glm::normalize(normal))
                                                        : glm::vec3(0, 0, 1));
    if (mesh.texture >= 0) mesh.texcoords.push_back(data.uv[v]);
  }
  // A mirroring scale turns the triangles over: their order is reversed to stay counter-clockwise
  // about the placed normals.
  const bool mirrored = glm::determinant(m) < 0.0;
  for (std::size_t t = 0; t + 2 < data.indices.size(); t += 3) {
    const std::uint32_t a = data.indices[t], b = data.indices[t + 1], c = data.indices[t + 2];
    if (mirrored) {
      mesh.indices.insert(mesh.indices.end(), {base + a, base + c, base + b});
    } else {
      mesh.indices.insert(mesh.indices.end(), {base + a, base + b, base + c});
    }
  }
  if (!(organs == OrganAttributeIndices{})) {
    OrganSurface record;
    record.kind = OrganSurfaceKind::Mesh;
    record.mesh = static_cast<int>(&mesh - scene.meshes.data());
    record.firstVertex = base;
    record.firstIndex = firstIndex;
    record.indexCount = static_cast<std::uint32_t>(mesh.indices.size()) - firstIndex;
    record.uv = data.uv;
    record.organs = organs;
    if (surface.flow) {
      const glm::vec3 flow(glm::normalize(m * *surface.flow));
      record.flow.assign(data.positions.size(), flow);
    }
    for (const glm::vec3& colour : data.colours) record.blend.push_back(colour.r);
    if (!data.atlasUv.empty()) {
      // Corner by corner as the triangles were written (a mirroring placement swaps two).
      record.atlasChart = data.atlasChart;
      for (std::size_t t = 0; t + 2 < data.atlasUv.size(); t += 3) {
        record.atlasUv.push_back(data.atlasUv[t]);
        record.atlasUv.push_back(data.atlasUv[t + (mirrored ? 2 : 1)]);
        record.atlasUv.push_back(data.atlasUv[t + (mirrored ? 1 : 2)]);
      }
    }
    scene.organSurfaces.push_back(std::move(record));
  }
  return data.triangles();
}

}  // namespace

std::size_t appendSurface(Scene& scene, const Surface& surface, const SurfacePlacement& placement,
                          const SurfaceAppearance& appearance,
                          const OrganAttributeIndices& organs) {
  if (surface.mesh) return appendMesh(scene, surface, placement, appearance, organs);
  const bool organsSet = !(organs == OrganAttributeIndices{});
  const glm::dmat3 m = placementMatrix(surface, placement);
  const int sSteps = std::max(1, surface.sPrecision), tSteps = std::max(1, surface.tPrecision);
  const std::size_t rowLength = static_cast<std::size_t>(sSteps) + 1;

  // Sample every patch first: the per-surface texture mapping needs the bounds of all points.
  std::vector<std::vector<PatchSample>> samples(surface.patches.size());
  glm::dvec2 low(1e300), high(-1e300);
  const glm::dmat3 local =
      fileFrame(surface) *
      (surface.fileSize != 0 ? surface.viewSize / surface.fileSize : surface.viewSize);
  for (std::size_t p = 0; p < surface.patches.size(); ++p) {
    for (int j = 0; j <= tSteps; ++j) {
      for (int i = 0; i <= sSteps; ++i) {
        PatchSample sample = evaluate(surface.patches[p], static_cast<double>(i) / sSteps,
                                      static_cast<double>(j) / tSteps);
        const glm::dvec3 q = local * (sample.point - surface.contact);
        low = glm::min(low, glm::dvec2(q));
        high = glm::max(high, glm::dvec2(q));
        samples[p].push_back(sample);
      }
    }
  }
  const glm::dvec2 span = glm::max(high - low, glm::dvec2(1e-300));

  std::size_t triangles = 0;
  for (std::size_t p = 0; p < surface.patches.size(); ++p) {
    const BezierPatch& patch = surface.patches[p];
    TriangleMesh& mesh = scene.meshFor(appearance.material(patch.topColor), appearance.texture);
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    const auto firstIndex = static_cast<std::uint32_t>(mesh.indices.size());
    OrganSurface record;
    for (int j = 0; j <= tSteps; ++j) {
      for (int i = 0; i <= sSteps; ++i) {
        const PatchSample& sample =
            samples[p][static_cast<std::size_t>(j) * rowLength + static_cast<std::size_t>(i)];
        if (organsSet) {
          record.uv.push_back(
              glm::vec2(static_cast<float>(i) / sSteps, static_cast<float>(j) / tSteps));
        }
        mesh.positions.push_back(
            glm::vec3(placement.position + m * (sample.point - surface.contact)));
        // The normal of the placed surface: the cross product of the placed derivatives (this
        // also holds for a mirroring or flattening scale, where an inverse transpose would not).
        glm::dvec3 normal = glm::cross(m * sample.du, m * sample.dv);
        if (glm::dot(normal, normal) < 1e-24) {
          // A degenerate corner (coincident control points) has no derivative cross product:
          // the patch's diagonals stand in.
          const auto& q = patch.points;
          normal = glm::cross(m * (q[15] - q[0]), m * (q[12] - q[3]));
        }
        mesh.normals.push_back(glm::dot(normal, normal) > 0 ? glm::vec3(glm::normalize(normal))
                                                            : glm::vec3(0, 0, 1));
        if (mesh.texture >= 0) {
          if (appearance.perSurfaceTexture) {
            const glm::dvec2 q = glm::dvec2(local * (sample.point - surface.contact));
            mesh.texcoords.push_back(glm::vec2((q - low) / span));
          } else {
            mesh.texcoords.push_back(
                glm::vec2(static_cast<float>(i) / sSteps, static_cast<float>(j) / tSteps));
          }
        }
      }
    }
    for (int j = 0; j < tSteps; ++j) {
      for (int i = 0; i < sSteps; ++i) {
        const std::uint32_t a =
            base + static_cast<std::uint32_t>(static_cast<std::size_t>(j) * rowLength + i);
        const std::uint32_t b = a + 1, c = a + static_cast<std::uint32_t>(rowLength), d = c + 1;
        // Counter-clockwise about the placed du × dv, the vertex normals' side.
        mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
        triangles += 2;
      }
    }
    scene.markThin(mesh, firstIndex);
    if (organsSet) {
      record.kind = OrganSurfaceKind::BicubicPatch;
      record.mesh = static_cast<int>(&mesh - scene.meshes.data());
      record.firstVertex = base;
      record.firstIndex = firstIndex;
      record.indexCount = static_cast<std::uint32_t>(mesh.indices.size()) - firstIndex;
      record.organs = organs;
      scene.organSurfaces.push_back(std::move(record));
    }
  }
  return triangles;
}

}  // namespace hirsute
