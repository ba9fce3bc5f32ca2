// A coat laid in its layer order, each feather resting on the feathers beneath it instead of
// passing through them (docs/feathers.md, "Shingling"; docs/dynamics.md, "Resting contact").
// Production grooming orders feathers rather than colliding them (Liu et al. 2015: a growth
// order over the follicles and a height field over what is already laid); the guarantee is the
// dynamics' own: every state it leaves is checked by the exact intersection test
// (static_intersection.h) on the stems and vanes the simulator collides (feather_stem.h,
// stem_vane.h).
//
// The feathers below are fixed, as is the body. A stem is laid from its root out, one segment at
// a time: each segment turns about its inner node, towards the stem's front (its binormal U),
// by the least angle that keeps it and its vane quads clear of everything laid before it (the
// angles searched by doubling, then halving, each angle accepted only once the exact test has
// found it clear), plus a small angle of gap. The part of the stem beyond turns with it, so
// the segments' lengths are kept exactly and the root stays where the body put it; a segment
// that needs no lift turns back towards the groom's direction by at most a few degrees a node,
// so that a lifted stem bends back smoothly to the shape it was groomed in. The vane follows its
// stem's frames (rebuildFrames), as it does in the simulation.
//
// RestingLayer is what is laid: the obstacles a stem rests on, kept in a uniform grid. The pass
// over a whole coat (deintersectStems) adds each stem to it once laid; a resting-contact solve of
// the dynamics can lay one stem on the layer its neighbours make in the same way.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "hirsute/core/progress.h"
#include "hirsute/hairs/dynamics/feather_coat_simulation.h"
#include "hirsute/hairs/dynamics/feather_stem.h"

namespace hirsute::dynamics {

struct LayingParameters {
  // The gap a lifted segment is given above what it rests on, as a fraction of its stem's
  // length (a lift is the least clear angle plus the angle that opens this gap at the
  // segment's end, where that is clear too).
  double gap = 0.002;
  // A node turns the stem beyond it up by at most this (radians), and the stem's direction is
  // never turned up from its groom by more than `largestLift` in all.
  double liftPerNode = 1.0;
  double largestLift = 1.6;
  // Where a segment needs no lift, it turns back towards the groom by at most this a node.
  double returnPerNode = 0.2;
  // The search for the least clear angle: it doubles from `firstStep`, then halves the bracket
  // `halvings` times.
  double firstStep = 0.02;
  int halvings = 3;
  // A segment no turn of its own clears is reached by turning a node before it by more: by
  // `raiseStep` more, doubling, the stem laid again from its root each time, at most
  // `maxRelays` times.
  double raiseStep = 0.05;
  int maxRelays = 48;
  // Pairs of primitives whose boxes overlap, tested exactly, over the whole pass (the cost a
  // model drives: feathers crowded at one spot test every pair of them). Past it the feathers
  // not yet laid are left as grown.
  std::uint64_t maxPairTests = 400'000'000;
};

// What one stem's laying did.
struct LaidStem {
  bool moved = false;             // some node turned
  std::size_t intersections = 0;  // pairs of its primitives and the layer's still meeting
  double lift = 0;                // the largest turn of its direction from the groom (radians)
};

// The obstacles laid stems make for those laid after them: their rachis segments (calami
// aside, as the simulator's check leaves them: feather_coat_simulation.h), their vane
// triangles, and the body's triangles, which meet rachis segments only.
class RestingLayer {
 public:
  // `cellSize`: the grid's cell, about the size of a primitive.
  RestingLayer(const BodyMesh& body, double cellSize);

  // Adds the stem (its positions and vaneCorners as they are) to the layer.
  void add(const FeatherStem& stem);

  // Lays `stem` on the layer (its root, node 0, fixed; the anchor its frame at the root) and
  // rebuilds its frames and vane corners. Stops turning past the pair-test limit (then the
  // stem's remaining segments are left as they were).
  LaidStem lay(FeatherStem& stem, const StemFrame& anchor, const LayingParameters& parameters);

  // Pairs of the stem's primitives and the layer's that meet (exact), its calamus against vanes
  // and other rachis segments only.
  std::size_t meetingPairs(const FeatherStem& stem) const;

  std::uint64_t pairTests() const { return pairTests_; }
  bool overLimit(const LayingParameters& parameters) const {
    return pairTests_ > parameters.maxPairTests;
  }

 private:
  enum class Kind : std::uint8_t { Segment, Vane, Body };
  struct Obstacle {
    std::array<Eigen::Vector3d, 3> points;  // a segment's two, a triangle's three
    Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();  // its box
    Kind kind = Kind::Segment;
  };
  // A primitive of the stem being laid.
  struct Mover {
    std::array<Eigen::Vector3d, 3> points;
    bool triangle = false;
    bool calamus = false;
  };
  void insert(Obstacle obstacle);
  // Where a stem was before its segment k was laid.
  struct LayState {
    std::vector<Eigen::Vector3d> positions;
    StemFrame frame;    // node k's
    double turned = 0;  // the turns of the nodes before k
  };
  // An obstacle's box in single precision, rounded outwards, beside its index: what the grid's
  // cells and a query's answer hold, so that the boxes are compared where they lie.
  struct Entry {
    std::array<float, 3> low, high;
    std::uint32_t index;
  };
  bool meets(const Mover& mover, const Obstacle& obstacle) const;
  // The obstacles whose boxes overlap the box from `low` to `high`.
  void gather(const Eigen::Vector3d& low, const Eigen::Vector3d& high,
              std::vector<Entry>& found) const;
  // Pairs of `movers` and the obstacles `near` that meet; stops at the first when `firstOnly`.
  std::size_t meeting(const std::vector<Mover>& movers, const std::vector<Entry>& near,
                      bool firstOnly) const;
  // Lays the stem's segments from node `from` out (the stem as states[from] has it), none
  // turned below its floor; `turns` gets each node's turn, `states` where each segment started.
  // Returns the first segment that no turn clears, or -1.
  int laySegments(FeatherStem& stem, std::size_t from, const std::vector<double>& floors,
                  std::vector<double>& turns, std::vector<LayState>& states,
                  const LayingParameters& parameters);
  std::int64_t cellOf(double x) const;

  double cellSize_;
  std::vector<Obstacle> obstacles_;
  std::unordered_map<std::uint64_t, std::vector<Entry>> cells_;
  std::vector<Entry> large_;                 // obstacles over too many cells, tested by their boxes
  mutable std::vector<std::uint32_t> seen_;  // per obstacle, the last query that met it
  mutable std::uint32_t query_ = 0;
  mutable std::uint64_t pairTests_ = 0;
  std::vector<Entry> near_;  // the obstacles a segment being laid can reach
};

struct DeintersectionReport {
  std::size_t stems = 0;          // stems laid
  std::size_t moved = 0;          // of those, stems some node of which turned
  std::size_t intersections = 0;  // pairs of primitives still meeting after the pass
  std::size_t unresolved = 0;     // stems with some of those
  std::size_t leftAsGrown = 0;    // stems not laid: the pair-test limit was reached
  double largestLift = 0;         // radians
  std::uint64_t pairTests = 0;
};

// Lays `stems` in their order, the first at the bottom: each on the layer of those before it
// and the body. Deterministic: one stem after another, the same on any machine and any number of
// threads. Shows "shingling feathers: N/M" on `progress` where one is given.
DeintersectionReport deintersectStems(std::vector<FeatherStem>& stems,
                                      const std::vector<StemFrame>& anchors, const BodyMesh& body,
                                      const LayingParameters& parameters,
                                      Progress* progress = nullptr);

}  // namespace hirsute::dynamics
