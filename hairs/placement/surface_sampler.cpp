// The shared placement engine: the point pattern tiled over unfolded segments and their edges
// (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3.1, 3.2 and 4.4; DESIGN.md, "Organs").
#include "hirsute/hairs/placement/surface_sampler.h"

#include <algorithm>
#include <cmath>

namespace hirsute {

SurfaceSampler::SurfaceSampler(const PointDiffusionTexture& texture)
    : SurfaceSampler(texture.points(), texture.height()) {}

SurfaceSampler::SurfaceSampler(std::vector<TexturePoint> points, int rows)
    : points_(std::move(points)), rows_(rows) {
  rowStart_.assign(static_cast<std::size_t>(rows_) + 1, 0);
  for (const TexturePoint& p : points_) ++rowStart_[static_cast<std::size_t>(p.row) + 1];
  for (std::size_t r = 1; r < rowStart_.size(); ++r) rowStart_[r] += rowStart_[r - 1];
}

// Where the girth is below the largest, or the density below the largest, the organ thins the
// points (AttachmentPoint::girthRatio) so that the expected count is density × area everywhere.
void SurfaceSampler::sampleSurface(const SegmentUnfolding& unfolding, SurfaceFace face,
                                   float maxDensity, std::uint64_t key,
                                   AttachmentVisitor& visitor) const {
  if (!(maxDensity > 0.0f)) return;
  const CylinderSegment& seg = unfolding.segment();
  const std::size_t rings = unfolding.rings();
  const std::size_t perRing = static_cast<std::size_t>(seg.sides) + 1;
  const int faces = unfolding.faces();
  const float flip = face == SurfaceFace::Back ? -1.0f : 1.0f;
  auto normal = [&](std::size_t k, int j) { return flip * unfolding.normal(k, j); };
  const float maxGirth = unfolding.maxGirth();
  if (!(maxGirth > 0.0f)) return;

  const float tileArea = static_cast<float>(points_.size()) / maxDensity;
  const float tileSide = std::sqrt(tileArea);
  // Tiles around the girth: a whole number on closed contours.
  const float tilesAround =
      seg.closed ? std::max(1.0f, std::ceil(maxGirth / tileSide - 1e-3f)) : maxGirth / tileSide;
  const float tileWidth = maxGirth / tilesAround;  // at the widest girth
  const float tileHeight = tileArea / tileWidth;
  // The back uses the tile shifted by half, so its points are not the front's.
  const float shift = face == SurfaceFace::Back ? 0.5f : 0.0f;
  const int height = rows_;
  const auto& points = points_;

  // Corner frames of ring k, column j of strip (k-1, k): the shading normal reoriented by the
  // incline and wrap at that corner; h is the face's height vector.
  std::vector<CornerVectors> corners(2 * perRing);
  std::vector<float> cornerTwist(2 * perRing);
  for (std::size_t k = 1; k < rings; ++k) {
    const float tau0 = unfolding.tau(k - 1), tau1 = unfolding.tau(k);
    const glm::vec3 axis = normalizedOr(
        seg.rings[k].frame.position - seg.rings[k - 1].frame.position, seg.rings[k].frame.heading);
    for (int j = 0; j <= faces; ++j) {
      const glm::vec3 h =
          normalizedOr(unfolding.position(k, j) - unfolding.position(k - 1, j), axis);
      for (int r = 0; r < 2; ++r) {
        const std::size_t kk = k - 1 + static_cast<std::size_t>(r);
        const float tau = r == 0 ? tau0 : tau1;
        const float s = (unfolding.fraction(k - 1, j) + unfolding.fraction(k, j)) * 0.5f;
        const glm::vec3 n = normalizedOr(normal(kk, j), flip * glm::vec3(seg.rings[kk].frame.up));
        const CornerAngles angles = visitor.cornerAngles(s, tau);
        corners[static_cast<std::size_t>(r) * perRing + static_cast<std::size_t>(j)] =
            reorient(n, h, angles.incline, angles.wrap);
        cornerTwist[static_cast<std::size_t>(r) * perRing + static_cast<std::size_t>(j)] =
            angles.twist;
      }
    }

    const float v0 = unfolding.v(k - 1), v1 = unfolding.v(k);
    if (!(v1 > v0)) continue;
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
          // Bilinear placement on the face and interpolation of the corner frames.
          const FacePoint at = unfolding.face(k, t, s);
          const int lo = at.column;
          const float a = at.a;
          const float w00 = (1 - a) * (1 - t), w01 = a * (1 - t), w10 = (1 - a) * t, w11 = a * t;
          const CornerVectors& c00 = corners[static_cast<std::size_t>(lo)];
          const CornerVectors& c01 = corners[static_cast<std::size_t>(lo + 1)];
          const CornerVectors& c10 = corners[perRing + static_cast<std::size_t>(lo)];
          const CornerVectors& c11 = corners[perRing + static_cast<std::size_t>(lo + 1)];
          AttachmentFrame frame;
          frame.position = unfolding.at(at);
          frame.direction =
              w00 * c00.direction + w01 * c01.direction + w10 * c10.direction + w11 * c11.direction;
          frame.across = w00 * c00.across + w01 * c01.across + w10 * c10.across + w11 * c11.across;
          frame.twist = w00 * cornerTwist[static_cast<std::size_t>(lo)] +
                        w01 * cornerTwist[static_cast<std::size_t>(lo + 1)] +
                        w10 * cornerTwist[perRing + static_cast<std::size_t>(lo)] +
                        w11 * cornerTwist[perRing + static_cast<std::size_t>(lo + 1)];
          visitor.place(candidate, frame);
        }
      }
    }
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
