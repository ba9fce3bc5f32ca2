// Generalized cylinders as cpfg builds them: Hermite axis and radius profile between control
// points, rings of blended contours, strips of triangles, and the segment data appendages read
// (cpfg-generalized-cylinders.md §1–§4; cpfg general.c, blackbox.c, textures.c).
#include "hirsute/interpreter/generalized_cylinder.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

namespace hirsute {

namespace {

// §2: a segment shorter than this draws nothing (its end still becomes the next start).
constexpr double kMinimumSegmentLength = 1e-5;
// Strips per segment are capped like sides (kMaxContourSides): cpfg has no cap, but a model
// asking for more would only exhaust memory.
constexpr int kMaxStrips = 4096;

struct Frame {
  glm::dvec3 position{0.0};
  glm::dvec3 heading{0, 1, 0};
  glm::dvec3 left{-1, 0, 0};
  glm::dvec3 up{0, 0, -1};
};

Frame frameOf(const TurtleState& state) {
  return Frame{state.position, state.heading, state.left, state.up};
}

ControlFrame toControlFrame(const Frame& frame) {
  return ControlFrame{glm::vec3(frame.position), glm::vec3(frame.heading), glm::vec3(frame.left),
                      glm::vec3(frame.up)};
}

// Rodrigues' rotation of v about the unit axis k by angle radians (right-handed).
glm::dvec3 rotate(const glm::dvec3& v, const glm::dvec3& k, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1.0 - c);
}

// cpfg adjust_up_and_leftS(cur, prev, 0): the previous up vector rotated about H_prev × H_cur by
// asin(|H_prev × H_cur|), the rotation that carries H_prev onto H_cur for turns up to 90°; beyond
// 90° asin returns 180° minus the turn and the frame leans, as in cpfg. Left is H × U.
Frame transportFrame(const Frame& from, const glm::dvec3& position, const glm::dvec3& heading) {
  Frame to;
  to.position = position;
  to.heading = heading;
  const glm::dvec3 axis = glm::cross(from.heading, heading);
  const double sine = glm::length(axis);
  to.up = sine > 1e-12 ? rotate(from.up, axis / sine, std::asin(std::min(sine, 1.0))) : from.up;
  to.left = glm::cross(to.heading, to.up);
  return to;
}

// cpfg get_twist_angle(prev, cur): the signed angle about H_cur from the transported up vector
// to the turtle's own up vector.
double twistAngle(const Frame& transported, const Frame& actual) {
  const glm::dvec3 h = glm::normalize(actual.heading);
  return std::atan2(glm::dot(glm::cross(transported.up, actual.up), h),
                    glm::dot(transported.up, actual.up));
}

// textures.c: the image is clamped to 2^m × 2^n before it is bound.
int clampToPowerOfTwo(int size) {
  int power = 1;
  while (power * 2 <= size) power *= 2;
  return power;
}

// A contour sample j = 0..sides of a ring: closed contours wrap (j = sides is the seam again).
template <typename T>
T sampleAt(const std::vector<T>& samples, bool closed, int j) {
  const std::size_t size = samples.size();
  if (size == 0) return T(0);
  const std::size_t index =
      closed ? static_cast<std::size_t>(j) % size : std::min(static_cast<std::size_t>(j), size - 1);
  return samples[index];
}

struct Ring {
  Frame frame;
  double axisParameter = 0;
  double radius = 0;
  double normalScale = 1;  // radius · dX/ds: its sign turns the ring's normals (see emitTriangles)
  double axisDistance = 0;
  double textureT = 0;
};

}  // namespace

// The tube in progress: what `[` saves and `]` restores (§1).
struct GeneralizedCylinderBuilder::Saved {
  // A control point as the tube remembers it: the turtle state (its frame replaced by the
  // carried one when twist of cylinders is off), and the texture coordinate t and the arc length
  // from @Gs reached there.
  struct ControlPoint {
    TurtleState state;
    double textureT = 0;
    double axisDistance = 0;
  };

  bool active = false;
  bool addsPointsOnMoves = false;
  int tube = 0;
  ControlPoint last;
};

