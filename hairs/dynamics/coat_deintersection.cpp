// A coat laid in layer order, each stem turned segment by segment off what lies beneath it.
#include "hirsute/hairs/dynamics/coat_deintersection.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hirsute/hairs/dynamics/static_intersection.h"
#include "hirsute/hairs/dynamics/stem_vane.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// An obstacle over more cells than this is kept in a list of its own, its box tested by every
// query (a body's large triangles), so that a primitive costs a bounded number of cells.
constexpr std::int64_t kMostCells = 512;
// Cell coordinates are packed 21 bits each.
constexpr std::int64_t kCellRange = std::int64_t{1} << 20;

// rebuildFrames' binormal (feather_stem.cpp): the preferred direction made perpendicular to the
// tangent, or the fallback's, so that a segment turned here gets the frame the stem's rebuilt
// frames give it.
Vector3d perpendicularTowards(const Vector3d& preferred, const Vector3d& tangent,
                              const Vector3d& fallback) {
  for (const Vector3d& candidate : {preferred, fallback}) {
    const Vector3d p = candidate - candidate.dot(tangent) * tangent;
    if (p.norm() > 1e-9) return p.normalized();
  }
  return tangent.unitOrthogonal();
}

// Whether the first `count` of `points` lie strictly on one side of the plane of `triangle`, by
// a margin far above the rounding of the products (a million times the bound of Shewchuk's
// filters): then they cannot meet it, and the exact test is not needed. Otherwise the exact
// test decides.
bool clearlyOneSide(const std::array<Vector3d, 3>& triangle, const std::array<Vector3d, 3>& points,
                    int count) {
  const Vector3d u = triangle[1] - triangle[0], v = triangle[2] - triangle[0];
  const Vector3d n = u.cross(v);
  const Vector3d size = u.cwiseAbs().cwiseMax(v.cwiseAbs());
  const Vector3d bound(size.y() * size.z(), size.z() * size.x(), size.x() * size.y());
  int above = 0, below = 0;
  for (int i = 0; i < count; ++i) {
    const Vector3d d = points[i] - triangle[0];
    const double side = n.dot(d);
    const double margin = 1e-9 * 2 * bound.dot(d.cwiseAbs());
    if (side > margin)
      ++above;
    else if (side < -margin)
      ++below;
  }
  return above == count || below == count;
}

// A box in single precision that holds the double one.
std::array<float, 3> roundedDown(const Vector3d& v) {
  std::array<float, 3> out;
  for (int a = 0; a < 3; ++a) {
    out[a] = static_cast<float>(v[a]);
    if (static_cast<double>(out[a]) > v[a])
      out[a] = std::nextafter(out[a], -std::numeric_limits<float>::infinity());
  }
  return out;
}
std::array<float, 3> roundedUp(const Vector3d& v) {
  std::array<float, 3> out;
  for (int a = 0; a < 3; ++a) {
    out[a] = static_cast<float>(v[a]);
    if (static_cast<double>(out[a]) < v[a])
      out[a] = std::nextafter(out[a], std::numeric_limits<float>::infinity());
  }
  return out;
}

bool boxesOverlap(const std::array<float, 3>& lowA, const std::array<float, 3>& highA,
                  const std::array<float, 3>& lowB, const std::array<float, 3>& highB) {
  return lowA[0] <= highB[0] && lowB[0] <= highA[0] && lowA[1] <= highB[1] && lowB[1] <= highA[1] &&
         lowA[2] <= highB[2] && lowB[2] <= highA[2];
}

std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  const auto part = [](std::int64_t v) {
    return static_cast<std::uint64_t>(std::clamp(v, -kCellRange, kCellRange - 1) + kCellRange);
  };
  return (part(x) << 42) | (part(y) << 21) | part(z);
}

}  // namespace

RestingLayer::RestingLayer(const BodyMesh& body, double cellSize)
    : cellSize_(cellSize > 0 && std::isfinite(cellSize) ? cellSize : 1.0) {
  for (const auto& t : body.triangles) {
    Obstacle o;
    o.points = {body.vertices[t[0]], body.vertices[t[1]], body.vertices[t[2]]};
    o.kind = Kind::Body;
    insert(o);
  }
}

