#include "hirsute/viewer/trace/denoise.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace hirsute::trace {
namespace {

// A pair whose distance passes this has a weight under 1e-7: left out.
constexpr float kFarApart = 16;
// The least variance a feature's distance is measured against, so that two noiseless, smooth
// features still tolerate rounding and the shading of one surface.
constexpr float kFeatureFloor = 1e-3f;
// The colour distance's guard against dividing by a noise of zero.
constexpr float kColourFloor = 1e-10f;

float mean3(const glm::vec3& v) {
  return (v.x + v.y + v.z) / 3;
}

// A feature of the picture and, a pixel at a time, what a difference of it is measured
// against: its variance (at least the floor), and its squared gradient, which a smooth surface's
// feature follows away from the pixel (so that a sphere's normals count as alike across the
// window, and an edge's jump does not).
struct Feature {
  const std::vector<glm::vec3>* value;
  const std::vector<glm::vec3>* variance;
  std::vector<glm::vec3> floor;     // max(floor, variance)
  std::vector<glm::vec3> gradient;  // its squared length
  float k2;
};

Feature featureOf(const std::vector<glm::vec3>& value, const std::vector<glm::vec3>& variance,
                  int width, int height, float k) {
  Feature f{&value, &variance, std::vector<glm::vec3>(value.size()),
            std::vector<glm::vec3>(value.size()), k * k};
  auto at = [&](int x, int y) {
    x = std::clamp(x, 0, width - 1);
    y = std::clamp(y, 0, height - 1);
    return value[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(x)];
  };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec3 dx = (at(x + 1, y) - at(x - 1, y)) / 2.0f;
      const glm::vec3 dy = (at(x, y + 1) - at(x, y - 1)) / 2.0f;
      const std::size_t p =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      f.floor[p] = glm::max(glm::vec3(kFeatureFloor), variance[p]);
      f.gradient[p] = dx * dx + dy * dy;
    }
  }
  return f;
}

// How much farther apart two pixels' features are than their noise and p's gradient explain,
// the gradient's share growing with the `reach` between them (the offset's length: its square,
// a straight continuation of the gradient, filtered a sphere's shading half as well on the
// tests' sky-lit sphere, and the gradient itself alone a third less on the plants measured in
// docs/trace.md). ≤ 0: no farther.
float featureDistance(const Feature& f, std::size_t p, std::size_t q, float reach) {
  const glm::vec3 difference = (*f.value)[p] - (*f.value)[q];
  const glm::vec3& vp = (*f.variance)[p];
  const glm::vec3 noise = vp + glm::min(vp, (*f.variance)[q]);
  const glm::vec3 scale = f.k2 * glm::max(f.floor[p], reach * f.gradient[p]);
  return mean3((difference * difference - noise) / scale);
}

// A share of the window's offsets and the sums of their weights and weighted colours. The
// offsets are dealt to a fixed number of lanes, whichever thread runs one, and the lanes' sums
// are added in order: the picture is the same on any number of threads.
struct Lane {
  std::vector<float> weights;
  std::vector<glm::vec3> sums;
};
constexpr std::size_t kLanes = 8;

// The filter's work for one offset, with the scratch buffers of the thread that runs it.
class Filter {
 public:
  Filter(const NoisyImage& image, const std::vector<glm::vec3>& variance,
         const DenoiseOptions& options, const Feature& albedo, const Feature& normal)
      : image_(image),
        variance_(variance),
        options_(options),
        albedo_(albedo),
        normal_(normal),
        distance_(image.colour.size()),
        rows_(image.colour.size()),
        column_(static_cast<std::size_t>(image.width)) {}

  void add(int dx, int dy, Lane& lane) {
    const int w = image_.width, h = image_.height;
    // The pixels p whose partner q = p + (dx, dy) lies in the picture.
    const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
    const int y0 = std::max(0, -dy), y1 = std::min(h, h - dy);
    if (x0 >= x1 || y0 >= y1) return;
    const float k2 = options_.colourScale * options_.colourScale;
    const float reach = std::sqrt(static_cast<float>(std::max(1, dx * dx + dy * dy)));
    auto index = [w](int x, int y) {
      return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
    };
    // Per pixel: how much farther apart p's and q's colours are than their noise explains.
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        const std::size_t p = index(x, y), q = index(x + dx, y + dy);
        const glm::vec3 difference = image_.colour[p] - image_.colour[q];
        const glm::vec3& vp = variance_[p];
        const glm::vec3& vq = variance_[q];
        const glm::vec3 cancelled = difference * difference - (vp + glm::min(vp, vq));
        distance_[p] = mean3(cancelled / (kColourFloor + k2 * (vp + vq)));
      }
    }
    // Their mean over the patch (as much of it as lies where q does too): running sums along
    // the rows, then down the columns.
    const int f = options_.patch;
    for (int y = y0; y < y1; ++y) {
      float sum = 0;
      for (int x = x0; x < std::min(x1, x0 + f); ++x) sum += distance_[index(x, y)];
      for (int x = x0; x < x1; ++x) {
        if (x + f < x1) sum += distance_[index(x + f, y)];
        if (x - f - 1 >= x0) sum -= distance_[index(x - f - 1, y)];
        rows_[index(x, y)] = sum;
      }
    }
    std::fill(column_.begin(), column_.end(), 0.0f);
    for (int y = y0; y < std::min(y1, y0 + f); ++y) {
      for (int x = x0; x < x1; ++x) column_[static_cast<std::size_t>(x)] += rows_[index(x, y)];
    }
    for (int y = y0; y < y1; ++y) {
      const int below = y + f, above = y - f - 1;
      for (int x = x0; x < x1; ++x) {
        float& sum = column_[static_cast<std::size_t>(x)];
        if (below < y1) sum += rows_[index(x, below)];
        if (above >= y0) sum -= rows_[index(x, above)];
      }
      const int spanY = std::min(y1 - 1, y + f) - std::max(y0, y - f) + 1;
      for (int x = x0; x < x1; ++x) {
        const int spanX = std::min(x1 - 1, x + f) - std::max(x0, x - f) + 1;
        const float patch = column_[static_cast<std::size_t>(x)] / static_cast<float>(spanX * spanY);
        const std::size_t p = index(x, y), q = index(x + dx, y + dy);
        if (exact(p)) continue;
        const float apart = std::max({patch, featureDistance(albedo_, p, q, reach),
                                      featureDistance(normal_, p, q, reach), 0.0f});
        if (apart >= kFarApart) continue;
        const float weight = std::exp(-apart);
        lane.weights[p] += weight;
        lane.sums[p] += weight * image_.colour[q];
      }
    }
  }

 private:
  bool exact(std::size_t p) const { return variance_[p] == glm::vec3(0.0f); }

  const NoisyImage& image_;
  const std::vector<glm::vec3>& variance_;
  const DenoiseOptions& options_;
  const Feature& albedo_;
  const Feature& normal_;
  std::vector<float> distance_, rows_, column_;
};

