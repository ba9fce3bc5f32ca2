// Plant hairs on generalized-cylinder segments (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3–4;
// docs/design.md, "Plant hairs"): the attachment points of the shared placement engine
// (hairs/placement/), thinned by the @Hd density, each given a template, a length, a radius and
// the hair direction from the corner frames, by the attributes of Table 1.
#include "hirsute/hairs/plant/hair_placement.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "hirsute/hairs/placement/corner_frame.h"
#include "hirsute/hairs/placement/patch_unfolding.h"
#include "hirsute/hairs/placement/segment_unfolding.h"
#include "hirsute/hairs/placement/segment_values.h"
#include "hirsute/hairs/placement/surface_sampler.h"
#include "hirsute/hairs/plant/hair_part.h"

namespace hirsute {
namespace {

constexpr float kDegrees = std::numbers::pi_v<float> / 180.0f;

// The attributes of one side of one segment, between its two ends, with the template choice.
class SideValues : public SegmentValues<HairSideAttributes> {
 public:
  using SegmentValues::SegmentValues;

  // The largest density anywhere on the segment (sets the tile's size; hairs below it are
  // thinned out).
  float maxDensity() const { return peak(&HairSideAttributes::density); }
  // The template for a uniform number u, by the probabilities mixed along the segment; -1 when
  // every probability is zero.
  int chooseTemplate(float tau, float u, int templates) const {
    // Each end's probabilities are normalised before they are mixed, so that the probabilities
    // (not the raw @Hp weights) vary linearly along the segment.
    float startTotal = 0, endTotal = 0;
    for (int i = 0; i < templates; ++i) {
      startTotal += probability(start(), i, templates);
      endTotal += probability(end(), i, templates);
    }
    const float startScale = startTotal > 0.0f ? (1.0f - tau) / startTotal : 0.0f;
    const float endScale = endTotal > 0.0f ? tau / endTotal : 0.0f;
    float weights[kMaxHairTemplates];
    float total = 0;
    for (int i = 0; i < templates; ++i) {
      weights[i] = startScale * probability(start(), i, templates) +
                   endScale * probability(end(), i, templates);
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
};

struct Placer {
  Scene& scene;
  HairPart& part;  // the scene's
  const HairPlacementSettings& settings;
  SurfaceSampler& sampler;
  int templates = 1;
  HairPlacementReport report;

  std::size_t candidates = 0;  // attachment points considered (thinning rejects some)

  void checkLimit() {
    if (part.hairs.size() >= settings.maxHairs) {
      throw HairLimitError("more than " + std::to_string(settings.maxHairs) +
                           " hairs (raise the limit with --max-hairs, or lower @Hd)");
    }
  }
  // A density whose peak (a function's, or its range's) is far above where hairs are kept still
  // costs an attachment point per unit of the peak: bounded like the hairs themselves.
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
            glm::vec3 direction, glm::vec3 across, float twist, PlacementRandom& random) {
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
    part.hairs.push_back(hair);
    ++report.hairs;
  }

  const HairAttributes& attributesAt(int i) const {
    static const HairAttributes kNone{};
    return i >= 0 && static_cast<std::size_t>(i) < part.attributes.size()
               ? part.attributes[static_cast<std::size_t>(i)]
               : kNone;
  }
  void segment(std::size_t index);
  void surface(std::size_t index);
};

// The hairs of one side of a segment at the engine's attachment points: Sec. 4.4's corner angles
// from @Hi @Hw @Ht, thinning by @Hd, then a hair.
class SideHairs : public AttachmentVisitor {
 public:
  SideHairs(Placer& placer, const SideValues& values, HairSide side)
      : placer_(placer), values_(values), side_(side), maxDensity_(values.maxDensity()) {}

  float maxDensity() const { return maxDensity_; }

  CornerAngles cornerAngles(float s, float tau) const override {
    return {values_.value(&HairSideAttributes::incline, s, tau) * kDegrees,
            values_.value(&HairSideAttributes::wrap, s, tau) * kDegrees,
            values_.value(&HairSideAttributes::twist, s, tau)};
  }
  void expectPoints(double points) override { placer_.expectCandidates(points); }
  void pointTested() override { placer_.countCandidate(); }
  bool keep(AttachmentPoint& point) override {
    const float density =
        values_.sample(&HairSideAttributes::density, point.s, point.tau, point.random);
    if (point.edge) {
      // Per unit length along an edge: √density (docs/hairs.md).
      return random(point) < std::sqrt(std::max(0.0f, density)) / std::sqrt(maxDensity_);
    }
    // The local density over the tile's, and on closed contours the girth here over the widest
    // (the tile is stretched around it).
    const float keep = density / maxDensity_ * point.girthRatio;
    return random(point) < keep;
  }
  void place(AttachmentPoint& point, const AttachmentFrame& frame) override {
    placer_.emit(values_, side_, point.s, point.tau, frame.position, frame.direction, frame.across,
                 frame.twist, point.random);
  }

 private:
  static float random(AttachmentPoint& point) { return point.random.uniform(); }

