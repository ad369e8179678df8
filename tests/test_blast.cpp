// 3-D verification: Sedov's point blast (shock radius, symmetry); Noh's implosion is in
// test_noh.cpp (its own executable, so that CTest runs the two long tests side by side).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "exact/norms.hpp"
#include "support.hpp"

using namespace mp;

namespace {

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

// One run of the Sedov deck (split remap unless overridden).
struct SedovRun {
  RunResult result;
  std::vector<double> rho;
  double radius = NAN, asym = NAN, peak = 0, dx = NAN;
  int n = 0;  // cells per axis
};

SedovRun run_sedov(const std::vector<std::string>& overrides) {
  auto r = test::run_scene(test::load_scene("sedov.yaml", overrides));
  SedovRun out;
  out.result = r.result;
  if (!r.result.ok) return out;
  const Mesh& m = r.sim->mesh();
  out.dx = m.dx(0);
  out.n = m.global_cells(0);
  out.rho = test::gather(m, r.sim->hydro().state().rho, Centering::Cell);
  return out;
}

// A run measured: the shock radius and the axis-swap asymmetry. Where the captured shock stands:
// the outermost crossing of the level halfway between the ambient density (1) and the binned
// profile's peak. (Halfway to the exact jump, 3.5, measured this until 2026-12-05; at 48^3 the
// captured peak is only 3.5-3.6, so that level sat on the peak itself and moved with its shape:
// -0.88 % with the scalar viscosity, whose peak was 3.507, -2.41 % with the tensor one, whose
// peak is 3.587 and whose foot reaches further out.)
SedovRun measured(SedovRun out) {
  if (!out.result.ok) return out;
  out.radius = exact::octant_shock_radius(
      out.rho, out.n, out.dx, 0.5 * (1 + exact::octant_binned_peak(out.rho, out.n, out.dx)));
  out.asym = permutation_asymmetry(out.rho, out.n, &out.peak);
  return out;
}

// The deck as it is (48^3) and at 24^3, each run once per executable and shared by the tests
// below (CTest runs the verification, the consistency test and the pin as separate entries).
const SedovRun& sedov_split() {
  static const SedovRun s = measured(run_sedov({}));
  return s;
}

const SedovRun& sedov_coarse() {
  static const SedovRun s = measured(run_sedov({"mesh.cells=[24,24,24]"}));
  return s;
}

// L1(rho) over the octant against the exact profile (tests/exact/sedov.hpp) with the shock at
// R = t^(2/5), the measure the speed/accuracy harness (perf/tradeoff.cpp) reports for this scene.
double sedov_l1(const SedovRun& r) {
  return exact::octant_l1_density(r.rho, r.n, r.dx, exact::Sedov(3, 1.4), std::pow(0.41, 0.4));
}

}  // namespace

// The shock radius against R = (E t^2 / (alpha rho0))^(1/5) = t^(2/5) (E = alpha = 0.851072,
// full sphere) at 24^3 and 48^3, and total energy kept. The shock is where the density crosses
// halfway between ambient (1) and the captured peak (`measured` above; a measure of where
// the captured shock's middle is, chosen 2026-12-05 because halfway to the exact jump, 3.5, lies
// at or above the captured peak on these meshes: 2.80 at 24^3, 3.59 at 48^3). Observed
// (2026-12-07, double, the default cloverleaf step, 214 / 380 cycles): +0.56 % at 24^3, +0.45 %
// at 48^3 (the combined rule, 236 / 398 cycles: +0.53 %, +0.44 %; +0.38 % before the tensor
// viscosity's last change; the scalar viscosity's +1.86 % fails). Bounds: 1 % at both (1 % of R
// is 0.28 dx at 48^3, 0.14 dx at 24^3; 1.8x and 2.2x the observations) and the error falling
// (ratio 0.80; no theory gives a rate for this measure).
TEST(Sedov, ShockRadiusWithinOnePercentAtTwoResolutionsAndEnergyKept) {
  const SedovRun& c = sedov_coarse();
  const SedovRun& r = sedov_split();
  ASSERT_TRUE(c.result.ok) << c.result.health.what;
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  const double exact = std::pow(0.41, 0.4);
  for (const SedovRun* s : {&c, &r}) {
    std::printf(
        "Sedov %d^3: %ld cycles, shock radius %.4f, exact %.4f, error %.2f %% (dx = %.4f)\n", s->n,
        s->result.cycles, s->radius, exact, 100 * (s->radius / exact - 1), s->dx);
    EXPECT_NEAR(s->radius / exact, 1.0, 0.01) << s->n << "^3";
  }
  EXPECT_LT(std::abs(r.radius / exact - 1), std::abs(c.radius / exact - 1));
  const double de = (r.result.end.total() - r.result.start.total()) / r.result.start.total();
  std::printf("Sedov: relative total energy change %.3e, round-off bound %.3e\n", de,
              test::energy_roundoff(r.result.cycles));
  // Closed box (reflective walls; the blast has not reached them) and the KE fix returns the
  // remap's whole discrepancy: round-off only (test::energy_roundoff; observed -8.3e-13 in
  // double, 0.39x the bound 2.1e-12). Until 2026-11 the fix returned only dissipation: +2.3e-3.
  EXPECT_LT(std::abs(de), test::energy_roundoff(r.result.cycles));
}

