#include "hirsute/hairs/feathers/feather_scan.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "hirsute/hairs/feathers/feather_geometry.h"

namespace hirsute {
namespace {

constexpr double kDegrees = std::numbers::pi / 180;
constexpr int kSilhouetteSamples = 41;  // barbs traced a vane, rp = 0, 0.025, …, 1
constexpr std::size_t kMaxSilhouettePoints = 12;

// A float image, row-major, row 0 at the top.
struct Plane {
  int width = 0, height = 0;
  std::vector<float> values;
  Plane() = default;
  Plane(int w, int h, float fill = 0)
      : width(w), height(h), values(static_cast<std::size_t>(w) * h, fill) {}
  float& at(int x, int y) { return values[static_cast<std::size_t>(y) * width + x]; }
  float at(int x, int y) const { return values[static_cast<std::size_t>(y) * width + x]; }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  // Bilinear, clamped at the edges.
  float sample(glm::dvec2 p) const {
    const double x = std::clamp(p.x, 0.0, width - 1.0), y = std::clamp(p.y, 0.0, height - 1.0);
    const int x0 = std::min(static_cast<int>(x), width - 2 < 0 ? 0 : width - 2);
    const int y0 = std::min(static_cast<int>(y), height - 2 < 0 ? 0 : height - 2);
    const int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
    const double fx = x - x0, fy = y - y0;
    return static_cast<float>((1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) +
                              fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1)));
  }
};

// Separable Gaussian blur of standard deviation sigma (pixels), clamped at the edges.
Plane blurred(const Plane& in, double sigma) {
  const int radius = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
  std::vector<float> kernel(2 * radius + 1);
  float sum = 0;
  for (int i = -radius; i <= radius; ++i) {
    kernel[i + radius] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)));
    sum += kernel[i + radius];
  }
  for (float& k : kernel) k /= sum;
  Plane across(in.width, in.height), out(in.width, in.height);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      float v = 0;
      for (int i = -radius; i <= radius; ++i)
        v += kernel[i + radius] * in.at(std::clamp(x + i, 0, in.width - 1), y);
      across.at(x, y) = v;
    }
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      float v = 0;
      for (int i = -radius; i <= radius; ++i)
        v += kernel[i + radius] * across.at(x, std::clamp(y + i, 0, in.height - 1));
      out.at(x, y) = v;
    }
  return out;
}

glm::vec3 pixelColour(const Texture& image, int x, int y) {
  const std::uint8_t* p = &image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)];
  return glm::vec3(p[0], p[1], p[2]);
}

bool transparent(const Texture& image, int x, int y) {
  return image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x) + 3] < 128;
}

// The background: the median of the border's pixels, channel by channel (0..255).
glm::vec3 backgroundOf(const Texture& image) {
  std::array<std::vector<float>, 3> channels;
  auto add = [&](int x, int y) {
    if (transparent(image, x, y)) return;
    const glm::vec3 c = pixelColour(image, x, y);
    for (int k = 0; k < 3; ++k) channels[k].push_back(c[k]);
  };
  for (int x = 0; x < image.width; ++x) {
    add(x, 0);
    add(x, image.height - 1);
  }
  for (int y = 1; y + 1 < image.height; ++y) {
    add(0, y);
    add(image.width - 1, y);
  }
  glm::vec3 out(255.0f);
  for (int k = 0; k < 3; ++k) {
    std::vector<float>& c = channels[k];
    if (c.empty()) continue;
    std::nth_element(c.begin(), c.begin() + c.size() / 2, c.end());
    out[k] = c[c.size() / 2];
  }
  return out;
}

// Otsu's threshold of values 0..255.
int otsu(const Plane& distance) {
  std::array<double, 256> histogram{};
  for (float v : distance.values) histogram[std::clamp(static_cast<int>(v), 0, 255)] += 1;
  const double total = static_cast<double>(distance.values.size());
  double sumAll = 0;
  for (int i = 0; i < 256; ++i) sumAll += i * histogram[i];
  double below = 0, sumBelow = 0, best = -1;
  int threshold = 0;
  for (int t = 0; t < 256; ++t) {
    below += histogram[t];
    sumBelow += t * histogram[t];
    const double above = total - below;
    if (below == 0 || above == 0) continue;
    const double meanBelow = sumBelow / below, meanAbove = (sumAll - sumBelow) / above;
    const double between = below * above * (meanBelow - meanAbove) * (meanBelow - meanAbove);
    if (between > best) {
      best = between;
      threshold = t;
    }
  }
  return threshold;
}

// The largest 8-connected region of `mask`; the others cleared.
std::size_t keepLargestRegion(std::vector<std::uint8_t>& mask, int width, int height) {
  std::vector<int> label(mask.size(), 0);
  std::vector<std::size_t> sizes{0};
  std::vector<int> stack;
  for (std::size_t start = 0; start < mask.size(); ++start) {
    if (!mask[start] || label[start] != 0) continue;
    const int id = static_cast<int>(sizes.size());
    sizes.push_back(0);
    stack.push_back(static_cast<int>(start));
    label[start] = id;
    while (!stack.empty()) {
      const int at = stack.back();
      stack.pop_back();
      ++sizes[id];
      const int x = at % width, y = at / width;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const std::size_t n = static_cast<std::size_t>(ny) * width + nx;
          if (mask[n] && label[n] == 0) {
            label[n] = id;
            stack.push_back(static_cast<int>(n));
          }
        }
    }
  }
  const auto largest = std::max_element(sizes.begin(), sizes.end()) - sizes.begin();
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = label[i] == largest && largest > 0;
  return sizes[largest];
}

// The local orientation of lines (the barbs) from the structure tensor: a unit direction along
// them (its sign arbitrary) and the coherence, 0 (no direction) to 1.
struct Orientation {
  Plane along, across, coherence;  // along = cos, across = sin of the line's angle
  glm::dvec2 at(glm::dvec2 p, double* coherent = nullptr) const {
    // The doubled angle is what averages: sample cos 2φ, sin 2φ.
    const double c2 = along.sample(p), s2 = across.sample(p);
    if (coherent) *coherent = coherence.sample(p);
    const double phi = 0.5 * std::atan2(s2, c2);
    return {std::cos(phi), std::sin(phi)};
  }
};

// The derivative along x (or y) of `in`: the ideal differentiator's taps (-1)^(n+1) / n windowed
// by a Hann window over 12 pixels each side. Its response is within 1% of the true derivative's
// up to 0.4 cycles a pixel and 0.9 of it at 0.45, alike along x and y: the barbs of a flight
// feather's narrow vane, 2 to 3 pixels apart across where they leave the rachis at 15°, keep
// their direction. A central difference (its response sin(2πf) / 2πf, 0.11 at 0.45 cycles a
// pixel across the barbs and 0.90 at 0.125 along them) turns them by 10° and more towards the
// picture's axes.
Plane derivativeOf(const Plane& in, bool alongX) {
  constexpr int kTaps = 12;
  std::array<float, kTaps + 1> h{};
  for (int n = 1; n <= kTaps; ++n)
    h[n] = static_cast<float>((n % 2 == 1 ? 1.0 : -1.0) / n *
                              (0.5 + 0.5 * std::cos(std::numbers::pi * n / (kTaps + 1))));
  Plane out(in.width, in.height);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      float v = 0;
      for (int n = 1; n <= kTaps; ++n) {
        const float ahead = alongX ? in.at(std::min(x + n, in.width - 1), y)
                                   : in.at(x, std::min(y + n, in.height - 1));
        const float behind = alongX ? in.at(std::max(x - n, 0), y) : in.at(x, std::max(y - n, 0));
        v += h[n] * (ahead - behind);
      }
      out.at(x, y) = v;
    }
  return out;
}

