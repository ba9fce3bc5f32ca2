// Stems of particles: construction from a feather's rachis, the frames of Sec. 3.2, the implicit
// gold springs of Sec. 3.3.1 and strain limiting.
#include "hirsute/hairs/dynamics/feather_stem.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <glm/mat4x4.hpp>
#include <stdexcept>

#include "hirsute/hairs/feathers/bezier_curve.h"
#include "hirsute/hairs/feathers/feather_geometry.h"
#include "hirsute/hairs/feathers/feather_instances.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

Vector3d toEigen(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

// A unit vector perpendicular to `tangent` (unit), as near to `preferred` as possible; when
// `preferred` is along the tangent, `fallback` is used instead.
Vector3d perpendicularTowards(const Vector3d& preferred, const Vector3d& tangent,
                              const Vector3d& fallback) {
  for (const Vector3d& candidate : {preferred, fallback}) {
    const Vector3d p = candidate - candidate.dot(tangent) * tangent;
    if (p.norm() > 1e-9) return p.normalized();
  }
  // Both along the tangent: any perpendicular will do.
  return tangent.unitOrthogonal();
}

}  // namespace

StemFrame anchorFrameOf(const Feather& feather) {
  const Vector3d heading = toEigen(feather.heading).normalized();
  const Vector3d up = perpendicularTowards(toEigen(feather.up), heading, heading.unitOrthogonal());
  StemFrame frame;
  frame.origin = toEigen(feather.position);
  frame.axes.col(0) = up;
  frame.axes.col(1) = heading.cross(up);
  frame.axes.col(2) = heading;
  return frame;
}

FeatherStem buildFeatherStem(const Scene& scene, const Feather& feather, int segments,
                             const StemParameters& parameters) {
  if (segments < 1) throw std::invalid_argument("a stem needs at least one segment");
  const FeatherType type = featherTypeOf(scene, feather);
  const float cl = type.calamusLength, rl = type.rachisLength;
  // The rachis of feather_geometry.h (Streit & Heidrich 2002, Sec. 4.3.1), in the local frame.
  const float front = type.rachisFrontCurvature * rl, side = type.rachisSideCurvature * rl;
  const glm::vec3 rachis[4] = {glm::vec3(0, 0, cl), glm::vec3(front, side, cl + rl / 3),
                               glm::vec3(front, side, cl + 2 * rl / 3), glm::vec3(0, 0, cl + rl)};
  std::vector<glm::vec3> local{glm::vec3(0)};
  // The calamus is a segment of its own when there are segments to spare for the rachis.
  const bool calamusSegment = cl > 0 && rl > 0 && segments >= 2;
  if (calamusSegment) local.push_back(glm::vec3(0, 0, cl));
  const int rachisSegments = calamusSegment ? segments - 1 : segments;
  for (int j = 1; j <= rachisSegments; ++j) {
    const double t = static_cast<double>(j) / rachisSegments;
    local.push_back(rl > 0 ? glm::vec3(bezierPoint(rachis, t)) : glm::vec3(0, 0, cl * t));
  }
  const glm::mat4 toWorld = featherToWorld(feather);
  std::vector<Vector3d> points;
  for (const glm::vec3& p : local) points.push_back(toEigen(glm::vec3(toWorld * glm::vec4(p, 1))));
  FeatherStem stem = buildStemFromPoints(points, anchorFrameOf(feather), parameters);
  for (const glm::vec3& p : local) stem.heights.push_back(p.z);
  std::vector<Vector3d> nodes;
  for (const glm::vec3& p : local) nodes.push_back(toEigen(p));
  stem.vaneWidths = vaneHalfWidths(type, nodes);
  for (auto& w : stem.vaneWidths) w = {w[0] * feather.size, w[1] * feather.size};
  stem.vaneCorners = vaneCornersOf(stem);
  return stem;
}

