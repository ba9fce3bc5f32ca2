#include "hirsute/hairs/feathers/feather_coats.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/placement/patch_unfolding.h"
#include "hirsute/hairs/placement/placement_random.h"
#include "hirsute/hairs/placement/segment_unfolding.h"
#include "hirsute/hairs/placement/surface_sampler.h"

namespace hirsute {
namespace {

constexpr float kDegrees = 3.14159265358979f / 180.0f;

using SideValues = SegmentValues<FeatherSideAttributes>;

glm::vec3 normalizedOr(const glm::vec3& v, const glm::vec3& otherwise) {
  const float length = glm::length(v);
  return length > 1e-20f ? v / length : otherwise;
}

glm::vec3 rotated(const glm::vec3& v, const glm::vec3& axis, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1 - c);
}

struct CoatPlacer {
  Scene& scene;
  const FeatherCoatSettings& settings;
  FeatherCoatReport report;
  // Where each coat feather lies along the body, in the direction it points: the drawing order.
  std::vector<float> order;

  void segment(std::size_t index, SurfaceSampler& sampler);
  void surface(std::size_t index);
};

// The key feather's two types and its blend at girth position s (@Fk(k1, k2, fun)); on a mesh
// with vertex colours and no function, the colours' red there (`blend`, -1 elsewhere).
void keyAt(const KeyFeather& key, const GirthFunction& function, float s, float blend,
           std::uint16_t& a, std::uint16_t& b, float& t) {
  a = static_cast<std::uint16_t>(std::max(1, key.type));
  b = static_cast<std::uint16_t>(std::max(1, key.blendType));
  if (a == b) {
    t = 0;
    return;
  }
  t = key.function > 0 ? girthModulation(function, key.function, s) : blend >= 0 ? blend : s;
  t = std::clamp(t, 0.0f, 1.0f);
}

class SideCoat : public AttachmentVisitor {
 public:
  SideCoat(CoatPlacer& placer, const SideValues& values, const KeyFeather& startKey,
           const KeyFeather& endKey, float axisStart, float axisLength)
      : placer_(placer),
        values_(values),
        startKey_(startKey),
        endKey_(endKey),
        axisStart_(axisStart),
        axisLength_(axisLength),
        maxDensity_(values.peak(&FeatherSideAttributes::density)) {}

  float maxDensity() const { return maxDensity_; }

  // The follicle frame is the surface's own: lie and twist turn it in place().
  CornerAngles cornerAngles(float, float) const override { return {}; }
  void expectPoints(double points) override {
    if (!(points <= 8.0 * static_cast<double>(placer_.settings.maxFeathers) + 1e6)) {
      throw FeatherLimitError("the coat densities would test more than " +
                              std::to_string(8 * placer_.settings.maxFeathers + 1'000'000) +
                              " follicles (lower @Fd)");
    }
  }
  bool keep(AttachmentPoint& point) override {
    const float density =
        values_.sample(&FeatherSideAttributes::density, point.s, point.tau, point.random);
    return point.random.uniform() < density / maxDensity_ * point.girthRatio;
  }
  void place(AttachmentPoint& point, const AttachmentFrame& frame) override {
    Scene& scene = placer_.scene;
    if (scene.organ<FeatherPart>().feathers.size() >= placer_.settings.maxFeathers) {
      throw FeatherLimitError("more than " + std::to_string(placer_.settings.maxFeathers) +
                              " coat feathers (lower @Fd)");
    }
    const float s = point.s, tau = point.tau;
    PlacementRandom& random = point.random;
    const float size = values_.sample(&FeatherSideAttributes::size, s, tau, random);
    if (!(size > 0)) return;
    Feather feather;
    feather.origin = FeatherOrigin::Coat;
    feather.size = size;
    feather.age =
        std::clamp(values_.sample(&FeatherSideAttributes::age, s, tau, random), 0.0f, 1.0f);
    const float lie = values_.sample(&FeatherSideAttributes::lie, s, tau, random) * kDegrees;
    const float twist = values_.sample(&FeatherSideAttributes::twist, s, tau, random) * kDegrees;

    // The follicle's frame: n the surface normal, h the axis direction in the tangent plane
    // (the incline axis is n × h, so h = (n × h) × n). The rachis rises from h towards n by the
    // lie angle, turned about n by the twist; the front faces away from the surface.
    const glm::vec3 n = normalizedOr(frame.direction, glm::vec3(0, 0, 1));
    glm::vec3 h = glm::cross(frame.across, n);
    h = normalizedOr(h - n * glm::dot(h, n), glm::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0)
                                                                   : glm::vec3(0, 1, 0));
    h = rotated(h, n, twist);
    feather.heading = std::cos(lie) * h + std::sin(lie) * n;
    feather.up = std::cos(lie) * n - std::sin(lie) * h;
    feather.position = frame.position;