// The structure tensor of `grey`, its gradients' products averaged over a Gaussian window of
// sigma 1 pixel: a flight feather's narrow vane shows 20 to 40 pixels of barbs beside its
// rachis at 300 dpi, and a wider window mixes in the vane's rim and the rachis, both along the
// rachis, turning the barbs read there towards it (and the rachis found beside its place). The
// barbs' own noise averages out along the traced barb.
Orientation orientationOf(const Plane& grey) {
  constexpr double kIntegration = 1.0;
  const Plane gx = derivativeOf(grey, true), gy = derivativeOf(grey, false);
  Plane xx(grey.width, grey.height), xy(grey.width, grey.height), yy(grey.width, grey.height);
  for (std::size_t i = 0; i < grey.values.size(); ++i) {
    xx.values[i] = gx.values[i] * gx.values[i];
    xy.values[i] = gx.values[i] * gy.values[i];
    yy.values[i] = gy.values[i] * gy.values[i];
  }
  xx = blurred(xx, kIntegration);
  xy = blurred(xy, kIntegration);
  yy = blurred(yy, kIntegration);
  Orientation o{Plane(grey.width, grey.height), Plane(grey.width, grey.height),
                Plane(grey.width, grey.height)};
  for (std::size_t i = 0; i < grey.values.size(); ++i) {
    const double a = xx.values[i], b = xy.values[i], c = yy.values[i];
    const double difference = std::sqrt((a - c) * (a - c) + 4 * b * b);
    // The gradient's doubled angle is atan2(2b, a - c); lines run across it (+180° doubled).
    const double doubled = std::atan2(2 * b, a - c) + std::numbers::pi;
    const double coherent = a + c > 1e-6 ? difference / (a + c) : 0;
    o.along.values[i] = static_cast<float>(coherent * std::cos(doubled));
    o.across.values[i] = static_cast<float>(coherent * std::sin(doubled));
    o.coherence.values[i] = static_cast<float>(coherent);
  }
  return o;
}

// Least squares: the coefficients of `columns` (one row a sample) fitting `values`, samples whose
// residual is past three times the median's dropped once and the fit repeated.
Eigen::VectorXd robustFit(const Eigen::MatrixXd& columns, const Eigen::VectorXd& values) {
  Eigen::VectorXd fit = columns.colPivHouseholderQr().solve(values);
  const Eigen::VectorXd residual = (columns * fit - values).cwiseAbs();
  std::vector<double> sorted(residual.data(), residual.data() + residual.size());
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double limit = std::max(3 * sorted[sorted.size() / 2], 1e-9);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < residual.size(); ++i)
    if (residual[i] <= limit) kept.push_back(i);
  if (kept.size() < static_cast<std::size_t>(columns.cols()) + 2 ||
      kept.size() == static_cast<std::size_t>(residual.size()))
    return fit;
  Eigen::MatrixXd a(static_cast<Eigen::Index>(kept.size()), columns.cols());
  Eigen::VectorXd b(static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    a.row(static_cast<Eigen::Index>(k)) = columns.row(kept[k]);
    b[static_cast<Eigen::Index>(k)] = values[kept[k]];
  }
  return a.colPivHouseholderQr().solve(b);
}

// Douglas-Peucker on (rp, length) points: the fewest points within `tolerance` of the lengths,
// at most kMaxSilhouettePoints (the tolerance grows until they fit).
std::vector<SilhouettePoint> simplified(const std::vector<SilhouettePoint>& points,
                                        double tolerance) {
  if (points.size() <= 2) return points;
  for (int round = 0; round < 20; ++round, tolerance *= 1.5) {
    std::vector<bool> keep(points.size(), false);
    keep.front() = keep.back() = true;
    std::vector<std::pair<std::size_t, std::size_t>> spans{{0, points.size() - 1}};
    while (!spans.empty()) {
      const auto [a, b] = spans.back();
      spans.pop_back();
      double worst = 0;
      std::size_t at = a;
      for (std::size_t i = a + 1; i < b; ++i) {
        const double t = (points[i].position - points[a].position) /
                         std::max(1e-9f, points[b].position - points[a].position);
        const double line = points[a].length + t * (points[b].length - points[a].length);
        if (std::abs(points[i].length - line) > worst) {
          worst = std::abs(points[i].length - line);
          at = i;
        }
      }
      if (worst > tolerance) {
        keep[at] = true;
        spans.push_back({a, at});
        spans.push_back({at, b});
      }
    }
    std::vector<SilhouettePoint> out;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (keep[i]) out.push_back(points[i]);
    if (out.size() <= kMaxSilhouettePoints) return out;
  }
  return {points.front(), points.back()};
}

// The scan in the feather's frame: the rachis from its base (rp = 0) to its tip (rp = 1) as the
// .fea bends it, its lateral bulge 3 c t (1 - t) towards `left`.
struct RachisFit {
  glm::dvec2 base{0.0}, tip{0.0}, left{0.0};
  double bulge = 0;  // pixels at the middle: c · 3/4
  glm::dvec2 point(double t) const {
    return base + t * (tip - base) + 3 * bulge * t * (1 - t) * left;
  }
  glm::dvec2 tangent(double t) const {
    return glm::normalize(tip - base + 3 * bulge * (1 - 2 * t) * left);
  }
  double length() const { return glm::length(tip - base); }
};

// One traced barb: from the rachis along the orientation field to the vane's edge.
struct Traced {
  std::vector<glm::dvec2> path;  // from the attachment (on the rachis) to the edge
  double coherence = 0;          // mean along it
  bool valid() const { return path.size() >= 3; }
  glm::dvec2 chord() const { return path.back() - path.front(); }
};

class Scanner {
 public:
  Scanner(const Texture& image, const FeatherScanOptions& options)
      : image_(image), options_(options) {}

  FeatherScan run() {
    findFeather();
    findAxis();
    findCalamus();
    closeVane();
    grey_ = Plane(image_.width, image_.height);
    for (int y = 0; y < image_.height; ++y)
      for (int x = 0; x < image_.width; ++x) grey_.at(x, y) = distance_.at(x, y);
    orientation_ = orientationOf(grey_);
    trackRachis();
    // The barbs are traced on the vanes alone, the rachis known.
    orientation_ = orientationOf(vaneOnly());
    // The rachis tip lies inside the feather's end by what the tip's barbs reach beyond it.
    findTip(shaftSeen_ - calamusEnd_);
    measureVanes();
    measureSpacing();
    return finish();
  }

 private:
  // --- the feather and its axis -------------------------------------------------------------

  void findFeather() {
    if (image_.width < 16 || image_.height < 16)
      throw std::invalid_argument(
          "the scan is too small to hold a feather (16 × 16 pixels at the least)");
    background_ = backgroundOf(image_);
    distance_ = Plane(image_.width, image_.height);
    for (int y = 0; y < image_.height; ++y)
      for (int x = 0; x < image_.width; ++x) {
        if (transparent(image_, x, y)) continue;
        const glm::vec3 d = glm::abs(pixelColour(image_, x, y) - background_);
        distance_.at(x, y) = std::max({d.x, d.y, d.z});
      }
    // Otsu's threshold splits the feather's body from the background; the barbs' faint tips
    // reach below it, so the feather is what passes a fraction of it, around that body.
    threshold_ = std::clamp(static_cast<int>(0.4 * otsu(distance_)), 12, 60);
    mask_.assign(distance_.values.size(), 0);
    for (std::size_t i = 0; i < mask_.size(); ++i) mask_[i] = distance_.values[i] > threshold_;
    pixels_ = keepLargestRegion(mask_, image_.width, image_.height);
    if (pixels_ < 200) {
      throw std::invalid_argument(fmt::format(
          "no feather found: the largest region that differs from the background ({:.0f}, "
          "{:.0f}, {:.0f}) has {} pixels (a feather needs 200 at the least)",
          background_.x, background_.y, background_.z, pixels_));
    }
  }

