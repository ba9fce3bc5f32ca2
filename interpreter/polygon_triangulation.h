// Triangulation of the turtle's { } polygons, concave ones included. cpfg draws them as
// GL_POLYGON, or through the GLU tessellator with `concave polygons: on`; the interpreter must
// not link GL, and Debian 12 ships no small triangulation library (CGAL would be the only one),
// so this is ear clipping.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace hirsute {

struct PolygonTriangulation {
  glm::dvec3 normal{0.0};  // unit Newell normal; zero for a degenerate polygon
  // Triangles as indices into the input points, counter-clockwise seen from the normal's side.
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// Triangulates a simple polygon lying (nearly) in a plane: the plane is the Newell normal's
// (Foley et al., §11.1.3), the polygon is projected onto the coordinate plane the normal is most
// nearly perpendicular to, and ears are clipped (Eberly, "Triangulation by Ear Clipping", 2002;
// Meisters' two-ears theorem guarantees an ear while the polygon is simple). Repeated and
// collinear vertices are dropped without a triangle; a self-intersecting polygon, which may run
// out of ears, is finished by clipping vertices in turn so that every vertex is still covered.
PolygonTriangulation triangulatePolygon(const std::vector<glm::dvec3>& points);

// The polygon's own (u, v) for organs (scene.h, OrganSurface): world distances in its plane
// from its first vertex, u along its first edge of non-zero length (projected into the plane),
// v = normal × u, so that (u, v) is right-handed seen from the front. A polygon without a plane
// (zero normal) gets (0, 0) everywhere.
std::vector<glm::vec2> polygonPlaneCoordinates(const std::vector<glm::dvec3>& points,
                                               const glm::dvec3& normal);

}  // namespace hirsute