std::int64_t RestingLayer::cellOf(double x) const {
  const double c = std::floor(x / cellSize_);
  if (!(c > -static_cast<double>(kCellRange))) return -kCellRange;
  if (!(c < static_cast<double>(kCellRange))) return kCellRange - 1;
  return static_cast<std::int64_t>(c);
}

void RestingLayer::insert(Obstacle o) {
  const int corners = o.kind == Kind::Segment ? 2 : 3;
  o.low = o.high = o.points[0];
  for (int i = 1; i < corners; ++i) {
    o.low = o.low.cwiseMin(o.points[i]);
    o.high = o.high.cwiseMax(o.points[i]);
  }
  if (!o.low.allFinite() || !o.high.allFinite()) return;
  if (o.kind == Kind::Segment) o.points[2] = o.points[1];
  const Entry entry{roundedDown(o.low), roundedUp(o.high),
                    static_cast<std::uint32_t>(obstacles_.size())};
  obstacles_.push_back(o);
  seen_.push_back(0);
  std::array<std::int64_t, 3> from, to;
  std::int64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    from[a] = cellOf(o.low[a]);
    to[a] = cellOf(o.high[a]);
    count *= to[a] - from[a] + 1;
    if (count > kMostCells) break;
  }
  if (count > kMostCells) {
    large_.push_back(entry);
    return;
  }
  for (std::int64_t x = from[0]; x <= to[0]; ++x)
    for (std::int64_t y = from[1]; y <= to[1]; ++y)
      for (std::int64_t z = from[2]; z <= to[2]; ++z) cells_[cellKey(x, y, z)].push_back(entry);
}

void RestingLayer::add(const FeatherStem& stem) {
  // The calamus (segment 0) is left out, as the simulator's check leaves it: its root is on the
  // body, where the roots of neighbours crowd.
  for (std::size_t k = 1; k + 1 < stem.nodeCount(); ++k) {
    Obstacle o;
    o.points = {stem.positions[k], stem.positions[k + 1], stem.positions[k + 1]};
    o.kind = Kind::Segment;
    insert(o);
  }
  if (!stem.hasVane()) return;
  for (const VaneTriangle& t : vaneTrianglesOf(stem)) {
    Obstacle o;
    o.points = {positionOf(stem, t.vertices[0]), positionOf(stem, t.vertices[1]),
                positionOf(stem, t.vertices[2])};
    o.kind = Kind::Vane;
    insert(o);
  }
}

bool RestingLayer::meets(const Mover& m, const Obstacle& o) const {
  // The body meets rachis segments only; a calamus stands on it.
  if (o.kind == Kind::Body && (m.triangle || m.calamus)) return false;
  ++pairTests_;
  const auto& p = m.points;
  const auto& q = o.points;
  if (!m.triangle) {
    if (o.kind == Kind::Segment) return segmentsIntersect(p[0], p[1], q[0], q[1]);
    if (clearlyOneSide(q, p, 2)) return false;
    return segmentIntersectsTriangle(p[0], p[1], q[0], q[1], q[2]);
  }
  if (o.kind == Kind::Segment) {
    if (clearlyOneSide(p, q, 2)) return false;
    return segmentIntersectsTriangle(q[0], q[1], p[0], p[1], p[2]);
  }
  if (clearlyOneSide(q, p, 3) || clearlyOneSide(p, q, 3)) return false;
  return trianglesIntersect(p[0], p[1], p[2], q[0], q[1], q[2]);
}

void RestingLayer::gather(const Vector3d& low, const Vector3d& high,
                          std::vector<Entry>& found) const {
  found.clear();
  if (!low.allFinite() || !high.allFinite()) return;
  if (++query_ == 0) {  // wrapped: every stamp is stale
    std::fill(seen_.begin(), seen_.end(), 0);
    query_ = 1;
  }
  const std::array<float, 3> from = roundedDown(low), to = roundedUp(high);
  const auto take = [&](const Entry& e) {
    if (!boxesOverlap(from, to, e.low, e.high) || seen_[e.index] == query_) return;
    seen_[e.index] = query_;
    found.push_back(e);
  };
  for (const Entry& e : large_) take(e);
  const std::int64_t x0 = cellOf(low.x()), x1 = cellOf(high.x());
  const std::int64_t y0 = cellOf(low.y()), y1 = cellOf(high.y());
  const std::int64_t z0 = cellOf(low.z()), z1 = cellOf(high.z());
  for (std::int64_t x = x0; x <= x1; ++x)
    for (std::int64_t y = y0; y <= y1; ++y)
      for (std::int64_t z = z0; z <= z1; ++z) {
        const auto cell = cells_.find(cellKey(x, y, z));
        if (cell == cells_.end()) continue;
        for (const Entry& e : cell->second) take(e);
      }
}

