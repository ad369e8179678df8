// Shape of a Taylor-anvil rod from its volume-fraction field: the recovered length and the
// footprint (impact-face) diameter, on a quarter-symmetry mesh whose rod axis is the z axis
// (the line x = y = 0, the mesh's lower x and y faces are the symmetry planes) and whose wall
// is the plane z = 0 (the mesh's lower z face). Host-only: it reads a gathered global array
// (test::gather, x fastest).
#pragma once
#include <cmath>
#include <vector>

namespace mp::test {

struct TaylorShape {
  // Primary measures (the issue's): the 0.5 contour of the rod's volume fraction
  double length = NAN;     // along the axis column (i = j = 0), interpolated between centres
  double footprint = NAN;  // 2 x its radius along the x and y rows of the wall layer (k = 0)
  // Cross-checks, less sensitive to one cell's fraction
  double length_column = NAN;   // sum of fraction x dz over the axis column
  double footprint_area = NAN;  // 2 x sqrt(4 A / pi), A = quarter area (sum fraction x dx dy)
  double length_any = NAN;      // top face of the highest cell anywhere with fraction > 0.5
};

namespace detail {

// Where f, sampled at centres x0 + (n + 1/2) h, last crosses 0.5 going outward (the outermost
// crossing from >= 0.5 to < 0.5), linearly interpolated; the end of the line if it never drops.
inline double outer_half_crossing(const std::vector<double>& f, double x0, double h) {
  const int n = static_cast<int>(f.size());
  for (int a = n - 2; a >= 0; --a)
    if (f[a] >= 0.5 && f[a + 1] < 0.5)
      return x0 + (a + 0.5) * h + (f[a] - 0.5) / (f[a] - f[a + 1]) * h;
  if (n > 0 && f[n - 1] >= 0.5) return x0 + n * h;
  // f[0] < 0.5: the contour lies inside the first cell (between the boundary, where f is
  // taken as 1 by symmetry or contact, and the first centre)
  return n > 0 && f[0] > 0 ? x0 + f[0] * h : x0;
}

}  // namespace detail

// `frac`: the rod material's volume fraction, global cells nx * ny * nz, x fastest;
// cell sizes dx, dy, dz; the mesh's lower corner at (0, 0, 0).
inline TaylorShape measure_taylor(const std::vector<double>& frac, int nx, int ny, int nz,
                                  double dx, double dy, double dz) {
  auto at = [&](int i, int j, int k) { return frac[i + static_cast<long>(nx) * (j + ny * k)]; };
  TaylorShape s;
  std::vector<double> col(nz);
  double sum = 0;
  for (int k = 0; k < nz; ++k) {
    col[k] = at(0, 0, k);
    sum += col[k] * dz;
  }
  s.length = detail::outer_half_crossing(col, 0, dz);
  s.length_column = sum;

  std::vector<double> row_x(nx), row_y(ny);
  for (int i = 0; i < nx; ++i) row_x[i] = at(i, 0, 0);
  for (int j = 0; j < ny; ++j) row_y[j] = at(0, j, 0);
  s.footprint =
      detail::outer_half_crossing(row_x, 0, dx) + detail::outer_half_crossing(row_y, 0, dy);
  double area = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) area += at(i, j, 0) * dx * dy;
  s.footprint_area = 2 * std::sqrt(4 * area / M_PI);

  int top = -1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (at(i, j, k) > 0.5) top = k;
  s.length_any = (top + 1) * dz;
  return s;
}

}  // namespace mp::test
