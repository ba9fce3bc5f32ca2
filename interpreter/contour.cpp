// Generalized-cylinder contours: cpfg's `.con` files and the built-in circle, resampled to a
// number of sides (reference/cpfg-generalized-cylinders.md §3).
#include "hirsute/interpreter/contour.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/function_curve.h"
#include "hirsute/lsys/uniform_bspline.h"

namespace hirsute {
namespace {

// cpfg measures a contour with 10 samples per spline segment, in x and y only.
constexpr int kLengthSamplesPerSegment = 10;

// Id 0, and every id without a contour, is the unit circle c_j = (cos 2πj/n, sin 2πj/n), closed,
// with normals c_j.
ContourSamples circle(int sides) {
  ContourSamples out;
  out.closed = true;
  for (int j = 0; j < sides; ++j) {
    const double angle = 2.0 * std::numbers::pi * j / sides;
    const glm::dvec2 point(std::cos(angle), std::sin(angle));
    out.points.push_back(point);
    out.normals.push_back(point);
    out.z.push_back(0.0);
  }
  out.length = sides * 2.0 * std::sin(std::numbers::pi / sides);
  return out;
}

// The uniform cubic B-spline of a contour: periodic over n segments when closed, n − 3 segments
// when open (the file's multiplicity-3 ends make those interpolate their end points).
class ContourSpline {
 public:
  explicit ContourSpline(const Contour& contour)
      : points_(contour.controlPoints),
        segments_(contour.closed ? static_cast<int>(points_.size())
                                 : static_cast<int>(points_.size()) - 3) {}

  int segments() const { return segments_; }

  SplinePoint point(double u) const {
    const auto [segment, t] = locate(u);
    return uniformBSplinePoint(at(segment, 0), at(segment, 1), at(segment, 2), at(segment, 3), t);
  }
  SplinePoint tangent(double u) const {
    const auto [segment, t] = locate(u);
    return uniformBSplineTangent(at(segment, 0), at(segment, 1), at(segment, 2), at(segment, 3), t);
  }

 private:
  std::pair<int, double> locate(double u) const {
    const int segment = std::clamp(static_cast<int>(std::floor(u)), 0, segments_ - 1);
    return {segment, u - segment};
  }
  SplinePoint at(int segment, int k) const {
    const glm::dvec3& p = points_[static_cast<std::size_t>(segment + k) % points_.size()];
    return {p.x, p.y, p.z};
  }