struct GeneralizedCylinderBuilder::Impl {
  const ModelResources& resources;
  Scene* scene;
  Saved spline;
  int nextTube = 0;
  std::size_t maxVertices = kDefaultMaxVertices;

  Impl(const ModelResources& r, Scene* s) : resources(r), scene(s) {
    if (scene == nullptr) return;
    for (const CylinderSegment& segment : scene->cylinderSegments) {
      nextTube = std::max(nextTube, segment.tube + 1);
    }
  }

  void start(const TurtleState& state) {
    spline.active = true;
    spline.addsPointsOnMoves = false;
    spline.tube = nextTube++;
    // §4: the first control point takes the turtle's current texture coordinate.
    spline.last = Saved::ControlPoint{state, state.texCoordT, 0.0};
  }

  void addPoint(const TurtleState& state, int strips);
  void drawSegment(const Saved::ControlPoint& first, Saved::ControlPoint& second, int strips);
  // (W/H)/R of the first point's texture, or nothing when it has no valid texture (§4).
  std::optional<double> textureAspect(const TurtleState& state) const;
  void emitTriangles(const TurtleState& first, const std::vector<Ring>& rings,
                     const ContourSamples& c1, const ContourSamples& c2, int sides, double len,
                     bool textured, CylinderSegment& segment);
};

std::optional<double> GeneralizedCylinderBuilder::Impl::textureAspect(
    const TurtleState& state) const {
  if (state.texture < 1 || static_cast<std::size_t>(state.texture) > resources.textures.size()) {
    return std::nullopt;
  }
  const std::size_t index = static_cast<std::size_t>(state.texture - 1);
  const Texture& texture = resources.textures[index];
  if (texture.width <= 0 || texture.height <= 0) return std::nullopt;
  double ratio = 1.0;
  if (index < resources.view.textures.size() && resources.view.textures[index].ratio > 0.0f) {
    ratio = resources.view.textures[index].ratio;
  }
  return static_cast<double>(clampToPowerOfTwo(texture.width)) / clampToPowerOfTwo(texture.height) /
         ratio;
}

void GeneralizedCylinderBuilder::Impl::addPoint(const TurtleState& state, int strips) {
  Saved::ControlPoint current{state, spline.last.textureT, spline.last.axisDistance};
  const Frame previous = frameOf(spline.last.state);
  // §2 twist off: the control point's frame is replaced by the previous one carried to its
  // heading, so rolls between control points do not turn the tube.
  if (!resources.view.twistOfCylinders) {
    const Frame carried = transportFrame(previous, state.position, state.heading);
    current.state.up = carried.up;
    current.state.left = carried.left;
  }
  if (glm::length(state.position - spline.last.state.position) >= kMinimumSegmentLength) {
    drawSegment(spline.last, current, strips);
  }
  spline.last = current;
}