  // The feather with the gaps between its barbs closed (a morphological closing over a 9 × 9
  // square): what the barbs are traced across and the vanes measured in, so that thin barbs
  // far apart make one vane as dense ones do.
  bool inVane(glm::dvec2 p) const {
    const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
    return x >= 0 && y >= 0 && x < image_.width && y < image_.height &&
           vane_[static_cast<std::size_t>(y) * image_.width + x];
  }

  void closeVane() {
    constexpr int kRadius = 4;
    const int w = image_.width, h = image_.height;
    // Max (dilate) or min (erode) over a window of 2r + 1 along (dx, dy): a row or a column.
    auto pass = [&](const std::vector<std::uint8_t>& in, bool dilate, int dx, int dy) {
      std::vector<std::uint8_t> out(in.size());
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          std::uint8_t v = dilate ? 0 : 1;
          for (int k = -kRadius; k <= kRadius; ++k) {
            const int xx = std::clamp(x + k * dx, 0, w - 1), yy = std::clamp(y + k * dy, 0, h - 1);
            const std::uint8_t m = in[static_cast<std::size_t>(yy) * w + xx];
            v = dilate ? std::max(v, m) : std::min(v, m);
          }
          out[static_cast<std::size_t>(y) * w + x] = v;
        }
      return out;
    };
    vane_ = pass(pass(pass(pass(mask_, true, 1, 0), true, 0, 1), false, 1, 0), false, 0, 1);
  }

  bool inFeather(glm::dvec2 p) const {
    const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
    return x >= 0 && y >= 0 && x < image_.width && y < image_.height &&
           mask_[static_cast<std::size_t>(y) * image_.width + x];
  }

  void findAxis() {
    glm::dvec2 mean(0.0);
    for (int y = 0; y < image_.height; ++y)
      for (int x = 0; x < image_.width; ++x)
        if (mask_[static_cast<std::size_t>(y) * image_.width + x]) mean += glm::dvec2(x, y);
    mean /= static_cast<double>(pixels_);
    double sxx = 0, sxy = 0, syy = 0;
    for (int y = 0; y < image_.height; ++y)
      for (int x = 0; x < image_.width; ++x)
        if (mask_[static_cast<std::size_t>(y) * image_.width + x]) {
          const glm::dvec2 d = glm::dvec2(x, y) - mean;
          sxx += d.x * d.x;
          sxy += d.x * d.y;
          syy += d.y * d.y;
        }
    const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
    glm::dvec2 axis(std::cos(angle), std::sin(angle));
    // The extent along the axis and the width near each end.
    double low = 1e30, high = -1e30;
    forEachPixel([&](glm::dvec2 p) {
      const double s = glm::dot(p - mean, axis);
      low = std::min(low, s);
      high = std::max(high, s);
    });
    const double span = high - low;
    if (span < 20) throw std::invalid_argument("no feather found: the region is too small");
    double nearLow = 0, nearHigh = 0;
    forEachPixel([&](glm::dvec2 p) {
      const double s = glm::dot(p - mean, axis);
      if (s < low + 0.06 * span) nearLow += 1;
      if (s > high - 0.06 * span) nearHigh += 1;
    });
    bool baseAtLow = nearLow <= nearHigh;
    const glm::dvec2 given = options_.base == ScanBase::Top      ? glm::dvec2(0, -1)
                             : options_.base == ScanBase::Bottom ? glm::dvec2(0, 1)
                             : options_.base == ScanBase::Left   ? glm::dvec2(-1, 0)
                             : options_.base == ScanBase::Right  ? glm::dvec2(1, 0)
                                                                 : glm::dvec2(0.0);
    if (options_.base != ScanBase::Auto) baseAtLow = glm::dot(axis, given) < 0;
    axis_ = baseAtLow ? axis : -axis;
    // Left of a feather seen from its front with the tip up is the picture's left.
    left_ = glm::dvec2(axis_.y, -axis_.x);
    if (options_.back) left_ = -left_;
    start_ = mean + axis_ * (baseAtLow ? low : -high);
    end_ = mean + axis_ * (baseAtLow ? high : -low);
  }

  template <typename F>
  void forEachPixel(F&& f) const {
    for (int y = 0; y < image_.height; ++y)
      for (int x = 0; x < image_.width; ++x)
        if (mask_[static_cast<std::size_t>(y) * image_.width + x]) f(glm::dvec2(x, y));
  }

  // The run of feather pixels across the axis at distance s from the start that holds (or is
  // nearest to) lateral position `near`: its centre and width, in pixels.
  std::optional<std::pair<double, double>> runAt(double s, double near, double reach) const {
    const glm::dvec2 centre = start_ + s * axis_;
    std::optional<std::pair<double, double>> best;
    double bestGap = 1e30;
    double runStart = 0;
    bool inRun = false;
    for (double t = -reach; t <= reach + 1; t += 1) {
      const bool in = t <= reach && inFeather(centre + t * left_);
      if (in && !inRun) runStart = t;
      if (!in && inRun) {
        const double a = runStart, b = t - 1;
        const double gap = near < a ? a - near : near > b ? near - b : 0;
        if (gap < bestGap) {
          bestGap = gap;
          best = std::make_pair(0.5 * (a + b), b - a + 1);
        }
      }
      inRun = in;
    }
    return best;
  }

  // --- the calamus ---------------------------------------------------------------------------

  // How far the feather reaches across the axis at distance s from the start, around `near`:
  // from its leftmost to its rightmost pixel within `reach`.
  double extentAt(double s, double near, double reach) const {
    const glm::dvec2 centre = start_ + s * axis_;
    double low = 1e30, high = -1e30;
    for (double t = near - reach; t <= near + reach; t += 1)
      if (inFeather(centre + t * left_)) {
        low = std::min(low, t);
        high = std::max(high, t);
      }
    return high >= low ? high - low + 1 : 0;
  }

  void findCalamus() {
    const double span = glm::length(end_ - start_);
    const double reach = span;  // across: a feather is at most as wide as it is long
    std::vector<double> widths, centres;
    double near = 0, typical = 0;
    // The calamus is the bare shaft: the first barbs make the feather wider than it at once.
    int k = 0;
    for (; k < static_cast<int>(span); ++k) {
      const auto run = runAt(k + 0.5, near, reach);
      if (!run) {
        if (k > 3) break;
        continue;
      }
      if (widths.size() >= 4) {
        std::vector<double> sorted = widths;
        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
        typical = sorted[sorted.size() / 2];
        if (extentAt(k + 0.5, run->first, 0.5 * span) > std::max(1.8 * typical, typical + 4)) break;
      }
      widths.push_back(run->second);
      centres.push_back(run->first);
      near = run->first;
    }
    if (widths.size() < 4 || k >= static_cast<int>(span) - 2) {
      throw std::invalid_argument(
          "no calamus found: the feather's narrower end widens at once (a scan of a feather "
          "without its bare shaft, or give its base with --base)");
    }
    // The barbs fan out from where they begin: back along their extent to the calamus width.
    {
      std::vector<double> at, extent;
      for (int j = k; j < k + 8 && j < static_cast<int>(span); ++j) {
        at.push_back(j + 0.5);
        extent.push_back(extentAt(j + 0.5, near, 0.5 * span));
      }
      Eigen::MatrixXd a(static_cast<Eigen::Index>(at.size()), 2);
      Eigen::VectorXd b(a.rows());
      for (std::size_t j = 0; j < at.size(); ++j) {
        a.row(static_cast<Eigen::Index>(j)) << 1.0, at[j];
        b[static_cast<Eigen::Index>(j)] = extent[j];
      }
      const Eigen::VectorXd line = a.colPivHouseholderQr().solve(b);
      double begins = k;
      if (line[1] > 0.5) begins = (typical - line[0]) / line[1];
      k = static_cast<int>(std::lround(std::clamp(begins, k - 8.0, static_cast<double>(k))));
      while (static_cast<int>(widths.size()) > std::max(k, 4)) {
        widths.pop_back();
        centres.pop_back();
      }
    }
    calamusEnd_ = static_cast<double>(k);
    // The calamus tapers linearly: its width at the base and at the first barbs.
    const std::size_t first = std::min<std::size_t>(2, widths.size() - 2);
    Eigen::MatrixXd a(static_cast<Eigen::Index>(widths.size() - first), 2);
    Eigen::VectorXd b(a.rows());
    for (std::size_t i = first; i < widths.size(); ++i) {
      a.row(static_cast<Eigen::Index>(i - first)) << 1.0, static_cast<double>(i) / calamusEnd_;
      b[static_cast<Eigen::Index>(i - first)] = widths[i];
    }
    const Eigen::VectorXd fit = robustFit(a, b);
    calamusBaseWidth_ = std::max(1.0, fit[0]);
    rachisWidth_ = std::max(1.0, fit[0] + fit[1]);
    // The calamus is straight and points along the rachis's chord (the .fea's z axis): its
    // centre line, not the feather's principal axis (which a bent rachis tilts), is the axis.
    Eigen::MatrixXd line(static_cast<Eigen::Index>(centres.size() - first), 2);
    Eigen::VectorXd lateral(line.rows());
    for (std::size_t i = first; i < centres.size(); ++i) {
      line.row(static_cast<Eigen::Index>(i - first)) << 1.0, static_cast<double>(i) + 0.5;
      lateral[static_cast<Eigen::Index>(i - first)] = centres[i];
    }
    const Eigen::VectorXd centre = robustFit(line, lateral);
    featherBase_ = start_ + centre[0] * left_;
    base_ = start_ + calamusEnd_ * axis_ + (centre[0] + centre[1] * calamusEnd_) * left_;
    axis_ = glm::normalize(base_ - featherBase_);
    left_ = glm::dvec2(axis_.y, -axis_.x) * (options_.back ? -1.0 : 1.0);
    start_ = featherBase_;
    calamusEnd_ = glm::length(base_ - featherBase_);
    calamusCentre_ = 0;
    double farthest = 0;
    forEachPixel([&](glm::dvec2 p) { farthest = std::max(farthest, glm::dot(p - start_, axis_)); });
    end_ = start_ + farthest * axis_;
  }

  // --- the rachis ----------------------------------------------------------------------------

  // How strongly the barbs lean towards `left` (positive) or away from it (negative) at p: the
  // doubled angle of their orientation against the axis.
  double lean(glm::dvec2 p) const {
    // The coherence times sin 2φ, φ from the axis towards left: with d = (cos θ, sin θ) the
    // barbs' direction in the picture, 2 (d·axis)(d·left) = cos 2θ (ax lx - ay ly) +
    // sin 2θ (ax ly + ay lx), the axis and left being orthogonal; the field holds the coherence
    // times cos 2θ and sin 2θ.
    return orientation_.along.sample(p) * (axis_.x * left_.x - axis_.y * left_.y) +
           orientation_.across.sample(p) * (axis_.x * left_.y + axis_.y * left_.x);
  }

  // How much the picture at p looks like the calamus rather than the vane: 1 its colour, 0 the
  // vane's or farther (along the axis, over the rachis's width).
  double shaftLikeness(glm::dvec2 p) const {
    const double apart = glm::length(shaftColour_ - vaneColour_);
    if (apart < 8) return 0;  // shaft and vane alike: the colour cannot tell them apart
    glm::dvec3 sum(0.0);
    int n = 0;
    for (int k = -2; k <= 2; ++k) {
      const glm::dvec2 q = p + static_cast<double>(k) * axis_;
      const int x = static_cast<int>(std::lround(q.x)), y = static_cast<int>(std::lround(q.y));
      if (x < 0 || y < 0 || x >= image_.width || y >= image_.height) continue;
      sum += glm::dvec3(pixelColour(image_, x, y));
      ++n;
    }
    if (n == 0) return 0;
    return std::clamp(1 - glm::length(sum / static_cast<double>(n) - shaftColour_) / apart, 0.0,
                      1.0);
  }

  void measureColours() {
    glm::dvec3 shaft(0.0), all(0.0);
    double shafts = 0, alls = 0;
    for (double at = 2; at < calamusEnd_ - 1; at += 1) {
      const glm::dvec2 p = start_ + at * axis_;
      const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
      if (x < 0 || y < 0 || x >= image_.width || y >= image_.height) continue;
      shaft += glm::dvec3(pixelColour(image_, x, y));
      shafts += 1;
    }
    forEachPixel([&](glm::dvec2 p) {
      all += glm::dvec3(pixelColour(image_, static_cast<int>(p.x), static_cast<int>(p.y)));
      alls += 1;
    });
    shaftColour_ = shafts > 0 ? shaft / shafts : glm::dvec3(0.0);
    vaneColour_ = alls > 0 ? all / alls : glm::dvec3(0.0);
  }

  void trackRachis() {
    measureColours();
    const double span = glm::length(end_ - start_);
    const double window = std::max(4.0, 1.5 * rachisWidth_);
    const int half = std::clamp(static_cast<int>(rachisWidth_), 4, 12);
    std::vector<double> s, t, weight;
    double predicted = calamusCentre_, slope = 0;
    double shaftSeen = 0;  // how far the rachis is seen in the calamus's colour
    for (double at = calamusEnd_ + 2; at < span - 2; at += 1) {
      const glm::dvec2 centre = start_ + at * axis_;
      double best = 0, bestT = predicted;
      for (double c = predicted - window; c <= predicted + window; c += 0.5) {
        // Left barbs lean one way, right barbs the other: the rachis is where it flips; and it
        // looks like the calamus it continues.
        double above = 0, below = 0;
        for (int k = 1; k <= half; ++k) {
          above += lean(centre + (c + k) * left_);
          below += lean(centre + (c - k) * left_);
        }
        const double contrast = (above - below) / half + shaftLikeness(centre + c * left_);
        if (contrast > best) {
          best = contrast;
          bestT = c;
        }
      }
      if (best > 0.5) {
        s.push_back(at);
        t.push_back(bestT);
        weight.push_back(best);
        if (shaftLikeness(centre + bestT * left_) > 0.5) shaftSeen = at;
        if (s.size() >= 8) {
          const std::size_t n = s.size();
          slope = (t[n - 1] - t[n - 8]) / (s[n - 1] - s[n - 8]);
        }
        predicted = bestT + slope;
      } else {
        predicted += slope;
      }
    }
    // The rachis from its base at the calamus to the feather's end, then bent as the .fea bends
    // it: lateral offset from the base line = a + b u + c u (1 - u).
    tip_ = end_;
    const double length = glm::dot(tip_ - base_, axis_);
    if (s.size() < 10) {
      fit_ = RachisFit{base_, base_ + length * axis_, left_, 0};
      notes_.push_back("the rachis could not be followed along the barbs: it is taken straight");
      return;
    }
    Eigen::MatrixXd a(static_cast<Eigen::Index>(s.size()), 2);
    Eigen::VectorXd b(a.rows());
    // The rachis's tip lies on the calamus's line (the chord), so only the bend is fitted. Near
    // the tip the vanes thin out and the flip is lost: the fit leaves out the last 15%.
    Eigen::MatrixXd q(static_cast<Eigen::Index>(s.size()), 1);
    Eigen::Index rows = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double u = (s[i] - calamusEnd_) / length;
      if (u > 0.85) continue;
      q(rows, 0) = u * (1 - u);
      b[rows++] = t[i] - calamusCentre_;
    }
    q.conservativeResize(rows, 1);
    b.conservativeResize(rows);
    const Eigen::VectorXd fit = robustFit(q, b);
    tipOffset_ = 0;
    bulge_ = fit[0] / 3;
    shaftSeen_ = shaftSeen;
    setRachis(length);
  }

  void setRachis(double length) {
    const glm::dvec2 tip = base_ + length * axis_ + tipOffset_ * left_;
    // The .fea bends the rachis sideways from its chord, towards the left vane.
    const glm::dvec2 along = glm::normalize(tip - base_);
    glm::dvec2 side(along.y, -along.x);
    if (options_.back) side = -side;
    fit_ = RachisFit{base_, tip, side, bulge_};
  }

  // --- the vanes -----------------------------------------------------------------------------

  // The picture with the shaft and the background outside the vane painted over in the vane's
  // mean: what the barbs' orientation is read from once the rachis is known. The shaft's edges
  // and the vane's rim are far stronger than the barbs, and the structure tensor spreads them
  // over its window: beside them it would read the barbs turned towards the rachis, most of all
  // on a narrow vane whose barbs lie nearly along it.
  Plane vaneOnly() const {
    const double length = fit_.length();
    const glm::dvec2 along = (fit_.tip - fit_.base) / length;
    const double calamus = glm::length(base_ - featherBase_) / length;
    std::vector<std::uint8_t> keep(grey_.values.size(), 0);
    double sum = 0;
    std::size_t count = 0;
    for (int y = 0; y < grey_.height; ++y)
      for (int x = 0; x < grey_.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * grey_.width + x;
        if (!vane_[i]) continue;
        const glm::dvec2 d = glm::dvec2(x, y) - fit_.base;
        const double t = glm::dot(d, along) / length;
        const double u = std::clamp(t, 0.0, 1.0);
        const double lateral = glm::dot(d, fit_.left) - 3 * fit_.bulge * u * (1 - u);
        const double half =
            t < 0 ? 0.5 * std::max(rachisWidth_, calamusBaseWidth_) : rachisHalfWidth(u);
        if (t > -calamus - 0.01 && std::abs(lateral) < half + 1.5) continue;
        keep[i] = 1;
        sum += grey_.values[i];
        ++count;
      }
    const float mean = static_cast<float>(count > 0 ? sum / static_cast<double>(count) : 0.0);
    Plane out = grey_;
    for (std::size_t i = 0; i < keep.size(); ++i)
      if (!keep[i]) out.values[i] = mean;
    return out;
  }

  // Away from the rachis at rp, across its tangent, on the left (sideSign 1) or right (-1).
  glm::dvec2 outwardAt(double rp, double sideSign) const {
    const glm::dvec2 tangent = fit_.tangent(rp);
    const glm::dvec2 across(-tangent.y, tangent.x);
    return (glm::dot(across, fit_.left) > 0 ? sideSign : -sideSign) * across;
  }

  // Half the rachis's width at rp (pixels): as the .fea draws it, tapering linearly from its
  // width at the calamus to a point at the tip.
  double rachisHalfWidth(double rp) const { return 0.5 * rachisWidth_ * (1 - rp); }

  // The barbs' direction where they leave the rachis at rp on one side: the orientation field
  // averaged (its doubled angle, weighted by its coherence) over the vane beside the rachis,
  // from just clear of the rachis's edge outwards over a dozen pixels and a few pixels along
  // it, pointing away from the rachis. A narrow vane whose barbs lie nearly along the rachis (a
  // flight feather's leading vane) is read as well as a broad one: nothing is assumed about the
  // angle. None where the field there is too weak to tell.
  std::optional<glm::dvec2> startDirection(double rp, double sideSign) const {
    const glm::dvec2 attach = fit_.point(rp), tangent = fit_.tangent(rp);
    const glm::dvec2 outward = outwardAt(rp, sideSign);
    double c2 = 0, s2 = 0, weight = 0;
    for (double along = -4; along <= 4; along += 2) {
      for (double out = rachisHalfWidth(rp) + 3; out <= rachisHalfWidth(rp) + 15; out += 1) {
        const glm::dvec2 q = attach + along * tangent + out * outward;
        if (!inVane(q)) break;
        c2 += orientation_.along.sample(q);
        s2 += orientation_.across.sample(q);
        weight += 1;
      }
    }
    if (weight < 8 || std::hypot(c2, s2) < 0.2 * weight) return std::nullopt;
    const double phi = 0.5 * std::atan2(s2, c2);
    glm::dvec2 d(std::cos(phi), std::sin(phi));
    if (glm::dot(d, outward) < 0) d = -d;
    if (glm::dot(d, outward) < std::sin(3 * kDegrees)) return std::nullopt;
    return d;
  }

  Traced trace(double rp, double sideSign) const {
    Traced out;
    const glm::dvec2 attach = fit_.point(rp);
    const glm::dvec2 tangent = fit_.tangent(rp);
    const glm::dvec2 outward = outwardAt(rp, sideSign);
    // The barbs' direction where they leave the rachis (startDirection), or, where the field
    // shows none, a guess between the usual angles that the field turns.
    glm::dvec2 direction = startDirection(rp, sideSign)
                               .value_or(glm::normalize(std::cos(45 * kDegrees) * tangent +
                                                        std::sin(45 * kDegrees) * outward));
    out.path.push_back(attach);
    // From a pixel clear of the rachis's edge (as wide as the .fea draws it), along the barb.
    glm::dvec2 p = attach + (rachisHalfWidth(rp) + 1) /
                                std::max(glm::dot(direction, outward), 0.1) * direction;
    const double least = std::min(0.25, 0.6 * glm::dot(direction, outward));
    const double longest = 2.0 * glm::length(end_ - start_);
    // Thin barbs far apart leave gaps the path may cross while it follows one.
    const int gap = std::max(4, static_cast<int>(0.01 * longest));
    int outside = 0;
    double coherence = 0;
    int steps = 0;
    glm::dvec2 lastInside = p;
    for (double walked = 0; walked < longest; walked += 1) {
      if (inVane(p)) {
        outside = 0;
        lastInside = p;
      } else if (++outside > gap) {
        break;
      }
      double coherent = 0;
      glm::dvec2 field = orientation_.at(p, &coherent);
      if (glm::dot(field, direction) < 0) field = -field;
      coherence += coherent;
      ++steps;
      // Turn along the barbs, gently (a barb bends smoothly: at most 1° a pixel), and never
      // towards another edge (a colour band's, the rachis's, the vane's blurred rim).
      if (coherent > 0.2 && glm::dot(field, direction) > std::cos(30 * kDegrees)) {
        const double turn = std::clamp(
            std::atan2(direction.x * field.y - direction.y * field.x, glm::dot(direction, field)),
            -1.0 * kDegrees, 1.0 * kDegrees);
        direction = glm::dvec2(std::cos(turn) * direction.x - std::sin(turn) * direction.y,
                               std::sin(turn) * direction.x + std::cos(turn) * direction.y);
      }
      // A barb never turns much nearer to the rachis than it left it (a flight feather's
      // leading vane leaves it at 10° to 15°); a path that does follows the vane's blurred
      // edge, not a barb.
      const double away = glm::dot(direction, outward);
      if (away < least) {
        const glm::dvec2 up = direction - away * outward;
        direction =
            glm::normalize(least * outward + std::sqrt(1 - least * least) * glm::normalize(up));
      }
      p += direction;
      if (out.path.size() < 4096 && static_cast<int>(walked) % 2 == 0) out.path.push_back(p);
    }
    out.path.push_back(lastInside);
    while (out.path.size() > 2 && glm::dot(out.path[out.path.size() - 2] - attach, outward) >
                                      glm::dot(lastInside - attach, outward))
      out.path.erase(out.path.end() - 2);
    out.coherence = steps > 0 ? coherence / steps : 0;
    return out;
  }

  void measureVanes() {
    for (int side = 0; side < 2; ++side) {
      auto& traces = traces_[side];
      traces.clear();
      for (int i = 0; i < kSilhouetteSamples; ++i)
        traces.push_back(
            trace(static_cast<double>(i) / (kSilhouetteSamples - 1), side == 0 ? 1 : -1));
    }
  }

  // The length (pixels) of the straight chord at barb angle `angle` from the rachis at rp to
  // where the feather ends, past the gaps between barbs (a fluffy plumulaceous base has wide
  // ones: up to 2.5% of the feather's length).
  double chordToEdge(double rp, double sideSign, double angle) const {
    const glm::dvec2 attach = fit_.point(rp);
    const double beta = (180 - angle) * kDegrees;
    const glm::dvec2 direction =
        std::cos(beta) * fit_.tangent(rp) + std::sin(beta) * outwardAt(rp, sideSign);
    const double longest = glm::length(end_ - start_);
    const int gap = std::max(4, static_cast<int>(0.025 * longest));
    double last = 0;
    int outside = 0;
    for (double d = rachisHalfWidth(rp); d < longest; d += 1) {
      if (inVane(attach + d * direction)) {
        last = d;
        outside = 0;
      } else if (++outside > gap) {
        break;
      }
    }
    return last;
  }

  // The barb angle of a chord at rp (degrees: 180 along the rachis to the tip, 90 across it).
  double angleOf(const glm::dvec2& chord, double rp) const {
    const glm::dvec2 tangent = fit_.tangent(rp);
    const double along = glm::dot(chord, tangent);
    const double across = std::abs(tangent.x * chord.y - tangent.y * chord.x);
    return 180 - std::atan2(across, along) / kDegrees;
  }

  // What the tip's barbs reach along the rachis beyond its tip, for the rachis as it stands: their
  // chords' along-rachis lengths at rp 0.75 … 0.96, extrapolated linearly to rp = 1.
  double tipReach() {
    measureVanes();
    double reach = 0;
    int sides = 0;
    for (const auto& traces : traces_) {
      std::vector<double> rp, along;
      for (int i = 0; i < kSilhouetteSamples; ++i) {
        const double r = static_cast<double>(i) / (kSilhouetteSamples - 1);
        if (r < 0.75 || r > 0.96 || !traces[i].valid()) continue;
        rp.push_back(r);
        along.push_back(glm::dot(traces[i].chord(), fit_.tangent(r)));
      }
      if (rp.size() < 3) continue;
      Eigen::MatrixXd a(static_cast<Eigen::Index>(rp.size()), 2);
      Eigen::VectorXd b(a.rows());
      for (std::size_t i = 0; i < rp.size(); ++i) {
        a.row(static_cast<Eigen::Index>(i)) << 1.0, rp[i];
        b[static_cast<Eigen::Index>(i)] = along[i];
      }
      const Eigen::VectorXd fit = robustFit(a, b);
      reach += std::max(0.0, fit[0] + fit[1]);
      ++sides;
    }
    return sides > 0 ? reach / sides : 0;
  }

  // Where the rachis ends. Where its colour differs from the vane's it is seen to where it has
  // thinned to a pixel: tapering linearly from its width w at the base, it ends 1 / w of its
  // length further. Where it cannot be told apart, the tip's barbs say: the rachis ends inside
  // the feather's end by what they reach beyond it (tipReach, traced from the rachis as it
  // stands, twice).
  void findTip(double seen) {
    const double end = glm::dot(end_ - base_, axis_);
    if (seen > 0.5 * end && rachisWidth_ > 2) {
      setRachis(std::min(end, seen / (1 - 1 / rachisWidth_)));
      return;
    }
    setRachis(end);
    for (int round = 0; round < 2; ++round) setRachis(std::max(0.2 * end, end - tipReach()));
  }

  void measureSpacing() {
    spacing_ = {};
    // Beside the rachis on each vane, a third of the way out: the barbs cross it once a spacing.
    for (int part = 0; part < 2; ++part) {
      const double from = part == 0 ? 0.1 : 0.55, to = part == 0 ? 0.45 : 0.9;
      std::vector<double> periods;
      for (int side = 0; side < 2; ++side) {
        const double sign = side == 0 ? 1 : -1;
        std::vector<double> signal;
        const double length = fit_.length();
        for (double along = from * length; along <= to * length; along += 1) {
          const double rp = along / length;
          const int i = std::clamp(static_cast<int>(std::lround(rp * (kSilhouetteSamples - 1))), 0,
                                   kSilhouetteSamples - 1);
          const double width = traces_[side][i].valid()
                                   ? std::abs(glm::dot(traces_[side][i].chord(), fit_.left))
                                   : 0;
          if (width < 6) continue;
          signal.push_back(
              grey_.sample(fit_.point(rp) + sign * (rachisWidth_ + 0.3 * width) * fit_.left));
        }
        if (const auto period = periodOf(signal)) periods.push_back(*period);
      }
      if (!periods.empty()) spacing_[part] = *std::min_element(periods.begin(), periods.end());
    }
  }

  // The period (samples) of the strongest repetition in [2.5, 80] samples, if clear.
  static std::optional<double> periodOf(std::vector<double> signal) {
    if (signal.size() < 40) return std::nullopt;
    double mean = 0;
    for (double v : signal) mean += v;
    mean /= static_cast<double>(signal.size());
    for (double& v : signal) v -= mean;
    double energy = 0;
    for (double v : signal) energy += v * v;
    if (!(energy > 1e-6)) return std::nullopt;
    const int longest = std::min(80, static_cast<int>(signal.size() / 3));
    std::vector<double> r(longest + 2, 0);
    for (int lag = 1; lag <= longest + 1; ++lag) {
      double sum = 0;
      for (std::size_t i = 0; i + lag < signal.size(); ++i) sum += signal[i] * signal[i + lag];
      r[lag] = sum / energy * signal.size() / static_cast<double>(signal.size() - lag);
    }
    // The first peak past the first fall below zero.
    int lag = 2;
    while (lag <= longest && r[lag] > 0) ++lag;
    int best = 0;
    for (; lag <= longest; ++lag)
      if (r[lag] > r[lag - 1] && r[lag] >= r[lag + 1] && r[lag] > 0.25) {
        best = lag;
        break;
      }
    if (best == 0) return std::nullopt;
    // The parabola through the peak and its neighbours.
    const double a = r[best - 1], b = r[best], c = r[best + 1];
    const double shift = a - 2 * b + c < 0 ? 0.5 * (a - c) / (a - 2 * b + c) : 0;
    return best + shift;
  }

  // --- the type ------------------------------------------------------------------------------

  FeatherScan finish() {
    FeatherScan out;
    const double rachisPixels = fit_.length();
    const double calamusPixels = glm::length(base_ - featherBase_);
    const double unit = options_.length ? *options_.length / (rachisPixels + calamusPixels)
                                        : options_.unitsPerPixel;
    FeatherType& type = out.type;
    type.calamusLength = static_cast<float>(calamusPixels * unit);
    type.rachisLength = static_cast<float>(rachisPixels * unit);
    type.rachisWidth = static_cast<float>(rachisWidth_ * unit);
    type.calamusWidthRatio = static_cast<float>(calamusBaseWidth_ / rachisWidth_);
    type.rachisSideCurvature = static_cast<float>(bulge_ / rachisPixels);
    type.rachisFrontCurvature = 0;

    double coherence = 0;
    int traced = 0;
    for (int side = 0; side < 2; ++side) {
      Vane& vane = type.vane(side == 0 ? BarbSide::Left : BarbSide::Right);
      std::vector<double> rp, angles;
      for (int i = 0; i < kSilhouetteSamples; ++i) {
        const double r = static_cast<double>(i) / (kSilhouetteSamples - 1);
        const Traced& barb = traces_[side][i];
        const double length = barb.valid() ? glm::length(barb.chord()) : 0;
        if (!barb.valid()) continue;
        coherence += barb.coherence;
        ++traced;
        // A chord that points back towards the base (a path that ran along the vane's edge)
        // shows no barb.
        const double angle = angleOf(barb.chord(), r);
        if (r >= 0.1 && r <= 0.85 && length > 4 && angle > 90 && angle < 179) {
          rp.push_back(r);
          angles.push_back(angle);
        }
      }
      if (rp.size() >= 4) {
        Eigen::MatrixXd a(static_cast<Eigen::Index>(rp.size()), 2);
        Eigen::VectorXd b(a.rows());
        for (std::size_t i = 0; i < rp.size(); ++i) {
          a.row(static_cast<Eigen::Index>(i)) << 1.0, rp[i];
          b[static_cast<Eigen::Index>(i)] = angles[i];
        }
        const Eigen::VectorXd fit = robustFit(a, b);
        vane.baseAngle = static_cast<float>(std::clamp(fit[0], 90.0, 179.0));
        vane.tipAngle = static_cast<float>(std::clamp(fit[0] + fit[1], 90.0, 179.0));
      }
      // The silhouette: each traced barb's chord where it agrees with the vane's angle there
      // (within 15°), else the straight chord at that angle from the rachis to the edge; then a
      // running median over five places against what a stray path adds.
      std::vector<double> lengths;
      for (int i = 0; i < kSilhouetteSamples; ++i) {
        const double r = static_cast<double>(i) / (kSilhouetteSamples - 1);
        const double angle = vane.baseAngle + r * (vane.tipAngle - vane.baseAngle);
        const Traced& barb = traces_[side][i];
        const double straight = chordToEdge(r, side == 0 ? 1 : -1, angle);
        const double traced = barb.valid() ? glm::length(barb.chord()) : 0;
        const bool agrees = traced > 4 && std::abs(angleOf(barb.chord(), r) - angle) < 15;
        lengths.push_back(agrees ? traced : straight);
      }
      std::vector<SilhouettePoint> points;
      double longest = 0;
      for (int i = 0; i < kSilhouetteSamples; ++i) {
        std::vector<double> window;
        for (int j = std::max(0, i - 2); j <= std::min(kSilhouetteSamples - 1, i + 2); ++j)
          window.push_back(lengths[j]);
        std::nth_element(window.begin(), window.begin() + window.size() / 2, window.end());
        const double length = window[window.size() / 2] * unit;
        points.push_back(SilhouettePoint{static_cast<float>(i) / (kSilhouetteSamples - 1),
                                         static_cast<float>(length)});
        longest = std::max(longest, length);
      }
      vane.silhouette = simplified(points, 0.015 * longest);
      out.barbsSeen = true;
    }
    out.coherence = traced > 0 ? coherence / traced : 0;
    if (out.coherence < 0.25) {
      out.barbsSeen = false;
      notes_.push_back(fmt::format(
          "the barbs' direction is hardly visible in the scan (coherence {:.2f}): the barb "
          "angles, lengths and key barbs are rough; a sharper scan at a higher resolution helps",
          out.coherence));
    }
    proposeKeyBarbs(type);

    // Spacing: measured, or about 150 barbs along the rachis.
    out.spacingSeen = spacing_[0] > 0 || spacing_[1] > 0;
    const double fallback = rachisPixels / 150;
    const double atBase = spacing_[0] > 0 ? spacing_[0] : spacing_[1] > 0 ? spacing_[1] : fallback;
    const double atTip = spacing_[1] > 0 ? spacing_[1] : atBase;
    type.barbSpacingBase = static_cast<float>(atBase * unit);
    type.barbSpacingTip = static_cast<float>(atTip * unit);
    if (!out.spacingSeen)
      notes_.push_back("the barbs' spacing could not be seen: about 150 barbs a vane are assumed");

    // The colour: the mean of the vane's pixels.
    glm::dvec3 colour(0.0);
    std::size_t counted = 0;
    forEachPixel([&](glm::dvec2 p) {
      colour += glm::dvec3(pixelColour(image_, static_cast<int>(p.x), static_cast<int>(p.y)));
      ++counted;
    });
    type.appearance.colour = glm::clamp(glm::vec3(colour / std::max<double>(counted, 1) / 255.0),
                                        glm::vec3(0.0f), glm::vec3(1.0f));

    out.background = background_ / 255.0f;
    out.threshold = threshold_;
    out.featherPixels = pixels_;
    out.unitsPerPixel = unit;
    out.base = featherBase_;
    out.left = fit_.left;
    out.rachisBase = fit_.base;
    out.rachisTip = fit_.tip;
    const glm::dvec2 chord = fit_.tip - out.base;
    out.tiltDegrees = std::atan2(chord.x, -chord.y) / kDegrees;
    for (const Traced& t : traces_[0]) out.tracedLeft.push_back(t.path);
    for (const Traced& t : traces_[1]) out.tracedRight.push_back(t.path);
    out.notes = notes_;
    return out;
  }

  // Key barbs from the traced barbs around evenly spaced places, in each barb's own frame (x
  // along its chord, normalised to 1; y towards the tip), as cubic Béziers fitted by least squares
  // to the traced paths with their ends fixed.
  void proposeKeyBarbs(FeatherType& type) const {
    const int count = std::clamp(options_.keyBarbs, 1, 8);
    for (int side = 0; side < 2; ++side) {
      for (int k = 0; k < count; ++k) {
        const double rp = count == 1 ? 0.5 : 0.1 + 0.8 * k / (count - 1);
        const int centre = static_cast<int>(std::lround(rp * (kSilhouetteSamples - 1)));
        std::vector<glm::dvec2> samples;  // (u, y) and (u, x) in the chord frame
        std::vector<double> us;
        for (int i = std::max(0, centre - 1); i <= std::min(kSilhouetteSamples - 1, centre + 1);
             ++i) {
          const Traced& barb = traces_[side][i];
          const double length = barb.valid() ? glm::length(barb.chord()) : 0;
          if (length < 6) continue;
          const double r = static_cast<double>(i) / (kSilhouetteSamples - 1);
          const glm::dvec2 x = barb.chord() / length;
          glm::dvec2 y = fit_.tangent(r) - glm::dot(fit_.tangent(r), x) * x;
          y = glm::length(y) > 1e-9 ? glm::normalize(y) : glm::dvec2(-x.y, x.x);
          // Chord-length parameters along the path.
          std::vector<double> arc{0};
          for (std::size_t j = 1; j < barb.path.size(); ++j)
            arc.push_back(arc.back() + glm::length(barb.path[j] - barb.path[j - 1]));
          for (std::size_t j = 0; j < barb.path.size(); ++j) {
            const glm::dvec2 d = barb.path[j] - barb.path.front();
            samples.emplace_back(glm::dot(d, x) / length, glm::dot(d, y) / length);
            us.push_back(arc.back() > 0 ? arc[j] / arc.back() : 0);
          }
        }
        if (samples.size() < 6) continue;
        // B(u) = b0 (0,0) + b1 P1 + b2 P2 + b3 (1,0): solve for P1 and P2.
        Eigen::MatrixXd a(static_cast<Eigen::Index>(samples.size()), 2);
        Eigen::MatrixXd b(static_cast<Eigen::Index>(samples.size()), 2);
        for (std::size_t j = 0; j < samples.size(); ++j) {
          const double u = us[j], v = 1 - u;
          a.row(static_cast<Eigen::Index>(j)) << 3 * v * v * u, 3 * v * u * u;
          b.row(static_cast<Eigen::Index>(j)) << samples[j].x - u * u * u, samples[j].y;
        }
        const Eigen::MatrixXd p = a.colPivHouseholderQr().solve(b);
        KeyBarb key;
        key.side = side == 0 ? BarbSide::Left : BarbSide::Right;
        key.position = static_cast<float>(rp);
        key.vertices = {glm::vec3(0.0f), glm::vec3(p(0, 0), p(0, 1), 0),
                        glm::vec3(p(1, 0), p(1, 1), 0), glm::vec3(1, 0, 0)};
        type.keyBarbs.push_back(std::move(key));
      }
    }
  }

  const Texture& image_;
  const FeatherScanOptions& options_;
  glm::vec3 background_{255.0f};
  Plane distance_, grey_;
  Orientation orientation_;
  int threshold_ = 0;
  std::vector<std::uint8_t> mask_, vane_;
  std::size_t pixels_ = 0;
  glm::dvec2 axis_{0.0}, left_{0.0}, start_{0.0}, end_{0.0};
  glm::dvec2 featherBase_{0.0}, base_{0.0}, tip_{0.0};  // the calamus base, the rachis base
  double calamusEnd_ = 0, calamusCentre_ = 0, calamusBaseWidth_ = 1, rachisWidth_ = 1;
  double tipOffset_ = 0, bulge_ = 0;
  double shaftSeen_ = 0;  // how far from the start the rachis is seen in the calamus's colour
  glm::dvec3 shaftColour_{0.0}, vaneColour_{0.0};  // 0..255
  RachisFit fit_;
  std::array<std::vector<Traced>, 2> traces_;  // left, right
  std::array<double, 2> spacing_{};            // pixels near the base and near the tip
  std::vector<std::string> notes_;
};

