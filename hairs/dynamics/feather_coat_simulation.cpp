// The feather-coat step: internal dynamics, repulsion, continuous collisions with impulses and
// rigid impact zones, the final check, and retries with halved steps.
#include "hirsute/hairs/dynamics/feather_coat_simulation.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <string>

#include "hirsute/hairs/dynamics/box_tree.h"
#include "hirsute/hairs/dynamics/closest_points.h"
#include "hirsute/hairs/dynamics/continuous_collision.h"
#include "hirsute/hairs/dynamics/resting_contacts.h"
#include "hirsute/hairs/dynamics/static_intersection.h"
#include "hirsute/hairs/dynamics/stem_vane.h"
#include "hirsute/hairs/dynamics/step_state.h"
#include "hirsute/hairs/feathers/feather_part.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// The kinds of collision primitives, in the order their boxes are listed. The vane's
// (stem_vane.h): its edges (the outer edge, the quad's diagonal and the edge from a node to its
// corner), its corners and its triangles.
enum class Kind : std::uint8_t {
  StemEdge,
  BodyEdge,
  StemNode,
  BodyTriangle,
  VaneEdge,
  VaneCorner,
  VaneTriangle
};

bool isTriangle(Kind k) {
  return k == Kind::BodyTriangle || k == Kind::VaneTriangle;
}
bool isVane(Kind k) {
  return k >= Kind::VaneEdge;
}
int vertexCountOf(Kind k) {
  return k == Kind::StemNode || k == Kind::VaneCorner ? 1 : isTriangle(k) ? 3 : 2;
}

struct Primitive {
  Kind kind;
  std::array<int, 3> vertices;  // global vertex indices (edges use two, nodes one)
  int stem = -1;                // the stem of a stem or vane primitive
  int segment = -1;             // a stem edge's segment, a stem node's node
  // The stem segments (with their vanes) the primitive belongs to, from `first` to `last`: a
  // node, a corner and the edge between them to the segments either side of the node.
  int first = -1, last = -1;
};

// A pair of primitives about to touch, as four vertices with coefficients c: the gap between them
// is sum c_k x_k (the vertex or first edge side positive), zero where they touch.
struct Contact {
  std::array<int, 4> vertices;
  std::array<double, 4> coefficients;
  double timeOfImpact = 0;
  bool vertexFace = false;          // a stem node and a body triangle, else two segments
  std::array<int, 2> primitives{};  // the pair, as indices of the primitive list
};

// The CCD's answers of a step's last search at one separation, and where the vertices' ends
// were then (their starts do not change within a step). A pair of a later search none of whose
// vertices has moved since, asked again, gets the same answer.
struct KeptAnswers {
  double separation = 0;
  std::vector<std::pair<int, int>> pairs;  // asked, sorted as the searches give them
  std::vector<std::pair<std::size_t, CcdResult>> contacts;  // by index into `pairs`, sorted
  std::vector<Vector3d> ends;

  static constexpr int kAsk = -2, kNoContact = -1;

  // For each of `asked` (sorted), its kept answer where it was asked before and none of its
  // vertices (`vertexSet`) has moved since: kNoContact, or its index in `contacts`; kAsk where
  // it must be asked.
  template <class VertexSet>
  std::vector<int> earlierOf(const std::vector<std::pair<int, int>>& asked,
                             const std::vector<Vector3d>& now, VertexSet vertexSet) const {
    std::vector<int> out(asked.size(), kAsk);
    if (ends.size() != now.size()) return out;
    std::vector<char> moved(now.size());
    for (std::size_t v = 0; v < now.size(); ++v) moved[v] = now[v] != ends[v];
    std::size_t j = 0, c = 0;
    for (std::size_t k = 0; k < asked.size(); ++k) {
      while (j < pairs.size() && pairs[j] < asked[k]) ++j;
      if (j == pairs.size()) break;
      if (pairs[j] != asked[k]) continue;
      const std::array<int, 4> v = vertexSet(asked[k].first, asked[k].second);
      if (moved[v[0]] || moved[v[1]] || moved[v[2]] || moved[v[3]]) continue;
      while (c < contacts.size() && contacts[c].first < j) ++c;
      out[k] = c < contacts.size() && contacts[c].first == j ? static_cast<int>(c) : kNoContact;
    }
    return out;
  }

  void keep(const std::vector<std::pair<int, int>>& asked, const std::vector<CcdResult>& answers,
            const std::vector<Vector3d>& now) {
    pairs = asked;
    contacts.clear();
    for (std::size_t k = 0; k < answers.size(); ++k)
      if (answers[k].contact) contacts.emplace_back(k, answers[k]);
    ends = now;
  }
};

// The collision primitives of the coat and the body over the global vertex numbering.
struct Primitives {
  std::vector<Primitive> list;
  std::vector<int> stemOffset;  // global index of each stem's node 0
  int bodyOffset = 0;
  int vaneOffset = 0;                        // global index of the first vane corner
  std::vector<std::array<int, 3>> corner;    // per vane corner: its stem, node and side
  std::vector<std::array<int, 2>> cornerOf;  // per stem node: its corners' global indices, or -1

  const VaneOverlaps* overlaps = nullptr;  // segment pairs whose vanes are left out

