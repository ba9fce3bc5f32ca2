// Spacing measures of point sets on the unit torus [0,1)², used to measure the quality of the
// point-diffusion texture rather than assume it (docs/design.md, "Placement").
#pragma once

#include <span>
#include <vector>

namespace hirsute {

struct TorusPoint {
  double u = 0;
  double v = 0;
};

// The shortest offset from a to b on the unit torus, each component in [-0.5, 0.5].
TorusPoint toroidalOffset(const TorusPoint& a, const TorusPoint& b);

// For every point, the toroidal distance to its nearest other point (a grid of buckets, so
// near-linear in the number of points). Fewer than two points: every distance is 0.
std::vector<double> nearestNeighbourDistances(std::span<const TorusPoint> points);

// Lagae & Dutré 2008, "A Comparison of Methods for Generating Poisson Disk Distributions",
// Sec. 2: the relative radius ρ = r / r_max, with r half the smallest distance between two points
// and r_max = sqrt(1 / (2·sqrt(3)·N)) the radius of the densest packing of N disks in the unit
// torus (hexagonal). ρ near 1 is hexagonal order; dart throwing reaches about 0.75; a uniform
// random set is near 0. Fewer than two points: 0.
double relativeRadius(std::span<const TorusPoint> points);

}  // namespace hirsute
