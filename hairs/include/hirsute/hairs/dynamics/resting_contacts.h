// Resting contacts (docs/dynamics.md, "Resting contacts"): the pairs of a coat's primitives that
// lie within the repulsion thickness of each other, kept from step to step and held at a resting
// distance by a position-level solve, so that the layers of a coat that press on each other are
// not found again by the continuous collision detection at every search of every step.
//
// Bridson, Fedkiw & Anderson 2002 (Sec. 7) answer resting contact by repulsion and leave the CCD
// to what gets through; here the repulsion is a constraint on the step's end positions, solved
// by projected Gauss-Seidel over the contacts in the order of their keys (one thread, so the
// result is the same for any number of threads), with the multiplier of each contact carried to
// the next step as a warm start, and interleaved with the stems' strain limit. What the solve
// guarantees is only that a held pair's gap along its normal ends the step at the resting
// distance (or opening towards it): the exact machinery of the step (feather_coat_simulation.h)
// still answers every pair, and a held pair leaves its search only where a plane provably keeps
// it apart over the step (separatedThroughStep along the contact's normal).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "hirsute/hairs/dynamics/step_state.h"

namespace hirsute::dynamics {

// A pair found within the thickness at the start of a step: the gap between its primitives is
// sum c_k x_k over four vertices (the first primitive's side positive), the closest points'
// combination at the start.
struct NearPair {
  std::array<int, 2>
      primitives{};  // the key: indices into the coat's primitive list, first < second
  std::array<int, 4> vertices{};
  std::array<double, 4> coefficients{};
  // The coat's layer order (feathers are placed bottom to top): +1 where the first primitive's
  // feather lies over the second's, -1 under it, 0 within one feather or against the body.
  int layerSign = 0;
  // Where layerSign is not 0: the way from the lower feather to the upper one (the lower
  // feather's outward normal there), the normal of a pair whose gap vanishes.
  Eigen::Vector3d layerNormal = Eigen::Vector3d::Zero();
};

struct RestingContact {
  std::array<int, 2> primitives{};
  std::array<int, 4> vertices{};
  std::array<double, 4> coefficients{};
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // from the second primitive to the first
  double target = 0;      // the gap along the normal the solve holds at the end of the step
  double multiplier = 0;  // the position impulse (mass times length) the last solve applied
  int layerSign = 0;
  int steps = 0;  // the steps the pair has been held, this one included
};

// A stem segment whose length the solve keeps within the strain limit (feather_stem.h's
// limitStrain, applied to the step's end positions between the contacts' sweeps).
struct StrainSegment {
  std::array<int, 2> vertices{};
  double restLength = 0;
};

struct RestingOptions {
  double thickness = 0.01;      // pairs nearer than this at the start of a step are held
  double restDistance = 0.006;  // the gap a held pair is kept at
  double openingRate = 0.25;    // the part of (thickness - gap) a pair under the resting distance
                                // opens a step, as the repulsion it replaces
  int sweeps = 4;               // Gauss-Seidel sweeps over the contacts
  double strainLimit = 0.01;    // the stems' (StemParameters::strainLimit)
};

class RestingContacts {
 public:
  // Makes `near` (the pairs within the thickness at the start of the step, as `state.start`
  // places them) the step's set: each pair takes its normal from its gap at the start, or where
  // the gap vanishes the normal it was held with (oriented by the layer order for a new one),
  // and a pair held in the last step keeps its multiplier as the warm start.
  void update(std::vector<NearPair> near, const StepState& state, const RestingOptions& options);
  // Holds the set at the resting distance on `state.end`: the warm start, then sweeps over the
  // contacts, each followed by one over `segments` (the strain limit), the contacts last.
  // Returns the number of projections that moved a vertex.
  std::size_t solve(StepState& state, const std::vector<StrainSegment>& segments,
                    const RestingOptions& options);
  // The contact held for the pair, or none.
  const RestingContact* find(int first, int second) const;
  const std::vector<RestingContact>& contacts() const { return contacts_; }
  std::size_t size() const { return contacts_.size(); }
  void clear() { contacts_.clear(); }

 private:
  std::vector<RestingContact> contacts_;  // sorted by key
};

}  // namespace hirsute::dynamics
