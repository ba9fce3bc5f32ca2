#include "hirsute/hairs/placement/point_diffusion.h"

#include <cmath>
#include <random>
#include <stdexcept>

namespace hirsute {

namespace {

using namespace pointDiffusionRule;

int wrapIndex(int i, int n) {
  return ((i % n) + n) % n;
}

}  // namespace

PointDiffusionTexture PointDiffusionTexture::generate(const PointDiffusionSettings& settings) {
  const int width = settings.width;
  const int height = settings.height;
  const double fill = settings.fill;
  if (width < 4 || height < 4) {
    throw std::invalid_argument("point-diffusion texture: the grid must be at least 4 x 4 cells");
  }
  if (!(fill > 0.0 && fill <= 0.5)) {
    throw std::invalid_argument("point-diffusion texture: the fill must be in (0, 0.5]");
  }
  const std::size_t cellCount = static_cast<std::size_t>(width) * height;
  std::mt19937_64 random(settings.seed);

  // Lagae & Dutré 2008: r_max for the target count on the unit torus.
  const double targetCount = fill * static_cast<double>(cellCount);
  const double rMax = std::sqrt(1.0 / (2.0 * std::sqrt(3.0) * targetCount));
  const double minDistance = kSpacing * 2.0 * rMax;
  const double minDistanceSquared = minDistance * minDistance;
  // The neighbourhood searched for close points, in cells, kept under half the torus so that no
  // cell is seen twice.
  const int reachU =
      std::min(static_cast<int>(std::ceil(minDistance * width)) + 1, (width - 1) / 2);
  const int reachV =
      std::min(static_cast<int>(std::ceil(minDistance * height)) + 1, (height - 1) / 2);

  std::vector<double> diffusion(cellCount, 0.0);
  std::vector<int> placedInPass(cellCount, 0);  // 0: no point
  std::vector<double> pointU(cellCount, 0.0);
  std::vector<double> pointV(cellCount, 0.0);

  auto farFromPlacedPoints = [&](int x, int y, double u, double v, int pass) {
    for (int dy = -reachV; dy <= reachV; ++dy) {
      const int row = wrapIndex(y + dy, height);
      for (int dx = -reachU; dx <= reachU; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const std::size_t j = static_cast<std::size_t>(row) * width + wrapIndex(x + dx, width);
        if (placedInPass[j] == 0) continue;
        // Behind the cell in scan order (above, or left in the same row) every point counts:
        // this pass's, or where the offset wraps, the previous pass's that this one has not
        // replaced yet. Ahead of it only this pass's count: those are the cells reached across
        // the bottom or right edge, which this pass made first; the rest are stale.
        const bool behind = dy < 0 || (dy == 0 && dx < 0);
        if (!behind && placedInPass[j] != pass) continue;
        double du = pointU[j] - u;
        double dv = pointV[j] - v;
        du -= std::round(du);
        dv -= std::round(dv);
        if (du * du + dv * dv < minDistanceSquared) return false;
      }
    }
    return true;
  };

  for (int pass = 1; pass <= kPasses; ++pass) {
    for (int y = 0; y < height; ++y) {
      const int up = wrapIndex(y - 1, height);
      for (int x = 0; x < width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        placedInPass[i] = 0;
        const int left = wrapIndex(x - 1, width);
        const int right = wrapIndex(x + 1, width);
        const std::size_t upRow = static_cast<std::size_t>(up) * width;
        // The left neighbour is the cell before in scan order: at the start of a row, the end of
        // the row above (a helix around the girth). Every cell then hands its whole value on to
        // cells visited after it, so a pass loses no error at the left edge and the count holds.
        const std::size_t previous = i == 0 ? cellCount - 1 : i - 1;
        // Fuhrer et al. 2004, Sec. 3.1: one left and three upper neighbours, wrapping.
        const double value =
            fill + kWeightLeft * diffusion[previous] + kWeightUpperLeft * diffusion[upRow + left] +
            kWeightUpper * diffusion[upRow + x] + kWeightUpperRight * diffusion[upRow + right];
        const double threshold = 0.5 + kThresholdSpread * (unitDouble(random) - 0.5);
        const double u = (x + 0.5 + kJitter * (unitDouble(random) - 0.5)) / width;
        const double v = (y + 0.5 + kJitter * (unitDouble(random) - 0.5)) / height;
        const bool place = value >= threshold && farFromPlacedPoints(x, y, u, v, pass);
        diffusion[i] = value - (place ? 1.0 : 0.0);
        if (place) {
          placedInPass[i] = pass;
          pointU[i] = u;
          pointV[i] = v;
        }
      }
    }
  }

  PointDiffusionTexture texture;
  texture.width_ = width;
  texture.height_ = height;
  texture.fill_ = fill;
  texture.seed_ = settings.seed;
  texture.cells_.assign(cellCount, 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      if (placedInPass[i] == 0) continue;
      texture.cells_[i] = 1;
      texture.points_.push_back({x, y, pointU[i], pointV[i]});
    }
  }
  return texture;
}

bool PointDiffusionTexture::at(int column, int row) const {
  return cells_[static_cast<std::size_t>(wrapIndex(row, height_)) * width_ +
                wrapIndex(column, width_)] != 0;
}

bool PointDiffusionTexture::at(double u, double v) const {
  const int column = static_cast<int>(std::floor((u - std::floor(u)) * width_));
  const int row = static_cast<int>(std::floor((v - std::floor(v)) * height_));
  return at(std::min(column, width_ - 1), std::min(row, height_ - 1));
}

std::vector<TorusPoint> PointDiffusionTexture::positions() const {
  std::vector<TorusPoint> result;
  result.reserve(points_.size());
  for (const TexturePoint& p : points_) result.push_back({p.u, p.v});
  return result;
}

}  // namespace hirsute
