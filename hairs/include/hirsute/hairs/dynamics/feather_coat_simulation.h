// A feather coat in motion (docs/design.md, "Feather-coat dynamics"; docs/dynamics.md, "The
// simulator"): stems of particles (feather_stem.h) anchored to moving frames, under gravity, drag
// and gusty wind, colliding continuously with each other and with a body mesh, and never left
// in a state with an intersection.
//
// One step of length h (the study's Sec. 3.3.3, after Bridson, Fedkiw & Anderson 2002):
//   1. frames rebuilt from the positions (Sec. 3.2); half a step of velocity with the gold springs
//      implicit and gravity, drag and wind explicit: v^{n+1/2};
//   2. candidate positions x^{n+1} = x^n + h v^{n+1/2}, the anchors at their new frames;
//   3. strain limiting from the anchor to the tip, its corrections added to v^{n+1/2};
//   4. resting contacts (resting_contacts.h): pairs closer than the thickness at x^n join the
//      contact set kept from step to step and are held at the resting distance by a
//      position-level solve of x^{n+1}, interleaved with strain limiting (with the stage off:
//      repulsion, impulses that stop such pairs approaching, kept apart from the internal forces);
//   5. continuous collisions over x^n -> x^{n+1}: candidates from swept boxes (box_tree.h: a
//      list kept over several searches, less the pairs a plane keeps apart; a held pair is
//      passed over where its contact's normal, or another plane, keeps it apart at both ends
//      of the step: separatedThroughStep), the CCD of
//      continuous_collision.h on each, inelastic impulses in time-of-impact order,
//      repeated a few passes; then rigid impact zones (Provot 1997) until no contact within a
//      quarter of the minimum separation is left (the CCD's separation is a box, wider than a
//      ball of it, and a zone cannot open a gap it holds);
//   6. the exact check of the final state (static_intersection.h); a state that fails it, or a
//      step whose collisions cannot be resolved, is thrown away and the step is retried as two
//      halves, counted in `retries`;
//   7. the other half step of velocity at x^{n+1}: v^{n+1}.
//
// Each stem is its rachis polyline and, where it carries one, its vane (stem_vane.h: a ribbon of
// triangles either side, its corners carried by the nodes), kept at `thickness` from other stems
// and vanes by repulsion, aimed at `minimumSeparation` by the impulses and never closer than a
// quarter of it. The body meets the rachis, not the vane.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "hirsute/hairs/dynamics/box_tree.h"
#include "hirsute/hairs/dynamics/feather_stem.h"
#include "hirsute/hairs/dynamics/resting_contacts.h"
#include "hirsute/hairs/dynamics/stem_vane.h"
#include "hirsute/hairs/dynamics/wind_field.h"
#include "hirsute/hairs/dynamics/worker_pool.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::dynamics {

// The body the feathers collide with: triangles over shared vertices. Its vertices move with
// each step (FeatherCoatSimulation::step); its triangles stay.
struct BodyMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

// Every triangle mesh of a Scene as one body.
BodyMesh bodyMeshOf(const Scene& scene);

struct SimulationParameters {
  StemParameters stem;
  int segmentsPerFeather = 8;            // for stems built from a Scene's feathers
  Eigen::Vector3d gravity{0, 0, -9.81};  // acceleration
  double dragCoefficient = 0.05;         // force per unit length per unit speed
  WindParameters wind;                   // the air the drag is relative to
  double thickness = 0.01;               // repulsion keeps stems this far apart
  double minimumSeparation = 0.002;      // eta of the CCD: impulses keep this, zones a quarter
  double repulsionRate = 0.25;           // the part of a too-near gap closed a step
  int impulsePasses = 4;                 // CCD and impulse passes before zones
  int zoneIterations = 64;               // rigid impact zone passes before a retry
  int maxHalvings = 8;                   // a step is halved at most this many times
  // Stems that carry a vane (FeatherStem::vaneWidths) collide with it: vanes of different
  // feathers, and a vane and another feather's stem, are kept apart as stems are, and the final
  // check holds them to it. Off: the vanes follow their stems' frames and may pass through.
  bool vaneCollisions = false;
  // Whether the vanes that overlap where the coat is placed are found (a search of every vane,
  // some 1 CPU s for 2 000 feathers), to be left out of the vanes' collisions and of their count
  // (countVaneIntersections): always where the vanes collide; with them off, only for a count.
  bool findVaneOverlaps = false;
  // Threads of the step's parallel loops (the stems' dynamics and wind, the broad phase's
  // searches, the CCD of the candidates, the final checks); 0: one per core. The results are the
  // same bit for bit whatever the number.
  int threads = 0;
  // The step's searches for candidates filter a list of the pairs whose boxes, grown by this
  // much, overlap, until a primitive moves farther than this from where the list was made
  // (BoxTree::coherentPairs): more makes longer lists, made less often. The pairs found do not
  // depend on it.
  double candidateSlack = 0.01;
  // Whether a search of the step takes the CCD's answer of a pair from the step's last search at
  // the same separation where none of the pair's vertices has moved since (the same question):
  // the same results bit for bit, with less work in a coat whose vanes lie in layers.
  bool keepAnswers = true;
  // The resting stage (resting_contacts.h; docs/dynamics.md, "Resting contacts"): the pairs
  // within the thickness at the start of a step are kept from step to step and held at
  // restDistance() by a position-level solve of `restingSweeps` Gauss-Seidel sweeps, in place of
  // the repulsion's impulses. Off: the repulsion alone, every contact the CCD's. Either way the
  // continuous collisions and the final check hold every accepted state to the same guarantee.
  bool restingContacts = true;
  int restingSweeps = 4;
  // The gap a resting contact is held at: halfway between the separation and the thickness, so
  // that the plane test of the collisions' search (farther than the separation times up to
  // sqrt(3), the CCD's box) passes it over with room for the step's motion.
  double restDistance() const { return 0.5 * (thickness + minimumSeparation); }
};

