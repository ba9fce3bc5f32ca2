// The shared placement engine (docs/design.md, "Placement"): candidate attachment
// points on generalized-cylinder segments, for every organ placed on them (plant hairs, feather
// follicles, …). The sampler tiles a point pattern (Mitchell's point-diffusion texture,
// or any tile in scan-line order) over each segment unfolded into (u, v), maps every point to its
// face and interpolates the corner frames there; the organ decides, point by point, whether to
// keep it (density thinning) and what to place.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "hirsute/hairs/placement/corner_frame.h"
#include "hirsute/hairs/placement/diffusion_strip.h"
#include "hirsute/hairs/placement/patch_unfolding.h"
#include "hirsute/hairs/placement/placement_random.h"
#include "hirsute/hairs/placement/point_diffusion.h"
#include "hirsute/hairs/placement/segment_unfolding.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

// The angles of a corner frame at girth position s, fraction tau along the segment.
struct CornerAngles {
  float incline = 0;  // radians, about d × h
  float wrap = 0;     // radians, about d × (d × h)
  float twist = 0;    // interpolated across the face as given; the organ applies it
};

// A candidate attachment point, before the organ keeps it or not.
struct AttachmentPoint {
  float s = 0;           // girth position in [0, 1) (0 or 1 on the edges of open contours)
  float tau = 0;         // fraction along the segment: the attributes' interpolation parameter
  float girthRatio = 1;  // where a tile is stretched: the girth (or a surface's area ratio) here
                         // over the largest
  bool edge = false;     // on an edge of an open contour (placed per unit length)
  float blend = -1;      // a mesh's vertex colours' red here (OrganSurface::blend); -1: none
  PlacementRandom random{0};  // this point's numbers, keyed by the seed and the point
};

// Where a kept point lies and how it is oriented: on its face, bilinear in the corners (on an
// edge, linear along it).
struct AttachmentFrame {
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f};  // the corner directions interpolated (not normalised)
  glm::vec3 across{0.0f};     // the corners' incline axes interpolated
  float twist = 0;            // the corners' twists interpolated
};

// What an organ does with the points the sampler visits.
class AttachmentVisitor {
 public:
  virtual ~AttachmentVisitor() = default;
  // The angles of the corner frames at (s, tau).
  virtual CornerAngles cornerAngles(float s, float tau) const = 0;
  // Before each strip: about how many points it will visit (an organ may refuse too many).
  virtual void expectPoints(double points) { (void)points; }
  // A point is about to be tested (before its numbers are drawn).
  virtual void pointTested() {}
  // Density thinning: whether to place at this point (its numbers come from point.random).
  virtual bool keep(AttachmentPoint& point) = 0;
  // Places the organ at a kept point.
  virtual void place(AttachmentPoint& point, const AttachmentFrame& frame) = 0;
};

// Which face of the surface: the back has its normals flipped and the tile shifted by half, so
// that its points are not the front's.
enum class SurfaceFace { Front, Back };

class SurfaceSampler {
 public:
  // The texture's points, tiled over open contours; along closed tubes its diffusion is
  // generated for the girth instead (diffusion_strip.h), with the texture's fill and seed.
  explicit SurfaceSampler(const PointDiffusionTexture& texture);
  // Tiles any pattern of points in the unit tile, in scan-line order over `rows` rows (a point's
  // row is TexturePoint::row), on closed contours too (stretched to a whole number of tiles
  // around the girth).
  SurfaceSampler(std::vector<TexturePoint> points, int rows);
  ~SurfaceSampler();
  SurfaceSampler(SurfaceSampler&&) noexcept;

  std::size_t tilePoints() const { return points_.size(); }

  // Sec. 3.1 and Figure 2: the pattern over the unfolded segment in scan-line order, at
  // maxDensity points per unit area. On an open contour the tile, a tile with K points covering
  // K / maxDensity units of area. On a closed contour a diffusion strip along the tube (the
  // sampler remembers it: the next segment of the tube, sampled next for the same face, continues
  // it without a seam); with a pattern of its own, a whole number of tiles around the girth.
  // Every point gets the numbers of placementKey(key, the point).
  void sampleSurface(const SegmentUnfolding& unfolding, SurfaceFace face, float maxDensity,
                     std::uint64_t key, AttachmentVisitor& visitor);

  // Surfaces and polygons in their own (u, v) (patch_unfolding.h): the tile over the plane (U, V)
  // in scan-line order, a tile with K points covering K / (maxDensity · the largest area ratio)
  // of it, each point kept in the triangle it falls in. The organ thins where a triangle's area
  // ratio is below the largest (AttachmentPoint::girthRatio); on a polygon every ratio is 1.
  // The corner frames are the vertex normals with V's direction as the height vector h.
  void samplePatch(const PatchUnfolding& unfolding, SurfaceFace face, float maxDensity,
                   std::uint64_t key, AttachmentVisitor& visitor) const;

  // A mesh file's surface (OrganSurfaceKind::Mesh): maxDensity × its area points over the
  // triangles' world area (mesh_sampling.h), not over its (u, v); every point's girthRatio is
  // 1. The corner frames are those of samplePatch; the back's points are drawn anew.
  static void sampleMesh(const PatchUnfolding& unfolding, SurfaceFace face, float maxDensity,
                         std::uint64_t key, AttachmentVisitor& visitor);

  // Sec. 3.2: points along edge `which` (0: the contour's first point, 1: its last) of an open
  // segment, √maxDensity per unit length, spaced evenly with a jitter and counted in arc length
  // from @Gs, so that the rhythm continues from segment to segment. The direction is the edge
  // vector h × n, pointing away from the segment.
  static void sampleEdge(const SegmentUnfolding& unfolding, int which, float maxDensity,
                         std::uint64_t key, AttachmentVisitor& visitor);

 private:
  class Faces;
  struct OpenStrip;
  void sampleAlongTube(const SegmentUnfolding& unfolding, const Faces& faces, SurfaceFace face,
                       float maxDensity, std::uint64_t key, AttachmentVisitor& visitor);
  void sampleTiles(const SegmentUnfolding& unfolding, const Faces& faces, SurfaceFace face,
                   float maxDensity, std::uint64_t key, AttachmentVisitor& visitor) const;

  std::vector<TexturePoint> points_;
  int rows_ = 0;
  std::vector<std::uint32_t> rowStart_;  // points of row r: [rowStart_[r], rowStart_[r+1])
  double stripFill_ = 0;                 // 0: no strips (a pattern of the caller's)
  std::uint64_t stripSeed_ = 0;
  std::map<std::pair<int, int>, std::unique_ptr<OpenStrip>> strips_;  // by tube and face
};

}  // namespace hirsute