std::vector<std::array<double, 2>> vaneHalfWidths(const FeatherType& type,
                                                  const std::vector<Vector3d>& nodes) {
  std::vector<std::array<double, 2>> widths(nodes.size(), {0.0, 0.0});
  if (nodes.empty() || !(type.rachisLength > 0)) return widths;
  // The drawn barbs at a coarse detail: the barbs' shapes (their polylines' corners) are what
  // the vane's outline is made of, and a few segments a barb follow it to a small part of its
  // length; the number of barbs is the type's.
  FeatherDetail detail;
  detail.rachisSegments = 3;
  detail.barbSegments = 6;
  detail.shaftSides = 3;
  const FeatherGeometry geometry = buildFeatherGeometry(type, detail);
  const double base = type.calamusLength;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].z() < base) continue;
    const double below = i > 0 ? 0.5 * (nodes[i].z() + nodes[i - 1].z()) : nodes[i].z();
    const double above = i + 1 < nodes.size() ? 0.5 * (nodes[i].z() + nodes[i + 1].z())
                                              : nodes[i].z();
    const double from = std::max(below, base), to = above;
    for (const Barb& barb : geometry.barbs) {
      const int side = barb.side == BarbSide::Right ? 1 : 0;
      const double sign = side == 0 ? 1 : -1;
      auto reach = [&](double y) {
        widths[i][side] = std::max(widths[i][side], sign * (y - nodes[i].y()));
      };
      // Every barb point within the heights, and where the barb's segments cross their ends.
      for (std::uint32_t k = 0; k < barb.vertexCount; ++k) {
        const glm::vec3& p = geometry.vertices.positions[barb.firstVertex + k];
        if (p.z >= from && p.z <= to) reach(p.y);
        if (k == 0) continue;
        const glm::vec3& q = geometry.vertices.positions[barb.firstVertex + k - 1];
        for (const double z : {from, to}) {
          if ((q.z - z) * (p.z - z) < 0) reach(q.y + (p.y - q.y) * (z - q.z) / (p.z - q.z));
        }
      }
    }
  }
  return widths;
}

std::vector<std::array<Vector3d, 2>> vaneCornersAt(const FeatherStem& stem,
                                                   const StemFrame& anchor) {
  std::vector<std::array<Vector3d, 2>> corners(stem.vaneWidths.size());
  // The frames of rebuildFrames, walked without keeping them.
  Eigen::Matrix3d axes = anchor.axes;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    if (i > 0) {
      const Vector3d along = stem.positions[i] - stem.positions[i - 1];
      const Vector3d tangent = along.norm() > 0 ? along.normalized() : Vector3d(axes.col(2));
      const Vector3d binormal = perpendicularTowards(axes.col(0), tangent, axes.col(1));
      axes.col(0) = binormal;
      axes.col(1) = tangent.cross(binormal);
      axes.col(2) = tangent;
    }
    const Vector3d left = axes.col(1);
    corners[i] = {stem.positions[i] + stem.vaneWidths[i][0] * left,
                  stem.positions[i] - stem.vaneWidths[i][1] * left};
  }
  return corners;
}

std::vector<std::array<Vector3d, 2>> vaneCornersOf(const FeatherStem& stem) {
  std::vector<std::array<Vector3d, 2>> corners(stem.vaneWidths.size());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Vector3d left = stem.frames[i].axes.col(1);
    corners[i] = {stem.positions[i] + stem.vaneWidths[i][0] * left,
                  stem.positions[i] - stem.vaneWidths[i][1] * left};
  }
  return corners;
}

FeatherStem buildStemFromPoints(const std::vector<Vector3d>& points, const StemFrame& anchor,
                                const StemParameters& parameters) {
  if (points.size() < 2) throw std::invalid_argument("a stem needs at least two points");
  FeatherStem stem;
  stem.parameters = parameters;
  stem.positions = points;
  stem.velocities.assign(points.size(), Vector3d::Zero());
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const double length = (points[i + 1] - points[i]).norm();
    if (!(length > 0)) throw std::invalid_argument("a stem's segments must have a length");
    stem.restLengths.push_back(length);
  }
  // Each node carries half of each segment it ends (a lumped mass); the anchor's is unused.
  stem.masses.assign(points.size(), 0.0);
  for (std::size_t i = 0; i < stem.restLengths.size(); ++i) {
    const double half = 0.5 * parameters.linearDensity * stem.restLengths[i];
    stem.masses[i] += half;
    stem.masses[i + 1] += half;
  }
  rebuildFrames(stem, anchor);
  stem.goldPositions.assign(points.size(), Vector3d::Zero());
  for (std::size_t i = 1; i < points.size(); ++i) {
    const StemFrame& parent = stem.frames[i - 1];
    stem.goldPositions[i] = parent.axes.transpose() * (points[i] - parent.origin);
  }
  return stem;
}

void rebuildFrames(FeatherStem& stem, const StemFrame& anchor) {
  stem.frames.resize(stem.positions.size());
  stem.frames[0] = anchor;
  stem.frames[0].origin = stem.positions[0];
  for (std::size_t i = 1; i < stem.positions.size(); ++i) {
    const StemFrame& parent = stem.frames[i - 1];
    const Vector3d along = stem.positions[i] - stem.positions[i - 1];
    // A collapsed segment keeps its parent's tangent.
    const Vector3d tangent = along.norm() > 0 ? along.normalized() : Vector3d(parent.axes.col(2));
    const Vector3d binormal = perpendicularTowards(parent.axes.col(0), tangent, parent.axes.col(1));
    StemFrame& frame = stem.frames[i];
    frame.origin = stem.positions[i];
    frame.axes.col(0) = binormal;
    frame.axes.col(1) = tangent.cross(binormal);
    frame.axes.col(2) = tangent;
  }
}

