// Continuous collision detection by inclusion-based bisection over (t, u, v), with every discard
// backed by a bound on the rounding error (continuous_collision.h states the guarantee).
#include "hirsute/hairs/dynamics/continuous_collision.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "hirsute/hairs/dynamics/closest_points.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

enum class Kind { VertexFace, EdgeEdge };

constexpr double kUnitRoundoff = 0x1p-53;
// Both F expressions take at most 7 rounded operations from the inputs to a corner value: d = end
// - start, x(t) = start + t d (3 along the path), then 4 more for the combination. On absolute
// values each is at most 18 M, M the largest |coordinate| on that axis (t, u, v in [0, 1]):
// |x(t)| <= 3 M, the two terms of either form 9 M each. gamma_7 < 7.01 u; 10 u leaves room for
// the rounding of the comparisons that use the bound.
constexpr double kErrorPerMagnitude = 10.0 * kUnitRoundoff * 18.0;
// Gradual underflow adds at most 2^-1075 absolute error an operation; this covers all of them.
constexpr double kUnderflowError = 0x1p-1060;
// Boxes are not halved below this width: every bound stays a multiple of 2^-40, so the midpoints
// and the vertex-face test u0 + v0 > 1 are exact in double.
constexpr double kMinimumWidth = 0x1p-40;

// A box of (u, v) within a slab of time [t0, t1].
struct Box {
  double t0, t1, u0, u1, v0, v1;
};

struct Query {
  std::array<Vector3d, 4> start, delta;
  Vector3d error;       // bound on the rounding error of one corner value, per axis
  double acceptChange;  // changes of F smaller than this along a parameter are resolved
  double eta;
};

Query prepare(const MovingPrimitives& motion, const CcdOptions& options) {
  if (!(options.minimumSeparation >= 0) || !std::isfinite(options.minimumSeparation)) {
    throw std::invalid_argument("the minimum separation must be a finite number >= 0");
  }
  if (!(options.relativeTolerance >= 0) || !std::isfinite(options.relativeTolerance)) {
    throw std::invalid_argument("the CCD tolerance must be a finite number >= 0");
  }
  Query q;
  Vector3d largest = Vector3d::Zero();
  Vector3d low = motion.start[0], high = motion.start[0];
  for (int i = 0; i < 4; ++i) {
    for (const Vector3d* x : {&motion.start[i], &motion.end[i]}) {
      if (!x->allFinite()) throw std::invalid_argument("a CCD vertex is not finite");
      largest = largest.cwiseMax(x->cwiseAbs());
      low = low.cwiseMin(*x);
      high = high.cwiseMax(*x);
    }
    q.start[i] = motion.start[i];
    q.delta[i] = motion.end[i] - motion.start[i];
  }
  q.error = (largest * kErrorPerMagnitude).array() + kUnderflowError;
  const double span = (high - low).maxCoeff();
  q.acceptChange = std::max(4.0 * q.error.maxCoeff(), options.relativeTolerance * span);
  q.eta = options.minimumSeparation;
  return q;
}

// F at the eight corners of the box, corner index 4 ti + 2 ui + vi, in the evaluation order the
// error bound counts.
template <Kind kind>
void cornerValues(const Query& q, const Box& box, std::array<Vector3d, 8>& values) {
  const double ts[2] = {box.t0, box.t1}, us[2] = {box.u0, box.u1}, vs[2] = {box.v0, box.v1};
  for (int ti = 0; ti < 2; ++ti) {
    Vector3d x[4];
    for (int i = 0; i < 4; ++i) x[i] = q.start[i] + ts[ti] * q.delta[i];
    if constexpr (kind == Kind::EdgeEdge) {
      const Vector3d alongA = x[1] - x[0], alongB = x[3] - x[2];
      for (int ui = 0; ui < 2; ++ui) {
        const Vector3d onA = x[0] + us[ui] * alongA;
        for (int vi = 0; vi < 2; ++vi)
          values[4 * ti + 2 * ui + vi] = onA - (x[2] + vs[vi] * alongB);
      }
    } else {
      const Vector3d fromCorner = x[0] - x[1], edgeU = x[2] - x[1], edgeV = x[3] - x[1];
      for (int ui = 0; ui < 2; ++ui) {
        const Vector3d partial = fromCorner - us[ui] * edgeU;
        for (int vi = 0; vi < 2; ++vi) values[4 * ti + 2 * ui + vi] = partial - vs[vi] * edgeV;
      }
    }
  }
}