// L1(rho) over the octant against the exact profile at 24^3 and 48^3 (the deck's mesh): below a
// bound at each, and falling. Observed (double, 1 thread, the default mid-step geometry; the
// same as build/perf/tradeoff --scenes sedov prints): 8.392e-2 at 24^3, 5.045e-2 at 48^3, ratio
// 0.601 (order 0.73; 6.917e-2 at 32^3). The fixed geometry gives 8.506e-2 and 5.088e-2. The
// convergence is slow and no theory gives its rate, so the bounds are margins on these
// observations, chosen so that the next-worse scheme fails them: 9.0e-2 (1.07x) and 5.6e-2
// (1.11x; 6.5e-2 until the mid-step geometry became the default, when 5.90e-2 was observed);
// first-order advection (numerics.advection=first) gives 9.957e-2 and 6.797e-2, over both
// bounds, and so does a 16^3 mesh against the 24^3 bound (1.011e-1 with the fixed geometry);
// the unsplit remap, equally second order, gives 8.63e-2 and 5.37e-2 and passes. The finer mesh
// must be at least 20 % lower (ratio below 0.8, 1.33x above the observed 0.601): an error that
// stopped falling with resolution fails it. Observed 2026-12-07 under the default cloverleaf
// step: 8.309e-2 (214 cycles) and 4.994e-2 (380 cycles), ratio 0.601 (the combined rule
// 8.351e-2 / 5.011e-2 in 236 / 398 cycles). The 24^3 run adds about 1.4 s to the 12 s of the
// 48^3 one.
TEST(Sedov, DensityL1FallsWithResolution) {
  const SedovRun& fine = sedov_split();
  ASSERT_TRUE(fine.result.ok) << fine.result.health.what;
  const SedovRun& coarse = sedov_coarse();
  ASSERT_TRUE(coarse.result.ok) << coarse.result.health.what;
  const double l1c = sedov_l1(coarse), l1f = sedov_l1(fine);
  std::printf("Sedov L1(rho): %d^3 %.4e (%ld cycles), %d^3 %.4e (%ld cycles), ratio %.3f\n",
              coarse.n, l1c, coarse.result.cycles, fine.n, l1f, fine.result.cycles, l1f / l1c);
  EXPECT_LT(l1c, 9.0e-2);
  EXPECT_LT(l1f, 5.6e-2);
  EXPECT_LT(l1f, 0.8 * l1c);
}

// A regression pin, not a verification: the split remap alternates x,y,z and z,y,x, so
// swapping axes changes the splitting error, not only round-off, and no theory gives its size.
// Measured at 24^3 since 2026-12-06 (its own CTest entry runs only this mesh): 9.53e-4 of the
// peak density under the default cloverleaf step (2026-12-07; 9.17e-4 under the combined rule),
// 1.62e-3 at 48^3 (combined 1.07e-3; the mesh of its earlier bound 3e-3; the fixed geometry gave
// 1.39e-3 there). Bound 2.5e-3 (2.6x), which catches a change of the splitting or a real
// asymmetry, e.g. an axis treated differently. The unsplit remap (next test) is symmetric to
// round-off.
TEST(SedovRegressionPin, SplitRemapAsymmetry) {
  const SedovRun& r = sedov_coarse();
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  std::printf("Sedov (split remap, %d^3): asymmetry %.3e of the peak density %.3f\n", r.n, r.asym,
              r.peak);
  EXPECT_LT(r.asym, 2.5e-3) << "pin of the split remap's splitting asymmetry (no exact value)";
}