// What the simulation did, summed over all steps since it was built.
struct SimulationCounters {
  std::uint64_t steps = 0;           // calls of step()
  std::uint64_t substeps = 0;        // steps accepted, halves of retried steps included
  std::uint64_t candidates = 0;      // pairs whose swept boxes overlapped
  std::uint64_t contacts = 0;        // candidates the CCD found in contact
  std::uint64_t impulses = 0;        // inelastic impulses applied
  std::uint64_t repulsions = 0;      // repulsion impulses applied
  std::uint64_t impactZones = 0;     // rigid impact zones formed
  std::uint64_t retries = 0;         // steps thrown away and retried as two halves
  std::uint64_t penetrations = 0;    // intersections found by the final check (then retried)
  std::uint64_t keptNear = 0;        // pairs the impulses left within the separation, but clear
                                     // of the zones' over the step
  std::uint64_t calamiLeft = 0;      // pairs with a calamus the impulses left within the separation
  std::uint64_t calamiCrossed = 0;   // pairs with a calamus that met or passed through each other
                                     // in a step tried (retried as halves, or at the smallest
                                     // step put into impact zones)
  std::uint64_t calamiZoned = 0;     // of those, put into impact zones at the smallest step
  std::uint64_t vaneCandidates = 0;  // of the candidates, pairs with a vane's primitive
  std::uint64_t vaneContacts = 0;    // of the contacts, pairs with a vane's primitive
  std::uint64_t vanePenetrations = 0;  // of the penetrations, vanes' (stem_vane.h)
  std::uint64_t keptAnswers = 0;       // candidates answered as at an earlier search of their step
  // The resting stage and the cost of the collisions' net (docs/dynamics.md, "Resting contacts").
  std::uint64_t restingContacts = 0;  // resting contacts held, summed over the steps tried
  std::uint64_t restingMoves = 0;     // projections of the resting solve that moved vertices
  std::uint64_t searches = 0;         // searches for candidate pairs (repulsion's included)
  std::uint64_t searchedPairs = 0;    // the pairs those searches found
  std::uint64_t ccdQueries = 0;       // pairs handed to the CCD (the plane tests' and the kept
                                      // answers' aside)
  std::uint64_t netContacts = 0;      // contacts the first search of a step still finds: what got
                                      // past the resting stage (or the repulsion)
};

// A step that could not be resolved even at the smallest time step: the state is left as it
// was before the step.
struct StepFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Which primitives of a state intersect: stem segments through body triangles (exact), and stem
// segments that meet or come nearer than `minimumDistance` to each other (segments of one stem
// that share a node excepted). A stem's first segment, its calamus, whose root lies on the body,
// is not tested: the body places the roots, and where its bend brings two roots together the
// simulation cannot keep their calami apart; against other stems' segments a calamus is kept
// from crossing by the steps' continuous check (`SimulationCounters::calamiCrossed`), and the
// impulses keep it off them where they can (`calamiLeft` counts where they did not).
std::size_t countPenetrations(const std::vector<FeatherStem>& stems, const BodyMesh& body,
                              double minimumDistance);
