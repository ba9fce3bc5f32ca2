// A static coat laid shingled (docs/feathers.md, "Shingling"): the stage of the pipeline after
// the feathers' that lays every coat feather on the layer beneath it (coat_deintersection.h), so
// that `render`, `export`, `view` and the tracer draw a coat whose feathers rest on one another
// instead of passing through. The coat is laid from its bottom feather to its top one, the order
// the coat is placed and drawn in (feather_coats.h); each lifted feather gets the pose that bends
// it as its laid stem (FeatherPart::poses), the others keep their frames and their instances.
#pragma once

#include <cstddef>

#include "hirsute/core/progress.h"
#include "hirsute/hairs/dynamics/coat_deintersection.h"
#include "hirsute/hairs/organ_stage.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::dynamics {

struct ShinglingOptions {
  int segments = 8;  // of each feather's stem (the view file's `dynamics segments:`)
  int threads = 0;   // that build the stems (0: one per core); the result is the same on any
  LayingParameters laying;
  Progress* progress = nullptr;
};

struct ShinglingReport {
  std::size_t feathers = 0;       // coat feathers laid
  std::size_t lifted = 0;         // of those, lifted or bent off the layer beneath
  std::size_t intersections = 0;  // pairs of stem and vane primitives still meeting
  std::size_t unresolved = 0;     // feathers with some of those
  std::size_t leftAsGrown = 0;    // feathers past the pair-test limit, not laid
  double largestLift = 0;         // degrees: the most a stem's segment turned from its groom
  std::uint64_t pairTests = 0;
};

// Lays the coat feathers of `scene` (FeatherOrigin::Coat, in their order) on the body (every
// triangle mesh) and on each other, and sets the poses of those that moved; widens the
// feathers' bounds by where they went. Single feathers (@Fe, @Fi) are left as they are.
ShinglingReport shingleCoat(Scene& scene, const ShinglingOptions& options);

// The stage (organ_stage.h): after the feathers, when the scene has a coat; `--no-deintersect`
// (or the view file's `feather shingling: off`) leaves the groom as it grew.
const OrganStage& coatShinglingStage();

}  // namespace hirsute::dynamics