// Whether some axis of F over the box (the corners' hull, widened by the rounding bound) misses
// [-eta, eta]: then no point of the box is a contact, in exact arithmetic too.
bool discarded(const Query& q, const std::array<Vector3d, 8>& values) {
  for (int k = 0; k < 3; ++k) {
    double lo = values[0][k], hi = values[0][k];
    for (int c = 1; c < 8; ++c) {
      lo = std::min(lo, values[c][k]);
      hi = std::max(hi, values[c][k]);
    }
    if (lo - q.error[k] > q.eta || hi + q.error[k] < -q.eta) return true;
  }
  return false;
}

// How much F changes along t, u and v over the box: the largest difference between two corners
// that differ in that parameter alone, over the axes. F is multilinear, so its spread over the
// box is at most the sum of the three.
std::array<double, 3> changes(const std::array<Vector3d, 8>& values) {
  constexpr int kStrides[3] = {4, 2, 1};
  std::array<double, 3> result{0, 0, 0};
  for (int p = 0; p < 3; ++p) {
    for (int c = 0; c < 8; ++c) {
      if (c & kStrides[p]) continue;
      result[p] = std::max(result[p], (values[c + kStrides[p]] - values[c]).cwiseAbs().maxCoeff());
    }
  }
  return result;
}

// A box of (u, v) parameters.
struct ParameterBox {
  double u0, u1, v0, v1;
};

// How far the corners on the upper (or lower) side of the parameter of this stride lie from
// zero: the largest, over the axes, of the gap between their hull and 0. A heuristic only.
double gapOfCorners(const std::array<Vector3d, 8>& values, int stride, bool upper) {
  double gap = 0;
  for (int k = 0; k < 3; ++k) {
    double lo = INFINITY, hi = -INFINITY;
    for (int c = 0; c < 8; ++c) {
      if (((c & stride) != 0) != upper) continue;
      lo = std::min(lo, values[c][k]);
      hi = std::max(hi, values[c][k]);
    }
    gap = std::max(gap, std::max(lo, -hi));
  }
  return gap;
}

// The search of one time slab: whether some (u, v) box over it may hold a contact, resolved in
// u and v until F changes there no more along u and v than along t (or than the tolerance).
// `boxes` holds the (u, v) boxes still to search, the next at the back; on a possible contact it
// keeps every box not yet discarded, the one found at the back, and on none it is empty. A box
// discarded over a slab is discarded over every part of it, so a slab's halves need search only
// what it left.
struct SlabAnswer {
  bool possible = false;
  double changeAlongT = 0;  // of the box found
};

template <Kind kind>
SlabAnswer searchSlab(const Query& q, double t0, double t1, std::vector<ParameterBox>& boxes,
                      int& checks, int maxChecks) {
  std::array<Vector3d, 8> values;
  while (!boxes.empty()) {
    if (checks >= maxChecks) return SlabAnswer{true, 0};  // out of budget: may still hold one
    const ParameterBox uv = boxes.back();
    if (kind == Kind::VertexFace && uv.u0 + uv.v0 > 1) {  // outside the triangle
      boxes.pop_back();
      continue;
    }
    ++checks;
    cornerValues<kind>(q, Box{t0, t1, uv.u0, uv.u1, uv.v0, uv.v1}, values);
    if (discarded(q, values)) {
      boxes.pop_back();
      continue;
    }
    const std::array<double, 3> change = changes(values);
    const double resolved = std::max(change[0], q.acceptChange);
    const bool splitU = uv.u1 - uv.u0 > kMinimumWidth && change[1] > resolved;
    const bool splitV = uv.v1 - uv.v0 > kMinimumWidth && change[2] > resolved;
    if (!splitU && !splitV) return SlabAnswer{true, change[0]};
    ParameterBox low = uv, high = uv;
    const bool alongU = splitU && (!splitV || change[1] >= change[2]);
    if (alongU) {
      low.u1 = high.u0 = 0.5 * (uv.u0 + uv.u1);
    } else {
      low.v1 = high.v0 = 0.5 * (uv.v0 + uv.v1);
    }
    // The half whose own corners come nearer to zero is searched first: it more likely holds
    // the contact, and the search stops at the first box that may.
    const int stride = alongU ? 2 : 1;
    if (gapOfCorners(values, stride, true) < gapOfCorners(values, stride, false)) {
      std::swap(low, high);
    }
    boxes.back() = low;
    boxes.push_back(high);
  }
  return SlabAnswer{};
}

