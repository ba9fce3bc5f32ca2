// Plant hairs on generalized-cylinder segments (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3–4;
// DESIGN.md, "Plant hairs"): the point-diffusion texture tiled over each segment unfolded in
// scan-line order, the hair direction from the corner vectors, the attributes of Table 1.
#include "hirsute/hairs/hair_placement.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace hirsute {
namespace {

constexpr float kDegrees = std::numbers::pi_v<float> / 180.0f;

// Counter-based randomness: every number a hair draws is a hash of the seed and where the hair
// is, so placement is reproducible and independent of the order segments are visited in.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

class HairRandom {
 public:
  explicit HairRandom(std::uint64_t key) : state_(mix(key)) {}
  // Uniform in [0, 1).
  float uniform() {
    state_ = mix(state_);
    return static_cast<float>(state_ >> 40) * (1.0f / 16777216.0f);
  }
  // Uniform in [-1, 1).
  float symmetric() { return 2.0f * uniform() - 1.0f; }

 private:
  std::uint64_t state_;
};

std::uint64_t key(std::uint64_t a, std::uint64_t b) {
  return mix(a ^ mix(b));
}

// Rotation of v about the unit axis by angle (radians), Rodrigues' formula.
glm::vec3 rotate(const glm::vec3& v, const glm::vec3& axis, float angle) {
  if (angle == 0.0f) return v;
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0f - c));
}

glm::vec3 normalizedOr(const glm::vec3& v, const glm::vec3& otherwise) {
  const float length = glm::length(v);
  return length > 1e-12f && std::isfinite(length) ? v / length : otherwise;
}

// A perpendicular of the unit vector n (for frames where h runs along n).
glm::vec3 anyPerpendicular(const glm::vec3& n) {
  const glm::vec3 other = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(n, other));
}

// The attributes of one side of one segment, between its two ends (the same at both without
// interpolation), with the model's functions.
class SideValues {
 public:
  SideValues(const HairSideAttributes& start, const HairSideAttributes& end,
             const std::function<double(int, double)>& function)
      : start_(start), end_(end), function_(function) {}

  // The value of Table 1 at girth position s and fraction tau along the segment, before the
  // per-hair random offset: value × fun(s), each end's, mixed linearly.
  float value(HairValue HairSideAttributes::*member, float s, float tau) const {
    const HairValue& a = start_.*member;
    const HairValue& b = end_.*member;
    if (tau >= 1.0f || (a == b)) return b.value * modulation(b.function, s);
    return (1.0f - tau) * a.value * modulation(a.function, s) +
           tau * b.value * modulation(b.function, s);
  }
  float range(HairValue HairSideAttributes::*member, float tau) const {
    return (1.0f - tau) * (start_.*member).range + tau * (end_.*member).range;
  }
  // value ± a uniform offset up to the range.
  float sample(HairValue HairSideAttributes::*member, float s, float tau,
               HairRandom& random) const {
    const float r = range(member, tau);
    return value(member, s, tau) + (r != 0.0f ? r * random.symmetric() : 0.0f);
  }
  // The largest density anywhere on the segment (sets the tile's size; hairs below it are
  // thinned out).
  float maxDensity() const {
    auto extreme = [&](const HairValue& v) {
      return std::abs(v.value) * maxModulation(v.function) + v.range;
    };
    return std::max(extreme(start_.density), extreme(end_.density));
  }
  // The template for a uniform number u, by the probabilities mixed along the segment; -1 when
  // every probability is zero.
  int chooseTemplate(float tau, float u, int templates) const {
    // Each end's probabilities are normalised before they are mixed, so that the probabilities
    // (not the raw @Hp weights) vary linearly along the segment.
    float startTotal = 0, endTotal = 0;
    for (int i = 0; i < templates; ++i) {
      startTotal += probability(start_, i, templates);
      endTotal += probability(end_, i, templates);
    }
    const float startScale = startTotal > 0.0f ? (1.0f - tau) / startTotal : 0.0f;
    const float endScale = endTotal > 0.0f ? tau / endTotal : 0.0f;
    float weights[kMaxHairTemplates];
    float total = 0;
    for (int i = 0; i < templates; ++i) {
      weights[i] = startScale * probability(start_, i, templates) +
                   endScale * probability(end_, i, templates);
      total += weights[i];
    }
    if (!(total > 0.0f)) return -1;
    float x = u * total;
    for (int i = 0; i < templates; ++i) {
      if (x < weights[i]) return i;
      x -= weights[i];
    }
    for (int i = templates - 1; i >= 0; --i) {
      if (weights[i] > 0.0f) return i;
    }
    return -1;
  }