  Primitives(const std::vector<FeatherStem>& stems, const BodyMesh& body,
             const std::vector<std::array<int, 2>>& bodyEdges, bool vanes,
             const VaneOverlaps* leftOut)
      : overlaps(leftOut) {
    int offset = 0;
    for (const FeatherStem& stem : stems) {
      stemOffset.push_back(offset);
      offset += static_cast<int>(stem.nodeCount());
    }
    bodyOffset = offset;
    vaneOffset = bodyOffset + static_cast<int>(body.vertices.size());
    cornerOf.assign(bodyOffset, {-1, -1});
    if (vanes)
      for (int s = 0; s < static_cast<int>(stems.size()); ++s)
        for (int i = 0; i < static_cast<int>(stems[s].vaneWidths.size()); ++i)
          for (int side = 0; side < 2; ++side)
            if (hasVaneCorner(stems[s], i, side)) {
              cornerOf[stemOffset[s] + i][side] = vaneOffset + static_cast<int>(corner.size());
              corner.push_back({s, i, side});
            }
    for (int s = 0; s < static_cast<int>(stems.size()); ++s)
      for (int i = 0; i + 1 < static_cast<int>(stems[s].nodeCount()); ++i)
        list.push_back({Kind::StemEdge, {stemOffset[s] + i, stemOffset[s] + i + 1, -1}, s, i});
    for (const auto& e : bodyEdges)
      list.push_back({Kind::BodyEdge, {bodyOffset + e[0], bodyOffset + e[1], -1}, -1, -1});
    for (int s = 0; s < static_cast<int>(stems.size()); ++s)
      for (int i = 1; i < static_cast<int>(stems[s].nodeCount()); ++i)
        list.push_back({Kind::StemNode, {stemOffset[s] + i, -1, -1}, s, i});
    for (const auto& t : body.triangles)
      list.push_back(
          {Kind::BodyTriangle, {bodyOffset + t[0], bodyOffset + t[1], bodyOffset + t[2]}, -1, -1});
    if (corner.empty()) return;
    // The segments a stem primitive belongs to, as the vanes' check sees them (stem_vane.h): a
    // rachis segment other than the calamus, and the vane's quads.
    const auto spanOf = [&](Primitive& p, int node, int side) {
      const FeatherStem& stem = stems[p.stem];
      const auto holds = [&](int j) {
        if (j < 0 || j + 2 > static_cast<int>(stem.nodeCount())) return false;
        if (side >= 0) return hasVaneQuad(stem, j, side);
        return j >= 1 || hasVaneQuad(stem, j, 0) || hasVaneQuad(stem, j, 1);
      };
      p.first = holds(node - 1) ? node - 1 : node;
      p.last = holds(node) ? node : node - 1;
    };
    for (Primitive& p : list)
      if (p.kind == Kind::StemEdge)
        p.first = p.last = p.segment;
      else if (p.kind == Kind::StemNode)
        spanOf(p, p.segment, -1);
    // The vanes: edges, corners, triangles (in that order, after the rest).
    std::vector<std::vector<VaneTriangle>> triangles;
    for (const FeatherStem& stem : stems) triangles.push_back(vaneTrianglesOf(stem));
    const auto vertexOf = [&](int s, VaneVertex v) {
      return v.side < 0 ? stemOffset[s] + v.node : cornerOf[stemOffset[s] + v.node][v.side];
    };
    for (int s = 0; s < static_cast<int>(stems.size()); ++s) {
      for (const VaneTriangle& t : triangles[s]) {
        // The first triangle of a quad holds its diagonal (p_i, c_i+1), the second its outer
        // edge (c_i+1, c_i): each quad's edges once, the rachis being the stem's.
        const int a = vertexOf(s, t.vertices[0]), b = vertexOf(s, t.vertices[1]),
                  c = vertexOf(s, t.vertices[2]);
        const int j = t.segment;
        if (t.vertices[0].side < 0 && t.vertices[1].side < 0)
          list.push_back({Kind::VaneEdge, {a, c, -1}, s, j, j, j});
        else
          list.push_back({Kind::VaneEdge, {b, c, -1}, s, j, j, j});
      }
      for (int i = 0; i < static_cast<int>(stems[s].vaneWidths.size()); ++i)
        for (int side = 0; side < 2; ++side)
          if (const int c = cornerOf[stemOffset[s] + i][side]; c >= 0) {
            list.push_back({Kind::VaneEdge, {stemOffset[s] + i, c, -1}, s, i});
            spanOf(list.back(), i, side);
          }
    }
    for (int k = 0; k < static_cast<int>(corner.size()); ++k) {
      const auto& [s, i, side] = corner[k];
      list.push_back({Kind::VaneCorner, {vaneOffset + k, -1, -1}, s, i});
      spanOf(list.back(), i, side);
    }
    for (int s = 0; s < static_cast<int>(stems.size()); ++s)
      for (const VaneTriangle& t : triangles[s])
        list.push_back(
            {Kind::VaneTriangle,
             {vertexOf(s, t.vertices[0]), vertexOf(s, t.vertices[1]), vertexOf(s, t.vertices[2])},
             s,
             t.segment,
             t.segment,
             t.segment});
  }

  // The primitives' kinds as groups of the broad phase: the stems' move; stem edges meet stem
  // and body edges, stem nodes body triangles.
  BoxGroups groups() const {
    BoxGroups out;
    out.of.reserve(list.size());
    for (const Primitive& p : list) out.of.push_back(static_cast<std::uint8_t>(p.kind));
    const auto bit = [](Kind k) { return static_cast<std::uint8_t>(1u << static_cast<int>(k)); };
    out.pairsWith[static_cast<int>(Kind::StemEdge)] = bit(Kind::StemEdge) | bit(Kind::BodyEdge);
    out.pairsWith[static_cast<int>(Kind::BodyEdge)] = bit(Kind::StemEdge);
    out.pairsWith[static_cast<int>(Kind::StemNode)] = bit(Kind::BodyTriangle);
    out.pairsWith[static_cast<int>(Kind::BodyTriangle)] = bit(Kind::StemNode);
    out.moving = bit(Kind::StemEdge) | bit(Kind::StemNode);
    if (!corner.empty()) {
      // Vanes meet other feathers' vanes and stems, not the body (docs/dynamics.md, "Vanes").
      out.pairsWith[static_cast<int>(Kind::StemEdge)] |= bit(Kind::VaneEdge);
      out.pairsWith[static_cast<int>(Kind::StemNode)] |= bit(Kind::VaneTriangle);
      out.pairsWith[static_cast<int>(Kind::VaneEdge)] = bit(Kind::StemEdge) | bit(Kind::VaneEdge);
      out.pairsWith[static_cast<int>(Kind::VaneCorner)] = bit(Kind::VaneTriangle);
      out.pairsWith[static_cast<int>(Kind::VaneTriangle)] =
          bit(Kind::StemNode) | bit(Kind::VaneCorner);
      out.moving |= bit(Kind::VaneEdge) | bit(Kind::VaneCorner) | bit(Kind::VaneTriangle);
    }
    return out;
  }

  // The parts of the kept list (BoxTree::KeptList): each stem with its vane a part, the body
  // one; of the primitives and of the vertices.
  std::pair<std::vector<int>, std::vector<int>> parts() const {
    const int body = static_cast<int>(stemOffset.size());
    std::vector<int> ofPrimitive, ofVertex;
    ofPrimitive.reserve(list.size());
    for (const Primitive& p : list) ofPrimitive.push_back(p.stem >= 0 ? p.stem : body);
    for (int s = 0; s < body; ++s) {
      const int end = s + 1 < body ? stemOffset[s + 1] : bodyOffset;
      ofVertex.insert(ofVertex.end(), end - stemOffset[s], s);
    }
    ofVertex.insert(ofVertex.end(), vaneOffset - bodyOffset, body);
    for (const auto& c : corner) ofVertex.push_back(c[0]);
    return {std::move(ofPrimitive), std::move(ofVertex)};
  }

  // Whether the pair (a < b in list order) is tested: segments of different stems (but not two
  // first segments, whose roots the body moves) or of one stem that share no node; stem segments
  // against body edges and stem nodes against body triangles, except a stem's first segment,
  // whose root lies on the body.
  bool wanted(int a, int b) const {
    const Primitive &p = list[a], &q = list[b];
    // A vane meets the vanes and stems of other feathers (the groups say which kinds), unless
    // every pair of segments the two belong to is left out (their vanes overlapped from the
    // start and have not yet come apart).
    if (isVane(q.kind)) {
      // A calamus is left out: the bare base of the quill, in its follicle under the vanes of
      // the feathers around it.
      if (p.stem == q.stem || (p.kind == Kind::StemEdge && p.segment == 0)) return false;
      if (overlaps == nullptr || overlaps->empty()) return true;
      for (int x = p.first; x <= p.last; ++x)
        for (int y = q.first; y <= q.last; ++y)
          if (!overlaps->contains(overlaps->segmentIndex(p.stem, x),
                                  overlaps->segmentIndex(q.stem, y)))
            return true;
      return false;
    }
    if (p.kind == Kind::StemEdge && q.kind == Kind::StemEdge)
      return (p.stem != q.stem && (p.segment > 0 || q.segment > 0)) ||
             (p.stem == q.stem && std::abs(p.segment - q.segment) > 1);
    if (p.kind == Kind::StemEdge && q.kind == Kind::BodyEdge) return p.segment > 0;
    return p.kind == Kind::StemNode && q.kind == Kind::BodyTriangle;
  }

  // Whether the pair holds a stem's first segment, its calamus: the impulses keep calami off
  // other stems, but the zones and the final check leave them out. Its root is fixed to the
  // skin, and where the body's bend drives a calamus against a stem lying over it, a zone can
  // move neither of them away.
  bool holdsCalamus(int a, int b) const {
    return (list[a].kind == Kind::StemEdge && list[a].segment == 0) ||
           (list[b].kind == Kind::StemEdge && list[b].segment == 0);
  }

