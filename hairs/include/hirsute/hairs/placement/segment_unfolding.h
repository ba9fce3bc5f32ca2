// A generalized-cylinder segment unfolded into (u, v) (Fuhrer, Jensen & Prusinkiewicz 2004,
// Sec. 3.1 and Figure 2; docs/design.md, "Placement"): u is arc length around the contour at each
// ring (across the leaf, edge to edge, for an open contour), v is arc length along the cylinder
// axis accumulated from `@Gs`, so that patterns continue from segment to segment.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/interpreter/scene.h"

namespace hirsute {

// A point of a face between rings `ring` - 1 and `ring`: column `column` to `column` + 1, `a`
// across it, `t` along it (the bilinear coordinates of its corners).
struct FacePoint {
  std::size_t ring = 1;
  int column = 0;
  float a = 0;
  float t = 0;
};

class SegmentUnfolding {
 public:
  // The segment must be drawn as triangles (segment.mesh the index of `mesh`, two rings or more).
  SegmentUnfolding(const CylinderSegment& segment, const TriangleMesh& mesh);

  const CylinderSegment& segment() const { return segment_; }
  std::size_t rings() const { return segment_.rings.size(); }
  int faces() const { return segment_.sides; }  // faces around a ring
  const glm::vec3& position(std::size_t ring, int column) const {
    return mesh_.positions[vertex(ring, column)];
  }
  // The shading normal at a vertex (of the front).
  const glm::vec3& normal(std::size_t ring, int column) const {
    return mesh_.normals[vertex(ring, column)];
  }
  // u over the girth at a vertex, in [0, 1]: the arc-length fraction around its ring.
  float fraction(std::size_t ring, int column) const {
    return fraction_[ring * perRing() + static_cast<std::size_t>(column)];
  }
  // Arc length around ring `ring` (edge to edge on open contours), and the largest.
  float girth(std::size_t ring) const { return girth_[ring]; }
  float maxGirth() const { return maxGirth_; }
  // v at ring `ring`: arc length along the axis from @Gs.
  float v(std::size_t ring) const { return segment_.rings[ring].axisDistance; }
  // The fraction along the segment of ring `ring` (the interpolation parameter of its
  // attributes).
  float tau(std::size_t ring) const;
  // The face at girth position s (in [0, 1)) in the strip between rings `ring` - 1 and `ring`,
  // a fraction t along it: the fractions mixed between the strip's two rings.
  FacePoint face(std::size_t ring, float t, float s) const;
  // The position of a face point: bilinear in its corners.
  glm::vec3 at(const FacePoint& p) const;

 private:
  std::size_t perRing() const { return static_cast<std::size_t>(segment_.sides) + 1; }
  std::size_t vertex(std::size_t ring, int column) const {
    return segment_.firstVertex + ring * perRing() + static_cast<std::size_t>(column);
  }

  const CylinderSegment& segment_;
  const TriangleMesh& mesh_;
  std::vector<float> fraction_;  // by ring, then column
  std::vector<float> girth_;
  float maxGirth_ = 0;
};

// The fraction along the segment of ring k (the interpolation parameter of its attributes).
float ringTau(const CylinderSegment& segment, std::size_t k);

}  // namespace hirsute
