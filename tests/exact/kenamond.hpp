// Exact lighting times of the Kenamond high-explosive burn-table problems (M. A. Kenamond, "HE
// Burn Table Verification Problems", LA-UR-11-03096, Los Alamos, 2011; formulas as documented
// by LANL's ExactPack, exactpack/solvers/kenamond/kenamond1.py and kenamond3.py, written here
// from the geometry, not from that code):
// - problem 1: one point detonator in an unbounded explosive, t = t_d + |x - x_d| / D;
// - problem 3: the same around an inert sphere (3-D) or circle (2-D) of radius R centred at
//   the origin. Where the segment from the detonator to x misses the obstacle the time is the
//   line-of-sight one; otherwise (the shadow) the front wraps the obstacle along the shortest
//   path in the plane through the origin, x_d and x: the tangent from x_d (length
//   sqrt(|x_d|^2 - R^2)), an arc of angle theta on the obstacle and the tangent to x,
//     theta = angle(x_d, x) - acos(R / |x_d|) - acos(R / |x|),
//     t = t_d + (sqrt(|x_d|^2 - R^2) + R theta + sqrt(|x|^2 - R^2)) / D.
// Kenamond's defaults (ExactPack): problem 3 with R = 3, D = 2, x_d = (0, 5), t_d = 0.
// Double precision throughout (a reference, not a kernel).
#pragma once
#include <array>
#include <cmath>
#include <stdexcept>

namespace mp::exact {

using Point3 = std::array<double, 3>;

inline double kenamond_norm(const Point3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

// Problem 1.
inline double kenamond1_time(const Point3& x, const Point3& xd, double d, double td = 0) {
  return td + kenamond_norm({x[0] - xd[0], x[1] - xd[1], x[2] - xd[2]}) / d;
}

// True when the segment xd -> x passes through the open ball |y| < r.
inline bool segment_hits_ball(const Point3& xd, const Point3& x, double r) {
  const Point3 s{x[0] - xd[0], x[1] - xd[1], x[2] - xd[2]};
  const double ss = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
  if (ss == 0) return false;
  // Closest point of the segment to the origin: xd + u s, u in [0, 1].
  double u = -(xd[0] * s[0] + xd[1] * s[1] + xd[2] * s[2]) / ss;
  u = std::fmin(1.0, std::fmax(0.0, u));
  const Point3 c{xd[0] + u * s[0], xd[1] + u * s[1], xd[2] + u * s[2]};
  return kenamond_norm(c) < r;
}

// Problem 3: inert ball of radius r at the origin; x and xd outside it.
inline double kenamond3_time(const Point3& x, const Point3& xd, double r, double d, double td = 0) {
  const double lx = kenamond_norm(x), ld = kenamond_norm(xd);
  if (lx < r || ld <= r) throw std::invalid_argument("kenamond3_time: point inside the obstacle");
  if (!segment_hits_ball(xd, x, r)) return kenamond1_time(x, xd, d, td);
  const double cosang = (x[0] * xd[0] + x[1] * xd[1] + x[2] * xd[2]) / (lx * ld);
  const double angle = std::acos(std::fmax(-1.0, std::fmin(1.0, cosang)));
  const double theta = angle - std::acos(r / ld) - std::acos(r / lx);
  return td + (std::sqrt(ld * ld - r * r) + r * theta + std::sqrt(lx * lx - r * r)) / d;
}

}  // namespace mp::exact
