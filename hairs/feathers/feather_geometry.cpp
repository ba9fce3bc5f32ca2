#include "hirsute/hairs/feathers/feather_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <limits>
#include <numbers>

#include "hirsute/hairs/feathers/barb_interpolation.h"
#include "hirsute/hairs/feathers/bezier_curve.h"
#include "hirsute/hairs/feathers/default_barbs.h"
#include "hirsute/hairs/feathers/silhouette.h"

namespace hirsute {
namespace {

constexpr double kDegrees = std::numbers::pi / 180;
constexpr double kTiny = 1e-12;
constexpr float kTwoSegmentPixels = 32;  // thinned feathers this long or shorter: 2 barb segments
constexpr float kPixelsPerThinnedBarb = 4;  // of a small feather's length, a barb a vane kept
constexpr float kCoarsePixels = 64;         // a small feather: this long or shorter
constexpr int kFewestThinnedBarbs = 8;      // a thinned vane keeps at least these

// The rachis of Sec. 4.3.1 and its frame.
class Rachis {
 public:
  explicit Rachis(const FeatherType& type) {
    const float cl = type.calamusLength;
    const float rl = type.rachisLength;
    const float front = type.rachisFrontCurvature * rl;
    const float side = type.rachisSideCurvature * rl;
    vertices_ = {glm::vec3(0, 0, cl), glm::vec3(front, side, cl + rl / 3),
                 glm::vec3(front, side, cl + 2 * rl / 3), glm::vec3(0, 0, cl + rl)};
  }

  glm::dvec3 point(double t) const { return bezierPoint(vertices_, t); }

  // Tangent T, left L and front F at parameter t. dz/dt = rl everywhere (the control vertices'
  // heights are evenly spaced), so T is never parallel to x and L = T × x is well defined.
  struct Frame {
    glm::dvec3 tangent, left, front;
    double speed;  // |dP/dt|
  };
  Frame frame(double t) const {
    const glm::dvec3 derivative = bezierDerivative(vertices_, t);
    const double speed = glm::length(derivative);
    const glm::dvec3 tangent = speed > kTiny ? derivative / speed : glm::dvec3(0, 0, 1);
    const glm::dvec3 left = glm::normalize(glm::cross(tangent, glm::dvec3(1, 0, 0)));
    return Frame{tangent, left, glm::cross(left, tangent), speed};
  }