void GeneralizedCylinderBuilder::Impl::drawSegment(const Saved::ControlPoint& first,
                                                   Saved::ControlPoint& second, int strips) {
  const TurtleState& tu1 = first.state;
  const TurtleState& tu2 = second.state;
  const int n = std::clamp(strips, 1, kMaxStrips);
  const int sides = std::clamp(tu1.cylinderSides, 3, kMaxContourSides);
  const Frame frame1 = frameOf(tu1);
  const Frame frame2 = frameOf(tu2);
  const glm::dvec3 p1 = tu1.position;
  const glm::dvec3 p2 = tu2.position;
  const double len = glm::length(p2 - p1);

  // §2 axis: Hermite curve with tangents scaled by the segment length and @Gt's parameters
  // (the outgoing one of the first point, the incoming one of the second).
  const glm::dvec3 r1 = frame1.heading * (len * tu1.tangentParameter[1]);
  const glm::dvec3 r2 = frame2.heading * (len * tu2.tangentParameter[0]);
  const glm::dvec3 a2 = 3.0 * (p2 - p1) - 2.0 * r1 - r2;
  const glm::dvec3 a3 = 2.0 * (p1 - p2) + r1 + r2;
  auto axisPoint = [&](double t) { return p1 + r1 * t + a2 * (t * t) + a3 * (t * t * t); };
  auto axisTangent = [&](double t) { return r1 + a2 * (2.0 * t) + a3 * (3.0 * t * t); };

  // §2 radius profile: Hermite curve in the (t, r) plane; @Gr tangents, r-components scaled by
  // the length when the second point says so, a zero tangent meaning the straight line.
  const double radius1 = tu1.lineWidth / 2.0;
  const double radius2 = tu2.lineWidth / 2.0;
  const double deltaR = radius2 - radius1;
  glm::dvec2 t0 = tu1.radiusTangent[1];
  glm::dvec2 t1 = tu2.radiusTangent[0];
  if (tu2.scaleRadiusTangents) {
    t0.y *= len;
    t1.y *= len;
  }
  if (t0 == glm::dvec2(0.0)) t0 = glm::dvec2(1.0, deltaR);
  if (t1 == glm::dvec2(0.0)) t1 = glm::dvec2(1.0, deltaR);
  auto profileT = [&](double s) {
    return t0.x * s + (3.0 - 2.0 * t0.x - t1.x) * s * s + (-2.0 + t0.x + t1.x) * s * s * s;
  };
  auto profileSlope = [&](double s) {  // dX/ds
    return t0.x + 2.0 * (3.0 - 2.0 * t0.x - t1.x) * s + 3.0 * (-2.0 + t0.x + t1.x) * s * s;
  };
  auto profileRadius = [&](double s) {
    return radius1 + t0.y * s + (3.0 * deltaR - 2.0 * t0.y - t1.y) * s * s +
           (-2.0 * deltaR + t0.y + t1.y) * s * s * s;
  };

  // §2 twist on: the twist between the carried frame and the turtle's own frame at the end is
  // spread linearly over the axis parameter.
  const bool twist = resources.view.twistOfCylinders;
  const double twistTotal =
      twist ? twistAngle(transportFrame(frame1, p2, frame2.heading), frame2) : 0.0;

  // §2 rings: ring 0 at the first point in its frame, ring n at the second in its (carried or
  // own) frame; with one strip the curve is not used at all.
  std::vector<Ring> rings(static_cast<std::size_t>(n) + 1);
  rings.front() = Ring{frame1, 0.0, radius1, radius1 * t0.x};
  rings.back() = Ring{frame2, 1.0, radius2, radius2 * t1.x};
  for (int i = 1; i < n; ++i) {
    const double s = static_cast<double>(i) / n;
    const double t = profileT(s);
    glm::dvec3 heading = axisTangent(t);
    heading = glm::length(heading) > 0.0 ? glm::normalize(heading) : glm::normalize(p2 - p1);
    Frame frame = transportFrame(frame1, axisPoint(t), heading);
    if (twist) {
      frame.up = rotate(frame.up, heading, twistTotal * t);
      frame.left = glm::cross(frame.heading, frame.up);
    }
    const double radius = profileRadius(s);
    rings[static_cast<std::size_t>(i)] = Ring{frame, t, radius, radius * profileSlope(s)};
  }

  // §4 texture t: the chord between ring centres over the circumference at the ring, in units
  // of the texture's aspect; arc length along the axis for appendages.
  const std::optional<double> aspect = textureAspect(tu1);
  rings.front().axisDistance = first.axisDistance;
  rings.front().textureT = first.textureT;
  for (std::size_t k = 1; k < rings.size(); ++k) {
    const double chord = glm::length(rings[k].frame.position - rings[k - 1].frame.position);
    const double diameter = 2.0 * rings[k].radius;
    rings[k].axisDistance = rings[k - 1].axisDistance + chord;
    rings[k].textureT = rings[k - 1].textureT;
    if (aspect && diameter != 0.0) {
      rings[k].textureT += chord / (std::numbers::pi * diameter) * *aspect;
    }
  }
  second.axisDistance = rings.back().axisDistance;
  second.textureT = rings.back().textureT;

  // §3: both contours are resampled with the first point's side count.
  const ContourSamples& c1 = resources.contours.samples(tu1.contour, sides);
  const ContourSamples& c2 = resources.contours.samples(tu2.contour, sides);
  const bool closed = c1.closed && c2.closed;
  const int samplesAround = closed ? sides : sides + 1;

  CylinderSegment segment;
  segment.start = toControlFrame(frame1);
  segment.end = toControlFrame(frame2);
  segment.radiusStart = static_cast<float>(radius1);
  segment.radiusEnd = static_cast<float>(radius2);
  for (int j = 0; j < samplesAround; ++j) {
    segment.contourStart.push_back(glm::vec2(radius1 * sampleAt(c1.points, c1.closed, j)));
    segment.contourEnd.push_back(glm::vec2(radius2 * sampleAt(c2.points, c2.closed, j)));
  }
  segment.closed = closed;
  segment.organStart = tu1.organs;
  segment.organEnd = tu2.organs;
  segment.girthStart = static_cast<float>(c1.length * radius1);
  segment.girthEnd = static_cast<float>(c2.length * radius2);
  segment.axisStart = static_cast<float>(first.axisDistance);
  segment.axisLength = static_cast<float>(rings.back().axisDistance - first.axisDistance);
  segment.strips = n;
  segment.tube = spline.tube;
  segment.sides = sides;
  for (const Ring& ring : rings) {
    segment.rings.push_back(
        CylinderRing{toControlFrame(ring.frame), static_cast<float>(ring.radius),
                     static_cast<float>(ring.axisParameter), static_cast<float>(ring.axisDistance),
                     static_cast<float>(ring.textureT)});
  }

  if (scene == nullptr) return;
  if (resources.view.lineStyle == LineStyle::Cylinder) {
    emitTriangles(tu1, rings, c1, c2, sides, len, aspect.has_value(), segment);
  } else {
    // §2 line styles: pixel and polygon styles draw the axis as one line per strip.
    for (std::size_t k = 1; k < rings.size(); ++k) {
      scene->lines.push_back(LineSegment{glm::vec3(rings[k - 1].frame.position),
                                         glm::vec3(rings[k].frame.position),
                                         static_cast<float>(2.0 * rings[k - 1].radius),
                                         static_cast<float>(2.0 * rings[k].radius), tu1.color});
    }
  }
  scene->cylinderSegments.push_back(std::move(segment));
}

