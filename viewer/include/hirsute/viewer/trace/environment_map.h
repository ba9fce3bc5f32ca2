// The sky as a picture: an HDR latitude-longitude map of the radiance arriving from every
// direction (an OpenEXR file of the model's, `trace environment:`, or the physical sky of
// sky_model.h made into one), lighting the plant from all around and seen behind it.
//
// The map's top row looks along `trace up:`, its bottom row straight down; its middle column
// looks along +z (the default view's eye side) turned about up by the view file's rotation, a
// quarter of the way to its right end along up × +z (+x for the default up).
//
// Directions are sampled in proportion to the map's radiance (pbrt-v4's image infinite light):
// a piecewise-constant density over the map's texels, each weighted by its luminance times
// sin θ (the solid angle a texel's row covers), drawn as a row by the rows' marginal density,
// then a texel by that row's conditional one. The density in solid angle of a direction is that
// of its texel divided by 2π² sin θ. The integrator combines this sampling with the materials'
// by multiple importance sampling.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute::trace {

// A piecewise-constant density over [0, 1)², from non-negative cell values `values` (row-major,
// `width` × `height`), proportional to them; uniform where every value is 0.
class PiecewiseConstant2D {
 public:
  PiecewiseConstant2D() = default;
  PiecewiseConstant2D(const std::vector<float>& values, int width, int height);

  // A point with its density over the unit square.
  glm::vec2 sample(glm::vec2 u, float& pdf) const;
  float pdf(glm::vec2 point) const;
  // The integral of the values over the unit square (their mean).
  double integral() const { return integral_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<float> conditional_;  // per row, its cumulative distribution (width + 1 entries)
  std::vector<float> rowSums_;      // each row's mean
  std::vector<float> marginal_;     // the rows' cumulative distribution (height + 1 entries)
  std::vector<float> values_;
  double integral_ = 0;
};

struct EnvironmentSample {
  glm::vec3 direction{0.0f};
  glm::vec3 radiance{0.0f};
  float pdf = 0;  // in solid angle
};

class EnvironmentMap {
 public:
  EnvironmentMap() = default;
  // `pixels`: linear RGB radiance, row 0 at the top; `scale` multiplies it; `rotation` turns
  // the map about `up` (degrees).
  EnvironmentMap(int width, int height, std::vector<glm::vec3> pixels, const glm::vec3& up,
                 float rotationDegrees = 0, float scale = 1);

  bool empty() const { return width_ == 0; }
  int width() const { return width_; }
  int height() const { return height_; }
  glm::vec3 radiance(const glm::vec3& direction) const;
  EnvironmentSample sample(glm::vec2 u) const;
  float pdf(const glm::vec3& direction) const;

  // The map's point (u across, v down, each in [0, 1)) that looks along `direction`, and back.
  glm::vec2 pointOf(const glm::vec3& direction) const;
  glm::vec3 directionOf(glm::vec2 point) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<glm::vec3> pixels_;
  glm::vec3 up_{0, 1, 0}, front_{0, 0, 1}, side_{1, 0, 0};
  PiecewiseConstant2D distribution_;
};

// What an environment map file may hold: a side of at most kMaxEnvironmentSide texels,
// kMaxEnvironmentTexels in all (some 600 MB while it is decoded, its floats and its sampling
// tables), and a file of at most kMaxEnvironmentBytes.
inline constexpr int kMaxEnvironmentSide = 16384;
inline constexpr std::size_t kMaxEnvironmentTexels = std::size_t{1} << 24;
inline constexpr std::size_t kMaxEnvironmentBytes = std::size_t{512} << 20;

struct EnvironmentImage {
  int width = 0, height = 0;
  std::vector<glm::vec3> pixels;  // linear RGB, row 0 at the top
};

// Decodes an OpenEXR file's RGB (a missing channel reads as 0, a luminance-only file as grey;
// negative values and values that are no number as 0, infinities as half's largest). Throws
// DiagnosticError at `where`, naming `name`, when the bytes are no OpenEXR file it can read or
// the picture exceeds the limits above.
EnvironmentImage decodeEnvironmentImage(const std::string& bytes, const std::string& name,
                                        const SourceLocation& where);

// Reads `name` beneath `folder` (model_folder.h: no name that leaves it, regular files only) and
// decodes it; errors as decodeEnvironmentImage's, and for a file that cannot be opened.
EnvironmentImage readEnvironmentImage(const std::string& folder, const std::string& name,
                                      const SourceLocation& where);

}  // namespace hirsute::trace
