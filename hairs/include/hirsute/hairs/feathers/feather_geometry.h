// The geometry of one feather at a level of detail (Streit & Heidrich 2002, Sec. 4.3): the shaft
// as a tube, every barb as a polyline with what polylines, strips and textures need, and the
// afterfeather. Recomputed for every drawing, never stored in the FeatherType (Sec. 4.3).
//
// The local frame, the turtle's at the feather (docs/design.md, "Feathers"):
//   origin  the calamus base;
//   +z      the rachis direction (the turtle's H): the calamus runs from the origin to (0,0,cl),
//           the rachis is the cubic Bézier of Sec. 4.3.1 with control vertices (0,0,cl),
//           (rvdc·rl, rlc·rl, cl + rl/3), (rvdc·rl, rlc·rl, cl + 2rl/3), (0,0,cl + rl);
//   +y      the left vane's side (the turtle's L); the vane plane is the z–y plane, bent with the
//           rachis: at each rachis point it holds the tangent T and L = T × x normalised;
//   +x      the feather's front (the turtle's U), F = L × T at each rachis point.
// A barb attached at rp ∈ [0, 1] hangs at the rachis point of Bézier parameter rp: the rachis
// rises linearly in z with its parameter, so rp is also the fraction of the rachis height.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "hirsute/hairs/feathers/feather_type.h"

namespace hirsute {

// Tessellation (Sec. 4.3, Fig. 8). The lowest detail, 3 segments and 3 sides, is the paper's
// four vertices per barb and rachis with a triangular shaft.
struct FeatherDetail {
  int rachisSegments = 8;  // segments of the rachis tube, at least 1 (the calamus has 1)
  int barbSegments = 6;    // segments of every barb polyline, at least 1
  int shaftSides = 6;      // sides of the shaft's cross-section, at least 3
  // At most this many barbs a vane, 0 for every barb. A vane of n > barbsPerVane barbs keeps
  // every k-th, k = ceil(n / barbsPerVane), and its strips are k times as wide, so that the vane
  // keeps its coverage and its colour when its barbs are closer than the picture can show
  // (thinnedFeatherDetail; the paper's level of detail, Sec. 4.3, carried to the barb count).
  int barbsPerVane = 0;
};

// The detail for a feather whose length cl + rl covers `pixels` on the screen: about a rachis
// segment per 8 pixels (3 to 64), a barb segment per 24 pixels (3 to 32) and one more shaft side
// per 40 pixels (3 to 12).
FeatherDetail featherDetailForProjectedLength(float pixels);

// The same detail, thinned for a picture that cannot show every barb (FeatherDetail::barbsPerVane):
// a vane keeps a barb per 4 pixels of the feather's length up to 64 pixels, per 2 pixels above
// (polyline barbs, which GL draws a pixel wide and cannot widen, one a pixel), and at least 8, a
// few wide strips at the smallest sizes; barbs of a feather 32 pixels long or less have two
// segments. The thresholds were chosen
// by comparing coats drawn both ways (docs/feathers.md, "Dense coats").
FeatherDetail thinnedFeatherDetail(float pixels, BarbStyle drawing);

struct FeatherMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;      // unit, outward
  std::vector<std::uint32_t> indices;  // triangles, counter-clockwise seen from outside
};

struct Barb {
  BarbSide side = BarbSide::Left;  // Left or Right
  float position = 0;              // rp: where it is attached along the rachis, in [0, 1]
  std::uint32_t firstVertex = 0;   // into FeatherGeometry::vertices
  std::uint32_t vertexCount = 0;   // barbSegments + 1
};

// The vertices of all barbs, barb after barb, as parallel arrays (what a vertex buffer takes).
struct BarbVertices {
  std::vector<glm::vec3> positions;
  // The fraction of the barb's arc length from its attachment (0) to its tip (1): alpha fades
  // towards the tip with it (Sec. 4.3.1).
  std::vector<float> s;
  // Sec. 4.3.3. Barb: (s, rp), fixed to the barb whatever its shape. Vane: the vertex projected
  // onto the vane plane with the rachis straightened, (y, z) normalised by the bounding box of
  // all barbs, so the texture swims when barb shapes or angles change. Growth: the feather as it
  // grows rolled up in its sheath: u around the sheath's circular cross-section (0.5 at the
  // rachis, which lies at the front, the two vanes wrapping round to meet at u = 0 and 1 at the
  // back: u = 0.5 ± 0.5 s, + on the left), v the time the material left the collar at the base
  // (0 first, the feather's tip; 1 last, the rachis base), from the vertex's height in the
  // sheath with barbs lying along the rachis, h = rl·rp + s·(barb chord length),
  // v = 1 - h / max h.
  std::vector<glm::vec2> barbUv;
  std::vector<glm::vec2> vaneUv;
  std::vector<glm::vec2> growthUv;
  // With strips only (empty otherwise): a unit vector in the vane plane, perpendicular to the
  // barb; the two strips of Sec. 4.3.1 run from p to p ± stripWidth · side.
  std::vector<glm::vec3> stripSides;
};

struct FeatherGeometry {
  FeatherMesh shaft;                 // calamus and rachis, one tube, open at the calamus base
  std::vector<glm::vec3> shaftAxis;  // the calamus base, then the rachis points of the tube rings
  std::vector<Barb> barbs;           // left vane base to tip, then right vane base to tip
  BarbVertices vertices;
  FeatherAppearance appearance;  // copied from the type; a thinned vane's strips widened
  int barbStride = 1;  // every barbStride-th barb of the type (FeatherDetail::barbsPerVane)
  // The afterfeather (Sec. 3.1): its own geometry, already in this feather's frame: its calamus
  // base at the back of this calamus's tip, (-rw/2, 0, cl), parallel to this feather, scaled by
  // the type's afterfeather size. It has its own afterfeather in its own list.
  std::vector<FeatherGeometry> afterfeathers;

  // Bytes held by every array, the afterfeathers included.
  std::size_t byteSize() const;
  // Barbs in this feather and its afterfeathers.
  std::size_t totalBarbCount() const;
};

// The attachment positions rp of one vane's barbs (Sec. 4.3.1): the first at the rachis base,
// each next one a spacing further along the rachis length rl, the spacing interpolated linearly
// from spb at the base to spt at the tip at the previous barb, sp(rp) = (1 - rp) spb + rp spt,
// while rp ≤ 1: rp_{k+1} = rp_k + sp(rp_k) / rl. With equal spacings sp that is
// floor(rl / sp) + 1 barbs. No barbs without a rachis (rl = 0).
std::vector<float> barbPositions(const FeatherType& type);

FeatherGeometry buildFeatherGeometry(const FeatherType& type, const FeatherDetail& detail);

}  // namespace hirsute