std::size_t RestingLayer::meeting(const std::vector<Mover>& movers, const std::vector<Entry>& near,
                                  bool firstOnly) const {
  std::size_t found = 0;
  for (const Mover& m : movers) {
    const int corners = m.triangle ? 3 : 2;
    Vector3d low = m.points[0], high = m.points[0];
    for (int i = 1; i < corners; ++i) {
      low = low.cwiseMin(m.points[i]);
      high = high.cwiseMax(m.points[i]);
    }
    const std::array<float, 3> from = roundedDown(low), to = roundedUp(high);
    for (const Entry& e : near) {
      if (!boxesOverlap(from, to, e.low, e.high) || !meets(m, obstacles_[e.index])) continue;
      ++found;
      if (firstOnly) return found;
    }
  }
  return found;
}

std::size_t RestingLayer::meetingPairs(const FeatherStem& stem) const {
  // Segment by segment: the rachis segment and its vane quads, gathered once by their box.
  const std::vector<VaneTriangle> triangles =
      stem.hasVane() ? vaneTrianglesOf(stem) : std::vector<VaneTriangle>{};
  std::size_t found = 0;
  std::vector<Mover> movers;
  std::vector<Entry> near;
  for (std::size_t k = 0; k + 1 < stem.nodeCount(); ++k) {
    movers.clear();
    movers.push_back(
        {{stem.positions[k], stem.positions[k + 1], stem.positions[k + 1]}, false, k == 0});
    for (const VaneTriangle& t : triangles) {
      if (t.segment != static_cast<int>(k)) continue;
      movers.push_back({{positionOf(stem, t.vertices[0]), positionOf(stem, t.vertices[1]),
                         positionOf(stem, t.vertices[2])},
                        true,
                        false});
    }
    Vector3d low = movers[0].points[0], high = low;
    for (const Mover& m : movers)
      for (const Vector3d& p : m.points) {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
    gather(low, high, near);
    found += meeting(movers, near, false);
  }
  return found;
}

int RestingLayer::laySegments(FeatherStem& stem, std::size_t from,
                              const std::vector<double>& floors, std::vector<double>& turns,
                              std::vector<LayState>& states, const LayingParameters& parameters) {
  const std::size_t n = stem.nodeCount();
  double length = 0;
  for (std::size_t k = 0; k + 1 < n; ++k) length += stem.restLengths[k];
  const double gap = parameters.gap * length;
  const auto width = [&](std::size_t node, int side) {
    return stem.hasVane() ? stem.vaneWidths[node][side] : 0.0;
  };
  std::vector<Mover> movers;
  int failed = -1;
  // How far the stem's direction has been turned up from the groom so far.
  double turned = states[from].turned;
  for (std::size_t k = from; k + 1 < n; ++k) {
    states[k].positions = stem.positions;
    states[k].frame = stem.frames[k];
    states[k].turned = turned;
    const Vector3d pk = stem.positions[k];
    const Vector3d along = stem.positions[k + 1] - pk;
    const Eigen::Matrix3d axes = stem.frames[k].axes;
    // Turning about along × U moves the segment towards its front U, away from the feathers it
    // lies over (beneath its back, the side that faces the body).
    Vector3d axis = along.cross(axes.col(0));
    axis = axis.norm() > 1e-12 * (1 + along.norm()) ? Vector3d(axis.normalized())
                                                    : Vector3d(axes.col(1));
    const std::array<Vector3d, 2> inner = {pk + width(k, 0) * axes.col(1),
                                           pk - width(k, 1) * axes.col(1)};
    // The segment's primitives with the stem beyond node k turned by `angle`.
    const auto place = [&](double angle) {
      const Vector3d q = pk + Eigen::AngleAxisd(angle, axis) * along;
      const Vector3d tangent =
          (q - pk).norm() > 0 ? Vector3d((q - pk).normalized()) : Vector3d(axes.col(2));
      const Vector3d binormal = perpendicularTowards(axes.col(0), tangent, axes.col(1));
      const Vector3d left = tangent.cross(binormal);
      movers.clear();
      movers.push_back({{pk, q, q}, false, k == 0});
      for (int side = 0; side < 2 && stem.hasVane(); ++side) {
        if (!hasVaneQuad(stem, static_cast<int>(k), side)) continue;
        const Vector3d outer =
            side == 0 ? Vector3d(q + width(k + 1, 0) * left) : Vector3d(q - width(k + 1, 1) * left);
        movers.push_back({{pk, q, outer}, true, false});
        movers.push_back({{pk, outer, inner[side]}, true, false});
      }
    };
    // Whatever the segment and its vane can reach turning about node k.
    double reach = along.norm() + std::max(width(k + 1, 0), width(k + 1, 1));
    reach = std::max(reach, std::max(width(k, 0), width(k, 1)));
    gather(pk.array() - reach, pk.array() + reach, near_);
    const auto clear = [&](double angle) {
      place(angle);
      return meeting(movers, near_, true) == 0;
    };
    const double highest = std::min(parameters.liftPerNode, parameters.largestLift - turned);
    double lowest = turned > 0 ? -std::min(turned, parameters.returnPerNode) : 0.0;
    lowest = std::min(std::max(lowest, floors[k]), std::max(highest, lowest));
    // Past the limit the rest of the stem is left as it lies.
    double chosen = overLimit(parameters) ? 0.0 : lowest;
    if (!overLimit(parameters) && !clear(lowest)) {
      double below = lowest;
      double found = std::numeric_limits<double>::quiet_NaN();
      if (lowest < 0) {
        if (clear(0))
          found = 0;
        else
          below = 0;
      }
      for (double step = parameters.firstStep; std::isnan(found) && below < highest; step *= 2) {
        const double angle = std::min(below + step, highest);
        if (clear(angle))
          found = angle;
        else
          below = angle;
        if (overLimit(parameters)) break;
      }
      if (std::isnan(found)) {
        // Nothing up to the highest angle is clear: the segment keeps the direction nearest
        // its groom's, and the caller lifts a node nearer the root.
        if (failed < 0) failed = static_cast<int>(k);
      } else {
        for (int h = 0; h < parameters.halvings; ++h) {
          const double middle = 0.5 * (below + found);
          if (clear(middle))
            found = middle;
          else
            below = middle;
        }
        chosen = found;
        const double extra = gap / std::max(along.norm(), 1e-300);
        if (found + extra <= highest && clear(found + extra)) chosen = found + extra;
      }
    }
    turns[k] = chosen;
    if (chosen != 0) {
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(chosen, axis).toRotationMatrix();
      for (std::size_t j = k + 1; j < n; ++j)
        stem.positions[j] = pk + turn * (stem.positions[j] - pk);
      turned += chosen;
    }
    // Node k + 1's frame as rebuildFrames makes it, for the next segment.
    const Vector3d next = stem.positions[k + 1] - pk;
    const Vector3d tangent = next.norm() > 0 ? Vector3d(next.normalized()) : Vector3d(axes.col(2));
    const Vector3d binormal = perpendicularTowards(axes.col(0), tangent, axes.col(1));
    StemFrame& frame = stem.frames[k + 1];
    frame.origin = stem.positions[k + 1];
    frame.axes.col(0) = binormal;
    frame.axes.col(1) = tangent.cross(binormal);
    frame.axes.col(2) = tangent;
  }
  return failed;
}

LaidStem RestingLayer::lay(FeatherStem& stem, const StemFrame& anchor,
                           const LayingParameters& parameters) {
  LaidStem out;
  const std::size_t n = stem.nodeCount();
  if (n < 2) return out;
  const std::vector<Vector3d> grown = stem.positions;
  // A segment that no turn of its own clears (a neighbour's vane slants across its way) is
  // reached from higher up: the node before it is made to turn by more, doubling, then the one
  // before that, the stem laid again from that node each time, until every segment is clear,
  // the root has turned by the most a node may, or the relays allowed are spent (then the stem
  // is left as first laid, nearest its groom, and what it meets is counted).
  std::vector<double> floors(n - 1, -std::numeric_limits<double>::infinity());
  std::vector<double> turns(n - 1, 0.0), raise(n - 1, 0.0);
  std::vector<LayState> states(n);
  rebuildFrames(stem, anchor);
  std::size_t from = 0;
  std::vector<Vector3d> first;
  for (int attempt = 0;; ++attempt) {
    if (attempt > 0) {
      // The segments before `from` lie as they were: the stem is laid again from there.
      stem.positions = states[from].positions;
      stem.frames[from] = states[from].frame;
    }
    const int failed = laySegments(stem, from, floors, turns, states, parameters);
    if (failed < 0 || overLimit(parameters)) break;
    // Kept in case nothing clears it: the stem laid nearest its groom.
    if (attempt == 0) first = stem.positions;
    int node = failed - 1;
    while (node >= 0) {
      const auto m = static_cast<std::size_t>(node);
      raise[m] = raise[m] > 0 ? 2 * raise[m] : parameters.raiseStep;
      if (turns[m] + raise[m] <= parameters.liftPerNode) break;
      raise[m] = 0;
      floors[m] = -std::numeric_limits<double>::infinity();
      --node;
    }
    if (node < 0 || attempt + 1 >= parameters.maxRelays) {
      stem.positions = first;
      break;
    }
    from = static_cast<std::size_t>(node);
    floors[from] = turns[from] + raise[from];
  }
  rebuildFrames(stem, anchor);
  if (stem.hasVane()) stem.vaneCorners = vaneCornersOf(stem);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Vector3d now = (stem.positions[k + 1] - stem.positions[k]).normalized();
    const Vector3d before = (grown[k + 1] - grown[k]).normalized();
    out.lift = std::max(out.lift, std::acos(std::clamp(now.dot(before), -1.0, 1.0)));
  }
  out.moved = stem.positions != grown;
  out.intersections = meetingPairs(stem);
  return out;
}

