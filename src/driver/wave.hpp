// The smooth entropy waves of a region's `wave` block (config/scene.hpp) as point functions:
// the profile P(s), period 1 in s, and its exact mean over a cell, for the set-up (setup.cpp)
// and for the convergence tests' reference (the exact solution after whole periods is the
// initial state).
//   sine:    P(s) = sin(2 pi s)
//   plateau: 0 up to s = 0.05, the septic smoothstep S(t) = t^4 (35 - 84 t + 70 t^2 - 20 t^3)
//            (three continuous derivatives) up to 1 over 0.4, flat over 0.1, down again over
//            0.4, flat to s = 1. No extremum but flat plateaus: a limiter acts only where the
//            differences are those of the smoothstep's t^4 foot, so an advection scheme meets
//            its unlimited order there (the sine's extrema clip any TVD limiter).
// s is the coordinate along the wave's axis in units of the box length, or for the diagonal
// the sum of the three such coordinates.
#pragma once

#include <cmath>

#include "core/math.hpp"

namespace mp::wave {

enum Shape { kSine = 0, kPlateau = 1 };
inline constexpr int kDiagonal = 3;  // the wave's axis: 0, 1, 2, or the diagonal

KOKKOS_INLINE_FUNCTION double smoothstep7(double t) {
  if (t <= 0) return 0;
  if (t >= 1) return 1;
  return t * t * t * t * (35 + t * (-84 + t * (70 - 20 * t)));
}

KOKKOS_INLINE_FUNCTION double profile(int shape, double s) {
  const double f = s - MP_KOKKOS_MATH::floor(s);
  if (shape == kSine) return MP_KOKKOS_MATH::sin(2 * M_PI * f);
  return smoothstep7((f - 0.05) / 0.4) - smoothstep7((f - 0.55) / 0.4);
}

// The mean of P(s0 + w T) for T the sum of n (1 or 3) independent uniform [0, 1) variables:
// a cell of width w (box lengths) along the axis for n = 1, a cube of width w along every axis
// for the diagonal (n = 3; T's density is then the quadratic B-spline on [0, 3]). Gauss-Legendre
// with 8 nodes on each piece between the B-spline's knots and the plateau's joints: exact to
// round-off for the plateau's polynomial pieces (degree 7, times 2 for the B-spline), and to
// (2 pi w)^16 for the sine.
KOKKOS_INLINE_FUNCTION double cell_mean(int shape, double s0, double w, int n) {
  // nodes and weights on [-1, 1] (Abramowitz & Stegun, table 25.4, n = 8)
  constexpr double x[4] = {0.183434642495649805, 0.525532409916328986, 0.796666477413626740,
                           0.960289856497536232};
  constexpr double g[4] = {0.362683783378361983, 0.313706645877887287, 0.222381034453374471,
                           0.101228536290376259};
  // the pieces' ends in T: the knots 0 .. n and the plateau's joints (shape != sine)
  double cut[24];
  int nc = 0;
  for (int k = 0; k <= n; ++k) cut[nc++] = k;
  if (shape == kPlateau) {
    const double joints[4] = {0.05, 0.45, 0.55, 0.95};
    const double s1 = s0 + n * w;
    for (int p = int(MP_KOKKOS_MATH::floor(s0)); p <= int(MP_KOKKOS_MATH::floor(s1)); ++p)
      for (int q = 0; q < 4; ++q) {
        const double t = (p + joints[q] - s0) / w;
        if (t > 0 && t < n && nc < 24) cut[nc++] = t;
      }
  }
  for (int a = 1; a < nc; ++a)  // (insertion sort: a handful of entries)
    for (int b = a; b > 0 && cut[b - 1] > cut[b]; --b) {
      const double tmp = cut[b];
      cut[b] = cut[b - 1];
      cut[b - 1] = tmp;
    }
  auto density = [&](double t) {
    if (n == 1) return 1.0;
    if (t < 1) return 0.5 * t * t;
    if (t < 2) return 0.5 * (-2 * t * t + 6 * t - 3);
    return 0.5 * (3 - t) * (3 - t);
  };
  double sum = 0;
  for (int c = 1; c < nc; ++c) {
    const double lo = cut[c - 1], hi = cut[c];
    if (!(hi > lo)) continue;
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    for (int q = 0; q < 4; ++q)
      for (int sg = -1; sg <= 1; sg += 2) {
        const double t = mid + sg * half * x[q];
        sum += half * g[q] * density(t) * profile(shape, s0 + w * t);
      }
  }
  return sum;
}

}  // namespace mp::wave
