// 3-D verification: Sedov's point blast (shock radius, symmetry) and Noh's implosion (plateau).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "exact/norms.hpp"
#include "support.hpp"

using namespace mp;

namespace {

// The spherically averaged crossing of `level` by the density binned in radius (shared with
// the speed/accuracy harness: tests/exact/norms.hpp).
double shock_radius(const Mesh& m, const std::vector<double>& rho, double level) {
  return exact::octant_shock_radius(rho, m.global_cells(0), m.dx(0), level);
}

// Largest difference between the density and its images under the three axis swaps, relative
// to the peak density.
double permutation_asymmetry(const std::vector<double>& rho, int n, double* peak) {
  double dxy = 0, dxz = 0, dyz = 0, rmax = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double a = rho[i + n * (j + n * k)];
        rmax = std::max(rmax, a);
        dxy = std::max(dxy, std::abs(a - rho[j + n * (i + n * k)]));
        dxz = std::max(dxz, std::abs(a - rho[k + n * (j + n * i)]));
        dyz = std::max(dyz, std::abs(a - rho[i + n * (k + n * j)]));
      }
  std::printf("  |rho - rho(permuted)| / peak: x<->y %.3e, x<->z %.3e, y<->z %.3e\n", dxy / rmax,
              dxz / rmax, dyz / rmax);
  *peak = rmax;
  return std::max({dxy, dxz, dyz}) / rmax;
}

}  // namespace

TEST(Sedov, ShockRadiusAndSymmetry) {
  auto r = test::run_scene(test::load_scene("sedov.yaml"));
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  const Mesh& m = r.sim->mesh();
  const auto rho = test::gather(m, r.sim->hydro().state().rho, Centering::Cell);
  const int n = m.global_cells(0);
  // R = (E t^2 / (alpha rho0))^(1/5) with E = alpha = 0.851072 (full sphere): R = t^(2/5).
  const double exact = std::pow(0.41, 0.4);
  // The shock is where the density crosses halfway between ambient (1) and the exact jump
  // (gamma+1)/(gamma-1) = 6.
  const double radius = shock_radius(m, rho, 3.5);
  std::printf("Sedov: %ld cycles, shock radius %.4f, exact %.4f, error %.2f %% (dx = %.4f)\n",
              r.result.cycles, radius, exact, 100 * (radius / exact - 1), m.dx(0));
  EXPECT_NEAR(radius / exact, 1.0, 0.02);

  // Symmetry under permutations of the axes. The Lagrangian phase is symmetric; the split
  // remap alternates x,y,z and z,y,x, so swapping axes changes the splitting error, not only
  // round-off: measured at 48^3, 1.5e-3 of the peak density. The unsplit remap (next test) is
  // symmetric to round-off.
  double peak = 0;
  const double asym = permutation_asymmetry(rho, n, &peak);
  std::printf("Sedov (split remap): asymmetry %.3e of the peak density %.3f\n", asym, peak);
  EXPECT_LT(asym, 3e-3);
  const double de = (r.result.end.total() - r.result.start.total()) / r.result.start.total();
  std::printf("Sedov: relative total energy change %.3e, round-off bound %.3e\n", de,
              test::energy_roundoff(r.result.cycles));
  // Closed box (reflective walls; the blast has not reached them) and the KE fix returns the
  // remap's whole discrepancy: round-off only (test::energy_roundoff; observed -8.5e-13 in
  // double, 0.4x the bound). Until 2026-11 the fix returned only dissipation: +2.3e-3.
  EXPECT_LT(std::abs(de), test::energy_roundoff(r.result.cycles));
}

TEST(Sedov, UnsplitRemapIsSymmetricToRoundOff) {
  auto r = test::run_scene(test::load_scene("sedov.yaml", {"numerics.remap=unsplit"}));
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  const Mesh& m = r.sim->mesh();
  const auto rho = test::gather(m, r.sim->hydro().state().rho, Centering::Cell);
  const int n = m.global_cells(0);
  const double exact = std::pow(0.41, 0.4);
  const double radius = shock_radius(m, rho, 3.5);
  double peak = 0;
  const double asym = permutation_asymmetry(rho, n, &peak);
  std::printf(
      "Sedov (unsplit remap): %ld cycles, shock radius %.4f (exact %.4f, error %.2f %%), "
      "asymmetry %.3e of the peak density %.3f\n",
      r.result.cycles, radius, exact, 100 * (radius / exact - 1), asym, peak);
  EXPECT_NEAR(radius / exact, 1.0, 0.02);
  EXPECT_LT(asym, test::roundoff(1e-12));
}

TEST(Noh, PostShockPlateau) {
  auto r = test::run_scene(test::load_scene("noh.yaml"));
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  const Mesh& m = r.sim->mesh();
  const auto rho = test::gather(m, r.sim->hydro().state().rho, Centering::Cell);
  const int n = m.global_cells(0);
  const double h = m.dx(0), t = r.result.time;
  const double rs = t / 3;  // shock radius
  // Cells well inside the shock but away from the origin's wall heating.
  double sum = 0, lo = 1e30, hi = 0;
  int count = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double rr =
            h * std::sqrt((i + 0.5) * (i + 0.5) + (j + 0.5) * (j + 0.5) + (k + 0.5) * (k + 0.5));
        if (rr > 0.4 * rs && rr < rs - 3 * h) {
          const double a = rho[i + n * (j + n * k)];
          sum += a;
          lo = std::min(lo, a);
          hi = std::max(hi, a);
          ++count;
        }
      }
  const double mean = sum / count;
  std::printf(
      "Noh: %ld cycles, plateau (%d cells, %.3f < r < %.3f): mean %.2f, min %.2f, max "
      "%.2f (exact 64)\n",
      r.result.cycles, count, 0.4 * rs, rs - 3 * h, mean, lo, hi);
  ASSERT_GT(count, 100);
  EXPECT_NEAR(mean / 64.0, 1.0, 0.05);
}
