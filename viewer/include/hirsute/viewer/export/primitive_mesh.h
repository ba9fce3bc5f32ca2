// Spheres and discs as triangles, for the formats that have no sphere or disc of their own (the
// scene for Blender, glTF): gathered into one mesh a material, each primitive appended to it.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace hirsute {

struct PrimitiveMesh {
  std::vector<glm::vec3> positions, normals;  // unit normals, one per position
  std::vector<std::uint32_t> indices;         // counter-clockwise seen from outside
};

// A UV sphere of 12 slices and 6 stacks: a point at each pole and 5 rings of 12 points between,
// 120 triangles.
void appendSphere(PrimitiveMesh& mesh, const glm::vec3& centre, float radius);

// A disc facing `normal` (of unit length) as a fan of 16 triangles about its centre.
void appendDisc(PrimitiveMesh& mesh, const glm::vec3& centre, float radius,
                const glm::vec3& normal);

}  // namespace hirsute
