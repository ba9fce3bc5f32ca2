// A model's feathers simulated frame by frame, their roots carried by the moving body.
#include "hirsute/hairs/dynamics/coat_motion.h"

#include <Eigen/Geometry>
#include <string>

#include "hirsute/hairs/dynamics/feather_stem.h"
#include "hirsute/hairs/dynamics/stem_vane.h"
#include "hirsute/hairs/feathers/feather_part.h"

namespace hirsute::dynamics {
namespace {

using Eigen::Vector3d;

// A root is on the body when it lies within half its calamus (the first segment of its stem)
// of a triangle: coat feathers stand on the surface the mesh tessellates, a little off its
// facets.
std::vector<BodyAnchor> bindRoots(const FeatherCoatSimulation& simulation) {
  std::vector<BodyAnchor> bound;
  const BodyMesh& body = simulation.body();
  for (std::size_t s = 0; s < simulation.stems().size(); ++s) {
    const FeatherStem& stem = simulation.stems()[s];
    std::vector<BodyAnchor> one =
        bindAnchors(body, {simulation.anchors()[s]}, 0.5 * stem.restLengths.front());
    bound.push_back(one.front());
  }
  return bound;
}

StemFrame between(const StemFrame& a, const StemFrame& b, double t) {
  StemFrame out;
  out.origin = (1 - t) * a.origin + t * b.origin;
  out.axes = Eigen::Quaterniond(a.axes)
                 .slerp(t, Eigen::Quaterniond(b.axes))
                 .normalized()
                 .toRotationMatrix();
  return out;
}

Vector3d toEigen(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

}  // namespace

SimulationParameters simulationParametersOf(const FeatherDynamicsSettings& view) {
  SimulationParameters p;
  p.gravity = toEigen(view.gravity);
  p.wind.velocity = toEigen(view.wind);
  p.wind.gustStrength = view.gustStrength;
  p.wind.gustScale = view.gustScale;
  p.wind.gustPeriod = view.gustPeriod;
  p.wind.seed = static_cast<int>(view.gustSeed);
  p.dragCoefficient = view.drag;
  p.stem.goldStiffness = view.stiffness;
  p.stem.goldDamping = view.damping;
  p.thickness = view.thickness;
  p.minimumSeparation = view.separation;
  p.segmentsPerFeather = view.segments;
  p.vaneCollisions = view.vanes;
  return p;
}

CoatMotion::CoatMotion(const Scene& first, const SimulationParameters& parameters)
    : simulation_(FeatherCoatSimulation::fromScene(first, parameters)),
      bound_(bindRoots(simulation_)),
      feathers_(first.organ<FeatherPart>().feathers),
      featherBounds_(first.organ<FeatherPart>().bounds) {}

std::size_t CoatMotion::boundRoots() const {
  std::size_t n = 0;
  for (const BodyAnchor& a : bound_) n += a.triangle >= 0;
  return n;
}

std::size_t CoatMotion::penetrations() const {
  return countPenetrations(simulation_.stems(), simulation_.body(),
                           simulation_.nearestAllowed());
}

std::size_t CoatMotion::vaneIntersections() const {
  return countVaneIntersections(simulation_.stems(), simulation_.nearestAllowed(),
                                &simulation_.vaneOverlaps());
}

CoatTarget CoatMotion::targetOf(const Scene& next) const {
  const std::vector<Vector3d>& fromBody = simulation_.body().vertices;
  if (boundRoots() < bound_.size() &&
      next.organ<FeatherPart>().feathers.size() != simulation_.stems().size()) {
    throw FrameMismatch(
        "the frame has " + std::to_string(next.organ<FeatherPart>().feathers.size()) +
        " feathers where the simulation has " + std::to_string(simulation_.stems().size()) +
        ": a simulation needs the same feathers in every frame");
  }
  BodyMesh body = bodyMeshOf(next);
  if (body.vertices.size() != fromBody.size() || body.triangles != simulation_.body().triangles) {
    throw FrameMismatch(
        "the frame's body has " + std::to_string(body.triangles.size()) + " triangles over " +
        std::to_string(body.vertices.size()) + " vertices where the first had " +
        std::to_string(simulation_.body().triangles.size()) + " over " +
        std::to_string(fromBody.size()) + ": the body may move and bend, but keep its mesh");
  }
  CoatTarget target;
  target.anchors.resize(simulation_.anchors().size());
  const std::vector<Vector3d> normals = vertexNormals(body);
  for (std::size_t s = 0; s < target.anchors.size(); ++s)
    target.anchors[s] = bound_[s].triangle >= 0
                            ? anchorOnBody(body, normals, bound_[s])
                            : anchorFrameOf(next.organ<FeatherPart>().feathers[s]);
  target.body = std::move(body.vertices);
  return target;
}

void CoatMotion::advance(double seconds, int steps, const Scene* next) {
  if (steps < 1 || !(seconds > 0)) throw std::invalid_argument("a frame needs a time and steps");
  if (next) {
    advance(seconds, steps, targetOf(*next));
    return;
  }
  advance(seconds, steps, CoatTarget{simulation_.anchors(), simulation_.body().vertices});
}

void CoatMotion::advance(double seconds, int steps, const CoatTarget& target) {
  if (steps < 1 || !(seconds > 0)) throw std::invalid_argument("a frame needs a time and steps");
  const std::vector<StemFrame> fromAnchors = simulation_.anchors();
  const std::vector<Vector3d> fromBody = simulation_.body().vertices;
  if (target.anchors.size() != fromAnchors.size() || target.body.size() != fromBody.size())
    throw std::invalid_argument("a target of another coat");
  std::vector<StemFrame> anchors(fromAnchors.size());
  std::vector<Vector3d> vertices(fromBody.size());
  for (int k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    for (std::size_t s = 0; s < anchors.size(); ++s)
      anchors[s] = between(fromAnchors[s], target.anchors[s], t);
    for (std::size_t v = 0; v < vertices.size(); ++v)
      vertices[v] = (1 - t) * fromBody[v] + t * target.body[v];
    simulation_.step(seconds / steps, anchors, vertices);
  }
  // Vanes that overlapped from the start and have come apart collide from the next frame on.
  simulation_.releaseVaneOverlaps();
}

void CoatMotion::pose(Scene& scene) const {
  FeatherPart& part = scene.organ<FeatherPart>();
  const auto& stems = simulation_.stems();
  part.feathers = feathers_;
  part.bounds = featherBounds_;
  part.poses.clear();
  part.poses.reserve(stems.size());
  const SimulationParameters& p = simulation_.parameters();
  for (std::size_t s = 0; s < stems.size(); ++s) {
    const Feather& feather = part.feathers[s];
    const FeatherStem rest = buildFeatherStem(scene, feather, p.segmentsPerFeather, p.stem);
    part.poses.push_back(featherPoseOf(feather, rest, stems[s]));
  }
}

}  // namespace hirsute::dynamics
