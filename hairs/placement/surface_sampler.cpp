// The shared placement engine: the point pattern tiled over unfolded segments and their edges
// (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3.1, 3.2 and 4.4; docs/design.md, "Placement").
#include "hirsute/hairs/placement/surface_sampler.h"

#include "hirsute/hairs/placement/mesh_sampling.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

namespace hirsute {

SurfaceSampler::SurfaceSampler(const PointDiffusionTexture& texture)
    : SurfaceSampler(texture.points(), texture.height()) {
  stripFill_ = texture.fill();
  stripSeed_ = texture.seed();
}

SurfaceSampler::SurfaceSampler(std::vector<TexturePoint> points, int rows)
    : points_(std::move(points)), rows_(rows) {
  rowStart_.assign(static_cast<std::size_t>(rows_) + 1, 0);
  for (const TexturePoint& p : points_) ++rowStart_[static_cast<std::size_t>(p.row) + 1];
  for (std::size_t r = 1; r < rowStart_.size(); ++r) rowStart_[r] += rowStart_[r - 1];
}

// The corner frames of every strip of a segment, and placing a point on a face of one.
class SurfaceSampler::Faces {
 public:
  Faces(const SegmentUnfolding& unfolding, SurfaceFace face, AttachmentVisitor& visitor)
      : unfolding_(unfolding),
        perRing_(static_cast<std::size_t>(unfolding.faces()) + 1),
        corners_(2 * perRing_ * unfolding.rings()),
        twist_(corners_.size()) {
    const CylinderSegment& seg = unfolding.segment();
    const float flip = face == SurfaceFace::Back ? -1.0f : 1.0f;
    // Corner frames of ring k, column j of strip (k-1, k): the surface's normal reoriented by the
    // incline and wrap at that corner; h is the face's height vector. A tube's shading normals
    // are those of a cylinder (perpendicular to the axis, as cpfg shades them); where the tube
    // tapers the surface slopes, and its true normal is the shading normal without its part
    // along h, so that organs stand on a cone as on a cylinder.
    for (std::size_t k = 1; k < unfolding.rings(); ++k) {
      const float tau0 = unfolding.tau(k - 1), tau1 = unfolding.tau(k);
      const glm::vec3 axis =
          normalizedOr(seg.rings[k].frame.position - seg.rings[k - 1].frame.position,
                       seg.rings[k].frame.heading);
      for (int j = 0; j <= unfolding.faces(); ++j) {
        const glm::vec3 h =
            normalizedOr(unfolding.position(k, j) - unfolding.position(k - 1, j), axis);
        for (std::size_t r = 0; r < 2; ++r) {
          const std::size_t kk = k - 1 + r;
          const float tau = r == 0 ? tau0 : tau1;
          const float s = (unfolding.fraction(k - 1, j) + unfolding.fraction(k, j)) * 0.5f;
          const glm::vec3 shading = normalizedOr(flip * unfolding.normal(kk, j),
                                                 flip * glm::vec3(seg.rings[kk].frame.up));
          const glm::vec3 n = normalizedOr(shading - h * glm::dot(shading, h), shading);
          const CornerAngles angles = visitor.cornerAngles(s, tau);
          const std::size_t at = corner(k, r, j);
          corners_[at] = reorient(n, h, angles.incline, angles.wrap);
          twist_[at] = angles.twist;
        }
      }
    }
  }

  // Bilinear placement on the face of strip k at (t, s) and interpolation of its corner frames.
  void place(std::size_t k, float t, float s, AttachmentPoint& candidate,
             AttachmentVisitor& visitor) const {
    const FacePoint at = unfolding_.face(k, t, s);
    const int lo = at.column;
    const float a = at.a;
    const float w[4] = {(1 - a) * (1 - t), a * (1 - t), (1 - a) * t, a * t};
    const std::size_t c[4] = {corner(k, 0, lo), corner(k, 0, lo + 1), corner(k, 1, lo),
                              corner(k, 1, lo + 1)};
    AttachmentFrame frame;
    frame.position = unfolding_.at(at);
    for (int i = 0; i < 4; ++i) {
      frame.direction += w[i] * corners_[c[i]].direction;
      frame.across += w[i] * corners_[c[i]].across;
      frame.twist += w[i] * twist_[c[i]];
    }
    visitor.place(candidate, frame);
  }

