// A stem's vane as collision geometry (docs/dynamics.md, "Vanes"; issue 26, item 2): a ribbon of
// triangles on each side of the rachis, between the rachis nodes and the vane's corners (the
// node plus the vane's half-width along the frame's L, FeatherStem::vaneWidths and
// vaneCorners). Between nodes i and i + 1, where both have a width on a side, the side's quad is
// the triangles (p_i, p_i+1, c_i+1) and (p_i, c_i+1, c_i): ordinary triangles whose corners move
// linearly over a step, so that the vertex-face and edge-edge CCD stays exact on them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_set>
#include <utility>
#include <vector>

#include "hirsute/hairs/dynamics/box_tree.h"
#include "hirsute/hairs/dynamics/feather_stem.h"

namespace hirsute::dynamics {

// A vertex of a vane: a rachis node (side -1) or the node's left (0) or right (1) corner.
struct VaneVertex {
  int node = 0;
  int side = -1;
};

// One triangle of a vane and the quad it belongs to: the segment (from node `segment`) and side.
struct VaneTriangle {
  int segment = 0;
  int side = 0;
  std::array<VaneVertex, 3> vertices;
};

// Whether the segment from node `segment` has a quad of vane on `side`.
bool hasVaneQuad(const FeatherStem& stem, int segment, int side);
// Whether node `node` has a vane corner on `side` that a quad uses.
bool hasVaneCorner(const FeatherStem& stem, int node, int side);

// The triangles of the stem's vane, quad after quad (left before right); none without a vane.
std::vector<VaneTriangle> vaneTrianglesOf(const FeatherStem& stem);

// Where a vane vertex is now.
const Eigen::Vector3d& positionOf(const FeatherStem& stem, VaneVertex v);

// Pairs of stem segments of different stems, each with its vane (the rachis segment and the
// vane's quads either side of it), left out of the vanes' collisions: the pairs whose vanes met
// when the simulation started (a coat placed on its body puts the neighbours of a row in one
// plane, their vanes overlapping). A pair is taken back once it has come apart: from then on
// its vanes are kept apart as any others. Segments are numbered over the stems (segmentIndex).
class VaneOverlaps {
 public:
  VaneOverlaps() = default;
  explicit VaneOverlaps(const std::vector<FeatherStem>& stems);

  int segmentIndex(int stem, int segment) const { return offset_[stem] + segment; }
  bool contains(int a, int b) const { return !pairs_.empty() && pairs_.count(keyOf(a, b)) > 0; }
  void insert(int a, int b) { pairs_.insert(keyOf(a, b)); }
  std::size_t size() const { return pairs_.size(); }
  bool empty() const { return pairs_.empty(); }
  // Takes back the pairs whose segments (rachis and vane) are now farther apart than
  // `clearance`; returns how many.
  std::size_t release(const std::vector<FeatherStem>& stems, double clearance);

 private:
  static std::uint64_t keyOf(int a, int b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
  }
  std::vector<int> offset_;             // per stem, the index of its first segment
  std::vector<std::array<int, 2>> of_;  // per segment index, its stem and segment
  std::unordered_set<std::uint64_t> pairs_;
};

// Intersections of vanes in a state: a vane triangle and a triangle of another stem's vane, or a
// vane triangle and another stem's segment (calami aside, as the stems' check leaves them:
// feather_coat_simulation.h), that meet (exact, static_intersection.h) or come nearer than
// `minimumDistance` to each other, the segments' pairs in `skip` left out. Vanes of one stem are
// not tested against each other, nor against the body.
std::size_t countVaneIntersections(const std::vector<FeatherStem>& stems, double minimumDistance,
                                   const VaneOverlaps* skip = nullptr);
// The same searching in `tree` (refitted from its last search where it can be; the pairs tested
// on its pool's threads); each pair of segments found (their segmentIndex in `numbering`) is
// added to `found` where one is given. With a `slack`, the tree's kept list of the pairs whose
// boxes grown by it overlap is filtered (BoxTree::coherentPairs), less the pairs a plane of one
// of them keeps farther apart than `minimumDistance` and the slack's moves allow for.
std::size_t countVaneIntersections(const std::vector<FeatherStem>& stems, double minimumDistance,
                                   BoxTree& tree, const VaneOverlaps* skip,
                                   VaneOverlaps* found = nullptr, double slack = 0);

// The distance between a segment and a triangle, and between two triangles (closed).
double segmentTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                               const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c);
double triangleTriangleDistance(const std::array<Eigen::Vector3d, 3>& s,
                                const std::array<Eigen::Vector3d, 3>& t);

}  // namespace hirsute::dynamics
