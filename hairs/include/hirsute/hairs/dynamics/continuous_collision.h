// Continuous collision detection between primitives whose vertices move linearly over a time
// step: a vertex against a triangle and an edge against an edge (docs/design.md, "Feather-coat
// dynamics"; docs/dynamics.md, "Continuous collision detection").
//
// Method: inclusion-based bisection over the contact parameters (Wang, Ferguson, Schneider, Jiang,
// Attene & Panozzo 2021, "A large scale benchmark and an inclusion-based algorithm for continuous
// collision detection"). With t the time and u, v the positions on the two primitives,
//   edge-edge:   F(t,u,v) = a0(t) + u (a1(t) - a0(t)) - b0(t) - v (b1(t) - b0(t)),
//   vertex-face: F(t,u,v) = p(t) - f0(t) - u (f1(t) - f0(t)) - v (f2(t) - f0(t)),  u + v <= 1,
// and the primitives touch at time t exactly where F(t,u,v) = 0 for some u, v in the domain.
// F is of degree one in each of t, u and v, so over a box of parameters each coordinate of F
// takes its extremes at the box's eight corners. A box is discarded when some coordinate of F
// over it stays outside [-eta, eta]. Time is searched in slabs, earliest first (halving [0, 1]
// depth first, the earlier half first); within a slab the (u, v) square is halved until a box
// survives whose F changes along u and v no more than along t (or than the tolerance), or every
// box is discarded and with it the slab. A slab with a surviving box is halved in time, its
// halves searching only the (u, v) boxes it left, until F changes along t by less than the
// tolerance over the surviving box: that slab's start is the time of impact.
//
// Guarantee (conservative): the corner values are rounded, and each is widened by a proven
// bound on its rounding error (Higham 2002, Sec. 3.1: an expression of k rounded operations is
// within gamma_k = k u / (1 - k u) times the same expression on absolute values), so a box is
// discarded only when exact arithmetic would discard it. Hence no contact is ever missed:
// whenever the primitives come within eta in every coordinate at some t in [0, 1] (and so
// whenever their Euclidean distance is at most eta), `contact` is true, and `timeOfImpact` is at
// most the earliest such t, since every slab before it was discarded. Degenerate queries need no
// special case: coplanar motion, parallel edges, contact at t = 0 or t = 1, zero-length motion and
// degenerate primitives are all boxes of the same test. Conversely a reported contact means the
// primitives came within eta + 3 tolerance + twice the rounding bound in every coordinate (F
// spreads over the accepted box by at most its changes along t, u and v), unless the check budget
// ran out first (then `budgetExhausted`, and the contact is reported at the start of the slab being
// searched, to stay conservative).
#pragma once

#include <Eigen/Core>
#include <array>

namespace hirsute::dynamics {

// Four vertices moving linearly from `start` (t = 0) to `end` (t = 1). Vertex-face: [0] is the
// vertex, [1..3] the triangle. Edge-edge: [0], [1] are the first edge's ends, [2], [3] the
// second's.
struct MovingPrimitives {
  std::array<Eigen::Vector3d, 4> start{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                       Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<Eigen::Vector3d, 4> end = start;
};

struct CcdOptions {
  // eta >= 0: the minimum separation. A contact is any t at which the primitives come within eta
  // of each other in every coordinate.
  double minimumSeparation = 0;
  // The resolution of the search, relative to the largest coordinate span of the query's
  // vertices: a box over which F changes less than this along each parameter is a contact, so it
  // bounds how near a near miss may come and still be reported (3 times this).
  double relativeTolerance = 1e-6;
  // Boxes examined before giving up and reporting a contact at the earliest remaining time.
  int maxChecks = 100000;
};

struct CcdResult {
  bool contact = false;
  // When `contact`: a time in [0, 1] no later than the first contact.
  double timeOfImpact = 1;
  int checks = 0;                // boxes examined
  bool budgetExhausted = false;  // the contact is reported because maxChecks ran out
};

CcdResult vertexFaceCcd(const MovingPrimitives& motion, const CcdOptions& options = {});

// Whether the primitives of `motion` stay farther apart over the whole step than any contact the
// CCD with `options` may report (vertex-face when `vertexFace`, else edge-edge): true only for a
// query the CCD answers with no contact (one it reports because its budget ran out aside). Over
// the step each primitive stays in the hull of its vertices at both ends, so where the two hulls'
// projections on a direction lie farther apart than a contact's reach along it (eta, the
// tolerance's three steps and the rounding bounds, times the direction's 1-norm), nothing meets.
// The directions: the face's normal (or the edges' common normal) at the start, the middle and
// the end of the step, and the line between the primitives' centres at the start. A few dozen
// multiplications that decide most candidates of a layered coat, whose vanes lie a plane's width
// apart with boxes that overlap.
bool separatedOverStep(const MovingPrimitives& motion, bool vertexFace,
                       const CcdOptions& options = {});
// The same question answered along the same directions (and `direction`, where given: a resting
// contact's normal) at each end of the step on its own: each vertex moves linearly, so along a
// fixed direction the projections of two vertices, one of each primitive, that keep their order
// beyond the reach at both ends keep it throughout. Decides more than separatedOverStep (a pair
// held apart while both sides move far over the step), but only of this one step's motion: a
// list kept over several steps needs the hulls of separatedOverStep.
bool separatedThroughStep(const MovingPrimitives& motion, bool vertexFace,
                          const CcdOptions& options = {},
                          const Eigen::Vector3d* direction = nullptr);
CcdResult edgeEdgeCcd(const MovingPrimitives& motion, const CcdOptions& options = {});

}  // namespace hirsute::dynamics