// The same searching in `tree`, refitted from the last search where it can be (and its pool's
// threads testing the pairs); with a `slack`, filtering the tree's kept list of the pairs whose
// boxes grown by it overlap (BoxTree::coherentPairs).
std::size_t countPenetrations(const std::vector<FeatherStem>& stems, const BodyMesh& body,
                              double minimumDistance, BoxTree& tree, double slack = 0);

class FeatherCoatSimulation {
 public:
  FeatherCoatSimulation(std::vector<FeatherStem> stems, BodyMesh body,
                        const SimulationParameters& parameters);
  // Every feather of the Scene as a stem, the Scene's meshes as the body.
  static FeatherCoatSimulation fromScene(const Scene& scene,
                                         const SimulationParameters& parameters);

  // Advances by `dt` seconds, the anchors (one per stem) moving linearly from their frames at
  // the start of the step to `anchors`. Throws StepFailure when the step cannot be resolved.
  void step(double dt, const std::vector<StemFrame>& anchors);
  // The same while the body's vertices move linearly from where they are to `bodyVertices` (one
  // per vertex of body().vertices): the body is kinematic, what it hits gives way.
  void step(double dt, const std::vector<StemFrame>& anchors,
            const std::vector<Eigen::Vector3d>& bodyVertices);
  // The same with the anchors and the body where they are.
  void step(double dt);

  const std::vector<FeatherStem>& stems() const { return stems_; }
  // For setting up a state (displacing or launching a stem); the next step starts from it.
  FeatherStem& stem(std::size_t i) { return stems_[i]; }
  const std::vector<StemFrame>& anchors() const { return anchors_; }
  const BodyMesh& body() const { return body_; }
  const SimulationCounters& counters() const { return counters_; }
  const SimulationParameters& parameters() const { return parameters_; }
  // The separation of the impact zones: no accepted state has two stems, or a stem and the
  // body, nearer than this (a quarter of the minimum separation the impulses keep).
  double nearestAllowed() const { return 0.25 * parameters_.minimumSeparation; }
  double time() const { return time_; }
  // The pairs of segments whose vanes are left out of each other's collisions: they met when the
  // simulation was built, and have not yet come apart (stem_vane.h).
  const VaneOverlaps& vaneOverlaps() const { return vaneOverlaps_; }
  std::size_t vaneOverlapsAtStart() const { return vaneOverlapsAtStart_; }
  // The resting contacts held in the last step accepted (resting_contacts.h).
  const RestingContacts& restingContacts() const { return resting_; }
  // Takes back into the collisions the pairs of vanes left out that have come apart by more
  // than the minimum separation (CoatMotion does so after each frame); returns how many.
  std::size_t releaseVaneOverlaps();

 private:
  // Where the anchors and the body's vertices are at the start or the end of a (sub)step.
  struct Kinematics {
    std::vector<StemFrame> anchors;
    std::vector<Eigen::Vector3d> body;
  };
  // One step of h; false, with failure_ saying why, when it must be done again as two halves.
  // `smallest`: the step cannot be halved again (a calamus crossing is then accepted, counted).
  bool advance(double h, const Kinematics& from, const Kinematics& to, bool smallest);
  void advanceOrHalve(double h, const Kinematics& from, const Kinematics& to, int depth);
  std::vector<Eigen::Vector3d> externalForces(std::size_t stem);

  std::vector<FeatherStem> stems_;
  BodyMesh body_;
  std::vector<std::array<int, 2>> bodyEdges_;
  SimulationParameters parameters_;
  WindField wind_;
  // The air last sampled at each node: a step's second half samples it where and when the next
  // step's first half does, and the gust field costs more than the rest of the forces.
  struct AirSample {
    Eigen::Vector3d position, air;
    double time = -1;
  };
  std::vector<std::vector<AirSample>> air_;
  std::vector<StemFrame> anchors_;
  std::string failure_;               // why the last advance() failed, for the error of a step
  std::unique_ptr<WorkerPool> pool_;  // on the heap: the trees point to it
  // The broad phase of the steps' collisions and of the final checks: each refits its trees
  // to the next search of the same primitives.
  BoxTree stepTree_, checkTree_, vaneTree_;
  VaneOverlaps vaneOverlaps_;
  std::uint64_t vaneOverlapsVersion_ = 0;  // counts the releases: which pairs are tested
  std::size_t vaneOverlapsAtStart_ = 0;
  // Kept from step to step; saved and restored with the stems when a step is retried.
  RestingContacts resting_;
  SimulationCounters counters_;
  double time_ = 0;
};

}  // namespace hirsute::dynamics
