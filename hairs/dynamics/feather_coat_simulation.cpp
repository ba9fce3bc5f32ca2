// The feather-coat step: internal dynamics, repulsion, continuous collisions with impulses and
// rigid impact zones, the final check, and retries with halved steps.
#include "hirsute/hairs/dynamics/feather_coat_simulation.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "hirsute/hairs/dynamics/collision_grid.h"
#include "hirsute/hairs/dynamics/continuous_collision.h"
#include "hirsute/hairs/dynamics/static_intersection.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// Closest points of segments p0p1 and q0q1: p0 + s (p1 - p0) and q0 + u (q1 - q0), s, u in [0, 1]
// (the usual clamped solution of the 2x2 normal equations, degenerate segments included).
std::pair<double, double> closestOnSegments(const Vector3d& p0, const Vector3d& p1,
                                            const Vector3d& q0, const Vector3d& q1) {
  const Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kTiny = 1e-300;
  if (a <= kTiny && e <= kTiny) return {0, 0};
  if (a <= kTiny) return {0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e <= kTiny) return {std::clamp(-c / a, 0.0, 1.0), 0};
  const double b = d1.dot(d2), denominator = a * e - b * b;
  double s = denominator > 0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  double u = (b * s + f) / e;
  if (u < 0) {
    u = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (u > 1) {
    u = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, u};
}

// Barycentric weights of the point of triangle abc closest to p (Voronoi regions of the corners,
// edges and face).
std::array<double, 3> closestOnTriangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                                        const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};  // a degenerate triangle
  return {va / sum, vb / sum, vc / sum};
}

// The kinds of collision primitives, in the order their boxes are listed.
enum class Kind : std::uint8_t { StemEdge, BodyEdge, StemNode, BodyTriangle };

struct Primitive {
  Kind kind;
  std::array<int, 3> vertices;  // global vertex indices (edges use two, nodes one)
  int stem = -1;                // the stem of a stem edge or node
  int segment = -1;             // a stem edge's segment, a stem node's node
};

// A pair of primitives about to touch, as four vertices with coefficients c: the gap between them
// is sum c_k x_k (the vertex or first edge side positive), zero where they touch.
struct Contact {
  std::array<int, 4> vertices;
  std::array<double, 4> coefficients;
  double timeOfImpact = 0;
};

// The state of a step as one set of vertices: every stem node, then every body vertex.
struct StepState {
  std::vector<Vector3d> start, end;
  std::vector<double> inverseMass;  // 0: kinematic (anchors, the body)
};

// The collision primitives of the coat and the body over the global vertex numbering.
struct Primitives {
  std::vector<Primitive> list;
  std::vector<int> stemOffset;  // global index of each stem's node 0
  int bodyOffset = 0;

  Primitives(const std::vector<FeatherStem>& stems, const BodyMesh& body,
             const std::vector<std::array<int, 2>>& bodyEdges) {
    int offset = 0;
    for (const FeatherStem& stem : stems) {
      stemOffset.push_back(offset);
      offset += static_cast<int>(stem.nodeCount());
    }
    bodyOffset = offset;
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
  }

  // Whether the pair (a < b in list order) is tested: segments of different stems or of one stem
  // that share no node; stem segments against body edges and stem nodes against body triangles,
  // except a stem's first segment, whose root lies on the body.
  bool wanted(int a, int b) const {
    const Primitive &p = list[a], &q = list[b];
    if (p.kind == Kind::StemEdge && q.kind == Kind::StemEdge)
      return p.stem != q.stem || std::abs(p.segment - q.segment) > 1;
    if (p.kind == Kind::StemEdge && q.kind == Kind::BodyEdge) return p.segment > 0;
    return p.kind == Kind::StemNode && q.kind == Kind::BodyTriangle;
  }

