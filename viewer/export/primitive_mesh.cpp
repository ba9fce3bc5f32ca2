#include "hirsute/viewer/export/primitive_mesh.h"

#include <cmath>

namespace hirsute {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSphereSlices = 12, kSphereStacks = 6, kDiscSegments = 16;

}  // namespace

void appendSphere(PrimitiveMesh& mesh, const glm::vec3& centre, float radius) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  auto add = [&](const glm::vec3& n) {
    mesh.positions.push_back(centre + radius * n);
    mesh.normals.push_back(n);
  };
  add({0, 1, 0});
  for (int i = 1; i < kSphereStacks; ++i) {
    const double polar = kPi * i / kSphereStacks;
    for (int j = 0; j < kSphereSlices; ++j) {
      const double azimuth = 2 * kPi * j / kSphereSlices;
      add(glm::vec3(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                    -std::sin(polar) * std::sin(azimuth)));
    }
  }
  add({0, -1, 0});
  auto ring = [&](int i, int j) {
    return first + static_cast<std::uint32_t>(1 + (i - 1) * kSphereSlices + (j % kSphereSlices));
  };
  const auto bottom = static_cast<std::uint32_t>(mesh.positions.size() - 1);
  std::vector<std::uint32_t>& indices = mesh.indices;
  for (int j = 0; j < kSphereSlices; ++j) {
    indices.insert(indices.end(), {first, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < kSphereStacks; ++i) {
      indices.insert(indices.end(), {ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      indices.insert(indices.end(), {ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
    indices.insert(indices.end(),
                   {ring(kSphereStacks - 1, j), bottom, ring(kSphereStacks - 1, j + 1)});
  }
}

void appendDisc(PrimitiveMesh& mesh, const glm::vec3& centre, float radius,
                const glm::vec3& normal) {
  const glm::vec3 helper = std::fabs(normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 u = glm::normalize(glm::cross(normal, helper));
  const glm::vec3 v = glm::cross(normal, u);
  const auto middle = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.push_back(centre);
  mesh.normals.push_back(normal);
  for (int i = 0; i < kDiscSegments; ++i) {
    const double angle = 2 * kPi * i / kDiscSegments;
    mesh.positions.push_back(centre + radius * (static_cast<float>(std::cos(angle)) * u +
                                                static_cast<float>(std::sin(angle)) * v));
    mesh.normals.push_back(normal);
    mesh.indices.insert(mesh.indices.end(),
                        {middle, middle + 1 + static_cast<std::uint32_t>(i),
                         middle + 1 + static_cast<std::uint32_t>((i + 1) % kDiscSegments)});
  }
}

}  // namespace hirsute