 private:
  static float probability(const HairSideAttributes& a, int i, int templates) {
    if (a.probabilityCount == 0) return 1.0f / static_cast<float>(templates);
    return i < a.probabilityCount ? a.probability[static_cast<std::size_t>(i)] : 0.0f;
  }
  float modulation(int function, float s) const {
    if (function <= 0 || !function_) return 1.0f;
    const double y = function_(function, s);
    return std::isfinite(y) ? static_cast<float>(y) : 1.0f;
  }
  float maxModulation(int function) const {
    if (function <= 0 || !function_) return 1.0f;
    float m = 0;
    for (int i = 0; i <= 64; ++i) m = std::max(m, std::abs(modulation(function, i / 64.0f)));
    return m;
  }

  const HairSideAttributes& start_;
  const HairSideAttributes& end_;
  const std::function<double(int, double)>& function_;
};

// The vectors a hair's direction is interpolated from, at one face corner: its direction after
// incline and wrap, and the incline axis carried with it (the hair's second axis before twist).
struct CornerVectors {
  glm::vec3 direction;
  glm::vec3 across;
};

// Sec. 4.4: incline about the incline axis, then wrap about the wrapping axis, of the frame
// (d, d × h, d × (d × h)); d is the shading normal for surface hairs, the edge vector for edge
// hairs. Positive incline tilts the hair toward h (the segment's end); positive wrap tilts it
// toward d × h.
CornerVectors reorient(const glm::vec3& d, const glm::vec3& h, float incline, float wrap) {
  glm::vec3 x = glm::cross(d, h);
  x = normalizedOr(x, anyPerpendicular(d));
  const glm::vec3 y = glm::cross(d, x);  // d × (d × h), normalised since d ⟂ x
  glm::vec3 direction = rotate(d, x, incline);
  direction = rotate(direction, y, wrap);
  const glm::vec3 across = rotate(x, y, wrap);
  return {direction, across};
}

struct Placer {
  Scene& scene;
  const HairPlacementSettings& settings;
  const PointDiffusionTexture& texture;
  std::vector<std::uint32_t> rowStart;  // points of texture row r: [rowStart[r], rowStart[r+1])
  int templates = 1;
  HairPlacementReport report;

  std::size_t candidates = 0;  // texture points considered (thinning rejects some)

  void checkLimit() {
    if (scene.hairs.size() >= settings.maxHairs) {
      throw HairLimitError("more than " + std::to_string(settings.maxHairs) +
                           " hairs (raise the limit with --max-hairs, or lower @Hd)");
    }
  }
  // A density whose peak (a function's, or its range's) is far above where hairs are kept still
  // costs a texture point per unit of the peak: bounded like the hairs themselves.
  std::size_t candidateBudget() const { return 8 * settings.maxHairs + 1'000'000; }
  [[noreturn]] void tooManyCandidates() const {
    throw HairLimitError("the densities would test more than " + std::to_string(candidateBudget()) +
                         " attachment points (the peak of @Hd's value, function and range sets "
                         "how many; raise --max-hairs or lower @Hd)");
  }
  void countCandidate() {
    if (++candidates > candidateBudget()) tooManyCandidates();
  }
  // Before a strip's loops: the points it would test, estimated in double, must fit the budget
  // (this also keeps an infinite or absurd density from reaching an integer conversion).
  void expectCandidates(double count) const {
    if (!(count <=
          static_cast<double>(candidateBudget() - std::min(candidates, candidateBudget())))) {
      tooManyCandidates();
    }
  }