  // The boxes of every primitive over the step (from `start` to `end`), grown by `margin`.
  std::vector<Box> boxes(const StepState& state, double margin) const {
    std::vector<Box> out;
    out.reserve(list.size());
    for (const Primitive& p : list) {
      const int n = p.kind == Kind::StemNode ? 1 : p.kind == Kind::BodyTriangle ? 3 : 2;
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
    if (q.kind == Kind::BodyTriangle) {
      const auto w = closestOnTriangle(at(p.vertices[0]), at(q.vertices[0]), at(q.vertices[1]),
                                       at(q.vertices[2]));
      c.vertices = {p.vertices[0], q.vertices[0], q.vertices[1], q.vertices[2]};
      c.coefficients = {1, -w[0], -w[1], -w[2]};
    } else {
      const auto [s, u] = closestOnSegments(at(p.vertices[0]), at(p.vertices[1]), at(q.vertices[0]),
                                            at(q.vertices[1]));
      c.vertices = {p.vertices[0], p.vertices[1], q.vertices[0], q.vertices[1]};
      c.coefficients = {1 - s, s, -(1 - u), -u};
    }
    return c;
  }

  MovingPrimitives motion(int a, int b, const StepState& state) const {
    const Primitive &p = list[a], &q = list[b];
    const std::array<int, 4> v =
        q.kind == Kind::BodyTriangle
            ? std::array<int, 4>{p.vertices[0], q.vertices[0], q.vertices[1], q.vertices[2]}
            : std::array<int, 4>{p.vertices[0], p.vertices[1], q.vertices[0], q.vertices[1]};
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
bool applyImpulse(const Contact& c, const Vector3d& normal, double target, StepState& state) {
  double approach = 0, weight = 0;
  for (int k = 0; k < 4; ++k) {
    approach +=
        c.coefficients[k] * normal.dot(state.end[c.vertices[k]] - state.start[c.vertices[k]]);
    weight += c.coefficients[k] * c.coefficients[k] * state.inverseMass[c.vertices[k]];
  }
  if (approach >= target || weight <= 0) return false;
  const double impulse = (target - approach) / weight;
  for (int k = 0; k < 4; ++k)
    state.end[c.vertices[k]] +=
        impulse * c.coefficients[k] * state.inverseMass[c.vertices[k]] * normal;
  return true;
}

int findRoot(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// Provot 1997: the zone moves as one rigid body with the zone's momentum and angular momentum.
// Its motion over the step is x0 + (v_cm + w x (x0 - x_cm)) h, an affine map I + h [w]x of the
// relative positions that never shortens a distance (|r + h w x r|^2 = |r|^2 + h^2 |w x r|^2), so
// no two of its primitives come closer than at the start. A zone holding kinematic vertices
// follows them when they all move alike; otherwise it cannot be made rigid (returns false).
bool moveRigidly(const std::vector<int>& members, StepState& state) {
  std::vector<int> kinematic;
  for (int v : members)
    if (state.inverseMass[v] == 0) kinematic.push_back(v);
  if (!kinematic.empty()) {
    const Vector3d shift = state.end[kinematic[0]] - state.start[kinematic[0]];
    for (int v : kinematic)
      if (state.end[v] - state.start[v] != shift) return false;
    for (int v : members) state.end[v] = state.start[v] + shift;
    return true;
  }
  double mass = 0;
  Vector3d centre = Vector3d::Zero(), momentum = Vector3d::Zero();
  for (int v : members) {
    const double m = 1 / state.inverseMass[v];
    mass += m;
    centre += m * state.start[v];
    momentum += m * (state.end[v] - state.start[v]);
  }
  centre /= mass;
  const Vector3d shift = momentum / mass;  // the centre's displacement over the step
  Vector3d angular = Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (int v : members) {
    const double m = 1 / state.inverseMass[v];
    const Vector3d r = state.start[v] - centre;
    angular += m * r.cross(state.end[v] - state.start[v] - shift);
    inertia += m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  // Collinear zones have a singular inertia about their line: no spin about it.
  const Vector3d spin = inertia.completeOrthogonalDecomposition().solve(angular);
  for (int v : members) state.end[v] = state.start[v] + shift + spin.cross(state.start[v] - centre);
  return true;
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
  std::size_t found = 0;
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
  const auto pairs = overlappingPairs(boxes, [&](int a, int b) {
    const Item &p = items[a], &q = items[b];
    if (p.triangle >= 0) return false;  // triangles come last: a triangle pairs only as q
    if (q.triangle >= 0) return p.segment > 0;
    return p.stem != q.stem || std::abs(p.segment - q.segment) > 1;
  });
  for (const auto& [a, b] : pairs) {
    const Item &p = items[a], &q = items[b];
    const Vector3d& p0 = stems[p.stem].positions[p.segment];
    const Vector3d& p1 = stems[p.stem].positions[p.segment + 1];
    if (q.triangle >= 0) {
      const auto& tri = body.triangles[q.triangle];
      found += segmentIntersectsTriangle(p0, p1, body.vertices[tri[0]], body.vertices[tri[1]],
                                         body.vertices[tri[2]]);
      continue;
    }
    const Vector3d& q0 = stems[q.stem].positions[q.segment];
    const Vector3d& q1 = stems[q.stem].positions[q.segment + 1];
    const auto [s, u] = closestOnSegments(p0, p1, q0, q1);
    const double distance = ((p0 + s * (p1 - p0)) - (q0 + u * (q1 - q0))).norm();
    found += segmentsIntersect(p0, p1, q0, q1) || distance < minimumDistance;
  }
  return found;
}

FeatherCoatSimulation::FeatherCoatSimulation(std::vector<FeatherStem> stems, BodyMesh body,
                                             const SimulationParameters& parameters)
    : stems_(std::move(stems)),
      body_(std::move(body)),
      parameters_(parameters),
      wind_(parameters.wind) {
  std::set<std::array<int, 2>> edges;
  for (const auto& t : body_.triangles)
    for (int k = 0; k < 3; ++k)
      edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  bodyEdges_.assign(edges.begin(), edges.end());
  for (const FeatherStem& stem : stems_) anchors_.push_back(stem.frames.front());
}

FeatherCoatSimulation FeatherCoatSimulation::fromScene(const Scene& scene,
                                                       const SimulationParameters& parameters) {
  std::vector<FeatherStem> stems;
  for (const Feather& feather : scene.feathers)
    stems.push_back(
        buildFeatherStem(scene, feather, parameters.segmentsPerFeather, parameters.stem));
  return FeatherCoatSimulation(std::move(stems), bodyMeshOf(scene), parameters);
}

std::vector<Vector3d> FeatherCoatSimulation::externalForces(const FeatherStem& stem) const {
  std::vector<Vector3d> forces(stem.nodeCount(), Vector3d::Zero());
  for (std::size_t i = 1; i < stem.nodeCount(); ++i) {
    // Drag on the length of rachis a node carries, relative to the air.
    const double length = stem.masses[i] / stem.parameters.linearDensity;
    const Vector3d air = wind_.velocityAt(stem.positions[i], time_);
    forces[i] = stem.masses[i] * parameters_.gravity -
                parameters_.dragCoefficient * length * (stem.velocities[i] - air);
  }
  return forces;
}

void FeatherCoatSimulation::step(double dt) {
  step(dt, anchors_);
}

void FeatherCoatSimulation::step(double dt, const std::vector<StemFrame>& anchors) {
  if (anchors.size() != stems_.size())
    throw std::invalid_argument("a step needs one anchor frame per stem");
  if (!(dt > 0)) throw std::invalid_argument("a time step must be positive");
  const std::vector<FeatherStem> before = stems_;
  const double timeBefore = time_;
  ++counters_.steps;
  try {
    advanceOrHalve(dt, anchors_, anchors, 0);
  } catch (const StepFailure&) {
    stems_ = before;
    time_ = timeBefore;
    throw;
  }
  anchors_ = anchors;
}

void FeatherCoatSimulation::advanceOrHalve(double h, const std::vector<StemFrame>& from,
                                           const std::vector<StemFrame>& to, int depth) {
  const std::vector<FeatherStem> saved = stems_;
  if (advance(h, from, to)) {
    time_ += h;
    ++counters_.substeps;
    return;
  }
  stems_ = saved;
  if (depth >= parameters_.maxHalvings)
    throw StepFailure("the step's collisions could not be resolved at the smallest time step");
  ++counters_.retries;
  std::vector<StemFrame> middle(from.size());
  for (std::size_t s = 0; s < from.size(); ++s) {
    middle[s].origin = 0.5 * (from[s].origin + to[s].origin);
    middle[s].axes = Eigen::Quaterniond(from[s].axes)
                         .slerp(0.5, Eigen::Quaterniond(to[s].axes))
                         .normalized()
                         .toRotationMatrix();
  }
  advanceOrHalve(h / 2, from, middle, depth + 1);
  advanceOrHalve(h / 2, middle, to, depth + 1);
}

bool FeatherCoatSimulation::advance(double h, const std::vector<StemFrame>& from,
                                    const std::vector<StemFrame>& to) {
  const Primitives primitives(stems_, body_, bodyEdges_);
  StepState state;
  // 1-3: half a step of velocity, candidate positions, strain limiting (Sec. 3.3.3).
  for (std::size_t s = 0; s < stems_.size(); ++s) {
    FeatherStem& stem = stems_[s];
    rebuildFrames(stem, from[s]);
    const std::vector<Vector3d> forces = externalForces(stem);
    const Vector3d anchorVelocity = (to[s].origin - from[s].origin) / h;
    advanceGoldSprings(stem, h / 2, forces, anchorVelocity);
    for (std::size_t i = 0; i < stem.nodeCount(); ++i) {
      state.start.push_back(stem.positions[i]);
      stem.positions[i] += h * stem.velocities[i];
    }
    stem.positions[0] = to[s].origin;
    limitStrain(stem, h);
    for (std::size_t i = 0; i < stem.nodeCount(); ++i) {
      state.end.push_back(stem.positions[i]);
      state.inverseMass.push_back(i == 0 ? 0.0 : 1 / stem.masses[i]);
    }
  }
  for (const Vector3d& v : body_.vertices) {
    state.start.push_back(v);
    state.end.push_back(v);
    state.inverseMass.push_back(0);
  }

  // 4: repulsion at the start of the step, apart from the internal forces (Bridson et al. 2002,
  // Sec. 7.2): a pair nearer than the thickness closes no further, and opens by a part of the gap.
  const double thickness = parameters_.thickness;
  {
    const StepState still{state.start, state.start, state.inverseMass};
    const auto pairs = overlappingPairs(primitives.boxes(still, thickness / 2),
                                        [&](int a, int b) { return primitives.wanted(a, b); });
    for (const auto& [a, b] : pairs) {
      const Contact c = primitives.contactAt(a, b, still, 0);
      Vector3d gap = Vector3d::Zero();
      for (int k = 0; k < 4; ++k) gap += c.coefficients[k] * state.start[c.vertices[k]];
      const double distance = gap.norm();
      if (!(distance < thickness) || distance == 0) continue;
      counters_.repulsions += applyImpulse(
          c, gap / distance, parameters_.repulsionRate * (thickness - distance), state);
    }
  }

  // 5: continuous collisions in time-of-impact order, then rigid impact zones (Provot 1997).
  CcdOptions ccd;
  ccd.minimumSeparation = parameters_.minimumSeparation;
  auto findContacts = [&]() {
    std::vector<Contact> contacts;
    const auto pairs = overlappingPairs(primitives.boxes(state, ccd.minimumSeparation),
                                        [&](int a, int b) { return primitives.wanted(a, b); });
    counters_.candidates += pairs.size();
    for (const auto& [a, b] : pairs) {
      const MovingPrimitives m = primitives.motion(a, b, state);
      const CcdResult r = primitives.list[b].kind == Kind::BodyTriangle ? vertexFaceCcd(m, ccd)
                                                                        : edgeEdgeCcd(m, ccd);
      if (r.contact) contacts.push_back(primitives.contactAt(a, b, state, r.timeOfImpact));
    }
    counters_.contacts += contacts.size();
    std::stable_sort(contacts.begin(), contacts.end(), [](const Contact& x, const Contact& y) {
      return x.timeOfImpact < y.timeOfImpact;
    });
    return contacts;
  };
  // Inelastic: the gap stops closing, and opens a tenth of the separation over the step, so that
  // the pair is not found again at once.
  const double opening = 0.1 * ccd.minimumSeparation;
  std::vector<Contact> contacts = findContacts();
  for (int pass = 0; pass < parameters_.impulsePasses && !contacts.empty(); ++pass) {
    for (const Contact& c : contacts)
      counters_.impulses += applyImpulse(c, contactNormal(c, state), opening, state);
    contacts = findContacts();
  }
  std::vector<int> parent(state.start.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (int iteration = 0; !contacts.empty(); ++iteration) {
    if (iteration >= parameters_.zoneIterations) return false;
    for (const Contact& c : contacts)
      for (int k = 1; k < 4; ++k)
        parent[findRoot(parent, c.vertices[k])] = findRoot(parent, c.vertices[0]);
    std::map<int, std::vector<int>> zones;
    std::set<int> touched;
    for (const Contact& c : contacts)
      for (int v : c.vertices) touched.insert(findRoot(parent, v));
    for (int v = 0; v < static_cast<int>(parent.size()); ++v) {
      const int root = findRoot(parent, v);
      if (touched.count(root)) zones[root].push_back(v);
    }
    for (const auto& [root, members] : zones)
      if (!moveRigidly(members, state)) return false;
    contacts = findContacts();
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
  }
  // 6: the exact check of the final state.
  const std::size_t penetrations =
      countPenetrations(stems_, body_, 0.5 * parameters_.minimumSeparation);
  if (penetrations > 0) {
    counters_.penetrations += penetrations;
    return false;
  }
  // 7: the second half step of velocity at the new positions.
  const double later = time_;
  time_ += h;  // the forces of the end of the step
  for (std::size_t s = 0; s < stems_.size(); ++s) {
    FeatherStem& stem = stems_[s];
    rebuildFrames(stem, to[s]);
    const std::vector<Vector3d> forces = externalForces(stem);
    advanceGoldSprings(stem, h / 2, forces, (to[s].origin - from[s].origin) / h);
  }
  time_ = later;
  return true;
}

}  // namespace hirsute::dynamics