  Placer& placer_;
  const SideValues& values_;
  HairSide side_;
  float maxDensity_;
};

void Placer::segment(std::size_t index) {
  const CylinderSegment& seg = scene.cylinderSegments[index];
  if (seg.organEnd.of<HairAttributes>() < 0 && seg.organStart.of<HairAttributes>() < 0) return;
  const HairAttributes& end = attributesAt(seg.organEnd.of<HairAttributes>());
  const HairAttributes& start =
      settings.interpolation ? attributesAt(seg.organStart.of<HairAttributes>()) : end;
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
  const SegmentUnfolding unfolding(seg, scene.meshes[static_cast<std::size_t>(seg.mesh)]);
  for (HairSide side : {HairSide::Front, HairSide::Back}) {
    if (side == HairSide::Front ? !front : !back) continue;
    const SideValues values(startOf(side), end.side(side), settings.function);
    SideHairs hairs(*this, values, side);
    const std::uint64_t sideKey =
        placementKey(settings.seed, placementKey(index, static_cast<std::uint64_t>(side)));
    sampler.sampleSurface(unfolding,
                          side == HairSide::Back ? SurfaceFace::Back : SurfaceFace::Front,
                          hairs.maxDensity(), sideKey, hairs);
  }
  if (edges) {
    const SideValues values(startOf(HairSide::Edge), end.side(HairSide::Edge), settings.function);
    SideHairs hairs(*this, values, HairSide::Edge);
    for (int which : {0, 1}) {
      const std::uint64_t edgeKey = placementKey(
          settings.seed,
          placementKey(static_cast<std::uint64_t>(seg.tube) * 2 + static_cast<std::uint64_t>(which),
                       0x65646765u));
      SurfaceSampler::sampleEdge(unfolding, which, hairs.maxDensity(), edgeKey, hairs);
    }
  }
}

// A `~` surface patch or a polygon: its front and back in its own (u, v), with the attributes in
// force where it was drawn (one record: nothing to interpolate). Edges are the cylinders' only.
void Placer::surface(std::size_t index) {
  const OrganSurface& record = scene.organSurfaces[index];
  if (record.organs.of<HairAttributes>() < 0 || record.mesh < 0 || record.indexCount < 3) return;
  const HairAttributes& attributes = attributesAt(record.organs.of<HairAttributes>());
  const bool front = attributes.side(HairSide::Front).enabled;
  const bool back = attributes.side(HairSide::Back).enabled;
  if (!front && !back) return;
  ++report.surfaces;
  const PatchUnfolding unfolding(record, scene.meshes[static_cast<std::size_t>(record.mesh)]);
  for (HairSide side : {HairSide::Front, HairSide::Back}) {
    if (side == HairSide::Front ? !front : !back) continue;
    const SideValues values(attributes.side(side), attributes.side(side), settings.function);
    SideHairs hairs(*this, values, side);
    const std::uint64_t sideKey = placementKey(
        settings.seed, placementKey(0x7375726661636500u + index, static_cast<std::uint64_t>(side)));
    const SurfaceFace face = side == HairSide::Back ? SurfaceFace::Back : SurfaceFace::Front;
    if (record.kind == OrganSurfaceKind::Mesh) {
      SurfaceSampler::sampleMesh(unfolding, face, hairs.maxDensity(), sideKey, hairs);
    } else {
      sampler.samplePatch(unfolding, face, hairs.maxDensity(), sideKey, hairs);
    }
  }
}

// The expected number of hairs, to reserve the vector once (bytes per hair stay near 32).
std::size_t expectedHairs(const Scene& scene) {
  const HairPart& part = scene.organ<HairPart>();
  double total = 0;
  for (const CylinderSegment& seg : scene.cylinderSegments) {
    const int end = seg.organEnd.of<HairAttributes>();
    if (end < 0 || static_cast<std::size_t>(end) >= part.attributes.size()) continue;
    const HairAttributes& a = part.attributes[static_cast<std::size_t>(end)];
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
  for (const OrganSurface& record : scene.organSurfaces) {
    const int index = record.organs.of<HairAttributes>();
    if (index < 0 || static_cast<std::size_t>(index) >= part.attributes.size()) continue;
    const HairAttributes& a = part.attributes[static_cast<std::size_t>(index)];
    const TriangleMesh& mesh = scene.meshes[static_cast<std::size_t>(record.mesh)];
    double area = 0;
    for (std::uint32_t i = record.firstIndex; i + 2 < record.firstIndex + record.indexCount;
         i += 3) {
      const glm::vec3 p = mesh.positions[mesh.indices[i]];
      area += 0.5 * glm::length(glm::cross(mesh.positions[mesh.indices[i + 1]] - p,
                                           mesh.positions[mesh.indices[i + 2]] - p));
    }
    for (HairSide side : {HairSide::Front, HairSide::Back}) {
      const HairSideAttributes& s = a.side(side);
      if (s.enabled && std::isfinite(s.density.value * area))
        total += std::abs(s.density.value) * area;
    }
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
  HairPart& part = scene.organ<HairPart>();
  if (part.templates.empty()) part.templates.push_back(straightHairTemplate());
  SurfaceSampler sampler(PointDiffusionTexture::generate(settings.texture));
  Placer placer{scene, part, settings, sampler, 0, {}};
  placer.templates =
      static_cast<int>(std::min<std::size_t>(part.templates.size(), kMaxHairTemplates));
  part.hairs.reserve(part.hairs.size() + std::min(expectedHairs(scene), settings.maxHairs));
  if (settings.progress) settings.progress->begin("placing hairs", Progress::Unit::Count);
  for (std::size_t i = 0; i < scene.cylinderSegments.size(); ++i) {
    placer.segment(i);
    if (settings.progress) settings.progress->update(static_cast<double>(placer.report.hairs));
  }
  for (std::size_t i = 0; i < scene.organSurfaces.size(); ++i) {
    placer.surface(i);
    if (settings.progress) settings.progress->update(static_cast<double>(placer.report.hairs));
  }
  return placer.report;
}

}  // namespace hirsute
