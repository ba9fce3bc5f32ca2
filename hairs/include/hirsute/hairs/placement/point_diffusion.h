// Mitchell's point-diffusion texture τ(u,v) → {0,1}: the attachment points of hairs
// (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3.1; docs/design.md, "Placement").
//
// An error-diffusion pass over a width × height grid whose input is the fill (points per cell)
// everywhere. Each cell gathers diffusion values from one left and three upper neighbours, all
// read toroidally, so the texture tiles seamlessly around the girth (u) and along the axis (v).
// Quality is measured (tests/hairs/point_diffusion_test.cpp, docs/hairs.md): relative radius
// ρ ≥ 0.65 for fills 0.02 to 0.3, a point count within 2% of fill·width·height, and
// nearest-neighbour distances across tile edges distributed as inside a tile.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "hirsute/hairs/placement/point_spacing.h"

namespace hirsute {

// The error-diffusion rule, shared by the texture below and the strip along closed tubes
// (diffusion_strip.h).
namespace pointDiffusionRule {

// Diffusion weights, gathered from the neighbours already visited: left, upper-left, upper,
// upper-right. Floyd & Steinberg 1976 scatter 7/16 right, 3/16 lower-left, 5/16 down and 1/16
// lower-right; gathered, those are left 7/16, upper-right 3/16, upper 5/16, upper-left 1/16.
// Mitchell 1987 ("Generating antialiased images at low sampling densities", SIGGRAPH) found that
// plain Floyd–Steinberg leaves low densities in strings and clumps (docs/design.md: ρ ≈ 0.27 at a
// fill of 0.02) and modified the diffusion and randomised the threshold. This implementation
// keeps the Floyd–Steinberg weights and does the low-density correction with the randomised
// threshold below plus the minimum-spacing test (kSpacing); the constants were chosen by
// measuring ρ and the count over fills 0.02 to 0.3 (docs/hairs.md), not copied from the paper.
inline constexpr double kWeightLeft = 7.0 / 16.0;
inline constexpr double kWeightUpperLeft = 1.0 / 16.0;
inline constexpr double kWeightUpper = 5.0 / 16.0;
inline constexpr double kWeightUpperRight = 3.0 / 16.0;
// The threshold is 0.5 ± half this, uniformly (Mitchell 1987: a randomised threshold breaks the
// regular strings that a fixed one grows at low densities).
inline constexpr double kThresholdSpread = 0.5;
// Minimum spacing between points as a fraction of 2·r_max for the target count (Lagae & Dutré
// 2008), enforced on the jittered positions: a cell whose diffusion value passes the threshold
// but lies closer than this to a point already placed stays empty and passes its whole value
// on, so the point lands on the next cell that is free (output-dependent feedback in the manner
// of Levien 1993 and Eschbach 1993; Mitchell's threshold changes alone leave occasional close
// pairs, which is what ρ, a minimum, measures).
inline constexpr double kSpacing = 0.68;
// Fraction of a cell over which a point is jittered around the cell centre.
inline constexpr double kJitter = 1.0;
// Passes over the torus: the first two are a run-in whose diffusion values and points stand in, in
// the last pass, for the neighbours across the top and left edges that the last pass has not
// reached yet; so the first row and column see the same kind of neighbourhood as every other.
inline constexpr int kPasses = 3;

// A double in [0, 1) from the top 53 bits: the same on every platform (std's distributions are
// implementation-defined).
inline double unitDouble(std::mt19937_64& random) {
  return static_cast<double>(random() >> 11) * 0x1.0p-53;
}

}  // namespace pointDiffusionRule

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
  // The settings' fill and seed (a strip along a closed tube runs the same diffusion with them).
  double fill() const { return fill_; }
  std::uint64_t seed() const { return seed_; }
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
  double fill_ = 0;
  std::uint64_t seed_ = 0;
  std::vector<std::uint8_t> cells_;
  std::vector<TexturePoint> points_;
};

}  // namespace hirsute