std::string number(double value) {
  std::string text = fmt::format("{:.4g}", value);
  return text == "-0" ? "0" : text;
}

}  // namespace

FeatherScan scanFeather(const Texture& scan, const FeatherScanOptions& options) {
  if (static_cast<long long>(scan.width) * scan.height > kMaxScanPixels) {
    throw std::invalid_argument(
        fmt::format("the scan has {} × {} pixels, more than {} Mpixel (the limit); scale it down",
                    scan.width, scan.height, kMaxScanPixels >> 20));
  }
  if (scan.rgba.size() < 4 * static_cast<std::size_t>(scan.width) * scan.height || scan.width <= 0)
    throw std::invalid_argument("the scan has no pixels");
  return Scanner(scan, options).run();
}

std::string featherFileText(const FeatherScan& scan, const std::string& scanName,
                            const std::string& textureName) {
  const FeatherType& t = scan.type;
  std::string out;
  auto line = [&out](const std::string& text, const std::string& comment = {}) {
    out += comment.empty() ? text + "\n" : fmt::format("{:<40} # {}\n", text, comment);
  };
  out += fmt::format(
      "# A feather type read from the scan {} by `hirsute feather-scan`: edit it freely.\n"
      "# The feather: {} pixels differing from the background ({:.0f}, {:.0f}, {:.0f}) by more "
      "than {};\n# {} model units a pixel; the calamus base at ({:.0f}, {:.0f}), the rachis from "
      "({:.0f}, {:.0f})\n# to ({:.0f}, {:.0f}), tilted {:.1f} degrees from the scan's vertical.\n",
      scanName, scan.featherPixels, scan.background.x * 255, scan.background.y * 255,
      scan.background.z * 255, scan.threshold, number(scan.unitsPerPixel), scan.base.x, scan.base.y,
      scan.rachisBase.x, scan.rachisBase.y, scan.rachisTip.x, scan.rachisTip.y, scan.tiltDegrees);
  for (const std::string& note : scan.notes) out += "# Note: " + note + ".\n";
  out += "\n";
  line("calamus length:         " + number(t.calamusLength),
       "the bare shaft below the first barbs");
  line("calamus width ratio:    " + number(t.calamusWidthRatio),
       "its width at the base / rachis width");
  line("rachis length:          " + number(t.rachisLength),
       "from the first barbs to the rachis tip");
  line("rachis width:           " + number(t.rachisWidth), "where the barbs begin");
  line("rachis side curvature:  " + number(t.rachisSideCurvature),
       "its bend towards the left vane");
  line("rachis front curvature: 0", "a flat scan cannot show it: add it by hand");
  out += "\n";
  line("barb spacing:       " + number(t.barbSpacingBase) + " " + number(t.barbSpacingTip),
       scan.spacingSeen ? "the barbs' period beside the rachis, base and tip"
                        : "not seen in the scan: a guess");
  for (BarbSide side : {BarbSide::Left, BarbSide::Right}) {
    const Vane& v = t.vane(side);
    const char* name = side == BarbSide::Left ? "left " : "right";
    line(fmt::format("{} barb angles:   {} {}", side == BarbSide::Left ? "left" : "right",
                     number(v.baseAngle), number(v.tipAngle)),
         scan.barbsSeen ? "the traced barbs' chords, fitted at base and tip"
                        : "barbs not visible: a guess");
    std::string silhouette = fmt::format("silhouette: {}", name);
    for (const SilhouettePoint& p : v.silhouette)
      silhouette += fmt::format(" ({} {})", number(p.position), number(p.length));
    line(silhouette);
  }
  out += "# (silhouettes: the traced barbs' chord lengths along the rachis)\n\n";
  out +=
      "# Key barbs proposed from the traced barbs (chord normalised to 1, y towards the tip);\n"
      "# a flat scan shows no front-to-back curvature: give the vertices a third coordinate.\n";
  for (const KeyBarb& k : t.keyBarbs) {
    std::string text = fmt::format("key barb: {} {}", k.side == BarbSide::Left ? "left " : "right",
                                   number(k.position));
    for (const glm::vec3& v : k.vertices) text += fmt::format(" ({} {})", number(v.x), number(v.y));
    line(text);
  }
  out += "\n";
  // A scanned vane is closed: strips half a spacing wide either side of each barb fill it.
  line("drawing: strips " + number(0.25 * (t.barbSpacingBase + t.barbSpacingTip)),
       "a closed vane, as scanned");
  const glm::vec3& c = t.appearance.colour;
  if (textureName.empty()) {
    line(fmt::format("colour: {} {} {}", number(c.x), number(c.y), number(c.z)),
         "the feather's mean colour in the scan");
  } else {
    line("colour: 1 1 1", "white: the texture carries the scan's colours");
    line("texture: " + textureName + " vane", "the scan's own vane");
  }
  return out;
}

