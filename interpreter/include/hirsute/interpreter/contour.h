// Cross-section contours of generalized cylinders: cpfg's `.con` files (`contour: id file`) and
// the built-in circle, resampled to a number of sides as cpfg does
// (cpfg-generalized-cylinders.md §3).
#pragma once

#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

#include "hirsute/lsys/function_curve.h"

namespace hirsute {

// A contour resampled to `sides` points: positions and outward normals in the contour plane
// (x along the turtle's U, y along -L). Closed contours have `sides` points (the seam is not
// repeated); open contours have sides + 1, from one edge to the other.
struct ContourSamples {
  std::vector<glm::dvec2> points;
  std::vector<glm::dvec2> normals;
  // The contour's z at each sample: cpfg adds z·H/len to ring vertices
  // (cpfg-generalized-cylinders.md §2). Zero for the circle and for cuspy's planar contours.
  std::vector<double> z;
  bool closed = true;
  // Perimeter (closed) or edge-to-edge length (open) of the resampled polygon, for a radius of
  // 1: the girth of the faces actually drawn.
  double length = 0;
};

// Side counts are clamped to [3, kMaxContourSides] (cpfg: fewer than 3 sides read as 3).
inline constexpr int kMaxContourSides = 4096;

// A contour as read from its file: the B-spline control points with multiplicities expanded.
struct Contour {
  std::string name;
  bool closed = true;
  std::vector<glm::dvec3> controlPoints;
};

class ContourLibrary {
 public:
  void add(int id, Contour contour);
  bool has(int id) const { return contours_.count(id) != 0; }
  // The samples of contour `id` (0 or unknown: the unit circle) with `sides` sides; computed
  // once per (id, sides). The reference stays valid while the library lives. Not thread-safe:
  // the cache fills on first use.
  const ContourSamples& samples(int id, int sides) const;

 private:
  std::map<int, Contour> contours_;
  mutable std::map<std::pair<int, int>, ContourSamples> cache_;
};

// Reads a `.con` file (versions 1.0 to 1.4). Throws DiagnosticError at the broken line.
Contour loadContour(const std::string& file);
// The same from a curve already read (the contour editor's); `file` names it in messages.
Contour contourOfCurve(const ContourCurve& curve, const std::string& file);

}  // namespace hirsute
