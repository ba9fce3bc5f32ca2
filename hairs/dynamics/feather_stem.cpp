// Stems of particles: construction from a feather's rachis, the frames of Sec. 3.2, the implicit
// gold springs of Sec. 3.3.1 and strain limiting.
#include "hirsute/hairs/dynamics/feather_stem.h"

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <glm/mat4x4.hpp>
#include <stdexcept>
#include <utility>

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

// [v]x: the matrix of v x .
Eigen::Matrix3d skew(const Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
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

void advanceGoldSprings(FeatherStem& stem, double h, double lookahead,
                        const std::vector<Vector3d>& forces, const Vector3d& anchorVelocity) {
  const int nodes = static_cast<int>(stem.nodeCount());
  const double k = stem.parameters.goldStiffness, b = stem.parameters.goldDamping;
  // The whole chain's system, anchor included, in 3 x 3 blocks: M + h b L + h lookahead K. The
  // anchor's rows are dropped and its columns, its velocity being known, go to the right-hand
  // side.
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(3 * nodes, 3 * nodes);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * nodes);
  auto block = [&](int row, int column) { return system.block<3, 3>(3 * row, 3 * column); };
  for (int node = 1; node < nodes; ++node) {
    block(node, node).diagonal().setConstant(stem.masses[node]);
    rhs.segment<3>(3 * node) = stem.masses[node] * stem.velocities[node] + h * forces[node];
  }
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  for (int node = 1; node < nodes; ++node) {
    // Spring `node` stretches by d = p_i - p_{i-1} - R_{i-1} g_i and pulls node i by -k d, its
    // parent by +k d, so that the springs keep momentum.
    const StemFrame& parent = stem.frames[node - 1];
    const Vector3d offset = parent.axes * stem.goldPositions[node];  // R_{i-1} g_i
    const Vector3d d = stem.positions[node] - stem.positions[node - 1] - offset;
    rhs.segment<3>(3 * node) -= h * k * d;
    rhs.segment<3>(3 * (node - 1)) += h * k * d;
    // How d changes with the positions. The parent's frame turns with the tangent of the
    // segment that ends at the parent (rebuildFrames' transport: by w = t x dt, the twist it
    // carries from further up left out); dt = (I - t t^T)(dp_{i-1} - dp_{i-2}) / l, so that
    // d(R g) = w x (R g) = -[R g]x [t]x (dp_{i-1} - dp_{i-2}) / l =: J (dp_{i-1} - dp_{i-2}).
    // The anchor's frame is kinematic: node 1's turn stays with the anchor's motion.
    Eigen::Matrix3d turn = Eigen::Matrix3d::Zero();
    if (node >= 2) {
      const double length = (stem.positions[node - 1] - stem.positions[node - 2]).norm();
      if (length > 0) turn = -skew(offset) * skew(parent.axes.col(2)) / length;
    }
    // Rows of node i take k dd, rows of its parent -k dd (K = -df/dx); the damping b L acts on
    // the relative velocity v_i - v_{i-1}.
    const double stiff = h * lookahead * k, damp = h * b;
    const Eigen::Matrix3d ofNode = (stiff + damp) * identity;
    const Eigen::Matrix3d ofParent = -(stiff + damp) * identity - stiff * turn;
    for (const auto& [row, sign] : {std::pair{node, 1.0}, std::pair{node - 1, -1.0}}) {
      block(row, node) += sign * ofNode;
      block(row, node - 1) += sign * ofParent;
      if (node >= 2) block(row, node - 2) += sign * stiff * turn;
    }
  }
  const int free = 3 * (nodes - 1);
  const Eigen::VectorXd known = rhs.tail(free) - system.bottomLeftCorner(free, 3) * anchorVelocity;
  const Eigen::VectorXd v = system.bottomRightCorner(free, free).partialPivLu().solve(known);
  stem.velocities[0] = anchorVelocity;
  for (int node = 1; node < nodes; ++node) stem.velocities[node] = v.segment<3>(3 * (node - 1));
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