  const std::vector<glm::dvec3>& points_;
  int segments_;
};

double planarLength(const SplinePoint& a, const SplinePoint& b) {
  return std::hypot(b[0] - a[0], b[1] - a[1]);
}

// The direction of the curve at parameter u in the contour plane. Where the derivative vanishes
// (the multiplicity-3 ends of cuspy's open contours, a cusp made of a tripled point) the limit
// direction is taken just beside it, inside the curve.
glm::dvec2 planarDirection(const ContourSpline& spline, double u, double scale) {
  const double tiny = 1e-12 * std::max(scale, 1e-300);
  SplinePoint d = spline.tangent(u);
  if (std::hypot(d[0], d[1]) > tiny) return glm::dvec2(d[0], d[1]);
  constexpr double kBeside = 1e-4;
  const double inside = u + kBeside <= spline.segments() ? u + kBeside : u - kBeside;
  d = spline.tangent(inside);
  if (std::hypot(d[0], d[1]) > tiny) return glm::dvec2(d[0], d[1]);
  const SplinePoint a = spline.point(std::max(0.0, u - kBeside));
  const SplinePoint b = spline.point(std::min<double>(spline.segments(), u + kBeside));
  return glm::dvec2(b[0] - a[0], b[1] - a[1]);
}

// cpfg-generalized-cylinders.md §3: an arc-length table with 10 samples per spline segment (x, y
// only), step = total / sides, sample j at arc length j·step (j = 0 … sides−1 closed, 0 … sides
// open), the parameter interpolated linearly in the table; normal (dy, −dx) normalised. Closed
// contours are then rotated about the origin so that sample 0 lies on +x; open ones are not.
//
// cpfg's table holds the points u = i/10 for i = 0 … 10·segments − 1: it stops one short of the
// curve's end, so the total leaves out the last tenth of the last segment and the last sample of
// an open contour lies at u = segments − 0.1. The rings of tools-LilyLeaf and tools-FernLeaf in
// cpfg's rayshade output fit this to the printed precision (4.7·10⁻⁶ and 2.9·10⁻⁵ in relative
// distances), a table that includes the end point 20 and 2 times worse. The conformance set has
// no closed contour; the same loop leaves the last tenth out of a closed contour's perimeter,
// which widens the step across the seam a little.
ContourSamples resample(const Contour& contour, int sides) {
  const ContourSpline spline(contour);
  const int tableSize = spline.segments() * kLengthSamplesPerSegment;
  std::vector<double> parameter(static_cast<std::size_t>(tableSize));
  std::vector<double> length(static_cast<std::size_t>(tableSize));
  SplinePoint previous = spline.point(0.0);
  for (int i = 0; i < tableSize; ++i) {
    parameter[i] = static_cast<double>(i) / kLengthSamplesPerSegment;
    const SplinePoint current = spline.point(parameter[i]);
    length[i] = i == 0 ? 0.0 : length[i - 1] + planarLength(previous, current);
    previous = current;
  }
  const double total = length.back();
  const double step = total / sides;

  ContourSamples out;
  out.closed = contour.closed;
  const int count = contour.closed ? sides : sides + 1;
  for (int j = 0; j < count; ++j) {
    const double target = j == sides ? total : j * step;
    auto above = std::lower_bound(length.begin() + 1, length.end(), target);
    if (above == length.end()) --above;
    const std::size_t i = static_cast<std::size_t>(above - length.begin());
    const double span = length[i] - length[i - 1];
    const double fraction = span > 0.0 ? (target - length[i - 1]) / span : 0.0;
    const double u = parameter[i - 1] + fraction * (parameter[i] - parameter[i - 1]);
    const SplinePoint p = spline.point(u);
    const glm::dvec2 d = planarDirection(spline, u, total);
    const glm::dvec2 normal(d.y, -d.x);
    const double normalLength = glm::length(normal);
    out.points.emplace_back(p[0], p[1]);
    out.normals.push_back(normalLength > 0.0 ? normal / normalLength : glm::dvec2(0.0));
    out.z.push_back(p[2]);
  }

  if (contour.closed && glm::length(out.points[0]) > 0.0) {
    const double angle = -std::atan2(out.points[0].y, out.points[0].x);
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    const auto rotate = [c, s](const glm::dvec2& v) {
      return glm::dvec2(c * v.x - s * v.y, s * v.x + c * v.y);
    };
    for (glm::dvec2& point : out.points) point = rotate(point);
    for (glm::dvec2& normal : out.normals) normal = rotate(normal);
  }

  for (std::size_t j = 1; j < out.points.size(); ++j) {
    out.length += glm::length(out.points[j] - out.points[j - 1]);
  }
  if (out.closed) out.length += glm::length(out.points.front() - out.points.back());
  return out;
}

}  // namespace

void ContourLibrary::add(int id, Contour contour) {
  if (id == 0) throw std::invalid_argument("contour id 0 is the built-in circle");
  const std::size_t needed = contour.closed ? 3 : 4;
  if (contour.controlPoints.size() < needed) {
    throw std::invalid_argument("a contour needs at least 3 (closed) or 4 (open) control points");
  }
  contours_[id] = std::move(contour);
  // A replaced contour must not be served from the cache.
  for (auto it = cache_.begin(); it != cache_.end();) {
    it = it->first.first == id ? cache_.erase(it) : std::next(it);
  }
}

const ContourSamples& ContourLibrary::samples(int id, int sides) const {
  sides = std::clamp(sides, 3, kMaxContourSides);
  const auto contour = id == 0 ? contours_.end() : contours_.find(id);
  const int key = contour == contours_.end() ? 0 : id;
  const auto cached = cache_.find({key, sides});
  if (cached != cache_.end()) return cached->second;
  ContourSamples samples = key == 0 ? circle(sides) : resample(contour->second, sides);
  return cache_.emplace(std::make_pair(key, sides), std::move(samples)).first->second;
}

Contour loadContour(const std::string& file) {
  // The reader is the one curveX/Y/Z use (lsys): every cuspy version, cver 1.0 to 1.3 and the
  // older `version: 1.4` curve format.
  return contourOfCurve(ContourCurve::load(file), file);
}

Contour contourOfCurve(const ContourCurve& curve, const std::string& file) {
  Contour contour;
  contour.name = curve.name();
  contour.closed = curve.closed();
  for (const std::array<double, 3>& p : curve.controlPoints()) {
    contour.controlPoints.emplace_back(p[0], p[1], p[2]);
  }
  if (!(curve.length() > 0.0)) {
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(file), 0, 0},
                          "the contour has no extent: all its control points coincide");
  }
  return contour;
}

}  // namespace hirsute
