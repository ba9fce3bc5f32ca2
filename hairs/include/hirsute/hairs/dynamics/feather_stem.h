// A feather as a stem of particles along its rachis (Fido Film 2008 study, Sec. 3.2 and 3.3.1;
// docs/design.md, "Feather-coat dynamics"; docs/dynamics.md, "Stems"). Node 0 is the calamus base,
// bound to the body (kinematic); nodes 1..n follow the rachis to its tip. Every node i >= 1 has a
// gold (rest) position in the frame of its parent node i - 1, held by an implicit damped linear
// spring, and every segment is kept within a strain limit of its rest length.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::dynamics {

// An orthonormal frame: `axes` holds, as columns, the binormal (the feather's front, the turtle's
// U), the left vane's side (L) and the tangent along the stem (H); `origin` is where it sits.
struct StemFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

// The physical parameters of a stem (docs/dynamics.md, "Parameters").
struct StemParameters {
  double linearDensity = 1.0;  // mass per unit length of rachis
  double goldStiffness = 200;  // k of the gold springs, force per unit length of displacement
  double goldDamping = 2;      // b of the gold springs, force per unit relative velocity
  double strainLimit = 0.01;   // every segment stays within this fraction of its rest length
};

struct FeatherStem {
  std::vector<Eigen::Vector3d> positions;  // node 0 the anchor, then to the rachis tip
  std::vector<Eigen::Vector3d> velocities;
  std::vector<double> masses;                  // masses[0] is unused: the anchor is kinematic
  std::vector<double> restLengths;             // restLengths[i]: segment from node i to i + 1
  std::vector<Eigen::Vector3d> goldPositions;  // goldPositions[i]: node i in its parent's frame
  std::vector<StemFrame> frames;               // frames[i]: the frame at node i (0: the anchor's)
  // Built from a Scene feather: each node's height z in the feather's local frame (its rest
  // place along the rachis), increasing; empty for stems built from points.
  std::vector<double> heights;
  StemParameters parameters;
  // The vane as collision geometry (docs/dynamics.md, "Vanes"): per node, the half-width of the
  // vane to the left (+L of the node's frame) and to the right at that rachis position; empty:
  // the stem is its rachis alone. The vane between nodes i and i + 1 is a quad on each side
  // where both nodes have a width there: the rachis segment and the two corners.
  std::vector<std::array<double, 2>> vaneWidths;
  // Per node, where the vane's left and right corners are (world space): the node plus its
  // width along the frame's L at the end of each step, moved with the node by the collisions
  // (FeatherCoatSimulation keeps them; a step starts from where the last one left them).
  std::vector<std::array<Eigen::Vector3d, 2>> vaneCorners;

  std::size_t nodeCount() const { return positions.size(); }
  bool hasVane() const { return !vaneWidths.empty(); }
};

// The vane's half-widths of a feather type, in its local units, at the local rachis points
// `nodes` (x front, y left, z along the rachis; feather_geometry.h): the extent of the drawn
// barbs projected on the vane plane (their x dropped), to the left and the right of the node's
// y, over the heights from half-way to the node below to half-way to the node above. The
// calamus has no vane: a node below the rachis base (z < cl) has none, and the heights searched
// start at the rachis base. Nodes must be in increasing z.
std::vector<std::array<double, 2>> vaneHalfWidths(const FeatherType& type,
                                                  const std::vector<Eigen::Vector3d>& nodes);

// The corners of the vane from the stem's frames: node i's left corner at p_i + w_left L_i,
// its right one at p_i - w_right L_i.
std::vector<std::array<Eigen::Vector3d, 2>> vaneCornersOf(const FeatherStem& stem);
// The same from the frames rebuildFrames(stem, anchor) would give, leaving the stem's frames as
// they are.
std::vector<std::array<Eigen::Vector3d, 2>> vaneCornersAt(const FeatherStem& stem,
                                                           const StemFrame& anchor);

// The anchor frame of a Scene feather: origin at the calamus base, axes (up, left, heading).
StemFrame anchorFrameOf(const Feather& feather);

// The stem of a Scene feather with `segments` segments (at least 1): node 0 at the calamus base,
// then points of the rachis (the cubic Bézier of feather_geometry.h, calamus included as its
// first segment) at equal parameter steps, in world space by the feather's frame and size, the
// type blended and grown as it is drawn. Gold positions are this rest shape; velocities zero.
// The stem carries its vane (vaneHalfWidths, times the feather's size).
FeatherStem buildFeatherStem(const Scene& scene, const Feather& feather, int segments,
                             const StemParameters& parameters = {});

// A stem from points given in world space (the first the anchor) and the anchor's frame.
FeatherStem buildStemFromPoints(const std::vector<Eigen::Vector3d>& points, const StemFrame& anchor,
                                const StemParameters& parameters = {});

// Sec. 3.2: the frames rebuilt from the current positions, anchor first. The tangent of node i is
// along p_i - p_{i-1}; the binormal is the parent's, made perpendicular to it (the paper's
// t = n x bn_{i-1}, bn = t x n, normalised), so a stem never twists about itself.
void rebuildFrames(FeatherStem& stem, const StemFrame& anchor);

// Node i's gold position in world space, from the current frame of its parent.
Eigen::Vector3d worldGoldPosition(const FeatherStem& stem, std::size_t node);

// Sec. 3.3.1 (after Selle, Lentine & Fedkiw 2008): the velocities after `h` of the gold springs,
// implicit in the velocity and in the turn of the frames, plus `forces` (per node, explicit):
// solves, linearised at the current positions (the frames must be rebuilt from them),
//   (M + h b L + h lookahead K) v' = M v + h (F_gold(x) + forces),
// L the chain's Laplacian, K = -dF_gold/dx the springs' full stiffness: the spring of node i pulls
// p_i towards p_{i-1} + R_{i-1} g_i (its gold position) and its parent the other way, and R_{i-1}
// turns with the segment that ends at node i - 1, so that a node's motion moves its children's
// gold positions (docs/dynamics.md, "Stems"). `lookahead` is how far the positions will move with
// v' (h for an implicit Euler step). The anchor's velocity `anchorVelocity` is known. Every
// spring's forces sum to zero, so the springs keep momentum. `velocities` is replaced; positions
// are unchanged.
void advanceGoldSprings(FeatherStem& stem, double h, double lookahead,
                        const std::vector<Eigen::Vector3d>& forces,
                        const Eigen::Vector3d& anchorVelocity);

// Strain limiting (Provot 1995; Bridson, Fedkiw & Anderson 2002), from the anchor to the tip:
// every segment longer or shorter than its rest length by more than the strain limit is brought
// back to the limit, moving both ends by their inverse masses (equal and opposite corrections, so
// linear momentum is kept; the anchor does not move), sweeping until all are within the limit; a
// last sweep that moves only the outer end makes the limit hold for certain. Each correction of
// a position is added to the velocity divided by `h` (Sec. 3.3.3). Returns the sweeps made.
int limitStrain(FeatherStem& stem, double h);

// The largest |length / rest length - 1| over the stem's segments.
double largestStrain(const FeatherStem& stem);

}  // namespace hirsute::dynamics
