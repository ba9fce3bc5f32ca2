// Mitchell's point diffusion made along a closed tube instead of tiled over it (docs/design.md,
// "Placement"; Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3.1). A square tile wraps around a
// closed girth only when the girth is a whole number of tile widths, so a tiled tube must
// stretch the tile (anisotropic: ρ measured on the surface falls to about 0.61 on a tube of
// radius one tile width, far lower on thin ones) and thin it where the tube tapers. The strip
// runs the same error diffusion (point_diffusion.h) in scan-line order over rows of square
// cells laid around the girth where each row lies: every row has as many cells as fit its girth,
// each row's diffusion values are carried to the next one whatever its cell count, and the
// minimum-spacing test is made in world distances on the unrolled surface, wrapping around the
// girth. So the points keep the texture's spacing on every girth and taper, the count is the
// density × area, and nothing marks the girth seam (it is a helix, as in the texture) or the
// boundaries of the segments the strip runs through.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "hirsute/hairs/placement/placement_random.h"

namespace hirsute {

// A point of the strip: s the girth position in [0, 1) (a fraction of the row's girth), v arc
// length along the axis, row and column its cell (rows counted from the strip's first, the
// run-in included).
struct StripPoint {
  double s = 0;
  double v = 0;
  long row = 0;
  int column = 0;
};

class DiffusionStrip {
 public:
  // The girth (world units) at axis position v.
  using GirthAt = std::function<double(double v)>;

  // A strip of `density` points per unit area whose cells hold `fill` points each (the texture's
  // fill: the cell side is sqrt(fill / density)); its points start at axis position vStart.
  // Rows before vStart are a run-in, generated and checked against like every row but never
  // returned, so the first returned rows see the neighbourhood every other row sees.
  DiffusionStrip(double fill, double density, std::uint64_t seed, double vStart,
                 const GirthAt& girthAtStart);

  double density() const { return density_; }
  // The density of the rows from here on (the next segment's): the cells take its size, the
  // spacing test its distance; the diffusion values carry on, so the strip continues unbroken.
  void setDensity(double density);
  // Where the next row starts: every point below it has been returned.
  double generatedTo() const { return nextV_; }

  // Generates the rows that start below vEnd, with the girth of each at its middle, and appends
  // their points at or above vStart to `points` (the last row may reach past vEnd).
  void extend(double vEnd, const GirthAt& girthAt, std::vector<StripPoint>& points);

 private:
  // The points of a row in order of s. The spacing test of the next rows walks each row's
  // points with a cursor that only moves on, since the cells of a row are tested in order of s.
  struct Row {
    std::vector<double> s, v;
    std::size_t cursor = 0;
  };
  void generateRow(double girth, std::vector<StripPoint>* points);
  bool farFromPlacedPoints(double s, double v, double girth);
  // A double in [0, 1) from the strip's own SplitMix64 sequence (the same on every platform).
  double unit() {
    random_ += 0x9e3779b97f4a7c15ull;
    return static_cast<double>(mixBits(random_) >> 11) * 0x1.0p-53;
  }

  double fill_, density_ = 0, cell_ = 0, minDistance_ = 0;
  double vStart_, nextV_;
  long row_ = 0;
  std::uint64_t random_;
  std::vector<double> diffusion_, upper_;  // the last row's values, and the row being made's
  // The rows the spacing test reaches, a ring: row r is rows_[r % rows_.size()], the newest the
  // one being made.
  std::vector<Row> rows_;
};

}  // namespace hirsute