void GeneralizedCylinderBuilder::Impl::emitTriangles(
    const TurtleState& first, const std::vector<Ring>& rings, const ContourSamples& c1,
    const ContourSamples& c2, int sides, double len, bool textured, CylinderSegment& segment) {
  // §2: the strip takes the first control point's colour and texture.
  const int texture = textured ? first.texture - 1 : -1;
  const std::size_t needed = (static_cast<std::size_t>(sides) + 1) * rings.size();
  if (scene->vertexCount() + needed > maxVertices) {
    throw GeometryLimitError("the geometry grew past " + std::to_string(maxVertices) +
                             " vertices (a generalized-cylinder segment of " +
                             std::to_string(rings.size() - 1) + " strips of " + std::to_string(sides) +
                             " sides would pass it; raise the limit with --max-vertices)");
  }
  TriangleMesh& mesh = scene->meshFor(first.color, texture);
  segment.mesh = static_cast<int>(&mesh - scene->meshes.data());
  const std::uint32_t perRing = static_cast<std::uint32_t>(sides) + 1;
  segment.firstVertex = static_cast<std::uint32_t>(mesh.positions.size());
  segment.vertexCount = perRing * static_cast<std::uint32_t>(rings.size());
  segment.firstIndex = static_cast<std::uint32_t>(mesh.indices.size());

  for (const Ring& ring : rings) {
    const double t = ring.axisParameter;
    const Frame& f = ring.frame;
    for (int j = 0; j <= sides; ++j) {
      // §2: contours blended by the axis parameter, contour x along U and y along -L. The
      // normals are the contour normals mapped the same way and scaled, without a slope term,
      // by radius · dX/ds as cpfg scales them (its rayshade output shows |n| = r·X' where that
      // is too small to normalise): a negative radius (@Gr tangents can dip the profile below
      // zero, turning the contour half around) or a backward profile turns them over, so they
      // keep facing the way the strip's triangles face.
      const glm::dvec2 q = ring.radius * ((1.0 - t) * sampleAt(c1.points, c1.closed, j) +
                                          t * sampleAt(c2.points, c2.closed, j));
      const glm::dvec2 m =
          (1.0 - t) * sampleAt(c1.normals, c1.closed, j) + t * sampleAt(c2.normals, c2.closed, j);
      const glm::dvec3 normal = (ring.normalScale < 0.0 ? -1.0 : 1.0) * (m.x * f.up - m.y * f.left);
      const double normalLength = glm::length(normal);
      // §2: a contour's z (none in cuspy's planar contours) shifts the vertex along H by z/len.
      const double z = ring.radius * ((1.0 - t) * sampleAt(c1.z, c1.closed, j) +
                                      t * sampleAt(c2.z, c2.closed, j));
      mesh.positions.push_back(
          glm::vec3(f.position + q.x * f.up - q.y * f.left + f.heading * (z / len)));
      mesh.normals.push_back(glm::vec3(normalLength > 0.0 ? normal / normalLength : normal));
      if (mesh.texture >= 0) {
        // §4: s runs 1 → 0 around from the seam at contour sample 0; t along the axis.
        mesh.texcoords.push_back(glm::vec2(static_cast<float>(1.0 - static_cast<double>(j) / sides),
                                           static_cast<float>(ring.textureT)));
      }
    }
  }
  // §2: one strip per pair of rings, 2·sides triangles, counter-clockwise seen from the side the
  // contour normals point to (cpfg's strip (ring_k[j], ring_k-1[j]) in the order its rayshade
  // output writes it).
  for (std::uint32_t k = 1; k < rings.size(); ++k) {
    const std::uint32_t upper = segment.firstVertex + k * perRing;
    const std::uint32_t lower = upper - perRing;
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(sides); ++j) {
      mesh.indices.insert(mesh.indices.end(), {upper + j, upper + j + 1, lower + j});
      mesh.indices.insert(mesh.indices.end(), {lower + j, upper + j + 1, lower + j + 1});
    }
  }
  segment.indexCount = static_cast<std::uint32_t>(mesh.indices.size()) - segment.firstIndex;
}