 private:
  // Corner j of ring k - 1 + r, as strip k sees it.
  std::size_t corner(std::size_t k, std::size_t r, int j) const {
    return (2 * k + r) * perRing_ + static_cast<std::size_t>(j);
  }

  const SegmentUnfolding& unfolding_;
  std::size_t perRing_;
  std::vector<CornerVectors> corners_;
  std::vector<float> twist_;
};

// A strip in progress along one tube and face, and the points it made past the segment it was
// extended for (they belong to the next segment of the tube).
struct SurfaceSampler::OpenStrip {
  DiffusionStrip strip;
  double segmentEnd = 0;   // v (along the axis) at the end of the segment it was extended for
  double segmentEndW = 0;  // and w (along the surface)
  std::vector<StripPoint> pending;
};

SurfaceSampler::~SurfaceSampler() = default;
SurfaceSampler::SurfaceSampler(SurfaceSampler&&) noexcept = default;

void SurfaceSampler::sampleSurface(const SegmentUnfolding& unfolding, SurfaceFace face,
                                   float maxDensity, std::uint64_t key,
                                   AttachmentVisitor& visitor) {
  if (!(maxDensity > 0.0f)) return;
  if (!(unfolding.maxGirth() > 0.0f)) return;
  const Faces faces(unfolding, face, visitor);
  if (unfolding.segment().closed && stripFill_ > 0.0) {
    sampleAlongTube(unfolding, faces, face, maxDensity, key, visitor);
  } else {
    sampleTiles(unfolding, faces, face, maxDensity, key, visitor);
  }
}

// Closed contours: the strip of the tube and face, continued from the segment before when this
// one starts where it ended, at this segment's density (diffusion_strip.h). The strip runs along w, the
// length along the surface: each strip of rings is as long in w as its surface area over its
// mean girth (its slant length on a taper; on a bend, by Pappus, its length along the axis), so
// that rows of square cells cover density × area on a taper too, unstretched.
void SurfaceSampler::sampleAlongTube(const SegmentUnfolding& unfolding, const Faces& faces,
                                     SurfaceFace face, float maxDensity, std::uint64_t key,
                                     AttachmentVisitor& visitor) {
  const CylinderSegment& seg = unfolding.segment();
  const std::size_t rings = unfolding.rings();
  const double v0 = unfolding.v(0), v1 = unfolding.v(rings - 1);
  if (!(v1 > v0)) return;
  const auto id = std::make_pair(seg.tube, static_cast<int>(face));
  // The texture's seed and the place seed the strip, as the texture alone sets the tiles'
  // points: another per-organ seed (--hair-seed) draws other values at the same points.
  auto stripSeed = [&](int tube, SurfaceFace f) {
    return placementKey(
        stripSeed_, placementKey(static_cast<std::uint64_t>(tube), static_cast<std::uint64_t>(f)));
  };
  auto open = strips_.find(id);
  const bool continues = open != strips_.end() &&
                         std::abs(open->second->segmentEnd - v0) <= 1e-5 * std::max(1.0, v1);

  // w at each ring, from where the tube's strip stands.
  std::vector<double> w(rings);
  w[0] = continues ? open->second->segmentEndW : 0.0;
  for (std::size_t k = 1; k < rings; ++k) {
    double area = 0;
    for (int j = 0; j < unfolding.faces(); ++j) {
      const glm::vec3 a = unfolding.position(k - 1, j), b = unfolding.position(k - 1, j + 1);
      const glm::vec3 c = unfolding.position(k, j), d = unfolding.position(k, j + 1);
      area += 0.5 * (glm::length(glm::cross(b - a, d - a)) + glm::length(glm::cross(d - a, c - a)));
    }
    const double girth = 0.5 * (unfolding.girth(k - 1) + unfolding.girth(k));
    const double along = unfolding.v(k) - unfolding.v(k - 1);
    w[k] = w[k - 1] + (girth > 0.0 && along > 0.0 ? area / girth : std::max(0.0, along));
  }
  const double w0 = w.front(), w1 = w.back();
  if (!(w1 > w0)) return;
  // The strip of rings holding w (searched on from the last one asked for), and the girth at w,
  // linear between the rings.
  std::size_t k = 1;
  auto stripAt = [&](double at) {
    while (k + 1 < rings && w[k] <= at) ++k;
    while (k > 1 && w[k - 1] > at) --k;
    return k;
  };
  auto girthAt = [&](double at) {
    const std::size_t r = stripAt(at);
    const double t =
        w[r] > w[r - 1] ? std::clamp((at - w[r - 1]) / (w[r] - w[r - 1]), 0.0, 1.0) : 1.0;
    return (1.0 - t) * unfolding.girth(r - 1) + t * unfolding.girth(r);
  };
  const double cell = std::sqrt(stripFill_ / maxDensity);
  visitor.expectPoints((w1 - w0 + 32.0 * cell) * unfolding.maxGirth() * maxDensity +
                       unfolding.maxGirth() / cell + 1.0);
  if (!continues) {
    auto fresh = std::make_unique<OpenStrip>(
        OpenStrip{DiffusionStrip(stripFill_, maxDensity, stripSeed(seg.tube, face), w0, girthAt),
                  v0,
                  w0,
                  {}});
    open = strips_.insert_or_assign(id, std::move(fresh)).first;
  }
  OpenStrip& strip = *open->second;
  strip.strip.setDensity(maxDensity);
  std::vector<StripPoint> points;
  points.swap(strip.pending);
  strip.strip.extend(w1, girthAt, points);
  strip.segmentEnd = v1;
  strip.segmentEndW = w1;

  for (const StripPoint& p : points) {
    if (p.v >= w1) {
      strip.pending.push_back(p);
      continue;
    }
    if (p.v < w0) continue;
    const std::size_t r = stripAt(p.v);
    if (!(w[r] > w[r - 1])) continue;
    visitor.pointTested();
    const float t = static_cast<float>(std::clamp((p.v - w[r - 1]) / (w[r] - w[r - 1]), 0.0, 1.0));
    AttachmentPoint candidate;
    candidate.s = static_cast<float>(p.s);
    candidate.tau = (1.0f - t) * unfolding.tau(r - 1) + t * unfolding.tau(r);
    candidate.random =
        PlacementRandom(placementKey(key, placementKey(static_cast<std::uint64_t>(p.row),
                                                       static_cast<std::uint64_t>(p.column))));
    if (!visitor.keep(candidate)) continue;
    faces.place(r, t, candidate.s, candidate, visitor);
  }
}

// Open contours (and patterns other than the diffusion texture): the tile repeated over the
// unfolded segment. Where the girth is below the largest, or the density below the largest,
// the organ thins the points (AttachmentPoint::girthRatio) so that the expected count is
// density × area everywhere.
void SurfaceSampler::sampleTiles(const SegmentUnfolding& unfolding, const Faces& faces,
                                 SurfaceFace face, float maxDensity, std::uint64_t key,
                                 AttachmentVisitor& visitor) const {
  const CylinderSegment& seg = unfolding.segment();
  const std::size_t rings = unfolding.rings();
  const float maxGirth = unfolding.maxGirth();
  const float tileArea = static_cast<float>(points_.size()) / maxDensity;
  const float tileSide = std::sqrt(tileArea);
  // Tiles around the girth: a whole number on closed contours (the tile stretched to fit).
  const float tilesAround =
      seg.closed ? std::max(1.0f, std::ceil(maxGirth / tileSide - 1e-3f)) : maxGirth / tileSide;
  const float tileWidth = maxGirth / tilesAround;  // at the widest girth
  const float tileHeight = tileArea / tileWidth;
  // The back uses the tile shifted by half, so its points are not the front's.
  const float shift = face == SurfaceFace::Back ? 0.5f : 0.0f;
  const int height = rows_;
  const auto& points = points_;

  for (std::size_t k = 1; k < rings; ++k) {
    const float v0 = unfolding.v(k - 1), v1 = unfolding.v(k);
    if (!(v1 > v0)) continue;
    const float tau0 = unfolding.tau(k - 1), tau1 = unfolding.tau(k);
    const float tv0 = v0 / tileHeight - shift, tv1 = v1 / tileHeight - shift;
    visitor.expectPoints(
        (static_cast<double>(tv1) - tv0 + 1.0) *
        (height + static_cast<double>(points.size()) * (static_cast<double>(tilesAround) + 1.0)));
    // Tile rows in [tv0, tv1), tile by tile.
    const long firstRow = static_cast<long>(std::floor(tv0 * height));
    const long lastRow = static_cast<long>(std::floor(tv1 * height));
    for (long row = firstRow; row <= lastRow; ++row) {
      const long tileRow = row >= 0 ? row / height : -((-row + height - 1) / height);
      const int r = static_cast<int>(row - tileRow * height);
      for (std::uint32_t p = rowStart_[static_cast<std::size_t>(r)];
           p < rowStart_[static_cast<std::size_t>(r) + 1]; ++p) {
        const TexturePoint& point = points[p];
        const float tv = static_cast<float>(tileRow) + static_cast<float>(point.v);
        if (tv < tv0 || tv >= tv1) continue;
        const float t = (tv - tv0) / (tv1 - tv0);
        const float g = (1.0f - t) * unfolding.girth(k - 1) + t * unfolding.girth(k);
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
          visitor.pointTested();
          AttachmentPoint candidate;
          candidate.s = s;
          candidate.tau = tau;
          candidate.girthRatio = seg.closed ? g / maxGirth : 1.0f;
          candidate.random = PlacementRandom(placementKey(
              key, placementKey(
                       static_cast<std::uint64_t>(row) * 65536u + k,
                       static_cast<std::uint64_t>(p) * 4096u + static_cast<std::uint64_t>(tile))));
          if (!visitor.keep(candidate)) continue;
          faces.place(k, t, s, candidate, visitor);
        }
      }
    }
  }
}

