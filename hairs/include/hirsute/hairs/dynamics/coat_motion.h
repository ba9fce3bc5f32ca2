// A model's feathers simulated frame by frame (docs/dynamics.md, "hirsute simulate"): what the
// `simulate` command and the viewer drive. The first frame's Scene gives the stems (one per
// feather) and the body (its triangle meshes); each root is bound to the body triangle it grows
// on by barycentric coordinates, so that when a later frame's Scene moves the body (a frame of
// the model's animation), the roots follow it; a root on no triangle follows its feather's own
// frame in the later Scene. The feathers are the first frame's throughout (a coat the later
// frames place anew on the moved body is not used); every frame the drawn Scene gets them, bent.
#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "hirsute/hairs/dynamics/feather_coat_simulation.h"
#include "hirsute/hairs/dynamics/feather_poses.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_settings.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::dynamics {

// The parameters a view file's `dynamics …:` lines give (docs/dynamics.md); the rest default.
SimulationParameters simulationParametersOf(const FeatherDynamicsSettings& view);

// A later frame that cannot carry on the simulation: other feathers, or a body of other
// triangles.
struct FrameMismatch : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Where a later frame puts the body's vertices and the roots (CoatMotion::targetOf): what a step
// moves them to, taken from the frame's Scene once, so that the Scene need not outlive it.
struct CoatTarget {
  std::vector<StemFrame> anchors;
  std::vector<Eigen::Vector3d> body;
};

class CoatMotion {
 public:
  CoatMotion(const Scene& first, const SimulationParameters& parameters);

  // Simulates `seconds` in `steps` equal steps (halved where a step is retried; the gold springs
  // hold at any step, docs/dynamics.md) while the body and the roots move linearly from where
  // they are to where `next` has them (null: they stay). `next` must have a body of the same
  // triangles and, when some roots are on no triangle, the first frame's feathers (as many),
  // else FrameMismatch. A step that cannot be resolved throws StepFailure, the state left at the
  // last step that could.
  void advance(double seconds, int steps, const Scene* next = nullptr);
  // The same with the body and the roots moving to `target` (targetOf a later frame).
  void advance(double seconds, int steps, const CoatTarget& target);
  // Where `next` puts the body and the roots; FrameMismatch as advance.
  CoatTarget targetOf(const Scene& next) const;

  // Gives `scene` (the frame drawn) the first frame's feathers, each bent as its stem is now
  // (FeatherPart::poses).
  void pose(Scene& scene) const;

  const FeatherCoatSimulation& simulation() const { return simulation_; }
  // Roots bound to a body triangle.
  std::size_t boundRoots() const;
  // Intersections in the current state, by the exact check (0 after every accepted step).
  std::size_t penetrations() const;
  // Vanes that meet other vanes or stems in the current state, by the exact check
  // (countVaneIntersections): 0 after every accepted step when the vanes collide.
  std::size_t vaneIntersections() const;

 private:
  FeatherCoatSimulation simulation_;
  std::vector<BodyAnchor> bound_;
  std::vector<Feather> feathers_;  // the first frame's
  Bounds featherBounds_;
};

}  // namespace hirsute::dynamics