    std::uint16_t a0 = 1, b0 = 1, a1 = 1, b1 = 1;
    keyAt(startKey_, placer_.settings.function, s, point.blend, a0, b0, feather.across[0]);
    keyAt(endKey_, placer_.settings.function, s, point.blend, a1, b1, feather.across[1]);
    feather.types = {a0, b0, a1, b1};
    feather.along = tau;
    scene.organ<FeatherPart>().feathers.push_back(feather);
    // Bottom to top (Sec. 4.4): a feather lies over those its rachis points to, so those are
    // drawn first.
    const float v = axisStart_ + tau * axisLength_;
    placer_.order.push_back(std::cos(twist) >= 0 ? -v : v);
    ++placer_.report.feathers;
  }

 private:
  CoatPlacer& placer_;
  const SideValues& values_;
  const KeyFeather& startKey_;
  const KeyFeather& endKey_;
  float axisStart_, axisLength_;
  float maxDensity_;
};

void CoatPlacer::segment(std::size_t index, SurfaceSampler& sampler) {
  const CylinderSegment& seg = scene.cylinderSegments[index];
  static const FeatherAttributes kNone{};
  auto attributesAt = [&](int i) -> const FeatherAttributes& {
    return i >= 0 && static_cast<std::size_t>(i) < scene.organ<FeatherPart>().attributes.size()
               ? scene.organ<FeatherPart>().attributes[static_cast<std::size_t>(i)]
               : kNone;
  };
  if (seg.organStart.of<FeatherAttributes>() < 0 && seg.organEnd.of<FeatherAttributes>() < 0)
    return;
  const FeatherAttributes& end = attributesAt(seg.organEnd.of<FeatherAttributes>());
  const FeatherAttributes& start = attributesAt(seg.organStart.of<FeatherAttributes>());
  const bool front = end.side(FeatherSide::Front).enabled;
  const bool back = !seg.closed && end.side(FeatherSide::Back).enabled;
  if (!front && !back) return;
  if (seg.mesh < 0 || seg.rings.size() < 2 || seg.sides < 1) {
    ++report.segmentsWithoutMesh;
    return;
  }
  ++report.segments;
  // A key feather set only at one end stands for both.
  const KeyFeather& endKey = end.key.type > 0 ? end.key : start.key;
  const KeyFeather& startKey = start.key.type > 0 ? start.key : endKey;
  const SegmentUnfolding unfolding(seg, scene.meshes[static_cast<std::size_t>(seg.mesh)]);
  for (FeatherSide side : {FeatherSide::Front, FeatherSide::Back}) {
    if (side == FeatherSide::Front ? !front : !back) continue;
    const FeatherSideAttributes& startSide =
        start.side(side).enabled ? start.side(side) : end.side(side);
    const SideValues values(startSide, end.side(side), settings.function);
    SideCoat coat(*this, values, startKey, endKey, seg.axisStart, seg.axisLength);
    if (!(coat.maxDensity() > 0)) continue;
    const std::uint64_t key = placementKey(
        settings.seed, placementKey(index, 0x66656100u + static_cast<std::uint64_t>(side)));
    sampler.sampleSurface(unfolding, side == FeatherSide::Back ? SurfaceFace::Back
                                                                : SurfaceFace::Front,
                          coat.maxDensity(), key, coat);
  }
}