  // The boxes of every primitive over the step (from `start` to `end`), grown by `margin`.
  std::vector<Box> boxes(const StepState& state, double margin) const {
    std::vector<Box> out;
    out.reserve(list.size());
    for (const Primitive& p : list) {
      const int n = vertexCountOf(p.kind);
      Box box = boxOf({state.start[p.vertices[0]], state.end[p.vertices[0]]}, margin);
      for (int k = 1; k < n; ++k) {
        const Box more = boxOf({state.start[p.vertices[k]], state.end[p.vertices[k]]}, margin);
        box.min = box.min.cwiseMin(more.min);
        box.max = box.max.cwiseMax(more.max);
      }
      out.push_back(box);
    }
    return out;
  }

  // The pair as a contact at time t of the step, the coefficients from the closest points then.
  Contact contactAt(int a, int b, const StepState& state, double t) const {
    const Primitive &p = list[a], &q = list[b];
    auto at = [&](int v) -> Vector3d {
      return state.start[v] + t * (state.end[v] - state.start[v]);
    };
    Contact c;
    c.timeOfImpact = t;
    c.primitives = {a, b};
    if (isTriangle(q.kind)) {
      const auto w = closestOnTriangle(at(p.vertices[0]), at(q.vertices[0]), at(q.vertices[1]),
                                       at(q.vertices[2]));
      c.vertices = {p.vertices[0], q.vertices[0], q.vertices[1], q.vertices[2]};
      c.coefficients = {1, -w[0], -w[1], -w[2]};
      c.vertexFace = true;
    } else {
      const auto [s, u] = closestOnSegments(at(p.vertices[0]), at(p.vertices[1]), at(q.vertices[0]),
                                            at(q.vertices[1]));
      c.vertices = {p.vertices[0], p.vertices[1], q.vertices[0], q.vertices[1]};
      c.coefficients = {1 - s, s, -(1 - u), -u};
    }
    return c;
  }

  // The distance between a contact's two primitives at the start of the step.
  double distanceAtStart(const Contact& c, const StepState& state) const {
    const auto& x = state.start;
    const auto& v = c.vertices;
    if (c.vertexFace) {
      const auto w = closestOnTriangle(x[v[0]], x[v[1]], x[v[2]], x[v[3]]);
      return (x[v[0]] - (w[0] * x[v[1]] + w[1] * x[v[2]] + w[2] * x[v[3]])).norm();
    }
    const auto [s, u] = closestOnSegments(x[v[0]], x[v[1]], x[v[2]], x[v[3]]);
    return ((x[v[0]] + s * (x[v[1]] - x[v[0]])) - (x[v[2]] + u * (x[v[3]] - x[v[2]]))).norm();
  }

  // A vertex as a user finds it: "feather 12's node 3" or "body vertex 40".
  std::string vertexName(int v) const {
    if (v >= vaneOffset) {
      const auto& [s, node, side] = corner[v - vaneOffset];
      return "feather " + std::to_string(s) + "'s " + (side == 0 ? "left" : "right") +
             " vane corner at node " + std::to_string(node);
    }
    if (v >= bodyOffset) return "body vertex " + std::to_string(v - bodyOffset);
    const auto s = std::upper_bound(stemOffset.begin(), stemOffset.end(), v) - 1;
    return "feather " + std::to_string(s - stemOffset.begin()) + "'s node " +
           std::to_string(v - *s);
  }

  // The four vertices of a pair (a < b in list order): a node and a triangle, or two segments.
  std::array<int, 4> vertexSet(int a, int b) const {
    const Primitive &p = list[a], &q = list[b];
    return isTriangle(q.kind)
               ? std::array<int, 4>{p.vertices[0], q.vertices[0], q.vertices[1], q.vertices[2]}
               : std::array<int, 4>{p.vertices[0], p.vertices[1], q.vertices[0], q.vertices[1]};
  }

  MovingPrimitives motion(int a, int b, const StepState& state) const {
    const std::array<int, 4> v = vertexSet(a, b);
    MovingPrimitives m;
    for (int k = 0; k < 4; ++k) {
      m.start[k] = state.start[v[k]];
      m.end[k] = state.end[v[k]];
    }
    return m;
  }
};

// The unit normal of a contact: along the gap at time t, or, where the primitives touch, along
// the gap at the start of the step (an accepted state keeps them apart).
Vector3d contactNormal(const Contact& c, const StepState& state) {
  Vector3d gap = Vector3d::Zero(), gapAtStart = Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    const Vector3d& x0 = state.start[c.vertices[k]];
    gap += c.coefficients[k] * (x0 + c.timeOfImpact * (state.end[c.vertices[k]] - x0));
    gapAtStart += c.coefficients[k] * x0;
  }
  if (gap.norm() > 1e-12 * (1 + gapAtStart.norm())) return gap.normalized();
  if (gapAtStart.norm() > 0) return gapAtStart.normalized();
  return Vector3d::UnitZ();
}

// An impulse along `normal` that makes the gap's velocity along it at least `target` (per step:
// a change of the end positions), shared by inverse masses. Returns whether it was needed and
// possible.
// A vane corner's share goes to the node that carries it (the corner is the node plus an offset
// the impulse does not change), and the node's move moves its corners.
bool applyImpulse(const Contact& c, const Vector3d& normal, double target, StepState& state) {
  double approach = 0, weight = 0;
  std::array<int, 4> owners{};
  std::array<double, 4> shares{};
  int count = 0;
  for (int k = 0; k < 4; ++k) {
    approach +=
        c.coefficients[k] * normal.dot(state.end[c.vertices[k]] - state.start[c.vertices[k]]);
    const int owner = state.owner[c.vertices[k]];
    int j = 0;
    while (j < count && owners[j] != owner) ++j;
    if (j == count) owners[count++] = owner;
    shares[j] += c.coefficients[k];
  }
  for (int j = 0; j < count; ++j) weight += shares[j] * shares[j] * state.inverseMass[owners[j]];
  if (approach >= target || weight <= 0) return false;
  const double impulse = (target - approach) / weight;
  for (int j = 0; j < count; ++j)
    if (state.inverseMass[owners[j]] > 0)
      state.moveEnd(owners[j], impulse * shares[j] * state.inverseMass[owners[j]] * normal);
  return true;
}