DeintersectionReport deintersectStems(std::vector<FeatherStem>& stems,
                                      const std::vector<StemFrame>& anchors, const BodyMesh& body,
                                      const LayingParameters& parameters, Progress* progress) {
  if (anchors.size() != stems.size())
    throw std::invalid_argument("laying a coat needs one anchor frame per stem");
  // The grid's cell: the mean extent of a segment with its vane, so that a primitive's box
  // covers a few cells and a cell holds a few primitives of each feather over it.
  double extent = 0;
  std::size_t segments = 0;
  for (const FeatherStem& stem : stems) {
    for (std::size_t k = 0; k + 1 < stem.nodeCount(); ++k) {
      double e = (stem.positions[k + 1] - stem.positions[k]).norm();
      if (stem.hasVane()) e = std::max(e, stem.vaneWidths[k + 1][0] + stem.vaneWidths[k + 1][1]);
      if (std::isfinite(e)) {
        extent += e;
        ++segments;
      }
    }
  }
  RestingLayer layer(body, segments > 0 ? 2 * extent / static_cast<double>(segments) : 1.0);
  DeintersectionReport report;
  if (progress)
    progress->begin("shingling feathers", Progress::Unit::Steps, static_cast<double>(stems.size()),
                    "feathers");
  for (std::size_t s = 0; s < stems.size(); ++s) {
    if (layer.overLimit(parameters)) {
      report.leftAsGrown = stems.size() - s;
      break;
    }
    const LaidStem laid = layer.lay(stems[s], anchors[s], parameters);
    ++report.stems;
    report.moved += laid.moved;
    report.intersections += laid.intersections;
    report.unresolved += laid.intersections > 0;
    report.largestLift = std::max(report.largestLift, laid.lift);
    layer.add(stems[s]);
    if (progress) progress->tick(static_cast<double>(s + 1));
  }
  report.pairTests = layer.pairTests();
  return report;
}

}  // namespace hirsute::dynamics