  // One hair: values at (s, tau), direction from the interpolated corner vectors, random offsets.
  void emit(const SideValues& values, HairSide side, float s, float tau, const glm::vec3& root,
            glm::vec3 direction, glm::vec3 across, float twist, HairRandom& random) {
    const int chosen = values.chooseTemplate(tau, random.uniform(), templates);
    if (chosen < 0) return;
    const float length = values.sample(&HairSideAttributes::length, s, tau, random);
    if (!(length > 0.0f)) return;
    const float radius = std::max(0.0f, values.sample(&HairSideAttributes::radius, s, tau, random));
    direction = normalizedOr(direction, glm::vec3(0, 1, 0));
    across =
        normalizedOr(across - direction * glm::dot(across, direction), anyPerpendicular(direction));
    // rng of the angles: offsets about the hair's own axes, after interpolation.
    const float inclineOffset =
        values.range(&HairSideAttributes::incline, tau) * random.symmetric();
    const float wrapOffset = values.range(&HairSideAttributes::wrap, tau) * random.symmetric();
    const float twistOffset = values.range(&HairSideAttributes::twist, tau) * random.symmetric();
    if (inclineOffset != 0.0f || wrapOffset != 0.0f) {
      const glm::vec3 y = glm::cross(direction, across);
      direction = rotate(direction, across, inclineOffset * kDegrees);
      direction = rotate(direction, y, wrapOffset * kDegrees);
      across = rotate(across, y, wrapOffset * kDegrees);
    }
    across = rotate(across, direction, (twist + twistOffset) * kDegrees);
    checkLimit();
    Hair hair;
    hair.root = root;
    hair.setRotation(glm::quat_cast(glm::mat3(direction, across, glm::cross(direction, across))));
    hair.length = length;
    hair.radius = radius;
    hair.templateIndex = static_cast<std::uint8_t>(chosen);
    hair.side = side;
    scene.hairs.push_back(hair);
    ++report.hairs;
  }

  void segment(std::size_t index);
  void surface(std::size_t index, const CylinderSegment& seg, const TriangleMesh& mesh,
               const SideValues& values, HairSide side);
  void edge(const CylinderSegment& seg, const TriangleMesh& mesh, const SideValues& values,
            int which);
};

// The fraction along the segment of ring k (the interpolation parameter of its attributes).
float ringTau(const CylinderSegment& seg, std::size_t k) {
  if (seg.axisLength <= 0.0f)
    return static_cast<float>(k) / static_cast<float>(seg.rings.size() - 1);
  return std::clamp((seg.rings[k].axisDistance - seg.axisStart) / seg.axisLength, 0.0f, 1.0f);
}

void Placer::segment(std::size_t index) {
  const CylinderSegment& seg = scene.cylinderSegments[index];
  if (seg.organEnd.hair < 0 && seg.organStart.hair < 0) return;
  static const HairAttributes kNone{};
  auto attributesAt = [&](int i) -> const HairAttributes& {
    return i >= 0 && static_cast<std::size_t>(i) < scene.hairAttributes.size()
               ? scene.hairAttributes[static_cast<std::size_t>(i)]
               : kNone;
  };
  const HairAttributes& end = attributesAt(seg.organEnd.hair);
  const HairAttributes& start = settings.interpolation ? attributesAt(seg.organStart.hair) : end;
  // Closed cylinders expose only their front (Sec. 2).
  const bool front = end.side(HairSide::Front).enabled;
  const bool back = !seg.closed && end.side(HairSide::Back).enabled;
  const bool edges = !seg.closed && end.side(HairSide::Edge).enabled;
  if (!front && !back && !edges) return;
  if (seg.mesh < 0 || seg.rings.size() < 2 || seg.sides < 1) {
    ++report.segmentsWithoutMesh;
    return;
  }
  ++report.segments;
  // With interpolation, a side switched on only after the segment's first control point (the
  // paper's Algorithm 1 puts @Hf after @Gs) has no values of its own there: it takes the end's.
  auto startOf = [&](HairSide side) -> const HairSideAttributes& {
    return start.side(side).enabled ? start.side(side) : end.side(side);
  };
  const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(seg.mesh)];
  for (HairSide side : {HairSide::Front, HairSide::Back}) {
    if (side == HairSide::Front ? !front : !back) continue;
    const SideValues values(startOf(side), end.side(side), settings.function);
    surface(index, seg, mesh, values, side);
  }
  if (edges) {
    const SideValues values(startOf(HairSide::Edge), end.side(HairSide::Edge), settings.function);
    edge(seg, mesh, values, 0);
    edge(seg, mesh, values, 1);
  }
}