void SurfaceSampler::samplePatch(const PatchUnfolding& unfolding, SurfaceFace face,
                                 float maxDensity, std::uint64_t key,
                                 AttachmentVisitor& visitor) const {
  const float maxRatio = unfolding.maxAreaRatio();
  if (!(maxDensity > 0.0f) || !(maxRatio > 0.0f) || points_.empty()) return;
  const double tileSide =
      std::sqrt(static_cast<double>(points_.size()) / (static_cast<double>(maxDensity) * maxRatio));
  const float flip = face == SurfaceFace::Back ? -1.0f : 1.0f;
  // The back uses the tile shifted by half, so its points are not the front's.
  const double shift = face == SurfaceFace::Back ? 0.5 : 0.0;
  const int height = rows_;
  for (std::size_t i = 0; i < unfolding.triangles(); ++i) {
    const float ratio = unfolding.areaRatio(i);
    if (!(ratio > 0.0f)) continue;
    std::uint32_t vertex[3];
    glm::dvec2 tile[3];
    glm::vec2 where[3];
    CornerVectors corner[3];
    float twist[3];
    const glm::vec3 h = unfolding.heightVector(i);
    for (int c = 0; c < 3; ++c) {
      vertex[c] = unfolding.corner(i, c);
      tile[c] = glm::dvec2(unfolding.plane(vertex[c])) / tileSide - shift;
      where[c] = unfolding.normalized(vertex[c]);
      const glm::vec3 n = normalizedOr(flip * unfolding.normal(vertex[c]), anyPerpendicular(h));
      const CornerAngles angles = visitor.cornerAngles(where[c].x, where[c].y);
      corner[c] = reorient(n, h, angles.incline, angles.wrap);
      twist[c] = angles.twist;
    }
    const glm::dvec2 low = glm::min(tile[0], glm::min(tile[1], tile[2]));
    const glm::dvec2 high = glm::max(tile[0], glm::max(tile[1], tile[2]));
    const glm::dvec2 e1 = tile[1] - tile[0], e2 = tile[2] - tile[0];
    const double det = e1.x * e2.y - e1.y * e2.x;
    if (det == 0.0) continue;
    visitor.expectPoints((high.x - low.x + 1.0) * (high.y - low.y + 1.0) *
                             static_cast<double>(points_.size()) +
                         (high.y - low.y + 1.0) * height);
    const long firstRow = static_cast<long>(std::floor(low.y * height));
    const long lastRow = static_cast<long>(std::floor(high.y * height));
    const long firstColumn = static_cast<long>(std::floor(low.x));
    const long lastColumn = static_cast<long>(std::floor(high.x));
    for (long row = firstRow; row <= lastRow; ++row) {
      const long tileRow = row >= 0 ? row / height : -((-row + height - 1) / height);
      const int r = static_cast<int>(row - tileRow * height);
      for (std::uint32_t p = rowStart_[static_cast<std::size_t>(r)];
           p < rowStart_[static_cast<std::size_t>(r) + 1]; ++p) {
        const TexturePoint& point = points_[p];
        const double v = static_cast<double>(tileRow) + point.v;
        if (v < low.y || v > high.y) continue;
        for (long column = firstColumn; column <= lastColumn; ++column) {
          const double u = static_cast<double>(column) + point.u;
          if (u < low.x || u > high.x) continue;
          // Barycentric coordinates in the triangle's (U, V).
          const glm::dvec2 d = glm::dvec2(u, v) - tile[0];
          const double b1 = (d.x * e2.y - d.y * e2.x) / det;
          const double b2 = (e1.x * d.y - e1.y * d.x) / det;
          const double b0 = 1.0 - b1 - b2;
          if (b0 < 0.0 || b1 < 0.0 || b2 < 0.0) continue;
          visitor.pointTested();
          const float w[3] = {static_cast<float>(b0), static_cast<float>(b1),
                              static_cast<float>(b2)};
          AttachmentPoint candidate;
          const glm::vec2 at = w[0] * where[0] + w[1] * where[1] + w[2] * where[2];
          candidate.s = at.x;
          candidate.tau = at.y;
          candidate.girthRatio = ratio / maxRatio;
          candidate.random = PlacementRandom(
              placementKey(key, placementKey(static_cast<std::uint64_t>(row),
                                             static_cast<std::uint64_t>(p) * 65536u +
                                                 static_cast<std::uint64_t>(column))));
          if (!visitor.keep(candidate)) continue;
          AttachmentFrame frame;
          for (int c = 0; c < 3; ++c) {
            frame.position += w[c] * unfolding.position(vertex[c]);
            frame.direction += w[c] * corner[c].direction;
            frame.across += w[c] * corner[c].across;
            frame.twist += w[c] * twist[c];
          }
          visitor.place(candidate, frame);
        }
      }
    }
  }
}

