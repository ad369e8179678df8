// Error measures against the exact solutions, shared by the tests and the speed/accuracy
// harness (perf/tradeoff.cpp), so that both report the same numbers.
#pragma once
#include <cmath>
#include <vector>

#include "mader.hpp"
#include "noh.hpp"
#include "riemann.hpp"
#include "sedov.hpp"

namespace mp::exact {

// L1 norm of a 1-D profile f at the points x (spacing dx) against exact(x): sum |f - exact| dx.
// The measures below are this with their exact solutions.
template <class Exact>
double l1_profile(const std::vector<double>& x, const std::vector<double>& f, double dx,
                  const Exact& exact) {
  double err = 0;
  for (std::size_t i = 0; i < x.size(); ++i) err += std::abs(f[i] - exact(x[i])) * dx;
  return err;
}

// Distance from the origin of the centre of octant cell (i, j, k), cells of size h.
inline double octant_radius(int i, int j, int k, double h) {
  return h * std::sqrt((i + 0.5) * (i + 0.5) + (j + 0.5) * (j + 0.5) + (k + 0.5) * (k + 0.5));
}

// L1 norm of the density error of a 1-D profile (cell centres x, spacing dx) against a Riemann
// problem with its diaphragm at x0, at time t.
inline double l1_density(const std::vector<double>& x, const std::vector<double>& rho, double dx,
                         const Riemann& rs, double x0, double t) {
  return l1_profile(x, rho, dx, [&](double xi) { return rs.sample((xi - x0) / t).rho; });
}

// L1 norm of the pressure error of a 1-D profile against a Riemann problem (as l1_density).
inline double l1_pressure(const std::vector<double>& x, const std::vector<double>& p, double dx,
                          const Riemann& rs, double x0, double t) {
  return l1_profile(x, p, dx, [&](double xi) { return rs.sample((xi - x0) / t).p; });
}

// L1 norm of the pressure error of a 1-D profile against the Mader solution at time t.
inline double l1_pressure(const std::vector<double>& x, const std::vector<double>& p, double dx,
                          const Mader& m, double t) {
  return l1_profile(x, p, dx, [&](double xi) { return m.sample(xi, t).p; });
}

// The largest mean density of the half-cell radial shells octant_shock_radius bins.
inline double octant_binned_peak(const std::vector<double>& rho, int n, double h) {
  std::vector<double> sum(2 * n, 0.0), cnt(2 * n, 0.0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int b = static_cast<int>(octant_radius(i, j, k, h) / (0.5 * h));
        if (b < 2 * n) {
          sum[b] += rho[i + n * (j + n * k)];
          cnt[b] += 1;
        }
      }
  double peak = 0;
  for (int b = 0; b < 2 * n; ++b)
    if (cnt[b] > 0) peak = std::max(peak, sum[b] / cnt[b]);
  return peak;
}

// The spherically averaged radius where a 3-D octant's density (n^3 cells of size h from the
// origin, x fastest) falls through `level` from inside, or NaN.
inline double octant_shock_radius(const std::vector<double>& rho, int n, double h, double level) {
  std::vector<double> sum(2 * n, 0.0), cnt(2 * n, 0.0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double r = octant_radius(i, j, k, h);
        const int b = static_cast<int>(r / (0.5 * h));
        if (b < 2 * n) {
          sum[b] += rho[i + n * (j + n * k)];
          cnt[b] += 1;
        }
      }
  for (int b = 2 * n - 2; b > 0; --b) {
    if (cnt[b] == 0 || cnt[b + 1] == 0) continue;
    const double a0 = sum[b] / cnt[b], a1 = sum[b + 1] / cnt[b + 1];
    if (a0 >= level && a1 < level) {
      const double r0 = (b + 0.5) * 0.5 * h, r1 = (b + 1.5) * 0.5 * h;
      return r0 + (level - a0) / (a1 - a0) * (r1 - r0);
    }
  }
  return NAN;
}

// L1 norm of the velocity error at the nodes x (spacing dx) against a Riemann problem with its
// diaphragm at x0, at time t.
inline double l1_velocity(const std::vector<double>& x, const std::vector<double>& u, double dx,
                          const Riemann& rs, double x0, double t) {
  return l1_profile(x, u, dx, [&](double xi) { return rs.sample((xi - x0) / t).u; });
}

// L1 norm of the density error of a 1-D profile (cell centres x measured from the wall) against
// planar Noh at time t.
inline double l1_density(const std::vector<double>& x, const std::vector<double>& rho, double dx,
                         const Noh& noh, double t) {
  return l1_profile(x, rho, dx, [&](double xi) { return noh.density(xi, t); });
}

// L1 norm of the error of a cell field over a 3-D octant (n^3 cells of size h from the origin,
// x fastest) against a radial profile exact(r): the integral of |f - exact(r)| over the cells
// whose centre lies within r_max of the origin.
template <class Exact>
double octant_l1(const std::vector<double>& f, int n, double h, const Exact& exact, double r_max) {
  double err = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double r = octant_radius(i, j, k, h);
        if (r < r_max) err += std::abs(f[i + n * (j + n * k)] - exact(r));
      }
  return err * h * h * h;
}

// The density's L1 over an octant against spherical Noh at time t, over r < r_max (a box's
// outflow faces do not supply the exact converging inflow; their error runs in with the gas,
// at speed u0, so by time t it has reached no closer to the origin than the faces' nearest
// distance minus u0 t).
inline double octant_l1_density(const std::vector<double>& rho, int n, double h, const Noh& noh,
                                double t, double r_max) {
  return octant_l1(
      rho, n, h, [&](double r) { return noh.density(r, t); }, r_max);
}

// The density's L1 over a whole octant against the Sedov blast with its shock at radius R.
inline double octant_l1_density(const std::vector<double>& rho, int n, double h, const Sedov& sd,
                                double R) {
  return octant_l1(
      rho, n, h, [&](double r) { return sd.density(r, R); }, INFINITY);
}

// The shape error of a transported body: the L1 difference of its final and initial volume
// fractions (cells of equal volume `cell`) relative to its initial volume. Zero when the
// transport returns the body to its start unchanged.
inline double shape_error(const std::vector<double>& f0, const std::vector<double>& f1,
                          double cell) {
  double err = 0, v0 = 0;
  for (std::size_t i = 0; i < f0.size(); ++i) {
    err += std::abs(f1[i] - f0[i]) * cell;
    v0 += f0[i] * cell;
  }
  return err / v0;
}

// The first node from x = 0 (nodes at i dx) where u falls below `level`, linearly interpolated,
// or NaN: the front of a wave running away from the wall at x = 0 (moving away means more
// negative u here).
inline double falling_front(const std::vector<double>& u, double dx, double level) {
  for (std::size_t i = 1; i < u.size(); ++i)
    if (u[i] < level && u[i - 1] >= level)
      return (double(i) - 1 + (level - u[i - 1]) / (u[i] - u[i - 1])) * dx;
  return NAN;
}

}  // namespace mp::exact