// The colours' variances as the filter takes them. A pixel whose samples all agree among
// neighbours that are noisy is a hole in a sparse fuzz (every sample missed the hairs, or hit
// them): it is taken to be as noisy as those neighbours, on average, so that it is filtered with
// them instead of standing out as a dot. One whose neighbours agree too (the background) keeps
// no noise, and so its value.
std::vector<glm::vec3> colourVarianceOf(const NoisyImage& image) {
  std::vector<glm::vec3> variance = image.colourVariance;
  const int w = image.width, h = image.height;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                            static_cast<std::size_t>(x);
      if (image.colourVariance[p] != glm::vec3(0.0f)) continue;
      glm::vec3 sum(0.0f);
      int noisy = 0;
      for (int v = std::max(0, y - 1); v <= std::min(h - 1, y + 1); ++v) {
        for (int u = std::max(0, x - 1); u <= std::min(w - 1, x + 1); ++u) {
          const glm::vec3& n = image.colourVariance[static_cast<std::size_t>(v) *
                                                        static_cast<std::size_t>(w) +
                                                    static_cast<std::size_t>(u)];
          if (n == glm::vec3(0.0f)) continue;
          sum += n;
          ++noisy;
        }
      }
      if (noisy > 0) variance[p] = sum / static_cast<float>(noisy);
    }
  }
  return variance;
}

}  // namespace

std::vector<glm::vec3> denoise(const NoisyImage& image, const DenoiseOptions& options) {
  const std::size_t pixels =
      static_cast<std::size_t>(std::max(0, image.width)) * static_cast<std::size_t>(std::max(0, image.height));
  for (const auto* buffer : {&image.colour, &image.colourVariance, &image.albedo,
                             &image.albedoVariance, &image.normal, &image.normalVariance}) {
    if (buffer->size() != pixels) throw std::invalid_argument("denoise: a buffer of the wrong size");
  }
  if (pixels == 0) return {};
  if (options.window < 0 || options.patch < 0) {
    throw std::invalid_argument("denoise: the window and the patch cannot be negative");
  }
  const Feature albedo =
      featureOf(image.albedo, image.albedoVariance, image.width, image.height, options.featureScale);
  const Feature normal =
      featureOf(image.normal, image.normalVariance, image.width, image.height, options.featureScale);

  const std::vector<glm::vec3> variance = colourVarianceOf(image);

  std::vector<glm::ivec2> offsets;
  for (int dy = -options.window; dy <= options.window; ++dy) {
    for (int dx = -options.window; dx <= options.window; ++dx) offsets.emplace_back(dx, dy);
  }
  std::vector<Lane> lanes(std::min(kLanes, offsets.size()));
  for (Lane& lane : lanes) {
    lane.weights.assign(pixels, 0.0f);
    lane.sums.assign(pixels, glm::vec3(0.0f));
  }
  const int threads = std::clamp(
      options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency()),
      1, static_cast<int>(lanes.size()));
  std::atomic<std::size_t> nextLane{0};
  auto work = [&] {
    Filter filter(image, variance, options, albedo, normal);
    for (std::size_t l; (l = nextLane.fetch_add(1)) < lanes.size();) {
      for (std::size_t k = l; k < offsets.size(); k += lanes.size()) {
        filter.add(offsets[k].x, offsets[k].y, lanes[l]);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();

  std::vector<float> weights(pixels, 0.0f);
  std::vector<glm::vec3> sums(pixels, glm::vec3(0.0f));
  for (const Lane& lane : lanes) {
    for (std::size_t p = 0; p < pixels; ++p) {
      weights[p] += lane.weights[p];
      sums[p] += lane.sums[p];
    }
  }
  std::vector<glm::vec3> out(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    // A pixel whose samples all agree is kept; any other weighs itself 1, so its sum is not 0.
    out[p] = weights[p] > 0 ? sums[p] / weights[p] : image.colour[p];
  }
  return out;
}

}  // namespace hirsute::trace