void SurfaceSampler::sampleMesh(const PatchUnfolding& unfolding, SurfaceFace face,
                                 float maxDensity, std::uint64_t key,
                                 AttachmentVisitor& visitor) {
  if (!(maxDensity > 0.0f)) return;
  const double expected = static_cast<double>(maxDensity) * unfolding.area();
  visitor.expectPoints(expected);
  if (!(expected >= 0.5) || !std::isfinite(expected)) return;
  if (expected > static_cast<double>(kMaxMeshPoints)) {
    throw SamplingLimitError(fmt::format(
        "a mesh surface would take {:.0f} points on one side at its peak density, more than the "
        "{} a mesh side may have (lower the density)",
        expected, kMaxMeshPoints));
  }
  const float flip = face == SurfaceFace::Back ? -1.0f : 1.0f;
  const std::vector<SurfaceSample> samples =
      sampleSurfaceArea(unfolding, static_cast<std::size_t>(std::llround(expected)),
                        placementKey(key, face == SurfaceFace::Back ? 2u : 1u));
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const SurfaceSample& sample = samples[k];
    const OrganSurface& record = unfolding.surface();
    const float w[3] = {1.0f - sample.b1 - sample.b2, sample.b1, sample.b2};
    // The flow: the view file's direction where it gives one, else where v grows.
    glm::vec3 h = unfolding.heightVector(sample.triangle);
    if (!record.flow.empty()) {
      h = glm::vec3(0.0f);
      for (int c = 0; c < 3; ++c) h += w[c] * record.flow[unfolding.corner(sample.triangle, c)];
    }
    AttachmentPoint candidate;
    glm::vec2 at(0.0f);
    std::uint32_t vertex[3];
    for (int c = 0; c < 3; ++c) {
      vertex[c] = unfolding.corner(sample.triangle, c);
      at += w[c] * unfolding.normalized(vertex[c]);
    }
    candidate.s = at.x;
    candidate.tau = at.y;
    candidate.girthRatio = 1.0f;
    if (!record.blend.empty()) {
      candidate.blend = 0.0f;
      for (int c = 0; c < 3; ++c) candidate.blend += w[c] * record.blend[vertex[c]];
    }
    candidate.random = PlacementRandom(placementKey(key, k));
    visitor.pointTested();
    if (!visitor.keep(candidate)) continue;
    AttachmentFrame frame;
    for (int c = 0; c < 3; ++c) {
      const glm::vec2 where = unfolding.normalized(vertex[c]);
      const CornerAngles angles = visitor.cornerAngles(where.x, where.y);
      const glm::vec3 n = normalizedOr(flip * unfolding.normal(vertex[c]), anyPerpendicular(h));
      const CornerVectors corner = reorient(n, normalizedOr(h, anyPerpendicular(n)),
                                            angles.incline, angles.wrap);
      frame.position += w[c] * unfolding.position(vertex[c]);
      frame.direction += w[c] * corner.direction;
      frame.across += w[c] * corner.across;
      frame.twist += w[c] * angles.twist;
    }
    visitor.place(candidate, frame);
  }
}