// A mesh surface's coat (OrganSurfaceKind::Mesh, docs/meshes.md): follicles over its area
// (SurfaceSampler::sampleMesh), each feather lying along the direction in which the mesh's v
// grows (its flow), the key feather blended across u by its function as around a girth; the
// coat is drawn from low v to high.
void CoatPlacer::surface(std::size_t index) {
  const OrganSurface& record = scene.organSurfaces[index];
  const int attributes = record.organs.of<FeatherAttributes>();
  if (record.kind != OrganSurfaceKind::Mesh || attributes < 0 ||
      static_cast<std::size_t>(attributes) >= scene.organ<FeatherPart>().attributes.size() ||
      record.mesh < 0 || record.indexCount < 3) {
    return;
  }
  const FeatherAttributes& coat = scene.organ<FeatherPart>().attributes[static_cast<std::size_t>(attributes)];
  const PatchUnfolding unfolding(record, scene.meshes[static_cast<std::size_t>(record.mesh)]);
  bool any = false;
  for (FeatherSide side : {FeatherSide::Front, FeatherSide::Back}) {
    if (!coat.side(side).enabled) continue;
    const SideValues values(coat.side(side), coat.side(side), settings.function);
    SideCoat sideCoat(*this, values, coat.key, coat.key, 0.0f, 1.0f);
    if (!(sideCoat.maxDensity() > 0)) continue;
    any = true;
    const std::uint64_t key = placementKey(
        settings.seed,
        placementKey(0x6d65736800000000u + index, 0x66656100u + static_cast<std::uint64_t>(side)));
    SurfaceSampler::sampleMesh(unfolding, side == FeatherSide::Back ? SurfaceFace::Back
                                                                     : SurfaceFace::Front,
                               sideCoat.maxDensity(), key, sideCoat);
  }
  if (any) ++report.surfaces;
}

}  // namespace

std::vector<TexturePoint> hexagonalFollicles(int columns, int rows) {
  std::vector<TexturePoint> points;
  points.reserve(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows));
  for (int row = 0; row < rows; ++row) {
    // Every other row shifted by half a column: the lattice of equilateral triangles.
    const double shift = (row % 2 == 0 ? 0.25 : 0.75) / columns;
    for (int column = 0; column < columns; ++column) {
      TexturePoint p;
      p.column = column;
      p.row = row;
      p.u = static_cast<double>(column) / columns + shift;
      p.v = (row + 0.5) / rows;
      points.push_back(p);
    }
  }
  return points;
}

FeatherCoatReport placeFeatherCoats(Scene& scene, const FeatherCoatSettings& settings) {
  bool any = false;
  for (const FeatherAttributes& a : scene.organ<FeatherPart>().attributes)
    any = any || a.anyEnabled();
  if (!any) return {};
  const int hexColumns = 26, hexRows = 30;
  SurfaceSampler sampler = settings.layout == FollicleLayout::Hexagonal
                               ? SurfaceSampler(hexagonalFollicles(hexColumns, hexRows), hexRows)
                               : SurfaceSampler(PointDiffusionTexture::generate(settings.texture));
  CoatPlacer placer{scene, settings, {}, {}};
  const std::size_t first = scene.organ<FeatherPart>().feathers.size();
  if (settings.progress) settings.progress->begin("placing feather coats", Progress::Unit::Count);
  for (std::size_t i = 0; i < scene.cylinderSegments.size(); ++i) {
    placer.segment(i, sampler);
    if (settings.progress) settings.progress->update(static_cast<double>(placer.report.feathers));
  }
  for (std::size_t i = 0; i < scene.organSurfaces.size(); ++i) {
    placer.surface(i);
    if (settings.progress) settings.progress->update(static_cast<double>(placer.report.feathers));
  }

  // The coat from its bottom feather to its top one; singles keep their place before it.
  std::vector<std::size_t> byOrder(placer.order.size());
  std::iota(byOrder.begin(), byOrder.end(), std::size_t{0});
  std::stable_sort(byOrder.begin(), byOrder.end(), [&](std::size_t a, std::size_t b) {
    return placer.order[a] < placer.order[b];
  });
  std::vector<Feather> coat;
  coat.reserve(byOrder.size());
  for (std::size_t i : byOrder) coat.push_back(scene.organ<FeatherPart>().feathers[first + i]);
  std::copy(coat.begin(), coat.end(),
            scene.organ<FeatherPart>().feathers.begin() + static_cast<std::ptrdiff_t>(first));
  return placer.report;
}

}  // namespace hirsute
