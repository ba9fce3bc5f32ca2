// Mitchell's point-diffusion texture τ(u,v) → {0,1}: the attachment points of hairs
// (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3.1; DESIGN.md, "Plant hairs").
//
// An error-diffusion pass over a width × height grid whose input is the fill (points per cell)
// everywhere. Each cell gathers diffusion values from one left and three upper neighbours, all
// read toroidally, so the texture tiles seamlessly around the girth (u) and along the axis (v).
// Quality is measured (tests/hairs/point_diffusion_test.cpp, docs/hairs.md): relative radius
// ρ ≥ 0.65 for fills 0.02 to 0.3, a point count within 2% of fill·width·height, and
// nearest-neighbour distances across tile edges distributed as inside a tile.
#pragma once

#include <cstdint>
#include <vector>

#include "hirsute/hairs/placement/point_spacing.h"

namespace hirsute {

struct PointDiffusionSettings {
  int width = 100;   // cells around the girth (u)
  int height = 100;  // cells along the axis (v)
  // Points per cell. The measured range is 0.02 to 0.3; values in (0, 0.5] are accepted.
  double fill = 0.1;
  // The seed of the generator the texture owns; the same settings give the same texture.
  std::uint64_t seed = 1;
};

// One attachment point: its cell and its position in the unit tile. The position is jittered
// inside the cell (not the cell centre) because the grid would otherwise show through as rows
// and columns at the higher fills; the minimum spacing is enforced on the jittered positions,
// so the jitter costs no quality.
struct TexturePoint {
  int column = 0;
  int row = 0;
  double u = 0;  // in [column / width, (column + 1) / width)
  double v = 0;  // in [row / height, (row + 1) / height)
};

class PointDiffusionTexture {
 public:
  // Throws std::invalid_argument for a grid under 4 × 4 cells or a fill outside (0, 0.5].
  static PointDiffusionTexture generate(const PointDiffusionSettings& settings);

  int width() const { return width_; }
  int height() const { return height_; }
  // τ on the cell: true where the cell holds an attachment point.
  bool at(int column, int row) const;
  // τ(u,v) for any u, v: the texture repeats with period 1 in both.
  bool at(double u, double v) const;
  // The points in scan-line order (row by row, each row left to right).
  const std::vector<TexturePoint>& points() const { return points_; }
  std::vector<TorusPoint> positions() const;

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> cells_;
  std::vector<TexturePoint> points_;
};

}  // namespace hirsute