// Sec. 3.1 and Figure 2: the texture tiled over the unfolded segment in scan-line order, u the
// arc length around the contour (edge to edge on open contours), v the arc length along the
// axis from @Gs; a tile with K points covers K / density units of area. Around a closed contour
// a whole number of tiles fits, so the pattern wraps without a seam; where the girth is below
// the largest, or the density below the largest, points are thinned so that the expected count
// is density × area everywhere.
void Placer::surface(std::size_t index, const CylinderSegment& seg, const TriangleMesh& mesh,
                     const SideValues& values, HairSide side) {
  const float maxDensity = values.maxDensity();
  if (!(maxDensity > 0.0f)) return;
  const std::size_t rings = seg.rings.size();
  const std::size_t perRing = static_cast<std::size_t>(seg.sides) + 1;
  const int faces = seg.sides;
  const float flip = side == HairSide::Back ? -1.0f : 1.0f;
  auto position = [&](std::size_t k, int j) {
    return mesh.positions[seg.firstVertex + k * perRing + static_cast<std::size_t>(j)];
  };
  auto normal = [&](std::size_t k, int j) {
    return flip * mesh.normals[seg.firstVertex + k * perRing + static_cast<std::size_t>(j)];
  };

  // Arc-length fractions of the contour samples around each ring, and the girths.
  std::vector<float> fraction(rings * perRing);
  std::vector<float> girth(rings);
  float maxGirth = 0;
  for (std::size_t k = 0; k < rings; ++k) {
    float sum = 0;
    fraction[k * perRing] = 0;
    for (int j = 1; j <= faces; ++j) {
      sum += glm::length(position(k, j) - position(k, j - 1));
      fraction[k * perRing + static_cast<std::size_t>(j)] = sum;
    }
    girth[k] = sum;
    maxGirth = std::max(maxGirth, sum);
    for (int j = 1; j <= faces; ++j) {
      fraction[k * perRing + static_cast<std::size_t>(j)] =
          sum > 0.0f ? fraction[k * perRing + static_cast<std::size_t>(j)] / sum
                     : static_cast<float>(j) / static_cast<float>(faces);
    }
  }
  if (!(maxGirth > 0.0f)) return;

  const float tileArea = static_cast<float>(texture.points().size()) / maxDensity;
  const float tileSide = std::sqrt(tileArea);
  // Tiles around the girth: a whole number on closed contours.
  const float tilesAround =
      seg.closed ? std::max(1.0f, std::ceil(maxGirth / tileSide - 1e-3f)) : maxGirth / tileSide;
  const float tileWidth = maxGirth / tilesAround;  // at the widest girth
  const float tileHeight = tileArea / tileWidth;
  // The back uses the texture shifted by half a tile, so its points are not the front's.
  const float shift = side == HairSide::Back ? 0.5f : 0.0f;
  const int height = texture.height();
  const auto& points = texture.points();
  const std::uint64_t sideKey = key(settings.seed, key(index, static_cast<std::uint64_t>(side)));

  // Corner vectors of ring k, column j of strip (k-1, k): the shading normal reoriented by the
  // incline and wrap at that corner; h is the face's height vector.
  std::vector<CornerVectors> corners(2 * perRing);
  std::vector<float> cornerTwist(2 * perRing);
  for (std::size_t k = 1; k < rings; ++k) {
    const float tau0 = ringTau(seg, k - 1), tau1 = ringTau(seg, k);
    const glm::vec3 axis = normalizedOr(
        seg.rings[k].frame.position - seg.rings[k - 1].frame.position, seg.rings[k].frame.heading);
    for (int j = 0; j <= faces; ++j) {
      const glm::vec3 h = normalizedOr(position(k, j) - position(k - 1, j), axis);
      for (int r = 0; r < 2; ++r) {
        const std::size_t kk = k - 1 + static_cast<std::size_t>(r);
        const float tau = r == 0 ? tau0 : tau1;
        const float s = (fraction[(k - 1) * perRing + static_cast<std::size_t>(j)] +
                         fraction[k * perRing + static_cast<std::size_t>(j)]) *
                        0.5f;
        const glm::vec3 n = normalizedOr(normal(kk, j), flip * glm::vec3(seg.rings[kk].frame.up));
        corners[static_cast<std::size_t>(r) * perRing + static_cast<std::size_t>(j)] =
            reorient(n, h, values.value(&HairSideAttributes::incline, s, tau) * kDegrees,
                     values.value(&HairSideAttributes::wrap, s, tau) * kDegrees);
        cornerTwist[static_cast<std::size_t>(r) * perRing + static_cast<std::size_t>(j)] =
            values.value(&HairSideAttributes::twist, s, tau);
      }
    }

    const float v0 = seg.rings[k - 1].axisDistance, v1 = seg.rings[k].axisDistance;
    if (!(v1 > v0)) continue;
    const float tv0 = v0 / tileHeight - shift, tv1 = v1 / tileHeight - shift;
    expectCandidates(
        (static_cast<double>(tv1) - tv0 + 1.0) *
        (height + static_cast<double>(points.size()) * (static_cast<double>(tilesAround) + 1.0)));
    // Texture rows in [tv0, tv1), tile by tile.
    const long firstRow = static_cast<long>(std::floor(tv0 * height));
    const long lastRow = static_cast<long>(std::floor(tv1 * height));
    for (long row = firstRow; row <= lastRow; ++row) {
      const long tileRow = row >= 0 ? row / height : -((-row + height - 1) / height);
      const int r = static_cast<int>(row - tileRow * height);
      for (std::uint32_t p = rowStart[static_cast<std::size_t>(r)];
           p < rowStart[static_cast<std::size_t>(r) + 1]; ++p) {
        const TexturePoint& point = points[p];
        const float tv = static_cast<float>(tileRow) + static_cast<float>(point.v);
        if (tv < tv0 || tv >= tv1) continue;
        const float t = (tv - tv0) / (tv1 - tv0);
        const float g = (1.0f - t) * girth[k - 1] + t * girth[k];
        const float across = seg.closed ? tilesAround : g / tileWidth;
        const float tau = (1.0f - t) * tau0 + t * tau1;
        // Open contours start at an edge; the shifted back needs the tile before the first.
        for (int tile = shift > 0.0f && !seg.closed ? -1 : 0; static_cast<float>(tile) < across;
             ++tile) {
          float u = static_cast<float>(tile) + static_cast<float>(point.u) + shift;
          if (seg.closed && u >= tilesAround) u -= tilesAround;
          if (u < 0.0f) continue;
          const float s = u / across;
          if (s >= 1.0f) continue;
          countCandidate();
          HairRandom random(key(sideKey, key(static_cast<std::uint64_t>(row) * 65536u + k,
                                             static_cast<std::uint64_t>(p) * 4096u +
                                                 static_cast<std::uint64_t>(tile))));
          // Thinning: the local density over the tile's, and on closed contours the girth here
          // over the widest (the tile is stretched around it).
          const float density = values.sample(&HairSideAttributes::density, s, tau, random);
          float keep = density / maxDensity;
          if (seg.closed) keep *= g / maxGirth;
          if (!(random.uniform() < keep)) continue;
          // The face: fractions mixed between the strip's two rings.
          int lo = 0, hi = faces;  // fraction(lo) <= s < fraction(hi)
          auto boundary = [&](int j) {
            return (1.0f - t) * fraction[(k - 1) * perRing + static_cast<std::size_t>(j)] +
                   t * fraction[k * perRing + static_cast<std::size_t>(j)];
          };
          while (hi - lo > 1) {
            const int mid = (lo + hi) / 2;
            (boundary(mid) <= s ? lo : hi) = mid;
          }
          const float b0 = boundary(lo), b1 = boundary(lo + 1);
          const float a = b1 > b0 ? std::clamp((s - b0) / (b1 - b0), 0.0f, 1.0f) : 0.5f;
          // Bilinear placement on the face and interpolation of the corner vectors.
          const float w00 = (1 - a) * (1 - t), w01 = a * (1 - t), w10 = (1 - a) * t, w11 = a * t;
          const glm::vec3 root = w00 * position(k - 1, lo) + w01 * position(k - 1, lo + 1) +
                                 w10 * position(k, lo) + w11 * position(k, lo + 1);
          const CornerVectors& c00 = corners[static_cast<std::size_t>(lo)];
          const CornerVectors& c01 = corners[static_cast<std::size_t>(lo + 1)];
          const CornerVectors& c10 = corners[perRing + static_cast<std::size_t>(lo)];
          const CornerVectors& c11 = corners[perRing + static_cast<std::size_t>(lo + 1)];
          const glm::vec3 direction =
              w00 * c00.direction + w01 * c01.direction + w10 * c10.direction + w11 * c11.direction;
          const glm::vec3 axisAcross =
              w00 * c00.across + w01 * c01.across + w10 * c10.across + w11 * c11.across;
          const float twist = w00 * cornerTwist[static_cast<std::size_t>(lo)] +
                              w01 * cornerTwist[static_cast<std::size_t>(lo + 1)] +
                              w10 * cornerTwist[perRing + static_cast<std::size_t>(lo)] +
                              w11 * cornerTwist[perRing + static_cast<std::size_t>(lo + 1)];
          emit(values, side, s, tau, root, direction, axisAcross, twist, random);
        }
      }
    }
  }
}

