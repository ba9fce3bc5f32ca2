// Roots bound to a moving body by barycentric coordinates, and the poses of bent feathers.
#include "hirsute/hairs/dynamics/feather_poses.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "hirsute/hairs/dynamics/closest_points.h"
#include "hirsute/hairs/feathers/feather_instances.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Any unit vector perpendicular to the unit vector n.
Vector3d perpendicularTo(const Vector3d& n) {
  const Vector3d other = std::abs(n.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  return n.cross(other).normalized();
}

// The frame of triangle t at barycentric `weights`: (tangent, normal × tangent, normal), the
// normal interpolated from the vertices', the tangent along the first edge.
Matrix3d triangleFrame(const BodyMesh& body, const std::vector<Vector3d>& normals, int t,
                       const Vector3d& weights) {
  const auto& tri = body.triangles[t];
  const Vector3d& a = body.vertices[tri[0]];
  const Vector3d& b = body.vertices[tri[1]];
  const Vector3d& c = body.vertices[tri[2]];
  Vector3d n = weights[0] * normals[tri[0]] + weights[1] * normals[tri[1]] +
               weights[2] * normals[tri[2]];
  if (!(n.norm() > 1e-12)) n = (b - a).cross(c - a);
  n = n.norm() > 0 ? Vector3d(n.normalized()) : Vector3d::UnitZ();
  Vector3d tangent = (b - a) - (b - a).dot(n) * n;
  tangent = tangent.norm() > 1e-12 * (1 + (b - a).norm()) ? Vector3d(tangent.normalized())
                                                           : perpendicularTo(n);
  Matrix3d frame;
  frame.col(0) = tangent;
  frame.col(1) = n.cross(tangent);
  frame.col(2) = n;
  return frame;
}

Vector3d pointAt(const BodyMesh& body, int t, const Vector3d& weights) {
  const auto& tri = body.triangles[t];
  return weights[0] * body.vertices[tri[0]] + weights[1] * body.vertices[tri[1]] +
         weights[2] * body.vertices[tri[2]];
}

glm::mat4 toGlm(const Eigen::Matrix4d& m) {
  glm::mat4 out;
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row) out[column][row] = static_cast<float>(m(row, column));
  return out;
}

Eigen::Matrix4d toEigen(const glm::mat4& m) {
  Eigen::Matrix4d out;
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row) out(row, column) = m[column][row];
  return out;
}

}  // namespace

std::vector<Vector3d> vertexNormals(const BodyMesh& body) {
  std::vector<Vector3d> normals(body.vertices.size(), Vector3d::Zero());
  for (const auto& tri : body.triangles) {
    const Vector3d n = (body.vertices[tri[1]] - body.vertices[tri[0]])
                           .cross(body.vertices[tri[2]] - body.vertices[tri[0]]);
    for (int v : tri) normals[v] += n;
  }
  for (Vector3d& n : normals) n = n.norm() > 0 ? Vector3d(n.normalized()) : Vector3d::UnitZ();
  return normals;
}

std::vector<BodyAnchor> bindAnchors(const BodyMesh& body, const std::vector<StemFrame>& anchors,
                                    double tolerance) {
  const std::vector<Vector3d> normals = vertexNormals(body);
  std::vector<BodyAnchor> bound(anchors.size());
  for (std::size_t s = 0; s < anchors.size(); ++s) {
    const Vector3d& p = anchors[s].origin;
    double nearest = std::numeric_limits<double>::infinity();
    for (int t = 0; t < static_cast<int>(body.triangles.size()); ++t) {
      const auto& tri = body.triangles[t];
      const Vector3d& a = body.vertices[tri[0]];
      const Vector3d& b = body.vertices[tri[1]];
      const Vector3d& c = body.vertices[tri[2]];
      // Cheap rejection by the triangle's box grown by the tolerance.
      const Vector3d low = a.cwiseMin(b).cwiseMin(c).array() - tolerance;
      const Vector3d high = a.cwiseMax(b).cwiseMax(c).array() + tolerance;
      if ((p.array() < low.array()).any() || (p.array() > high.array()).any()) continue;
      const std::array<double, 3> w = closestOnTriangle(p, a, b, c);
      const Vector3d weights(w[0], w[1], w[2]);
      const double distance = (pointAt(body, t, weights) - p).norm();
      if (distance < nearest && distance <= tolerance) {
        nearest = distance;
        bound[s].triangle = t;
        bound[s].weights = weights;
      }
    }
    BodyAnchor& anchor = bound[s];
    if (anchor.triangle < 0) continue;
    const Matrix3d frame = triangleFrame(body, normals, anchor.triangle, anchor.weights);
    anchor.offset = frame.transpose() * (p - pointAt(body, anchor.triangle, anchor.weights));
    anchor.axes = frame.transpose() * anchors[s].axes;
  }
  return bound;
}

StemFrame anchorOnBody(const BodyMesh& body, const std::vector<Vector3d>& normals,
                       const BodyAnchor& anchor) {
  const Matrix3d frame = triangleFrame(body, normals, anchor.triangle, anchor.weights);
  StemFrame out;
  out.origin = pointAt(body, anchor.triangle, anchor.weights) + frame * anchor.offset;
  out.axes = frame * anchor.axes;
  return out;
}

FeatherPose featherPoseOf(const Feather& feather, const FeatherStem& rest,
                          const FeatherStem& moved) {
  const std::size_t n = rest.nodeCount();
  if (moved.nodeCount() != n || rest.heights.size() != n || n < 2)
    throw std::invalid_argument("a feather's pose needs its rest stem and a moved stem alike");
  // The turn of segment j (from node j to j + 1): its frame is the frame of node j + 1.
  std::vector<Eigen::Quaterniond> turns;
  for (std::size_t j = 0; j + 1 < n; ++j)
    turns.emplace_back(moved.frames[j + 1].axes * rest.frames[j + 1].axes.transpose());
  const Eigen::Matrix4d local = toEigen(featherToWorld(feather));
  FeatherPose pose;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Quaterniond turn = i == 0 ? turns.front() : i == n - 1 ? turns.back()
                                                                : turns[i - 1].slerp(0.5, turns[i]);
    Eigen::Matrix4d map = Eigen::Matrix4d::Identity();
    map.topLeftCorner<3, 3>() = turn.normalized().toRotationMatrix();
    map.topRightCorner<3, 1>() =
        moved.positions[i] - map.topLeftCorner<3, 3>() * rest.positions[i];
    pose.heights.push_back(static_cast<float>(rest.heights[i]));
    pose.toWorld.push_back(toGlm(map * local));
  }
  return pose;
}

}  // namespace hirsute::dynamics