int findRoot(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// The least-squares motion x0 -> x0 + shift + spin x (x0 - centre) of `vertices` over the step,
// each weighted by `weight(v)`: the centre's displacement and the spin that fits the rest.
struct ZoneMotion {
  Vector3d centre = Vector3d::Zero(), shift = Vector3d::Zero(), spin = Vector3d::Zero();
};

template <class Weight>
ZoneMotion fittedMotion(const std::vector<int>& vertices, const StepState& state, Weight weight) {
  ZoneMotion m;
  double total = 0;
  for (int v : vertices) {
    total += weight(v);
    m.centre += weight(v) * state.start[v];
    m.shift += weight(v) * (state.end[v] - state.start[v]);
  }
  m.centre /= total;
  m.shift /= total;
  Vector3d angular = Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (int v : vertices) {
    const Vector3d r = state.start[v] - m.centre;
    angular += weight(v) * r.cross(state.end[v] - state.start[v] - m.shift);
    inertia += weight(v) * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  // Collinear vertices have a singular inertia about their line: no spin about it.
  m.spin = inertia.completeOrthogonalDecomposition().solve(angular);
  return m;
}

// Provot 1997: the zone moves as one rigid body with the zone's momentum and angular momentum.
// Its motion over the step is x0 + (v_cm + w x (x0 - x_cm)) h, an affine map I + h [w]x of the
// relative positions that never shortens a distance (|r + h w x r|^2 = |r|^2 + h^2 |w x r|^2), so
// no two of its primitives come closer than at the start. A zone holding kinematic vertices
// (anchors, the body) cannot push them: its free vertices follow the motion of the same form
// fitted to the kinematic ones, exact when those move alike (a translation) and close to it over
// a short step of a body that turns or bends; the CCD that follows checks what that leaves.
ZoneMotion moveRigidly(const std::vector<int>& members, StepState& state) {
  std::vector<int> kinematic;
  for (int v : members)
    if (state.inverseMass[v] == 0) kinematic.push_back(v);
  const ZoneMotion m = kinematic.empty()
                           ? fittedMotion(members, state, [&](int v) { return state.weight(v); })
                           : fittedMotion(kinematic, state, [](int) { return 1.0; });
  for (int v : members)
    if (state.inverseMass[v] > 0)
      state.end[v] = state.start[v] + m.shift + m.spin.cross(state.start[v] - m.centre);
  return m;
}

// Where the zone's map takes the start of `v`.
Vector3d mapped(const ZoneMotion& m, const Vector3d& start) {
  return start + m.shift + m.spin.cross(start - m.centre);
}

// A zone held by kinematic vertices that do not move alike (a bending body) cannot open a gap
// between its free vertices and them by the fitted motion: the free vertices go on by one
// translation more (which keeps their own distances, as the rigid motion does), the least that
// opens each such contact by `opening` over the step along the gap it had at the start, at most
// `margin` longer than the longest kinematic move of the zone. Contacts it cannot open (the zone
// pinned between kinematic primitives on two sides) are left to the next round.
Vector3d liftOffKinematic(const std::vector<int>& members,
                          const std::vector<const Contact*>& contacts, double opening,
                          double margin, StepState& state) {
  double largest = margin;
  for (int v : members)
    if (state.inverseMass[v] == 0)
      largest = std::max(largest, margin + (state.end[v] - state.start[v]).norm());
  struct Need {
    Vector3d effect;  // the gap's change along its normal per unit of translation
    double missing;
  };
  std::vector<Need> needs;
  Vector3d direction = Vector3d::Zero();
  for (const Contact* c : contacts) {
    Vector3d gap = Vector3d::Zero();
    double freeShare = 0;
    bool holdsKinematic = false;
    for (int k = 0; k < 4; ++k) {
      const int v = c->vertices[k];
      gap += c->coefficients[k] * state.start[v];
      if (state.inverseMass[v] == 0)
        holdsKinematic = true;
      else
        freeShare += c->coefficients[k];
    }
    if (!holdsKinematic || !(gap.norm() > 0) || freeShare == 0) continue;
    const Vector3d normal = gap.normalized();
    double approach = 0;
    for (int k = 0; k < 4; ++k)
      approach +=
          c->coefficients[k] * normal.dot(state.end[c->vertices[k]] - state.start[c->vertices[k]]);
    if (approach >= opening) continue;
    const Vector3d effect = freeShare * normal;
    needs.push_back({effect, opening - approach});
    direction += (opening - approach) * effect.normalized();
  }
  if (needs.empty() || !(direction.norm() > 0)) return Vector3d::Zero();
  direction.normalize();
  double length = 0;
  for (const Need& need : needs) {
    const double along = need.effect.dot(direction);
    if (along > 0) length = std::max(length, need.missing / along);
  }
  const Vector3d shift = std::min(length, largest) * direction;
  for (int v : members)
    if (state.inverseMass[v] > 0) state.end[v] += shift;
  return shift;
}

}  // namespace

BodyMesh bodyMeshOf(const Scene& scene) {
  BodyMesh body;
  for (const TriangleMesh& mesh : scene.meshes) {
    const int base = static_cast<int>(body.vertices.size());
    for (const glm::vec3& p : mesh.positions) body.vertices.emplace_back(p.x, p.y, p.z);
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
      body.triangles.push_back({base + static_cast<int>(mesh.indices[i]),
                                base + static_cast<int>(mesh.indices[i + 1]),
                                base + static_cast<int>(mesh.indices[i + 2])});
  }
  return body;
}

std::size_t countPenetrations(const std::vector<FeatherStem>& stems, const BodyMesh& body,
                              double minimumDistance) {
  BoxTree tree;
  return countPenetrations(stems, body, minimumDistance, tree);
}

std::size_t countPenetrations(const std::vector<FeatherStem>& stems, const BodyMesh& body,
                              double minimumDistance, BoxTree& tree, double slack) {
  // Stem segments as (stem, segment) boxes, then body triangles.
  struct Item {
    int stem, segment, triangle;
  };
  std::vector<Item> items;
  std::vector<Box> boxes;
  for (int s = 0; s < static_cast<int>(stems.size()); ++s)
    for (int i = 0; i + 1 < static_cast<int>(stems[s].nodeCount()); ++i) {
      items.push_back({s, i, -1});
      boxes.push_back(boxOf({stems[s].positions[i], stems[s].positions[i + 1]}, minimumDistance));
    }
  for (int t = 0; t < static_cast<int>(body.triangles.size()); ++t) {
    const auto& tri = body.triangles[t];
    items.push_back({-1, -1, t});
    boxes.push_back(
        boxOf({body.vertices[tri[0]], body.vertices[tri[1]], body.vertices[tri[2]]}, 0));
  }
  std::vector<char> moving;
  for (const Item& item : items) moving.push_back(item.triangle < 0);
  const auto tested = [&](int a, int b) {
    const Item &p = items[a], &q = items[b];
    if (p.triangle >= 0) return false;  // triangles come last: a triangle pairs only as q
    if (q.triangle >= 0) return p.segment > 0;
    return p.segment > 0 && q.segment > 0 &&
           (p.stem != q.stem || std::abs(p.segment - q.segment) > 1);
  };
  BoxGroups groups;
  for (char m : moving) groups.of.push_back(m ? 0 : 1);
  groups.pairsWith = {0b11, 0b01};
  groups.moving = 1;
  std::vector<int> parts;  // each stem a part, the body one
  for (const Item& item : items)
    parts.push_back(item.triangle < 0 ? item.stem : static_cast<int>(stems.size()));
  BoxTree::KeptList list;
  list.slack = slack;
  list.tested = tested;
  list.boxParts = &parts;
  const auto pairs = slack > 0
                         ? tree.coherentPairs(boxes, groups, list, [](int, int) { return true; })
                         : tree.overlappingPairs(boxes, groups, tested);
  const auto meet = [&](int a, int b) {
    const Item &p = items[a], &q = items[b];
    const Vector3d& p0 = stems[p.stem].positions[p.segment];
    const Vector3d& p1 = stems[p.stem].positions[p.segment + 1];
    if (q.triangle >= 0) {
      const auto& tri = body.triangles[q.triangle];
      return segmentIntersectsTriangle(p0, p1, body.vertices[tri[0]], body.vertices[tri[1]],
                                       body.vertices[tri[2]]);
    }
    const Vector3d& q0 = stems[q.stem].positions[q.segment];
    const Vector3d& q1 = stems[q.stem].positions[q.segment + 1];
    const auto [s, u] = closestOnSegments(p0, p1, q0, q1);
    const double distance = ((p0 + s * (p1 - p0)) - (q0 + u * (q1 - q0))).norm();
    return segmentsIntersect(p0, p1, q0, q1) || distance < minimumDistance;
  };
  // Each pair into its own flag on the tree's threads.
  std::vector<char> meets(pairs.size(), 0);
  forEach(tree.pool(), pairs.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) meets[k] = meet(pairs[k].first, pairs[k].second);
  });
  return static_cast<std::size_t>(std::count(meets.begin(), meets.end(), 1));
}

