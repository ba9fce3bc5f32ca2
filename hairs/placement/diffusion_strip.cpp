// Point diffusion along a closed tube (diffusion_strip.h): the texture's error diffusion
// (point_diffusion.cpp) over rows of square cells fitted to the girth of each row.
#include "hirsute/hairs/placement/diffusion_strip.h"

#include <algorithm>
#include <cmath>

#include "hirsute/hairs/placement/placement_random.h"
#include "hirsute/hairs/placement/point_diffusion.h"

namespace hirsute {
namespace {

using namespace pointDiffusionRule;

// Rows generated before the first point returned: enough for the diffusion values and the
// spacing test to forget that the strip began with nothing above it (the texture's run-in
// passes do the same for its first row).
constexpr int kRunInRows = 16;

// The diffusion values of a row of `from.size()` cells around the girth, carried onto `cells`
// cells around it: each new cell takes the share of every old cell it overlaps, so the total,
// the error still owed to the next points, is kept exactly (a conservative remap).
void remapAroundGirth(const std::vector<double>& from, std::size_t cells, std::vector<double>& to) {
  to.assign(cells, 0.0);
  if (from.empty()) return;
  // Both rows in whole units of 1 / (old · new) of the girth: new cell i is [i·old, (i+1)·old),
  // old cell j is [j·new, (j+1)·new); exact, and without a division in the sweep. Cell counts
  // stay under 10⁹ (generateRow), so the units fit 64 bits.
  const std::uint64_t oldCells = from.size(), newCells = cells;
  const double share = 1.0 / static_cast<double>(newCells);  // of an old cell, per unit
  std::size_t i = 0, j = 0;
  std::uint64_t at = 0;
  while (i < cells && j < from.size()) {
    const std::uint64_t newEnd = (i + 1) * oldCells, oldEnd = (j + 1) * newCells;
    const std::uint64_t end = std::min(newEnd, oldEnd);
    to[i] += from[j] * static_cast<double>(end - at) * share;
    at = end;
    if (newEnd == end) ++i;
    if (oldEnd == end) ++j;
  }
}

}  // namespace

DiffusionStrip::DiffusionStrip(double fill, double density, std::uint64_t seed, double vStart,
                               const GirthAt& girthAtStart)
    : fill_(fill), vStart_(vStart), nextV_(vStart), random_(mixBits(seed)) {
  setDensity(density);
  nextV_ = vStart - kRunInRows * cell_;
  // A point of the row j rows back lies more than (j − 1) cells below any point of this row;
  // the spacing is the same number of cells at every density.
  rows_.resize(static_cast<std::size_t>(std::floor(minDistance_ / cell_)) + 2);
  const double girth = girthAtStart(vStart);
  for (int r = 0; r < kRunInRows; ++r) generateRow(girth, nullptr);
}

void DiffusionStrip::setDensity(double density) {
  density_ = density;
  cell_ = std::sqrt(fill_ / density);
  // Lagae & Dutré 2008: r_max for `density` points per unit area is sqrt(1 / (2·sqrt(3)·d)).
  minDistance_ = kSpacing * 2.0 * std::sqrt(1.0 / (2.0 * std::sqrt(3.0) * density));
}

void DiffusionStrip::extend(double vEnd, const GirthAt& girthAt, std::vector<StripPoint>& points) {
  while (nextV_ < vEnd) generateRow(girthAt(nextV_ + 0.5 * cell_), &points);
}

// The texture's minimum-spacing test in world distances on the unrolled surface, wrapping
// around the girth, against the points of the rows it reaches (the current one included).
bool DiffusionStrip::farFromPlacedPoints(double s, double v, double girth) {
  const double limit = minDistance_ * minDistance_;
  const double reach = girth > 0.0 ? minDistance_ / girth : 1.0;  // in fractions of the girth
  auto close = [&](const Row& row, std::size_t i) {
    double ds = row.s[i] - s;
    // The shorter way around the girth.
    if (ds > 0.5) {
      ds -= 1.0;
    } else if (ds < -0.5) {
      ds += 1.0;
    }
    const double du = ds * girth;
    const double dv = row.v[i] - v;
    return du * du + dv * dv < limit;
  };
  const std::size_t count = rows_.size();
  // The current row first: the point just before is where a close one most often lies.
  for (std::size_t back = 0; back < count && static_cast<long>(back) <= row_; ++back) {
    Row& row = rows_[static_cast<std::size_t>(row_ - static_cast<long>(back)) % count];
    const std::size_t n = row.s.size();
    if (n == 0) continue;
    if (reach >= 0.5) {
      for (std::size_t i = 0; i < n; ++i) {
        if (close(row, i)) return false;
      }
      continue;
    }
    const double low = s - reach, high = s + reach;
    if (back == 0) {
      // Every point of the current row lies before s.
      for (std::size_t i = n; i-- > 0 && row.s[i] >= low;) {
        if (close(row, i)) return false;
      }
    } else {
      while (row.cursor < n && row.s[row.cursor] < low) ++row.cursor;
      for (std::size_t i = row.cursor; i < n && row.s[i] <= high; ++i) {
        if (close(row, i)) return false;
      }
    }
    // Across the girth seam: the row's last points for a point near its start, its first points
    // for a point near its end.
    if (low < 0.0) {
      for (std::size_t i = n; i-- > 0 && row.s[i] >= low + 1.0;) {
        if (close(row, i)) return false;
      }
    }
    if (high > 1.0) {
      for (std::size_t i = 0; i < n && row.s[i] <= high - 1.0; ++i) {
        if (close(row, i)) return false;
      }
    }
  }
  return true;
}

// One row: the texture's gather (Fuhrer et al. 2004, Sec. 3.1: one left and three upper
// neighbours), the upper neighbours read from the row above carried onto this row's cells. The
// left neighbour of the first cell is the last cell of the row above (the texture's helix), read
// as it was, so every cell hands its whole value on and the count holds.
void DiffusionStrip::generateRow(double girth, std::vector<StripPoint>* points) {
  const double around = girth > 0.0 ? girth / cell_ : 0.0;
  const std::size_t cells = static_cast<std::size_t>(std::clamp(std::round(around), 1.0, 1e9));
  const double cellFill =
      density_ * (girth > 0.0 ? girth : 0.0) / static_cast<double>(cells) * cell_;
  const double lastAbove = diffusion_.empty() ? 0.0 : diffusion_.back();
  if (diffusion_.size() == cells) {
    upper_.swap(diffusion_);  // the same cells: the row above as it is
  } else {
    remapAroundGirth(diffusion_, cells, upper_);
  }
  diffusion_.resize(cells);  // every cell is written below
  for (Row& r : rows_) r.cursor = 0;
  Row& row = rows_[static_cast<std::size_t>(row_) % rows_.size()];
  row.s.clear();
  row.v.clear();
  const double rowStart = nextV_;
  // The threshold is never below this: a value under it places nothing and draws no number.
  constexpr double kLowestThreshold = 0.5 - 0.5 * kThresholdSpread;
  double left = lastAbove;
  for (std::size_t x = 0; x < cells; ++x) {
    const std::size_t upLeft = x == 0 ? cells - 1 : x - 1;
    const std::size_t upRight = x + 1 == cells ? 0 : x + 1;
    const double value = cellFill + kWeightLeft * left + kWeightUpperLeft * upper_[upLeft] +
                         kWeightUpper * upper_[x] + kWeightUpperRight * upper_[upRight];
    left = value;
    diffusion_[x] = value;
    if (value < kLowestThreshold) continue;
    const double threshold = 0.5 + kThresholdSpread * (unit() - 0.5);
    if (value < threshold) continue;
    const double s =
        (static_cast<double>(x) + 0.5 + kJitter * (unit() - 0.5)) / static_cast<double>(cells);
    const double v = rowStart + (0.5 + kJitter * (unit() - 0.5)) * cell_;
    if (!farFromPlacedPoints(s, v, girth)) continue;
    left = value - 1.0;
    diffusion_[x] = left;
    row.s.push_back(s);
    row.v.push_back(v);
    if (points != nullptr && v >= vStart_) {
      points->push_back({s, v, row_, static_cast<int>(x)});
    }
  }
  ++row_;
  nextV_ = rowStart + cell_;
}

}  // namespace hirsute