 private:
  std::array<glm::vec3, 4> vertices_;
};

// A ring of the shaft tube: `sides` vertices around `centre` in the plane of `front` and `left`;
// the normals lean along the tangent by the taper (radius change per arc length), so a cone
// shades as a cone.
void addRing(FeatherMesh& mesh, const glm::dvec3& centre, const Rachis::Frame& frame, double radius,
             double taper, int sides) {
  for (int j = 0; j < sides; ++j) {
    const double angle = 2 * std::numbers::pi * j / sides;
    const glm::dvec3 radial = std::cos(angle) * frame.front + std::sin(angle) * frame.left;
    mesh.positions.emplace_back(centre + radius * radial);
    mesh.normals.emplace_back(glm::normalize(radial - taper * frame.tangent));
  }
}

// Two triangles for every side between ring `a` and the ring after it.
void joinRings(FeatherMesh& mesh, std::uint32_t a, int sides) {
  const std::uint32_t b = a + static_cast<std::uint32_t>(sides);
  for (int j = 0; j < sides; ++j) {
    const std::uint32_t j0 = static_cast<std::uint32_t>(j);
    const std::uint32_t j1 = static_cast<std::uint32_t>((j + 1) % sides);
    mesh.indices.insert(mesh.indices.end(), {a + j0, a + j1, b + j1, a + j0, b + j1, b + j0});
  }
}

// The shaft (Sec. 4.1, 4.3.1): the calamus, straight from the origin, its width cwr·rw at the
// base and rw at its top, where the rachis starts with the same width (no discontinuity); the
// rachis tapering linearly in its parameter to a point at the tip.
void buildShaft(const FeatherType& type, const Rachis& rachis, const FeatherDetail& detail,
                FeatherGeometry& out) {
  const int sides = std::max(3, detail.shaftSides);
  const int segments = std::max(1, detail.rachisSegments);
  const double rachisRadius = type.rachisWidth / 2.0;
  FeatherMesh& mesh = out.shaft;
  const std::size_t rings = static_cast<std::size_t>(segments + 3);
  mesh.positions.reserve(rings * static_cast<std::size_t>(sides));
  mesh.normals.reserve(rings * static_cast<std::size_t>(sides));
  mesh.indices.reserve(static_cast<std::size_t>(segments + 1) * 6 * sides);
  out.shaftAxis.reserve(static_cast<std::size_t>(segments + 2));
  out.shaftAxis.emplace_back(0, 0, 0);
  if (type.calamusLength > 0) {
    const Rachis::Frame straight{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, 1};
    const double baseRadius = type.calamusWidthRatio * rachisRadius;
    const double taper = (rachisRadius - baseRadius) / type.calamusLength;
    const std::uint32_t first = static_cast<std::uint32_t>(mesh.positions.size());
    addRing(mesh, glm::dvec3(0), straight, baseRadius, taper, sides);
    addRing(mesh, glm::dvec3(0, 0, type.calamusLength), straight, rachisRadius, taper, sides);
    joinRings(mesh, first, sides);
  }
  const std::uint32_t first = static_cast<std::uint32_t>(mesh.positions.size());
  for (int i = 0; i <= segments; ++i) {
    const double t = static_cast<double>(i) / segments;
    const Rachis::Frame frame = rachis.frame(t);
    const glm::dvec3 centre = rachis.point(t);
    // dr/ds = (dr/dt) / (ds/dt), dr/dt = -rw/2.
    const double taper = frame.speed > kTiny ? -rachisRadius / frame.speed : 0;
    addRing(mesh, centre, frame, rachisRadius * (1 - t), taper, sides);
    out.shaftAxis.emplace_back(centre);
    if (i > 0) joinRings(mesh, first + static_cast<std::uint32_t>((i - 1) * sides), sides);
  }
}

// The rotation, in the barb frame, that turns the chord direction onto +x by the smallest angle
// (Sec. 4.3.1: the chord cv0→cvn then lies in the vane plane at the barb angle). For a chord in
// the vane plane this is the paper's rotation about the plane's normal. A chord of length 0 (all
// vertices at one point) needs no rotation.
struct ChordRotation {
  glm::dmat3 matrix{1.0};
  double chordLength = 0;
};

ChordRotation chordRotation(const std::vector<glm::vec3>& vertices) {
  ChordRotation out;
  const glm::dvec3 chord = glm::dvec3(vertices.back()) - glm::dvec3(vertices.front());
  out.chordLength = glm::length(chord);
  if (out.chordLength < kTiny) return out;
  const glm::dvec3 from = chord / out.chordLength;
  const glm::dvec3 to(1, 0, 0);
  const double cosine = glm::dot(from, to);
  const glm::dvec3 axisSine = glm::cross(from, to);
  const double sine = glm::length(axisSine);
  if (sine < 1e-9) {
    // Parallel: nothing to do; opposite: half a turn about the vane normal (the barb frame's z).
    if (cosine < 0) out.matrix = glm::dmat3(-1, 0, 0, 0, -1, 0, 0, 0, 1);
    return out;
  }
  // Rodrigues: R = I cosθ + sinθ [k]× + (1 - cosθ) k kᵀ.
  const glm::dvec3 k = axisSine / sine;
  const glm::dmat3 cross(0, k.z, -k.y, -k.z, 0, k.x, k.y, -k.x, 0);  // column-major [k]×
  const glm::dmat3 outer(k.x * k, k.y * k, k.z * k);
  out.matrix = glm::dmat3(cosine) + sine * cross + (1 - cosine) * outer;
  return out;
}

// The barb frame's axes in the feather frame at a rachis point, for a barb angle θ to the
// rachis direction towards the base (Fig. 4): along the chord, cos θ (-T) ± sin θ L; towards the
// tip in the vane plane, ± cos θ L + sin θ T; front, F. The right vane mirrors the left.
struct BarbAxes {
  glm::dvec3 along, towardsTip, front;
};

BarbAxes barbAxes(const Rachis::Frame& frame, double angleDegrees, BarbSide side) {
  const double c = std::cos(angleDegrees * kDegrees);
  const double s = std::sin(angleDegrees * kDegrees);
  const double mirror = side == BarbSide::Right ? -1 : 1;
  return BarbAxes{-c * frame.tangent + mirror * s * frame.left,
                  mirror * c * frame.left + s * frame.tangent, frame.front};
}

glm::dvec3 inFrame(const BarbAxes& axes, const glm::dvec3& v) {
  return v.x * axes.along + v.y * axes.towardsTip + v.z * axes.front;
}

void buildBarbs(const FeatherType& type, const Rachis& rachis, const FeatherDetail& detail,
                FeatherGeometry& out) {
  const std::vector<float> all = barbPositions(type);
  if (all.empty()) return;
  // Thinning (FeatherDetail::barbsPerVane): every stride-th barb, the middle one of each run of
  // stride, so that the kept barbs stand evenly over the vane; each keeps its index in the full
  // vane (the plumulaceous table's draw) and a strip widened by the stride.
  std::size_t stride = 1;
  if (detail.barbsPerVane > 0 && all.size() > static_cast<std::size_t>(detail.barbsPerVane)) {
    const std::size_t limit = static_cast<std::size_t>(detail.barbsPerVane);
    stride = (all.size() + limit - 1) / limit;
  }
  std::vector<float> positions;
  std::vector<std::size_t> indices;
  for (std::size_t k = (stride - 1) / 2; k < all.size(); k += stride) {
    positions.push_back(all[k]);
    indices.push_back(k);
  }
  out.barbStride = static_cast<int>(stride);
  out.appearance.stripWidth *= static_cast<float>(stride);
  const int segments = std::max(1, detail.barbSegments);
  const std::size_t perBarb = static_cast<std::size_t>(segments) + 1;
  const bool strips = type.appearance.drawing == BarbStyle::Strips;
  const PlumulaceousBarbTable table =
      type.seedBlend.empty() ? PlumulaceousBarbTable(type.seed) : PlumulaceousBarbTable(type.seedBlend);
  const std::array<BarbSide, 2> sides = {BarbSide::Left, BarbSide::Right};

  const std::size_t barbCount = 2 * positions.size();
  const std::size_t vertexCount = barbCount * perBarb;
  BarbVertices& v = out.vertices;
  out.barbs.reserve(barbCount);
  v.positions.reserve(vertexCount);
  v.s.reserve(vertexCount);
  v.barbUv.reserve(vertexCount);
  v.vaneUv.reserve(vertexCount);
  v.growthUv.reserve(vertexCount);
  if (strips) v.stripSides.reserve(vertexCount);

  // The straightened positions (y, z) for the vane mapping and the sheath heights for the
  // growth mapping, normalised once every barb is known.
  std::vector<glm::dvec2> straight;
  straight.reserve(vertexCount);
  std::vector<double> heights;
  heights.reserve(vertexCount);
  glm::dvec2 low(std::numeric_limits<double>::max());
  glm::dvec2 high(std::numeric_limits<double>::lowest());
  double highest = 0;

  std::vector<glm::dvec3> curve(perBarb);
  std::vector<double> arc(perBarb);
  for (BarbSide side : sides) {
    const VaneKeyBarbs keys(type, side);
    const Vane& vane = type.vane(side);
    for (std::size_t k = 0; k < positions.size(); ++k) {
      const float rp = positions[k];
      const BarbCurve barb = keys.barbAt(rp, indices[k], table);
      const ChordRotation rotation = chordRotation(barb.vertices);
      const double length = vaneBarbLength(vane, rp);
      const Rachis::Frame frame = rachis.frame(rp);
      const glm::dvec3 attach = rachis.point(rp);
      const BarbAxes axes = barbAxes(frame, barb.angle, side);
      // Sec. 4.3.3: the vane mapping ignores the rachis curvature.
      const BarbAxes straightAxes =
          barbAxes(Rachis::Frame{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, 1}, barb.angle, side);
      const double straightHeight = type.calamusLength + type.rachisLength * double(rp);

      out.barbs.push_back(Barb{side, rp, static_cast<std::uint32_t>(v.positions.size()),
                               static_cast<std::uint32_t>(perBarb)});
      const glm::dvec3 origin(barb.vertices.front());
      for (std::size_t i = 0; i < perBarb; ++i) {
        const double u = static_cast<double>(i) / segments;
        // Sec. 4.2.1: placed relative to cv0 and scaled by the barb length.
        curve[i] = length * (rotation.matrix * (bezierPoint(barb.vertices, u) - origin));
        arc[i] = i == 0 ? 0 : arc[i - 1] + glm::length(curve[i] - curve[i - 1]);
      }
      const double total = arc.back();
      const double chord = length * rotation.chordLength;
      for (std::size_t i = 0; i < perBarb; ++i) {
        const double s = total > kTiny ? arc[i] / total : static_cast<double>(i) / segments;
        v.positions.emplace_back(attach + inFrame(axes, curve[i]));
        v.s.push_back(static_cast<float>(s));
        v.barbUv.emplace_back(static_cast<float>(s), rp);
        const glm::dvec3 flat = glm::dvec3(0, 0, straightHeight) + inFrame(straightAxes, curve[i]);
        straight.emplace_back(flat.y, flat.z);
        low = glm::min(low, straight.back());
        high = glm::max(high, straight.back());
        heights.push_back(type.rachisLength * double(rp) + s * chord);
        highest = std::max(highest, heights.back());
        const double around = side == BarbSide::Left ? 0.5 + 0.5 * s : 0.5 - 0.5 * s;
        v.growthUv.emplace_back(static_cast<float>(around), 0.0f);
        if (strips) {
          // The strip side: in the vane plane (perpendicular to its normal F), across the barb.
          const glm::dvec3 tangent =
              inFrame(axes, curve[std::min(i + 1, perBarb - 1)] - curve[i > 0 ? i - 1 : 0]);
          glm::dvec3 across = glm::cross(frame.front, tangent);
          const double size = glm::length(across);
          across = size > kTiny ? across / size : axes.towardsTip;
          v.stripSides.emplace_back(across);
        }
      }
    }
  }
  const glm::dvec2 extent = high - low;
  for (std::size_t i = 0; i < straight.size(); ++i) {
    const glm::dvec2 relative = straight[i] - low;
    v.vaneUv.emplace_back(extent.x > kTiny ? relative.x / extent.x : 0.5,
                          extent.y > kTiny ? relative.y / extent.y : 0.5);
    v.growthUv[i].y = static_cast<float>(highest > kTiny ? 1 - heights[i] / highest : 0);
  }
}

void transform(FeatherGeometry& geometry, const glm::vec3& offset, float scale) {
  for (glm::vec3& p : geometry.shaft.positions) p = offset + scale * p;
  for (glm::vec3& p : geometry.shaftAxis) p = offset + scale * p;
  for (glm::vec3& p : geometry.vertices.positions) p = offset + scale * p;
  for (FeatherGeometry& after : geometry.afterfeathers) transform(after, offset, scale);
}

template <typename T>
std::size_t bytesOf(const std::vector<T>& values) {
  return values.capacity() * sizeof(T);
}

}  // namespace

FeatherDetail featherDetailForProjectedLength(float pixels) {
  const float p = std::isfinite(pixels) ? std::max(pixels, 0.0f) : 0.0f;
  const auto clampTo = [](float value, int low, int high) {
    return static_cast<int>(std::clamp(value, static_cast<float>(low), static_cast<float>(high)));
  };
  return FeatherDetail{clampTo(std::ceil(p / 8), 3, 64), clampTo(std::ceil(p / 24), 3, 32),
                       clampTo(3 + std::floor(p / 40), 3, 12)};
}

FeatherDetail thinnedFeatherDetail(float pixels, BarbStyle drawing) {
  FeatherDetail detail = featherDetailForProjectedLength(pixels);
  const float p = std::isfinite(pixels) ? std::max(pixels, 0.0f) : 0.0f;
  // Above kCoarsePixels a barb per 2 pixels: there a feather's barbs begin to show apart.
  const float perStrip = p <= kCoarsePixels ? kPixelsPerThinnedBarb : 2.0f;
  const float perBarb = drawing == BarbStyle::Strips ? perStrip : 1.0f;
  detail.barbsPerVane =
      std::max(kFewestThinnedBarbs, static_cast<int>(std::min(p / perBarb, 1e6f)));
  // A barb a few pixels long shows no curve beyond a bend: two segments.
  if (p <= kTwoSegmentPixels) detail.barbSegments = 2;
  return detail;
}

std::vector<float> barbPositions(const FeatherType& type) {
  std::vector<float> out;
  const double rl = type.rachisLength;
  if (!(rl > 0)) return out;
  // Slack for the float parameters: a spacing that divides the rachis exactly (0.05f is a little
  // more than 0.05) still puts the last barb at the tip.
  constexpr double kSlack = 1e-5;
  double rp = 0;
  while (rp <= 1 + kSlack) {
    out.push_back(static_cast<float>(std::min(rp, 1.0)));
    const double spacing = (1 - rp) * type.barbSpacingBase + rp * type.barbSpacingTip;
    if (!(spacing > 0)) break;
    rp += spacing / rl;
  }
  return out;
}

FeatherGeometry buildFeatherGeometry(const FeatherType& type, const FeatherDetail& detail) {
  FeatherGeometry out;
  out.appearance = type.appearance;
  const Rachis rachis(type);
  buildShaft(type, rachis, detail, out);
  buildBarbs(type, rachis, detail, out);
  if (type.afterfeather && type.afterfeatherSize > 0) {
    // A thinned afterfeather keeps barbs for its own, smaller, size in the picture.
    FeatherDetail afterDetail = detail;
    if (detail.barbsPerVane > 0) {
      afterDetail.barbsPerVane = std::max(
          kFewestThinnedBarbs,
          static_cast<int>(static_cast<float>(detail.barbsPerVane) * type.afterfeatherSize));
    }
    FeatherGeometry after = buildFeatherGeometry(*type.afterfeather, afterDetail);
    transform(after, glm::vec3(-type.rachisWidth / 2, 0, type.calamusLength),
              type.afterfeatherSize);
    out.afterfeathers.push_back(std::move(after));
  }
  return out;
}

std::size_t FeatherGeometry::byteSize() const {
  std::size_t bytes = sizeof(*this) + bytesOf(shaft.positions) + bytesOf(shaft.normals) +
                      bytesOf(shaft.indices) + bytesOf(shaftAxis) + bytesOf(barbs) +
                      bytesOf(vertices.positions) + bytesOf(vertices.s) + bytesOf(vertices.barbUv) +
                      bytesOf(vertices.vaneUv) + bytesOf(vertices.growthUv) +
                      bytesOf(vertices.stripSides) + appearance.texture.capacity();
  for (const FeatherGeometry& after : afterfeathers) bytes += after.byteSize();
  return bytes;
}

std::size_t FeatherGeometry::totalBarbCount() const {
  std::size_t count = barbs.size();
  for (const FeatherGeometry& after : afterfeathers) count += after.totalBarbCount();
  return count;
}

}  // namespace hirsute