FeatherCoatSimulation::FeatherCoatSimulation(std::vector<FeatherStem> stems, BodyMesh body,
                                             const SimulationParameters& parameters)
    : stems_(std::move(stems)),
      body_(std::move(body)),
      parameters_(parameters),
      wind_(parameters.wind),
      pool_(std::make_unique<WorkerPool>(parameters.threads)),
      stepTree_(pool_.get()),
      checkTree_(pool_.get()),
      vaneTree_(pool_.get()) {
  std::set<std::array<int, 2>> edges;
  for (const auto& t : body_.triangles)
    for (int k = 0; k < 3; ++k)
      edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  bodyEdges_.assign(edges.begin(), edges.end());
  for (FeatherStem& stem : stems_) {
    anchors_.push_back(stem.frames.front());
    if (stem.hasVane() && stem.vaneWidths.size() != stem.nodeCount())
      throw std::invalid_argument("a stem's vane needs a width per node");
    if (stem.hasVane() && stem.vaneCorners.size() != stem.nodeCount())
      stem.vaneCorners = vaneCornersOf(stem);
  }
  // Vanes that already meet are left out of each other's collisions until they come apart.
  if (parameters_.vaneCollisions || parameters_.findVaneOverlaps) {
    vaneOverlaps_ = VaneOverlaps(stems_);
    countVaneIntersections(stems_, nearestAllowed(), vaneTree_, nullptr, &vaneOverlaps_);
    vaneOverlapsAtStart_ = vaneOverlaps_.size();
  }
}

FeatherCoatSimulation FeatherCoatSimulation::fromScene(const Scene& scene,
                                                       const SimulationParameters& parameters) {
  std::vector<FeatherStem> stems;
  for (const Feather& feather : scene.organ<FeatherPart>().feathers)
    stems.push_back(
        buildFeatherStem(scene, feather, parameters.segmentsPerFeather, parameters.stem));
  return FeatherCoatSimulation(std::move(stems), bodyMeshOf(scene), parameters);
}

std::vector<Vector3d> FeatherCoatSimulation::externalForces(std::size_t s) {
  const FeatherStem& stem = stems_[s];
  std::vector<Vector3d> forces(stem.nodeCount(), Vector3d::Zero());
  std::vector<AirSample>& samples = air_[s];  // sized for every stem before the loops
  samples.resize(stem.nodeCount());
  for (std::size_t i = 1; i < stem.nodeCount(); ++i) {
    // Drag on the length of rachis a node carries, relative to the air.
    const double length = stem.masses[i] / stem.parameters.linearDensity;
    AirSample& sample = samples[i];
    if (sample.time != time_ || sample.position != stem.positions[i])
      sample = {stem.positions[i], wind_.velocityAt(stem.positions[i], time_), time_};
    forces[i] = stem.masses[i] * parameters_.gravity -
                parameters_.dragCoefficient * length * (stem.velocities[i] - sample.air);
  }
  return forces;
}

void FeatherCoatSimulation::step(double dt) {
  step(dt, anchors_, body_.vertices);
}

void FeatherCoatSimulation::step(double dt, const std::vector<StemFrame>& anchors) {
  step(dt, anchors, body_.vertices);
}

void FeatherCoatSimulation::step(double dt, const std::vector<StemFrame>& anchors,
                                 const std::vector<Vector3d>& bodyVertices) {
  if (anchors.size() != stems_.size())
    throw std::invalid_argument("a step needs one anchor frame per stem");
  if (bodyVertices.size() != body_.vertices.size())
    throw std::invalid_argument("a step needs one position per body vertex");
  if (!(dt > 0)) throw std::invalid_argument("a time step must be positive");
  const std::vector<FeatherStem> before = stems_;
  const RestingContacts restingBefore = resting_;
  const double timeBefore = time_;
  ++counters_.steps;
  try {
    advanceOrHalve(dt, Kinematics{anchors_, body_.vertices}, Kinematics{anchors, bodyVertices}, 0);
  } catch (const StepFailure&) {
    stems_ = before;
    resting_ = restingBefore;
    time_ = timeBefore;
    throw;
  }
  anchors_ = anchors;
  body_.vertices = bodyVertices;
}

std::size_t FeatherCoatSimulation::releaseVaneOverlaps() {
  if (vaneOverlaps_.empty()) return 0;
  const std::size_t released = vaneOverlaps_.release(stems_, parameters_.minimumSeparation);
  vaneOverlapsVersion_ += released > 0;
  return released;
}

void FeatherCoatSimulation::advanceOrHalve(double h, const Kinematics& from, const Kinematics& to,
                                           int depth) {
  const std::vector<FeatherStem> saved = stems_;
  const RestingContacts savedContacts = resting_;
  if (advance(h, from, to, depth >= parameters_.maxHalvings)) {
    time_ += h;
    ++counters_.substeps;
    return;
  }
  // The halves start from the state before the step, contacts and multipliers included.
  stems_ = saved;
  resting_ = savedContacts;
  if (depth >= parameters_.maxHalvings)
    throw StepFailure("the step's collisions could not be resolved at the smallest time step (" +
                      failure_ + ")");
  ++counters_.retries;
  Kinematics middle;
  middle.anchors.resize(from.anchors.size());
  for (std::size_t s = 0; s < from.anchors.size(); ++s) {
    middle.anchors[s].origin = 0.5 * (from.anchors[s].origin + to.anchors[s].origin);
    middle.anchors[s].axes = Eigen::Quaterniond(from.anchors[s].axes)
                                 .slerp(0.5, Eigen::Quaterniond(to.anchors[s].axes))
                                 .normalized()
                                 .toRotationMatrix();
  }
  middle.body.resize(from.body.size());
  for (std::size_t v = 0; v < from.body.size(); ++v)
    middle.body[v] = 0.5 * (from.body[v] + to.body[v]);
  advanceOrHalve(h / 2, from, middle, depth + 1);
  advanceOrHalve(h / 2, middle, to, depth + 1);
}

