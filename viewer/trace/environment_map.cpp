#include "hirsute/viewer/trace/environment_map.h"

#include <OpenEXR/Iex.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>

#include "hirsute/core/model_folder.h"
#include "hirsute/viewer/trace/sampling.h"

namespace hirsute::trace {
namespace {

// The cumulative distribution of `count` values from `values`, normalised to end at 1 (evenly
// spaced where they sum to 0); returns their mean.
float cumulative(const float* values, int count, float* cdf) {
  cdf[0] = 0;
  for (int i = 0; i < count; ++i) cdf[i + 1] = cdf[i] + values[i] / static_cast<float>(count);
  const float mean = cdf[count];
  for (int i = 1; i <= count; ++i) {
    cdf[i] = mean > 0 ? cdf[i] / mean : static_cast<float>(i) / static_cast<float>(count);
  }
  cdf[count] = 1;
  return mean;
}

// The cell of `u` in a cumulative distribution of `count` cells, and where in it u falls.
int cellOf(const float* cdf, int count, float u, float& within) {
  const float* at = std::upper_bound(cdf, cdf + count + 1, u);
  const int cell = std::clamp(static_cast<int>(at - cdf) - 1, 0, count - 1);
  const float width = cdf[cell + 1] - cdf[cell];
  within = width > 0 ? std::clamp((u - cdf[cell]) / width, 0.0f, 1.0f) : 0.5f;
  return cell;
}

// OpenEXR reads the file from the bytes already read beneath the model's folder.
class MemoryStream final : public Imf::IStream {
 public:
  explicit MemoryStream(const std::string& bytes) : Imf::IStream("memory"), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || position_ + static_cast<std::size_t>(n) > bytes_.size()) {
      throw IEX_NAMESPACE::InputExc("the file ends early");
    }
    std::memcpy(c, bytes_.data() + position_, static_cast<std::size_t>(n));
    position_ += static_cast<std::size_t>(n);
    return position_ < bytes_.size();
  }
  std::uint64_t tellg() override { return position_; }
  void seekg(std::uint64_t position) override {
    position_ = static_cast<std::size_t>(std::min<std::uint64_t>(position, bytes_.size()));
  }
  void clear() override {}

 private:
  const std::string& bytes_;
  std::size_t position_ = 0;
};

float cleanValue(float v) {
  if (std::isnan(v) || v < 0) return 0.0f;
  return std::min(v, 65504.0f);  // half's largest: an infinity of the file stays finite
}

}  // namespace

PiecewiseConstant2D::PiecewiseConstant2D(const std::vector<float>& values, int width, int height)
    : width_(width), height_(height), values_(values) {
  conditional_.resize(static_cast<std::size_t>(height) * static_cast<std::size_t>(width + 1));
  rowSums_.resize(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
    rowSums_[static_cast<std::size_t>(y)] =
        cumulative(values_.data() + row, width,
                   conditional_.data() + static_cast<std::size_t>(y) * (width + 1));
  }
  marginal_.resize(static_cast<std::size_t>(height) + 1);
  integral_ = cumulative(rowSums_.data(), height, marginal_.data());
}

glm::vec2 PiecewiseConstant2D::sample(glm::vec2 u, float& pdf) const {
  float dy, dx;
  const int y = cellOf(marginal_.data(), height_, u.y, dy);
  const float* row = conditional_.data() + static_cast<std::size_t>(y) * (width_ + 1);
  const int x = cellOf(row, width_, u.x, dx);
  const glm::vec2 point((static_cast<float>(x) + dx) / static_cast<float>(width_),
                        (static_cast<float>(y) + dy) / static_cast<float>(height_));
  pdf = this->pdf(point);
  return point;
}

float PiecewiseConstant2D::pdf(glm::vec2 point) const {
  if (width_ == 0) return 0;
  const int x = std::clamp(static_cast<int>(point.x * static_cast<float>(width_)), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(point.y * static_cast<float>(height_)), 0, height_ - 1);
  if (!(integral_ > 0)) return 1;
  return values_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                 static_cast<std::size_t>(x)] /
         static_cast<float>(integral_);
}

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<glm::vec3> pixels,
                               const glm::vec3& up, float rotationDegrees, float scale)
    : width_(width), height_(height), pixels_(std::move(pixels)) {
  up_ = glm::normalize(up);
  // +z along the ground, or +x when up is along z; turned about up by the rotation.
  glm::vec3 front = glm::vec3(0, 0, 1) - up_.z * up_;
  if (glm::length(front) < 1e-3f) front = glm::vec3(1, 0, 0) - up_.x * up_;
  front = glm::normalize(front);
  const glm::vec3 side = glm::cross(up_, front);
  const float turn = glm::radians(rotationDegrees);
  front_ = std::cos(turn) * front + std::sin(turn) * side;
  side_ = glm::cross(up_, front_);
  for (glm::vec3& p : pixels_) p *= scale;
  // Each texel's weight: its luminance times the sine of its row's polar angle (the share of
  // the sphere the row covers). A tiny floor keeps every direction reachable, so that the
  // density is positive wherever the map is.
  std::vector<float> weights(pixels_.size());
  for (int y = 0; y < height_; ++y) {
    const float sine = std::sin(kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(height_));
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                            static_cast<std::size_t>(x);
      weights[i] = std::max(luminance(pixels_[i]), 0.0f) * sine;
    }
  }
  double mean = 0;
  for (const float w : weights) mean += w;
  mean /= std::max<std::size_t>(1, weights.size());
  for (float& w : weights) w += static_cast<float>(1e-4 * mean);
  distribution_ = PiecewiseConstant2D(weights, width_, height_);
}