// Before a slab is halved: the boxes its search left untested (all but the one found, at the
// back) are tested over the whole slab once, and those discarded are dropped, so that neither
// half tests them again.
template <Kind kind>
void pruneOverSlab(const Query& q, double t0, double t1, std::vector<ParameterBox>& boxes,
                   int& checks) {
  std::array<Vector3d, 8> values;
  std::size_t kept = 0;
  for (std::size_t i = 0; i + 1 < boxes.size(); ++i) {
    const ParameterBox& uv = boxes[i];
    if (kind == Kind::VertexFace && uv.u0 + uv.v0 > 1) continue;
    ++checks;
    cornerValues<kind>(q, Box{t0, t1, uv.u0, uv.u1, uv.v0, uv.v1}, values);
    if (!discarded(q, values)) boxes[kept++] = uv;
  }
  boxes[kept++] = boxes.back();
  boxes.resize(kept);
}

// A time slab waiting its turn; its (u, v) boxes are arena[begin, end of arena).
struct PendingSlab {
  double t0, t1;
  std::size_t begin;
};

// Whether the primitives already lie within the separation where the step starts: F at t = 0
// and the (u, v) of their closest points, snapped to the grid of the boxes' bounds (so that u +
// v <= 1 is exact for a triangle), is within eta on every axis with its rounding bound to
// spare. Then the first contact is at 0, where the search would end too; found so, it costs a
// closest-point query instead of the hundreds of boxes that resolve F down to the tolerance
// about a contact (a pressed coat's contacts mostly start so).
template <Kind kind>
bool touchesAtStart(const Query& q) {
  const auto snapped = [](double x) {
    return std::floor(std::clamp(x, 0.0, 1.0) * 0x1p40) * 0x1p-40;
  };
  const std::array<Vector3d, 4>& x = q.start;
  Vector3d f;
  if constexpr (kind == Kind::EdgeEdge) {
    const auto [s, u] = closestOnSegments(x[0], x[1], x[2], x[3]);
    f = (x[0] + snapped(s) * (x[1] - x[0])) - (x[2] + snapped(u) * (x[3] - x[2]));
  } else {
    const std::array<double, 3> w = closestOnTriangle(x[0], x[1], x[2], x[3]);
    const double u = snapped(w[1]), v = std::min(snapped(w[2]), 1 - u);
    f = (x[0] - x[1]) - u * (x[2] - x[1]) - v * (x[3] - x[1]);
  }
  return ((f.cwiseAbs() + q.error).array() <= q.eta).all();
}

// Time slabs in increasing order of time (depth first, earlier half first): when a slab is
// accepted, every earlier one has been discarded, so its start is no later than the first
// contact. The later halves wait on a stack whose box lists lie end to end in one arena, so that
// the search allocates nothing once warm.
template <Kind kind>
CcdResult detect(const MovingPrimitives& motion, const CcdOptions& options) {
  const Query q = prepare(motion, options);
  CcdResult result;
  if (touchesAtStart<kind>(q)) {
    result.contact = true;
    result.timeOfImpact = 0;
    return result;
  }
  std::vector<ParameterBox> boxes = {ParameterBox{0, 1, 0, 1}}, arena;
  std::vector<PendingSlab> pending;
  double t0 = 0, t1 = 1;
  for (;;) {
    const SlabAnswer answer = searchSlab<kind>(q, t0, t1, boxes, result.checks, options.maxChecks);
    if (!answer.possible) {
      if (pending.empty()) return result;
      const PendingSlab next = pending.back();
      pending.pop_back();
      boxes.assign(arena.begin() + static_cast<std::ptrdiff_t>(next.begin), arena.end());
      arena.resize(next.begin);
      t0 = next.t0;
      t1 = next.t1;
      continue;
    }
    const bool exhausted = result.checks >= options.maxChecks;
    if (exhausted || answer.changeAlongT <= q.acceptChange || t1 - t0 <= kMinimumWidth) {
      result.contact = true;
      result.timeOfImpact = t0;
      result.budgetExhausted = exhausted;
      return result;
    }
    pruneOverSlab<kind>(q, t0, t1, boxes, result.checks);
    const double middle = 0.5 * (t0 + t1);
    pending.push_back(PendingSlab{middle, t1, arena.size()});
    arena.insert(arena.end(), boxes.begin(), boxes.end());
    t1 = middle;
  }
}

}  // namespace

CcdResult vertexFaceCcd(const MovingPrimitives& motion, const CcdOptions& options) {
  return detect<Kind::VertexFace>(motion, options);
}