// An edge has no area: points lie as densely as along a line through the surface pattern of
// the same density.
void SurfaceSampler::sampleEdge(const SegmentUnfolding& unfolding, int which, float maxDensity,
                                std::uint64_t key, AttachmentVisitor& visitor) {
  if (!(maxDensity > 0.0f)) return;
  const CylinderSegment& seg = unfolding.segment();
  const float maxLinear = std::sqrt(maxDensity);
  const int j = which == 0 ? 0 : seg.sides;
  const int inner = which == 0 ? 1 : seg.sides - 1;
  const float s = which == 0 ? 0.0f : 1.0f;
  for (std::size_t k = 1; k < unfolding.rings(); ++k) {
    const float v0 = unfolding.v(k - 1), v1 = unfolding.v(k);
    if (!(v1 > v0)) continue;
    const float tau0 = unfolding.tau(k - 1), tau1 = unfolding.tau(k);
    const glm::vec3 h = normalizedOr(unfolding.position(k, j) - unfolding.position(k - 1, j),
                                     glm::vec3(seg.rings[k].frame.heading));
    CornerVectors corner[2];
    float twist[2];
    for (int r = 0; r < 2; ++r) {
      const std::size_t kk = k - 1 + static_cast<std::size_t>(r);
      const float tau = r == 0 ? tau0 : tau1;
      const glm::vec3 n = normalizedOr(unfolding.normal(kk, j), glm::vec3(seg.rings[kk].frame.up));
      glm::vec3 e = normalizedOr(glm::cross(h, n), anyPerpendicular(h));
      if (glm::dot(e, unfolding.position(kk, j) - unfolding.position(kk, inner)) < 0.0f) e = -e;
      const CornerAngles angles = visitor.cornerAngles(s, tau);
      corner[r] = reorient(e, h, angles.incline, angles.wrap);
      twist[r] = angles.twist;
    }
    visitor.expectPoints((static_cast<double>(v1) - v0) * maxLinear + 1.0);
    const long first = static_cast<long>(std::floor(v0 * maxLinear));
    const long last = static_cast<long>(std::floor(v1 * maxLinear));
    for (long slot = first; slot <= last; ++slot) {
      visitor.pointTested();
      AttachmentPoint candidate;
      candidate.random = PlacementRandom(placementKey(key, static_cast<std::uint64_t>(slot)));
      const float v =
          (static_cast<float>(slot) + 0.5f + 0.35f * candidate.random.symmetric()) / maxLinear;
      if (v < v0 || v >= v1) continue;
      const float t = (v - v0) / (v1 - v0);
      candidate.s = s;
      candidate.tau = (1.0f - t) * tau0 + t * tau1;
      candidate.edge = true;
      if (!visitor.keep(candidate)) continue;
      AttachmentFrame frame;
      frame.position = (1.0f - t) * unfolding.position(k - 1, j) + t * unfolding.position(k, j);
      frame.direction = (1.0f - t) * corner[0].direction + t * corner[1].direction;
      frame.across = (1.0f - t) * corner[0].across + t * corner[1].across;
      frame.twist = (1.0f - t) * twist[0] + t * twist[1];
      visitor.place(candidate, frame);
    }
  }
}

}  // namespace hirsute