glm::vec2 EnvironmentMap::pointOf(const glm::vec3& direction) const {
  const float cosTheta = std::clamp(glm::dot(direction, up_), -1.0f, 1.0f);
  const float phi = std::atan2(glm::dot(direction, side_), glm::dot(direction, front_));
  float u = phi / (2 * kPi) + 0.5f;
  if (u >= 1) u -= 1;
  return {std::clamp(u, 0.0f, 1.0f), std::acos(cosTheta) / kPi};
}

glm::vec3 EnvironmentMap::directionOf(glm::vec2 point) const {
  const float theta = kPi * point.y, phi = 2 * kPi * (point.x - 0.5f);
  const float s = std::sin(theta);
  return std::cos(theta) * up_ + s * std::cos(phi) * front_ + s * std::sin(phi) * side_;
}

glm::vec3 EnvironmentMap::radiance(const glm::vec3& direction) const {
  if (empty()) return glm::vec3(0.0f);
  const glm::vec2 p = pointOf(direction);
  const int x = std::clamp(static_cast<int>(p.x * static_cast<float>(width_)), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(p.y * static_cast<float>(height_)), 0, height_ - 1);
  return pixels_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                 static_cast<std::size_t>(x)];
}

EnvironmentSample EnvironmentMap::sample(glm::vec2 u) const {
  EnvironmentSample s;
  if (empty()) return s;
  float density;
  const glm::vec2 point = distribution_.sample(u, density);
  const float sine = std::sin(kPi * point.y);
  if (!(sine > 0) || !(density > 0)) return s;
  s.direction = directionOf(point);
  s.pdf = density / (2 * kPi * kPi * sine);
  s.radiance = radiance(s.direction);
  return s;
}

float EnvironmentMap::pdf(const glm::vec3& direction) const {
  if (empty()) return 0;
  const glm::vec2 point = pointOf(direction);
  const float sine = std::sin(kPi * point.y);
  if (!(sine > 0)) return 0;
  return distribution_.pdf(point) / (2 * kPi * kPi * sine);
}

EnvironmentImage decodeEnvironmentImage(const std::string& bytes, const std::string& name,
                                        const SourceLocation& where) {
  const std::string what = "the environment map '" + name + "'";
  EnvironmentImage image;
  try {
    MemoryStream stream(bytes);
    Imf::RgbaInputFile file(stream, 1);
    const Imath::Box2i window = file.dataWindow();
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    if (width < 1 || height < 1 || width > kMaxEnvironmentSide || height > kMaxEnvironmentSide ||
        static_cast<std::size_t>(width * height) > kMaxEnvironmentTexels) {
      throw DiagnosticError(where, what + " is " + std::to_string(width) + "x" +
                                       std::to_string(height) + " texels; at most " +
                                       std::to_string(kMaxEnvironmentSide) + " a side and " +
                                       std::to_string(kMaxEnvironmentTexels) + " in all");
    }
    Imf::Array2D<Imf::Rgba> pixels(height, width);
    file.setFrameBuffer(&pixels[0][0] - window.min.x - window.min.y * width, 1,
                        static_cast<std::size_t>(width));
    file.readPixels(window.min.y, window.max.y);
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    image.pixels.resize(static_cast<std::size_t>(width * height));
    for (long long y = 0; y < height; ++y) {
      for (long long x = 0; x < width; ++x) {
        const Imf::Rgba& p = pixels[y][x];
        image.pixels[static_cast<std::size_t>(y * width + x)] =
            glm::vec3(cleanValue(p.r), cleanValue(p.g), cleanValue(p.b));
      }
    }
  } catch (const DiagnosticError&) {
    throw;
  } catch (const std::exception& e) {
    throw DiagnosticError(where, "cannot read " + what + " as OpenEXR: " + e.what());
  }
  return image;
}

EnvironmentImage readEnvironmentImage(const std::string& folder, const std::string& name,
                                      const SourceLocation& where) {
  std::string bytes, failure;
  if (!ModelFolder(folder).read(name, bytes, failure, kMaxEnvironmentBytes)) {
    throw DiagnosticError(where, "cannot read the environment map '" + name + "': " + failure);
  }
  return decodeEnvironmentImage(bytes, name, where);
}

}  // namespace hirsute::trace