// The unsplit remap treats the axes alike: symmetric to round-off under the axis swaps. At 24^3
// (48^3 until 2026-12-06, 16x the cost; symmetry does not depend on the mesh, and the shock
// radius it also checked there is the verification test's).
TEST(Sedov, UnsplitRemapIsSymmetricToRoundOff) {
  auto r = test::run_scene(
      test::load_scene("sedov.yaml", {"numerics.remap=unsplit", "mesh.cells=[24,24,24]"}));
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  const Mesh& m = r.sim->mesh();
  const auto rho = test::gather(m, r.sim->hydro().state().rho, Centering::Cell);
  const int n = m.global_cells(0);
  double peak = 0;
  const double asym = permutation_asymmetry(rho, n, &peak);
  std::printf("Sedov (unsplit remap, %d^3): %ld cycles, asymmetry %.3e of the peak density %.3f\n",
              n, r.result.cycles, asym, peak);
  // What differs under a permutation is the order of floating-point sums, a rounding of the
  // peak's size per cycle: 240 x 2.2e-16 = 5e-14 if all of one sign (observed at 48^3 2.9e-15;
  // at 24^3 2.1e-15, roundings of mixed sign cancel). Bound 1e-13; was 1e-12.
  EXPECT_LT(asym, test::roundoff(1e-13));
}

// The third-order remap (numerics.advection: third) at 24^3 and 48^3 against the default second
// order (issue #53; docs/studies/2026-12-06-third-order.md): L1(rho) and the half-peak shock
// radius's error, each run once for the two tests below. Observed (2026-12-06, the combined
// step, second / third): L1 8.351e-2 / 8.827e-2 at 24^3 and 5.011e-2 / 5.426e-2 at 48^3 (1.057x,
// 1.083x); |R/R_exact - 1| 5.30e-3 / 1.98e-3 and 4.40e-3 / 4.48e-3. Under the default cloverleaf
// step (2026-12-07, 214 / 222 and 380 / 382 cycles): L1 8.309e-2 / 8.792e-2 and 4.994e-2 /
// 5.396e-2 (1.058x, 1.080x); |R/R_exact - 1| 5.60e-3 / 2.29e-3 and 4.50e-3 / 4.62e-3 (1.026x,
// under the 1.05x bound).
namespace {
struct SedovOrders {
  double l1[2][2], radius[2][2];  // [second, third][24^3, 48^3]
};
const SedovOrders& sedov_orders() {
  static const SedovOrders o = [] {
    SedovOrders r{};
    const double exact = std::pow(0.41, 0.4);
    const auto measure = [&](const SedovRun& run, const char* what, int a, int n) {
      EXPECT_TRUE(run.result.ok) << what << ": " << run.result.health.what;
      r.l1[a][n] = sedov_l1(run);
      r.radius[a][n] = std::abs(exact::octant_shock_radius(
                                    run.rho, run.n, run.dx,
                                    0.5 * (1 + exact::octant_binned_peak(run.rho, run.n, run.dx))) /
                                    exact -
                                1);
      std::printf("Sedov %d^3 %s: L1(rho) %.4e, |R / R_exact - 1| %.4e (%ld cycles)\n", run.n, what,
                  r.l1[a][n], r.radius[a][n], run.result.cycles);
    };
    measure(run_sedov({"mesh.cells=[24,24,24]"}), "second", 0, 0);
    measure(run_sedov({"mesh.cells=[24,24,24]", "numerics.advection=third"}), "third", 1, 0);
    measure(sedov_split(), "second", 0, 1);
    measure(run_sedov({"numerics.advection=third"}), "third", 1, 1);
    return r;
  }();
  return o;
}
}  // namespace

// The shock radius: no more than 5 % worse with third order (the bound).
TEST(Sedov, ThirdOrderShockRadiusNoWorseThanSecond) {
  const SedovOrders& o = sedov_orders();
  for (int n = 0; n < 2; ++n) EXPECT_LE(o.radius[1][n], 1.05 * o.radius[0][n]) << n;
}

// A regression pin, not a verification: L1(rho) is 5.8 % and 8.0 % above second order's with
// third order (the bound is 5 %; the blast's hot, near-vacuum centre, as the expansion
// measures of test_hydro's ThirdOrderRegressionPin). Bounds: 1.1x the values observed under the
// combined step (8.827e-2, 5.426e-2), 1.10x and 1.11x those under the default cloverleaf step
// (8.792e-2, 5.396e-2).
TEST(SedovRegressionPin, ThirdOrderDensityL1) {
  const SedovOrders& o = sedov_orders();
  EXPECT_LE(o.l1[1][0], 1.1 * 8.827e-2);
  EXPECT_LE(o.l1[1][1], 1.1 * 5.426e-2);
}
