// Exact orientation predicates: a floating-point filter with a static error bound, GMP rationals
// behind it.
#include "hirsute/hairs/dynamics/exact_predicates.h"

#include <gmpxx.h>

#include <cmath>
#include <initializer_list>
#include <stdexcept>

namespace hirsute::dynamics {
namespace {

// Half an ulp of 1: the relative error of one rounded operation.
constexpr double kEpsilon = 0x1p-53;
// Shewchuk 1997, Sec. 4: |fl(det) - det| <= bound * permanent for these evaluation orders.
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;
// The bounds are relative and ignore underflow: below this permanent the products may lose
// absolute accuracy to subnormals, and the exact path decides.
constexpr double kSmallestFilteredPermanent = 0x1p-900;

int signOf(const mpq_class& value) {
  return sgn(value);
}

int filteredSign(double det, double permanent, double relativeBound) {
  if (!std::isfinite(det) || !std::isfinite(permanent) || permanent < kSmallestFilteredPermanent) {
    return 2;  // undecided
  }
  const double bound = relativeBound * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return 2;
}

// GMP cannot hold an infinity or a NaN (it traps on them).
void requireFinite(std::initializer_list<const Eigen::Vector3d*> points) {
  for (const Eigen::Vector3d* p : points) {
    if (!p->allFinite()) throw std::invalid_argument("an orientation test of a non-finite point");
  }
}

int exactOrient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d) {
  requireFinite({&a, &b, &c, &d});
  mpq_class m[3][3];
  const Eigen::Vector3d* rows[3] = {&a, &b, &c};
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) m[r][k] = mpq_class((*rows[r])[k]) - mpq_class(d[k]);
  }
  mpq_class det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                  m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                  m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return signOf(det);
}

}  // namespace

int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d) {
  const double adx = a.x() - d.x(), bdx = b.x() - d.x(), cdx = c.x() - d.x();
  const double ady = a.y() - d.y(), bdy = b.y() - d.y(), cdy = c.y() - d.y();
  const double adz = a.z() - d.z(), bdz = b.z() - d.z(), cdz = c.z() - d.z();
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  const int sign = filteredSign(det, permanent, kOrient3dBound);
  return sign != 2 ? sign : exactOrient3d(a, b, c, d);
}

int orient2d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int i,
             int j) {
  const double acx = a[i] - c[i], bcx = b[i] - c[i];
  const double acy = a[j] - c[j], bcy = b[j] - c[j];
  const double left = acx * bcy, right = acy * bcx;
  const double det = left - right;
  const double permanent = std::abs(left) + std::abs(right);
  const int sign = filteredSign(det, permanent, kOrient2dBound);
  if (sign != 2) return sign;
  requireFinite({&a, &b, &c});
  const mpq_class ax(a[i]), ay(a[j]), bx(b[i]), by(b[j]), cx(c[i]), cy(c[j]);
  return signOf((ax - cx) * (by - cy) - (ay - cy) * (bx - cx));
}

}  // namespace hirsute::dynamics