// Sec. 3.2: edge hairs along the two outer edges of an open cylinder, pointing along the edge
// vector h × n, away from the segment. An edge has no area: hairs lie as densely as along a line
// through the surface pattern of the same density, √density per unit length, spaced evenly with
// a jitter and counted in arc length from @Gs, so the rhythm continues from segment to segment.
void Placer::edge(const CylinderSegment& seg, const TriangleMesh& mesh, const SideValues& values,
                  int which) {
  const float maxDensity = values.maxDensity();
  if (!(maxDensity > 0.0f)) return;
  const float maxLinear = std::sqrt(maxDensity);
  const std::size_t perRing = static_cast<std::size_t>(seg.sides) + 1;
  const int j = which == 0 ? 0 : seg.sides;
  const int inner = which == 0 ? 1 : seg.sides - 1;
  const float s = which == 0 ? 0.0f : 1.0f;
  auto position = [&](std::size_t k, int jj) {
    return mesh.positions[seg.firstVertex + k * perRing + static_cast<std::size_t>(jj)];
  };
  const std::uint64_t edgeKey = key(settings.seed, key(static_cast<std::uint64_t>(seg.tube) * 2 +
                                                           static_cast<std::uint64_t>(which),
                                                       0x65646765u));
  for (std::size_t k = 1; k < seg.rings.size(); ++k) {
    const float v0 = seg.rings[k - 1].axisDistance, v1 = seg.rings[k].axisDistance;
    if (!(v1 > v0)) continue;
    const float tau0 = ringTau(seg, k - 1), tau1 = ringTau(seg, k);
    const glm::vec3 h =
        normalizedOr(position(k, j) - position(k - 1, j), glm::vec3(seg.rings[k].frame.heading));
    CornerVectors corner[2];
    float twist[2];
    for (int r = 0; r < 2; ++r) {
      const std::size_t kk = k - 1 + static_cast<std::size_t>(r);
      const float tau = r == 0 ? tau0 : tau1;
      const glm::vec3 n =
          normalizedOr(mesh.normals[seg.firstVertex + kk * perRing + static_cast<std::size_t>(j)],
                       glm::vec3(seg.rings[kk].frame.up));
      glm::vec3 e = normalizedOr(glm::cross(h, n), anyPerpendicular(h));
      if (glm::dot(e, position(kk, j) - position(kk, inner)) < 0.0f) e = -e;
      corner[r] = reorient(e, h, values.value(&HairSideAttributes::incline, s, tau) * kDegrees,
                           values.value(&HairSideAttributes::wrap, s, tau) * kDegrees);
      twist[r] = values.value(&HairSideAttributes::twist, s, tau);
    }
    expectCandidates((static_cast<double>(v1) - v0) * maxLinear + 1.0);
    const long first = static_cast<long>(std::floor(v0 * maxLinear));
    const long last = static_cast<long>(std::floor(v1 * maxLinear));
    for (long slot = first; slot <= last; ++slot) {
      countCandidate();
      HairRandom random(key(edgeKey, static_cast<std::uint64_t>(slot)));
      const float v = (static_cast<float>(slot) + 0.5f + 0.35f * random.symmetric()) / maxLinear;
      if (v < v0 || v >= v1) continue;
      const float t = (v - v0) / (v1 - v0);
      const float tau = (1.0f - t) * tau0 + t * tau1;
      const float density = values.sample(&HairSideAttributes::density, s, tau, random);
      if (!(random.uniform() < std::sqrt(std::max(0.0f, density)) / maxLinear)) continue;
      const glm::vec3 root = (1.0f - t) * position(k - 1, j) + t * position(k, j);
      const glm::vec3 direction = (1.0f - t) * corner[0].direction + t * corner[1].direction;
      const glm::vec3 across = (1.0f - t) * corner[0].across + t * corner[1].across;
      emit(values, HairSide::Edge, s, tau, root, direction, across,
           (1.0f - t) * twist[0] + t * twist[1], random);
    }
  }
}

