// Between the simulator and the model (docs/dynamics.md, "hirsute simulate"): the roots bound to
// the body they grow on, so that they follow it as it moves (the study's Sec. 3.2.1), and the
// pose that bends a drawn feather as its simulated stem is (FeatherPart::poses).
#pragma once
#include <Eigen/Core>
#include <vector>

#include "hirsute/hairs/dynamics/feather_coat_simulation.h"
#include "hirsute/hairs/dynamics/feather_stem.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute::dynamics {

// A root on a body triangle: where it lies in barycentric coordinates, and its frame and its
// offset from the triangle (along the normal, mostly) in the triangle's frame. The triangle's
// frame is the normal interpolated from its vertices' and the tangent of its first edge made
// perpendicular to it, so that it turns smoothly with the surface.
struct BodyAnchor {
  int triangle = -1;  // -1: not on the body
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

// The area-weighted unit normal at each vertex of the body.
std::vector<Eigen::Vector3d> vertexNormals(const BodyMesh& body);

// Each anchor bound to the body triangle nearest to its origin, when that lies within
// `tolerance`; triangle -1 otherwise.
std::vector<BodyAnchor> bindAnchors(const BodyMesh& body, const std::vector<StemFrame>& anchors,
                                    double tolerance);

// The frame of a bound anchor on the body as it is now (same triangles, vertices moved), with
// the body's vertex normals.
StemFrame anchorOnBody(const BodyMesh& body, const std::vector<Eigen::Vector3d>& normals,
                       const BodyAnchor& anchor);

// The pose of `feather` bent as `moved` is, `rest` being the feather's stem at rest
// (buildFeatherStem of the same feather, the same segments): each node maps the rest stem about
// it onto the moved one, turned by the mean of the turns of the two segments it ends.
FeatherPose featherPoseOf(const Feather& feather, const FeatherStem& rest,
                          const FeatherStem& moved);

}  // namespace hirsute::dynamics