Texture vaneTextureOf(const Texture& scan, const FeatherScan& found, int size) {
  // The vane mapping's box (feather_geometry.cpp): the straightened vane, y across and z along.
  FeatherType straight = found.type;
  straight.rachisSideCurvature = 0;
  const FeatherGeometry geometry = buildFeatherGeometry(straight, FeatherDetail{8, 12, 3});
  glm::dvec2 low(1e30), high(-1e30);
  for (const glm::vec3& p : geometry.vertices.positions) {
    low = glm::min(low, glm::dvec2(p.y, p.z));
    high = glm::max(high, glm::dvec2(p.y, p.z));
  }
  Texture out;
  out.file = "vane";
  out.width = out.height = size;
  out.rgba.assign(static_cast<std::size_t>(size) * size * 4, 255);
  const double unit = found.unitsPerPixel;
  const glm::dvec2 base = found.base;
  const glm::dvec2 rachis = found.rachisTip - found.rachisBase;
  const double rl = glm::length(rachis);
  const glm::dvec2 along = rl > 0 ? rachis / rl : glm::dvec2(0, -1);
  const glm::dvec2 left = found.left;
  const double bulge = found.type.rachisSideCurvature * rl;
  const double cl = found.type.calamusLength;
  for (int row = 0; row < size; ++row) {
    const double v = 1 - (row + 0.5) / size;  // row 0 is the top: v = 1
    const double z = low.y + v * (high.y - low.y);
    const double t = std::clamp(
        (z - cl) / std::max(1e-9, static_cast<double>(found.type.rachisLength)), 0.0, 1.0);
    for (int column = 0; column < size; ++column) {
      const double u = (column + 0.5) / size;
      const double y = low.x + u * (high.x - low.x);
      const glm::dvec2 p = base + (z / unit) * along + (y / unit + 3 * bulge * t * (1 - t)) * left;
      const int x = std::clamp(static_cast<int>(std::lround(p.x)), 0, scan.width - 1);
      const int yy = std::clamp(static_cast<int>(std::lround(p.y)), 0, scan.height - 1);
      const std::uint8_t* from = &scan.rgba[4 * (static_cast<std::size_t>(yy) * scan.width + x)];
      std::uint8_t* to = &out.rgba[4 * (static_cast<std::size_t>(row) * size + column)];
      std::copy(from, from + 3, to);
      to[3] = 255;
    }
  }
  return out;
}

}  // namespace hirsute