bool FeatherCoatSimulation::advance(double h, const Kinematics& fromState,
                                    const Kinematics& toState, bool smallest) {
  const std::vector<StemFrame>& from = fromState.anchors;
  const std::vector<StemFrame>& to = toState.anchors;
  const Primitives primitives(stems_, body_, bodyEdges_, parameters_.vaneCollisions,
                              &vaneOverlaps_);
  const BoxGroups groups = primitives.groups();
  StepState state;
  // The candidates of a search over `searched`, the boxes grown by `margin`, for which `wanted`
  // holds, from the list the tree keeps (BoxTree::coherentPairs). The list holds the pairs tested
  // (Primitives::wanted, which changes only with the vanes' pairs left out:
  // vaneOverlapsVersion_) whose boxes grown by the slack overlap, less those that a plane keeps
  // farther apart than the thickness and what the two sides may still move (separatedOverStep)
  // where the pair is listed. While every vertex stays within its grown box of then (in every
  // coordinate; else its stem, or the body, is searched again), such a pair's projections on
  // that plane's normal come no nearer than the thickness: no search may find it, the repulsion
  // (which acts within the thickness) nor the CCD (within the separation, at most the
  // thickness). The layered vanes of a coat, whose boxes overlap all round, are left out of the
  // list so, once per list instead of once a search; and a stem that moves more than the slack
  // has its own pairs found again, not the whole coat's.
  const auto parts = primitives.parts();  // of the primitives, of the vertices
  const double reach = std::max(parameters_.thickness, parameters_.minimumSeparation);
  const auto candidatesOf = [&](const StepState& searched, double margin,
                                const std::function<bool(int, int)>& wanted) {
    std::vector<Box> vertices(searched.start.size());
    for (std::size_t v = 0; v < vertices.size(); ++v)
      vertices[v] = {searched.start[v].cwiseMin(searched.end[v]),
                     searched.start[v].cwiseMax(searched.end[v])};
    BoxTree::KeptList list;
    list.slack = parameters_.candidateSlack;
    list.version = vaneOverlapsVersion_;
    list.tested = [&](int a, int b) { return primitives.wanted(a, b); };
    list.apart = [&](int a, int b, double strays) {
      CcdOptions listReach;
      listReach.minimumSeparation = reach + strays;
      return separatedOverStep(primitives.motion(a, b, searched),
                               isTriangle(primitives.list[b].kind), listReach);
    };
    list.vertices = &vertices;
    list.boxParts = &parts.first;
    list.vertexParts = &parts.second;
    auto pairs = stepTree_.coherentPairs(primitives.boxes(searched, margin), groups, list, wanted);
    ++counters_.searches;
    counters_.searchedPairs += pairs.size();
    return pairs;
  };
  // Where the vanes' corners would be at the end of the step: from the frames of the stems'
  // candidate positions.
  std::vector<std::vector<std::array<Vector3d, 2>>> cornersAtEnd(stems_.size());
  // 1-3: half a step of velocity, candidate positions, strain limiting (Sec. 3.3.3). Each stem
  // on its own, on the threads (the wind's gusts are most of it), into its own places.
  if (air_.size() != stems_.size()) air_.resize(stems_.size());
  state.start.resize(primitives.bodyOffset);
  state.end.resize(primitives.bodyOffset);
  state.inverseMass.resize(primitives.bodyOffset);
  forEach(pool_.get(), stems_.size(), 32, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      FeatherStem& stem = stems_[s];
      const std::size_t offset = primitives.stemOffset[s];
      rebuildFrames(stem, from[s]);
      const std::vector<Vector3d> forces = externalForces(s);
      const Vector3d anchorVelocity = (to[s].origin - from[s].origin) / h;
      // The positions move with this velocity over the whole step: the springs look that far
      // ahead, so that a stiff stem's fast turns are damped rather than flipped about their rest
      // each step (docs/dynamics.md, "How long a step may be").
      advanceGoldSprings(stem, h / 2, h, forces, anchorVelocity);
      for (std::size_t i = 0; i < stem.nodeCount(); ++i) {
        state.start[offset + i] = stem.positions[i];
        stem.positions[i] += h * stem.velocities[i];
      }
      stem.positions[0] = to[s].origin;
      limitStrain(stem, h);
      for (std::size_t i = 0; i < stem.nodeCount(); ++i) {
        state.end[offset + i] = stem.positions[i];
        state.inverseMass[offset + i] = i == 0 ? 0.0 : 1 / stem.masses[i];
      }
      if (stem.hasVane()) cornersAtEnd[s] = vaneCornersAt(stem, to[s]);
    }
  });
  for (std::size_t v = 0; v < body_.vertices.size(); ++v) {
    state.start.push_back(fromState.body[v]);
    state.end.push_back(toState.body[v]);
    state.inverseMass.push_back(0);
  }
  state.owner.resize(state.start.size());
  std::iota(state.owner.begin(), state.owner.end(), 0);
  state.corners = primitives.cornerOf;
  // The vanes' corners: from where the last step left them to the candidate frames' (a linear
  // move, as every vertex's, which the CCD sees exactly), carried by their nodes.
  for (const auto& [s, node, side] : primitives.corner) {
    const int owner = primitives.stemOffset[s] + node;
    state.start.push_back(stems_[s].vaneCorners[node][side]);
    state.end.push_back(cornersAtEnd[s][node][side]);
    state.inverseMass.push_back(state.inverseMass[owner]);
    state.owner.push_back(owner);
  }

  // 4: repulsion at the start of the step, apart from the internal forces (Bridson et al. 2002,
  // Sec. 7.2): a pair nearer than the thickness closes no further, and opens by a part of the gap.
  const double thickness = parameters_.thickness;
  {
    const StepState still{state.start, state.start, state.inverseMass, state.owner, state.corners};
    const auto pairs = candidatesOf(still, thickness / 2, [](int, int) { return true; });
    // The pairs' closest points on the threads; the impulses, which move what later pairs
    // see, in the pairs' order.
    std::vector<Contact> nearest(pairs.size());
    forEach(pool_.get(), pairs.size(), 512, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k)
        nearest[k] = primitives.contactAt(pairs[k].first, pairs[k].second, still, 0);
    });
    if (parameters_.restingContacts) {
      // The resting stage: every pair within the thickness is held at the resting distance
      // (resting_contacts.h), its multiplier carried from the step before.
      std::vector<NearPair> near;
      for (const Contact& c : nearest) {
        Vector3d gap = Vector3d::Zero();
        for (int k = 0; k < 4; ++k) gap += c.coefficients[k] * state.start[c.vertices[k]];
        if (!(gap.norm() < thickness)) continue;
        NearPair pair;
        pair.primitives = c.primitives;
        pair.vertices = c.vertices;
        pair.coefficients = c.coefficients;
        const Primitive &p = primitives.list[c.primitives[0]],
                        &q = primitives.list[c.primitives[1]];
        // The coat's feathers are placed bottom to top: a later stem lies over an earlier one.
        if (p.stem >= 0 && q.stem >= 0 && p.stem != q.stem) {
          pair.layerSign = p.stem > q.stem ? 1 : -1;
          const Primitive& lower = p.stem < q.stem ? p : q;
          const FeatherStem& stem = stems_[lower.stem];
          const int node = std::clamp(lower.segment, 0, static_cast<int>(stem.nodeCount()) - 1);
          pair.layerNormal = stem.frames[node].axes.col(0);
        }
        near.push_back(pair);
      }
      RestingOptions options;
      options.thickness = thickness;
      options.restDistance = parameters_.restDistance();
      options.openingRate = parameters_.repulsionRate;
      options.sweeps = parameters_.restingSweeps;
      options.strainLimit = parameters_.stem.strainLimit;
      resting_.update(std::move(near), state, options);
      counters_.restingContacts += resting_.size();
      std::vector<StrainSegment> segments;
      for (std::size_t s = 0; s < stems_.size(); ++s)
        for (std::size_t i = 0; i < stems_[s].restLengths.size(); ++i)
          segments.push_back({{primitives.stemOffset[s] + static_cast<int>(i),
                               primitives.stemOffset[s] + static_cast<int>(i) + 1},
                              stems_[s].restLengths[i]});
      counters_.restingMoves += resting_.solve(state, segments, options);
    } else {
      for (const Contact& c : nearest) {
        Vector3d gap = Vector3d::Zero();
        for (int k = 0; k < 4; ++k) gap += c.coefficients[k] * state.start[c.vertices[k]];
        const double distance = gap.norm();
        if (!(distance < thickness) || distance == 0) continue;
        counters_.repulsions += applyImpulse(
            c, gap / distance, parameters_.repulsionRate * (thickness - distance), state);
      }
    }
  }

  // 5: continuous collisions in time-of-impact order, then rigid impact zones (Provot 1997).
  // The impulses answer contacts within the minimum separation; the zones, the last resort,
  // those within a quarter of it, the distance the final check holds every state to. The
  // CCD's separation is a box (|x| <= eta on every axis), so it also finds pairs up to sqrt(3)
  // eta apart; a zone cannot open the gaps it holds (a rigid one keeps them as they were, one
  // moved with a bending body nearly so), and pairs it holds a little beyond its separation
  // would keep it from ever ending.
  CcdOptions ccd, zoneCcd;
  ccd.minimumSeparation = parameters_.minimumSeparation;
  zoneCcd.minimumSeparation = nearestAllowed();
  // The CCD of each pair on the threads, into its own slot, so that the results keep the pairs'
  // order; pairs a plane keeps apart over the step are left out first (the CCD would find no
  // contact). A pair asked at the last search of the same separation in this step, none of whose
  // vertices has moved since, has the answer it had then (the same question): the passes of
  // impulses and the zones' rounds move the vertices of their contacts, and most pairs of a
  // layered coat have none of them.
  std::vector<KeptAnswers> kept;  // one per separation
  // Whether the slab between the pair's primitives along `n` (the first one's lowest vertex
  // over the second's highest) is no thinner at the end of the step than at its start.
  const auto opensAlong = [](const MovingPrimitives& m, bool vertexFace, const Vector3d& n) {
    const int split = vertexFace ? 1 : 2;
    double slab[2];
    for (int end = 0; end < 2; ++end) {
      const auto& x = end == 0 ? m.start : m.end;
      double low = n.dot(x[0]), high = n.dot(x[split]);
      for (int k = 1; k < split; ++k) low = std::min(low, n.dot(x[k]));
      for (int k = split + 1; k < 4; ++k) high = std::max(high, n.dot(x[k]));
      slab[end] = low - high;
    }
    return slab[1] >= slab[0];
  };
  const auto ccdOf = [&](const std::vector<std::pair<int, int>>& pairs, const CcdOptions& options) {
    auto answers = std::find_if(kept.begin(), kept.end(), [&](const KeptAnswers& k) {
      return k.separation == options.minimumSeparation;
    });
    if (answers == kept.end()) {
      kept.push_back({options.minimumSeparation, {}, {}, {}});
      answers = kept.end() - 1;
    }
    const std::vector<int> earlier =
        parameters_.keepAnswers
            ? answers->earlierOf(pairs, state.end,
                                 [&](int a, int b) { return primitives.vertexSet(a, b); })
            : std::vector<int>(pairs.size(), KeptAnswers::kAsk);
    counters_.keptAnswers += pairs.size() - static_cast<std::size_t>(std::count(
                                                earlier.begin(), earlier.end(), KeptAnswers::kAsk));
    std::vector<CcdResult> results(pairs.size());
    std::vector<char> asked(pairs.size(), 0);
    forEach(pool_.get(), pairs.size(), 256, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        if (earlier[k] != KeptAnswers::kAsk) {
          if (earlier[k] != KeptAnswers::kNoContact)
            results[k] = answers->contacts[earlier[k]].second;
          continue;
        }
        const auto [a, b] = pairs[k];
        const MovingPrimitives m = primitives.motion(a, b, state);
        const bool vertexFace = isTriangle(primitives.list[b].kind);
        // A pair the resting stage holds is tried along its contact's normal first.
        const RestingContact* held = resting_.find(a, b);
        if (parameters_.restingContacts
                ? separatedThroughStep(m, vertexFace, options, held ? &held->normal : nullptr)
                : separatedOverStep(m, vertexFace, options))
          continue;
        // A held pair that the solve opens along its normal over the step and that stays beyond
        // the zones' separation throughout is the solve's: no accepted state can find it nearer
        // than a quarter of the separation, and the impulses would only open it the way the
        // next steps' solves do (docs/dynamics.md, "Resting contacts").
        if (held != nullptr && opensAlong(m, vertexFace, held->normal) &&
            separatedThroughStep(m, vertexFace, zoneCcd, &held->normal))
          continue;
        asked[k] = 1;
        results[k] = vertexFace ? vertexFaceCcd(m, options) : edgeEdgeCcd(m, options);
      }
    });
    counters_.ccdQueries += static_cast<std::size_t>(std::count(asked.begin(), asked.end(), 1));
    if (parameters_.keepAnswers) answers->keep(pairs, results, state.end);
    return results;
  };
  bool firstSearch = true;
  auto findContacts = [&](const CcdOptions& options, bool calami) {
    std::vector<Contact> contacts;
    const auto pairs = candidatesOf(state, options.minimumSeparation, [&](int a, int b) {
      return calami || !primitives.holdsCalamus(a, b);
    });
    counters_.candidates += pairs.size();
    const std::vector<CcdResult> results = ccdOf(pairs, options);
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const auto [a, b] = pairs[k];
      const Kind kind = primitives.list[b].kind;  // a vane's, where the pair holds one
      counters_.vaneCandidates += isVane(kind);
      if (results[k].contact) {
        contacts.push_back(primitives.contactAt(a, b, state, results[k].timeOfImpact));
        counters_.vaneContacts += isVane(kind);
      }
    }
    counters_.contacts += contacts.size();
    if (firstSearch) counters_.netContacts += contacts.size();
    firstSearch = false;
    std::stable_sort(contacts.begin(), contacts.end(), [](const Contact& x, const Contact& y) {
      return x.timeOfImpact < y.timeOfImpact;
    });
    return contacts;
  };
  // Inelastic: the gap stops closing, and opens a tenth of the separation over the step, so that
  // the pair is not found again at once.
  const double opening = 0.1 * ccd.minimumSeparation;
  // A contact in words, for the error of a step that cannot be resolved.
  auto describe = [&](const Contact& c) {
    const auto name = [&](int k) { return primitives.vertexName(c.vertices[k]); };
    const std::string what =
        c.vertexFace
            ? name(0) + " against the triangle of " + name(1) + ", " + name(2) + ", " + name(3)
            : "the segment " + name(0) + " to " + name(1) + " against the segment " + name(2) +
                  " to " + name(3);
    const Vector3d at = state.start[c.vertices[0]] +
                        c.timeOfImpact * (state.end[c.vertices[0]] - state.start[c.vertices[0]]);
    char where[96];
    std::snprintf(where, sizeof where, " near (%.4g, %.4g, %.4g)", at.x(), at.y(), at.z());
    return what + where;
  };
  std::vector<Contact> contacts = findContacts(ccd, true);
  for (int pass = 0; pass < parameters_.impulsePasses && !contacts.empty(); ++pass) {
    for (const Contact& c : contacts)
      counters_.impulses += applyImpulse(c, contactNormal(c, state), opening, state);
    contacts = findContacts(ccd, true);
  }
  // What the impulses leave within the separation but clear of the zones' stays as it is, and
  // so does what they leave of a calamus.
  // A calamus left within the separation may stay so, but should not meet or pass through the
  // stem it is near (checked once the zones have moved what they move, below).
  bool calami = false;
  std::erase_if(contacts, [&](const Contact& c) {
    if (primitives.holdsCalamus(c.primitives[0], c.primitives[1])) {
      ++counters_.calamiLeft;
      calami = true;
      return true;
    }
    const MovingPrimitives m = primitives.motion(c.primitives[0], c.primitives[1], state);
    ++counters_.ccdQueries;
    const bool near = (c.vertexFace ? vertexFaceCcd(m, zoneCcd) : edgeEdgeCcd(m, zoneCcd)).contact;
    counters_.keptNear += !near;
    return !near;
  });
  std::vector<int> parent(state.start.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::map<int, ZoneMotion> zoneMaps;  // each zone's map, by its root
  // Rigid impact zones (Provot 1997) for `pending`, then for what the CCD finds within the
  // zones' separation after each round, until it finds nothing; false (failure_ set) when
  // contacts remain after zoneIterations rounds. Zones grow over the rounds and the calls.
  const auto resolveInZones = [&](std::vector<Contact> pending) {
    for (int iteration = 0; !pending.empty(); ++iteration) {
      if (iteration >= parameters_.zoneIterations) {
        failure_ = std::to_string(pending.size()) +
                   " contacts still within a quarter of the minimum separation after " +
                   std::to_string(parameters_.zoneIterations) +
                   " passes of rigid impact zones; the first: " + describe(pending.front());
        return false;
      }
      // A vane corner moves with its node: a zone that takes one takes the other, and the
      // node's other corner.
      const auto join = [&](int v, int w) { parent[findRoot(parent, v)] = findRoot(parent, w); };
      for (const Contact& c : pending)
        for (int k = 0; k < 4; ++k) {
          const int v = c.vertices[k], owner = state.owner[v];
          join(v, c.vertices[0]);
          join(owner, c.vertices[0]);
          if (owner < static_cast<int>(state.corners.size()))
            for (int corner : state.corners[owner])
              if (corner >= 0) join(corner, c.vertices[0]);
        }
      std::map<int, std::vector<int>> zones;
      std::set<int> touched;
      for (const Contact& c : pending)
        for (int v : c.vertices) touched.insert(findRoot(parent, v));
      for (int v = 0; v < static_cast<int>(parent.size()); ++v) {
        const int root = findRoot(parent, v);
        if (touched.count(root)) zones[root].push_back(v);
      }
      std::map<int, std::vector<const Contact*>> zoneContacts;
      for (const Contact& c : pending) zoneContacts[findRoot(parent, c.vertices[0])].push_back(&c);
      for (const auto& [root, members] : zones) {
        ZoneMotion& m = zoneMaps[root] = moveRigidly(members, state);
        m.shift += liftOffKinematic(members, zoneContacts[root], opening, thickness, state);
      }
      pending = findContacts(zoneCcd, false);
      // The zone's map shortens no distance, so a pair within one zone is never nearer than at the
      // start of the step (when it was clear) less how far its kinematic vertices stray from that
      // map (each side's share of the gap at most its largest stray). A pair that stays clear so
      // is passed over: the CCD's box still finds one when the zone turns its gap towards a
      // diagonal, and the next step may find it inside the box from its start, which only this
      // rule, once its vertices share a zone, can pass.
      std::erase_if(pending, [&](const Contact& c) {
        const int root = findRoot(parent, c.vertices[0]);
        for (int v : c.vertices)
          if (findRoot(parent, v) != root) return false;
        const ZoneMotion& m = zoneMaps.at(root);
        double stray[2] = {0, 0};  // of the first primitive's vertices and of the second's
        for (int k = 0; k < 4; ++k) {
          const int v = c.vertices[k];
          const int side = k == 0 || (k == 1 && !c.vertexFace) ? 0 : 1;
          if (state.inverseMass[v] == 0)
            stray[side] = std::max(stray[side], (state.end[v] - mapped(m, state.start[v])).norm());
        }
        const double nearest = primitives.distanceAtStart(c, state);
        return nearest - stray[0] - stray[1] > (1 + 1e-9) * zoneCcd.minimumSeparation;
      });
    }
    return true;
  };
  if (!resolveInZones(std::move(contacts))) return false;

  // A calamus that meets or passes through another stem over the step as it now is (the
  // impulses' pairs, or any pair once zones have moved stems): the step is tried again as two
  // halves, as one with an intersection. At the smallest step, where the bend drives a calamus
  // against a stem no smaller step keeps it off, the pair goes into a rigid impact zone with the
  // calamus's root: the zone moves with the root, so the stem keeps its side of the calamus,
  // and the CCD then answers what the zone's move brings near in further rounds. A crossing
  // left after zoneIterations rounds fails the step; none is ever accepted.
  const auto calamusCrossings = [&] {
    CcdOptions touching;  // no separation: the pair meets (or passes through)
    touching.minimumSeparation = 0;
    const auto pairs =
        candidatesOf(state, 0, [&](int a, int b) { return primitives.holdsCalamus(a, b); });
    const std::vector<CcdResult> results = ccdOf(pairs, touching);
    std::vector<Contact> crossings;
    for (std::size_t k = 0; k < pairs.size(); ++k)
      if (results[k].contact)
        crossings.push_back(
            primitives.contactAt(pairs[k].first, pairs[k].second, state, results[k].timeOfImpact));
    return crossings;
  };
  bool zonesMoved = false;
  for (int v = 0; v < static_cast<int>(parent.size()) && !zonesMoved; ++v)
    zonesMoved = findRoot(parent, v) != v;
  if (calami || zonesMoved) {
    for (int round = 0;; ++round) {
      std::vector<Contact> crossings = calamusCrossings();
      if (crossings.empty()) break;
      counters_.calamiCrossed += crossings.size();
      if (!smallest) {
        failure_ = "a calamus meets another stem in the step: " + describe(crossings.front());
        return false;
      }
      if (round >= parameters_.zoneIterations) {
        failure_ = std::to_string(crossings.size()) + " calamus crossings left after " +
                   std::to_string(parameters_.zoneIterations) +
                   " rounds of impact zones; the first: " + describe(crossings.front());
        return false;
      }
      counters_.calamiZoned += crossings.size();
      if (!resolveInZones(std::move(crossings))) return false;
    }
  }
  std::set<int> zoneRoots;
  for (int v = 0; v < static_cast<int>(parent.size()); ++v)
    if (findRoot(parent, v) != v) zoneRoots.insert(findRoot(parent, v));
  counters_.impactZones += zoneRoots.size();

  // The positions and velocities the collisions leave.
  for (std::size_t s = 0; s < stems_.size(); ++s) {
    FeatherStem& stem = stems_[s];
    const int offset = primitives.stemOffset[s];
    for (std::size_t i = 1; i < stem.nodeCount(); ++i) {
      stem.positions[i] = state.end[offset + i];
      stem.velocities[i] = (state.end[offset + i] - state.start[offset + i]) / h;
    }
    // Vanes that do not collide follow the frames of where the stem ended up.
    if (stem.hasVane())
      stem.vaneCorners =
          parameters_.vaneCollisions ? std::move(cornersAtEnd[s]) : vaneCornersAt(stem, to[s]);
  }
  for (std::size_t k = 0; k < primitives.corner.size(); ++k) {
    const auto& [s, node, side] = primitives.corner[k];
    stems_[s].vaneCorners[node][side] = state.end[primitives.vaneOffset + k];
  }
  // 6: the exact check of the final state.
  const BodyMesh bodyAtEnd{toState.body, body_.triangles};
  const std::size_t penetrations = countPenetrations(stems_, bodyAtEnd, nearestAllowed(),
                                                     checkTree_, parameters_.candidateSlack);
  const std::size_t vanes =
      parameters_.vaneCollisions
          ? countVaneIntersections(stems_, nearestAllowed(), vaneTree_, &vaneOverlaps_, nullptr,
                                   parameters_.candidateSlack)
          : 0;
  if (penetrations + vanes > 0) {
    counters_.penetrations += penetrations + vanes;
    counters_.vanePenetrations += vanes;
    failure_ = "the final check found " + std::to_string(penetrations + vanes) +
               " intersections (" + std::to_string(vanes) + " of vanes)";
    return false;
  }
  // 7: the second half step of velocity at the new positions.
  const double later = time_;
  time_ += h;  // the forces of the end of the step
  forEach(pool_.get(), stems_.size(), 32, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s) {
      FeatherStem& stem = stems_[s];
      rebuildFrames(stem, to[s]);
      const std::vector<Vector3d> forces = externalForces(s);
      advanceGoldSprings(stem, h / 2, h / 2, forces, (to[s].origin - from[s].origin) / h);
    }
  });
  time_ = later;
  return true;
}

}  // namespace hirsute::dynamics