GeneralizedCylinderBuilder::GeneralizedCylinderBuilder(const ModelResources& resources,
                                                       Scene* scene)
    : impl_(std::make_unique<Impl>(resources, scene)) {}

GeneralizedCylinderBuilder::~GeneralizedCylinderBuilder() = default;

void GeneralizedCylinderBuilder::setMaxVertices(std::size_t vertices) {
  impl_->maxVertices = vertices;
}

bool GeneralizedCylinderBuilder::active() const {
  return impl_->spline.active;
}

bool GeneralizedCylinderBuilder::addsPointsOnMoves() const {
  return impl_->spline.active && impl_->spline.addsPointsOnMoves;
}

void GeneralizedCylinderBuilder::start(const TurtleState& state) {
  impl_->start(state);
}

void GeneralizedCylinderBuilder::point(const TurtleState& state, int strips) {
  // §1: @Gc without a tube starts one at this point (and F, f then add points too).
  if (!impl_->spline.active) {
    impl_->start(state);
    impl_->spline.addsPointsOnMoves = true;
    return;
  }
  impl_->addPoint(state, strips);
}

void GeneralizedCylinderBuilder::end(const TurtleState& state, int strips) {
  point(state, strips);
  impl_->spline.active = false;
  impl_->spline.addsPointsOnMoves = false;
}

std::shared_ptr<GeneralizedCylinderBuilder::Saved> GeneralizedCylinderBuilder::save() const {
  // Nothing to carry while no tube is active: restoring "none" ends a tube begun in the branch.
  if (!impl_->spline.active) return nullptr;
  return std::make_shared<Saved>(impl_->spline);
}

void GeneralizedCylinderBuilder::restore(const std::shared_ptr<Saved>& saved) {
  // §1: `]` drops the branch's tube state; the parent continues from its own last point, and a
  // tube started inside the branch ends here.
  impl_->spline = saved ? *saved : Saved{};
}

}  // namespace hirsute