// The expected number of hairs, to reserve the vector once (bytes per hair stay near 32).
std::size_t expectedHairs(const Scene& scene) {
  double total = 0;
  for (const CylinderSegment& seg : scene.cylinderSegments) {
    const int end = seg.organEnd.hair;
    if (end < 0 || static_cast<std::size_t>(end) >= scene.hairAttributes.size()) continue;
    const HairAttributes& a = scene.hairAttributes[static_cast<std::size_t>(end)];
    const double area = 0.5 * (seg.girthStart + seg.girthEnd) * seg.axisLength;
    // Only an estimate: terms that are not finite (a broken geometry or density) count nothing.
    auto add = [&](double term) {
      if (std::isfinite(term)) total += term;
    };
    for (HairSide side : {HairSide::Front, HairSide::Back}) {
      const HairSideAttributes& s = a.side(side);
      if (s.enabled && (side == HairSide::Front || !seg.closed))
        add(std::abs(s.density.value) * area);
    }
    const HairSideAttributes& e = a.side(HairSide::Edge);
    if (e.enabled && !seg.closed) add(2.0 * std::sqrt(std::abs(e.density.value)) * seg.axisLength);
  }
  return static_cast<std::size_t>(std::min(total * 1.02 + 64.0, 1e9));
}

}  // namespace