namespace {

// The plane tests of separatedOverStep and separatedThroughStep: along each direction, the two
// primitives' projections lie farther apart than a contact's reach, over the hulls of both ends
// of the step (`eachEnd` false) or at each end on its own (`eachEnd` true).
bool separatedAlongDirections(const MovingPrimitives& motion, bool vertexFace,
                              const CcdOptions& options, bool eachEnd,
                              const Vector3d* extraDirection) {
  // The reach of a reported contact: F within eta + 2 err + 3 acceptChange in every coordinate
  // (continuous_collision.h), more where boxes stopped at the smallest width (their spread is
  // under 3 * 8 M 2^-40); err and acceptChange as prepare() finds them, over all axes.
  double largest = 0;
  Vector3d low = motion.start[0], high = motion.start[0];
  for (int i = 0; i < 4; ++i)
    for (const Vector3d* x : {&motion.start[i], &motion.end[i]}) {
      if (!x->allFinite()) return false;  // the CCD says what is wrong with it
      largest = std::max(largest, x->cwiseAbs().maxCoeff());
      low = low.cwiseMin(*x);
      high = high.cwiseMax(*x);
    }
  if (!(options.minimumSeparation >= 0) || !(options.relativeTolerance >= 0)) return false;
  const double error = largest * kErrorPerMagnitude + kUnderflowError;
  const double acceptChange =
      std::max(4.0 * error, options.relativeTolerance * (high - low).maxCoeff());
  // Also the rounding of the projections below (a few units in the last place of 1-norm times
  // largest coordinate, far under 1e-10 of it).
  const double reach =
      options.minimumSeparation + 2 * error + 3 * acceptChange + 1e-9 * largest + kUnderflowError;
  // The first primitive's vertices are [0, split), the second's [split, 4).
  const int split = vertexFace ? 1 : 2;
  // Whether the projections of the vertices in `ends` (start, end or both) lie apart.
  const auto apartAt = [&](const Vector3d& n, std::initializer_list<bool> ends) {
    double lowA = std::numeric_limits<double>::infinity(), highA = -lowA, lowB = lowA,
           highB = -lowA;
    for (int i = 0; i < 4; ++i)
      for (const bool atEnd : ends) {
        const double along = n.dot(atEnd ? motion.end[i] : motion.start[i]);
        if (i < split) {
          lowA = std::min(lowA, along);
          highA = std::max(highA, along);
        } else {
          lowB = std::min(lowB, along);
          highB = std::max(highB, along);
        }
      }
    const double needed = n.cwiseAbs().sum() * reach;
    return lowB - highA > needed ? 1 : lowA - highB > needed ? -1 : 0;
  };
  // Over the step each vertex moves linearly, so along a fixed direction the difference of the
  // projections of a vertex of each primitive is linear in time: where every such difference
  // keeps one sign beyond the reach at both ends, it does so throughout, and so do the convex
  // combinations that are the primitives' points (a condition weaker than the hulls' of both
  // ends lying apart, and still exact).
  const auto apartAlong = [&](const Vector3d& n) {
    if (!n.allFinite() || !(n.cwiseAbs().sum() > 0)) return false;
    if (!eachEnd) return apartAt(n, {false, true}) != 0;
    const int atStart = apartAt(n, {false});
    return atStart != 0 && apartAt(n, {true}) == atStart;
  };
  const auto at = [&](int i, double t) -> Vector3d {
    return motion.start[i] + t * (motion.end[i] - motion.start[i]);
  };
  if (extraDirection != nullptr && apartAlong(*extraDirection)) return true;
  for (double t : {0.0, 0.5, 1.0}) {
    const Vector3d n = vertexFace ? (at(2, t) - at(1, t)).cross(at(3, t) - at(1, t))
                                  : (at(1, t) - at(0, t)).cross(at(3, t) - at(2, t));
    if (apartAlong(n)) return true;
  }
  Vector3d centreA = Vector3d::Zero(), centreB = Vector3d::Zero();
  for (int i = 0; i < 4; ++i) (i < split ? centreA : centreB) += motion.start[i];
  return apartAlong(centreB / (4 - split) - centreA / split);
}

}  // namespace

bool separatedOverStep(const MovingPrimitives& motion, bool vertexFace, const CcdOptions& options) {
  return separatedAlongDirections(motion, vertexFace, options, false, nullptr);
}

bool separatedThroughStep(const MovingPrimitives& motion, bool vertexFace,
                          const CcdOptions& options, const Eigen::Vector3d* direction) {
  return separatedAlongDirections(motion, vertexFace, options, true, direction);
}

CcdResult edgeEdgeCcd(const MovingPrimitives& motion, const CcdOptions& options) {
  return detect<Kind::EdgeEdge>(motion, options);
}

}  // namespace hirsute::dynamics