Vector3d worldGoldPosition(const FeatherStem& stem, std::size_t node) {
  const StemFrame& parent = stem.frames[node - 1];
  return parent.origin + parent.axes * stem.goldPositions[node];
}

void advanceGoldSprings(FeatherStem& stem, double h, const std::vector<Vector3d>& forces,
                        const Vector3d& anchorVelocity) {
  const int n = static_cast<int>(stem.nodeCount()) - 1;  // the free nodes 1..n are rows 0..n-1
  const double k = stem.parameters.goldStiffness, b = stem.parameters.goldDamping;
  const double coupling = h * (h * k + b);
  // A stem's system is small and tridiagonal: a dense factorization beats a sparse one's
  // ordering and allocations.
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixX3d rhs(n, 3);
  for (int row = 0; row < n; ++row) {
    const std::size_t node = row + 1;
    const bool hasChild = node + 1 < stem.nodeCount();
    system(row, row) = stem.masses[node] + coupling * (hasChild ? 2 : 1);
    if (row > 0) system(row, row - 1) = -coupling;
    if (hasChild) system(row, row + 1) = -coupling;
    rhs.row(row) = (stem.masses[node] * stem.velocities[node] + h * forces[node]).transpose();
  }
  // The elastic part at the current positions: spring i pulls node i to its gold position and
  // pushes its parent the other way.
  for (std::size_t node = 1; node < stem.nodeCount(); ++node) {
    const Vector3d f = -k * (stem.positions[node] - worldGoldPosition(stem, node));
    rhs.row(node - 1) += h * f.transpose();
    if (node >= 2) rhs.row(node - 2) -= h * f.transpose();
  }
  // The anchor's velocity is known: its coupling with node 1 moves to the right-hand side.
  rhs.row(0) += coupling * anchorVelocity.transpose();
  const Eigen::MatrixX3d v = system.llt().solve(rhs);  // symmetric positive definite
  stem.velocities[0] = anchorVelocity;
  for (int row = 0; row < n; ++row) stem.velocities[row + 1] = v.row(row).transpose();
}

int limitStrain(FeatherStem& stem, double h) {
  const double limit = stem.parameters.strainLimit;
  // Corrections aim a little inside the limit, so that rounding never leaves a segment outside.
  const double aim = limit * 0.999;
  auto correct = [&](std::size_t i, bool outerOnly) {
    const double rest = stem.restLengths[i];
    Vector3d along = stem.positions[i + 1] - stem.positions[i];
    const double length = along.norm();
    if (std::abs(length / rest - 1) <= limit) return false;
    const double target = std::clamp(length, rest * (1 - aim), rest * (1 + aim));
    const Vector3d direction = length > 0 ? Vector3d(along / length) : stem.frames[i].axes.col(2);
    const double inner = (i == 0 || outerOnly) ? 0.0 : 1 / stem.masses[i];
    const double outer = 1 / stem.masses[i + 1];
    const double excess = length - target;
    const Vector3d innerMove = excess * inner / (inner + outer) * direction;
    const Vector3d outerMove = -excess * outer / (inner + outer) * direction;
    stem.positions[i] += innerMove;
    stem.velocities[i] += innerMove / h;
    if (outerOnly) {
      // Exactly at the target from the (fixed) inner end.
      const Vector3d placed = stem.positions[i] + target * direction;
      stem.velocities[i + 1] += (placed - stem.positions[i + 1]) / h;
      stem.positions[i + 1] = placed;
    } else {
      stem.positions[i + 1] += outerMove;
      stem.velocities[i + 1] += outerMove / h;
    }
    return true;
  };
  constexpr int kMassWeightedSweeps = 16;
  int sweeps = 0;
  for (; sweeps < kMassWeightedSweeps; ++sweeps) {
    bool changed = false;
    for (std::size_t i = 0; i < stem.restLengths.size(); ++i) changed |= correct(i, false);
    if (!changed) return sweeps;
  }
  // Every segment is now placed from its (already final) inner end, so the limit holds.
  for (std::size_t i = 0; i < stem.restLengths.size(); ++i) correct(i, true);
  return sweeps + 1;
}

double largestStrain(const FeatherStem& stem) {
  double largest = 0;
  for (std::size_t i = 0; i < stem.restLengths.size(); ++i) {
    const double length = (stem.positions[i + 1] - stem.positions[i]).norm();
    largest = std::max(largest, std::abs(length / stem.restLengths[i] - 1));
  }
  return largest;
}

}  // namespace hirsute::dynamics