HairTemplate straightHairTemplate() {
  HairTemplate t;
  t.file = "(straight)";
  t.polylines = {{glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)}};
  t.material = 255;
  t.extent = 1.0f;
  return t;
}

HairPlacementReport placeHairs(Scene& scene, const HairPlacementSettings& settings) {
  if (scene.hairTemplates.empty()) scene.hairTemplates.push_back(straightHairTemplate());
  const PointDiffusionTexture texture = PointDiffusionTexture::generate(settings.texture);
  Placer placer{scene, settings, texture, {}, 0, {}};
  placer.templates =
      static_cast<int>(std::min<std::size_t>(scene.hairTemplates.size(), kMaxHairTemplates));
  placer.rowStart.assign(static_cast<std::size_t>(texture.height()) + 1, 0);
  for (const TexturePoint& p : texture.points())
    ++placer.rowStart[static_cast<std::size_t>(p.row) + 1];
  for (std::size_t r = 1; r < placer.rowStart.size(); ++r)
    placer.rowStart[r] += placer.rowStart[r - 1];
  scene.hairs.reserve(scene.hairs.size() + std::min(expectedHairs(scene), settings.maxHairs));
  for (std::size_t i = 0; i < scene.cylinderSegments.size(); ++i) placer.segment(i);
  return placer.report;
}

}  // namespace hirsute
