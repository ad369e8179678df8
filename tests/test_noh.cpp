// 3-D verification: Noh's spherical implosion (plateau, checkerboard, shock radius, wall
// heating). Noh.* (the fast path): the errors falling from 32^3 to 48^3. NohLong.* (CTest entry
// test_noh_long_np1, label long; ci/long.sh runs it in the double build): issue #16's targets at
// its resolutions, 64^3 and 96^3 (96^3 alone is 5x the cost of 64^3: 274 cycles of 885k cells).
// Its own executable (split from test_blast.cpp, 2026-12-05), so that CTest runs it beside the
// Sedov tests.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "exact/norms.hpp"
#include "support.hpp"

using namespace mp;

namespace {

// Noh's spherical implosion (configs/noh.yaml, the default numerics: KE fix on, tensor
// viscosity, mid-step geometry) at 64^3 and 96^3, measured as tools/noh_check.py does: the plateau
// mean over 0.3 R < r < 0.8 R (R = t/3; inside it the exact density is 64), the checkerboard (mean
// |rho - mean of its 6 face neighbours| / 64 over the same cells) and the shock radius from
// the volume of cells above rho = 40.
struct NohMeasure {
  double plateau = 0, checker = 0, radius = 0;
  int cells = 0;
  // mean density of the cells whose centres lie at s h <= r < (s + 1) h, s = 0 .. 5 (the wall
  // heating's shells, as tools/noh_check.py prints them)
  double shell[6] = {0, 0, 0, 0, 0, 0};
};

// The deck at h = 1/per_unit; with `box` < 1, on the smaller octant [0, box]^3 (box x per_unit
// whole cells).
// Every parcel inside the shock at t = 0.6 started within R + t = 0.8 of the origin (unit
// inflow speed), inside the sphere the box [0, 0.875]^3 holds; the gas that enters through its
// outflow faces after t = 0 is still ahead of the shock at the end (r > 0.875 - 0.6 = 0.275 >
// R = 0.2 along the axes). Observed (2026-12-06, tools/noh_check.py): h = 1/64 and 1/96 on
// [0, 0.875]^3 (56^3 and 84^3 cells) give the full box's plateau, checkerboard, shock radius
// and shells to the digits printed (-4.76 / -3.82 %, 2.70 / 2.18 %, +0.75 / +0.81 %), at 0.67
// of the cost (29 s and 121 s of one thread); [0, 0.8125]^3 moves the 64^3 plateau to -4.75 %,
// and at 32^3 the radius by 0.7 points.
constexpr double kBox = 0.875;

NohMeasure noh_at(int per_unit, double box = 1.0, const std::vector<std::string>& extra = {}) {
  const int n = static_cast<int>(std::lround(per_unit * box));
  const std::string c = std::to_string(n);
  char hi[96];
  std::snprintf(hi, sizeof hi, "mesh.hi=[%.17g,%.17g,%.17g]", box, box, box);
  std::vector<std::string> ov = {"mesh.cells=[" + c + "," + c + "," + c + "]", hi};
  ov.insert(ov.end(), extra.begin(), extra.end());
  auto r = test::run_scene(test::load_scene("noh.yaml", ov));
  NohMeasure out;
  EXPECT_TRUE(r.result.ok) << r.result.health.what;
  if (!r.result.ok) return out;
  const Mesh& m = r.sim->mesh();
  const auto rho = test::gather(m, r.sim->hydro().state().rho, Centering::Cell);
  const double h = m.dx(0), rs = r.result.time / 3;
  const auto at = [&](int i, int j, int k) { return rho[i + n * (j + n * k)]; };
  double sum = 0, chk = 0, shell_sum[6] = {0, 0, 0, 0, 0, 0};
  long above = 0, inner = 0, shell_cells[6] = {0, 0, 0, 0, 0, 0};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (at(i, j, k) > 40) ++above;
        const double rr = exact::octant_radius(i, j, k, h);
        const int s = static_cast<int>(rr / h);
        if (s < 6) {
          shell_sum[s] += at(i, j, k);
          ++shell_cells[s];
        }
        if (!(rr > 0.3 * rs && rr < 0.8 * rs)) continue;
        sum += at(i, j, k);
        ++out.cells;
        // the checkerboard over the cells with all six neighbours (not on a symmetry plane)
        if (i == 0 || j == 0 || k == 0) continue;
        const double mean6 = (at(i - 1, j, k) + at(i + 1, j, k) + at(i, j - 1, k) +
                              at(i, j + 1, k) + at(i, j, k - 1) + at(i, j, k + 1)) /
                             6;
        chk += std::abs(at(i, j, k) - mean6);
        ++inner;
      }
  out.plateau = sum / out.cells / 64 - 1;
  out.checker = chk / inner / 64;
  out.radius = std::cbrt(double(above) * h * h * h * 6 / M_PI) / rs - 1;
  for (int s = 0; s < 6; ++s) out.shell[s] = shell_cells[s] ? shell_sum[s] / shell_cells[s] : 0;
  std::printf(
      "Noh h = 1/%d on %d^3 cells%s (t = %.3f, %ld cycles): plateau %+.2f %% over %d cells, "
      "checkerboard %.2f %%, "
      "shock radius %+.2f %%, shells %.1f %.1f %.1f %.1f %.1f %.1f\n",
      per_unit, n, extra.empty() ? "" : (" " + extra[0]).c_str(), r.result.time, r.result.cycles,
      100 * out.plateau, out.cells, 100 * out.checker, 100 * out.radius, out.shell[0], out.shell[1],
      out.shell[2], out.shell[3], out.shell[4], out.shell[5]);
  return out;
}

}  // namespace

// The fast path's check: the same measures at 32^3 and 48^3 (4 s and 20 s of one thread against
// 60 s and 300 s for 64^3 and 96^3). Observed (2026-12-07, double, the default time step
// cloverleaf, 114 / 133 cycles): plateau -8.14 / -5.83 % (ratio 0.72, order 0.82), checkerboard
// 2.69 / 2.46 %, shock radius -0.55 / +0.77 %, inner shells from 54.4 / 58.5 up (under the
// combined rule, 134 / 167 cycles: -8.82 / -6.31 %, 2.79 / 2.93 %, -1.05 / +0.34 %, 53.9 /
// 57.1). Bounds: the plateau within 10 % / 7 % (1.23x, 1.20x) and falling (ratio below 0.85,
// 1.2x above the observed); the checkerboard within 3.5 % at both (1.30x, 1.42x: it does not
// fall much on these meshes); the shock radius within issue #16's 2 % (its error changes sign
// between the two, so no rate); at 48^3 every shell above 0.85 x 64 = 54.4 (min 58.5).
TEST(Noh, PlateauConvergesFrom32To48Cubed) {
  const NohMeasure a = noh_at(32);
  const NohMeasure b = noh_at(48);
  ASSERT_GT(a.cells, 50);  // (observed 65 and 227)
  EXPECT_LT(std::abs(a.plateau), 0.10);
  EXPECT_LT(std::abs(b.plateau), 0.07);
  EXPECT_LT(std::abs(b.plateau), 0.85 * std::abs(a.plateau));
  EXPECT_LT(a.checker, 0.035);
  EXPECT_LT(b.checker, 0.035);
  EXPECT_LT(std::abs(a.radius), 0.02);
  EXPECT_LT(std::abs(b.radius), 0.02);
  for (int s = 0; s < 6; ++s) EXPECT_GT(b.shell[s], 0.85 * 64) << "shell " << s;
}

// Issue #16's targets at 64^3 and 96^3, the resolutions it names. Observed (double,
// 2026-12-05; the same on 2026-12-06 but for the checkerboard, 2.70 / 2.18 %, and the radius at
// 96^3, +0.81 %; configs/noh.yaml with the default mid-step geometry and heat flux h = 16, the
// linear viscosity on the sum of the limited per-axis jumps): plateau -4.75 / -3.81 %,
// checkerboard 2.74 / 2.34 %, shock radius +0.75 / +0.76 %, shells 61.3 63.1 62.9 61.4 61.2 61.4
// and 61.7 64.0 63.3 62.2 62.0 61.8. Bounds, #16's targets: the plateau within 5 % of 64 at
// both and the finer mesh better; the checkerboard at most 3 % at both and falling; the shock
// radius within 2 % of t/3. Both linear and quadratic terms on the norm of the jumps (before
// 2026-12-05, seventh session) gave -4.40 / -3.63 %, 3.63 / 2.96 %, +0.75 / +0.69 %: it fails
// the checkerboard bound at 64^3; both on their sum -5.25 / -3.99 %, 1.75 / 1.47 %: it fails
// the plateau bound at 64^3 (docs/numerics.md, "Tensor viscosity"). With the fixed geometry
// (numerics.geometry=fixed, "Mid-step geometry") the norm gave -7.00 / -5.21 %, 3.20 / 2.63 %,
// +2.28 / +1.85 %: it fails the plateau bound at both and the radius bound at 64^3. Without the
// heat flux (numerics.heat_flux=0) the checkerboard was 11.09 % at 64^3 and the inner shells
// 39.9 .. 52.4: it fails the checkerboard and shell bounds. The wall heating (Noh's density
// deficit at the origin) is gone: every radial shell from the origin out holds more than
// 0.85 x 64 = 54.4. The error is first order in h / R at best (the discrete solution depends on
// R / h alone). Until 2026-12-05 the test ran 48^3 and 64^3 with bounds 10.5 / 8.4 % (plateau),
// 3.75 / 3.52 % (checkerboard) and 3 % (radius); then 64^3 and 96^3 with the checkerboard
// within 3.8 / 3.1 %.
// Labelled long (issue #55): ci/long.sh runs it in the double build, the float build's suite
// leaves it out (before, the float build ran 64^3 alone). Bounds: the targets, side by side
// with the observations (2026-12-07, the default cloverleaf step, 154 / 198 cycles: plateau
// -4.60 / -3.63 % against 5 %: 1.09x and 1.38x; checkerboard 2.30 / 2.11 % against 3 %: 1.30x
// and 1.42x; radius +0.75 / +0.89 % against 2 %; shells from 60.8 / 61.4; the combined rule's
// are above).
// Run on the octant [0, 0.875]^3 (56^3 and 84^3 cells, noh_at above; 0.67 of the full box's
// cost, the same numbers).
TEST(NohLong, Issue16TargetsAt64And96Cubed) {
  const NohMeasure a = noh_at(64, kBox);
  ASSERT_GT(a.cells, 100);  // (observed 553 and 1794)
  EXPECT_LT(std::abs(a.plateau), 0.05);
  EXPECT_LT(a.checker, 0.03);
  EXPECT_LT(std::abs(a.radius), 0.02);
  for (int s = 0; s < 6; ++s) EXPECT_GT(a.shell[s], 0.85 * 64) << "shell " << s;
  const NohMeasure b = noh_at(96, kBox);
  EXPECT_LT(std::abs(b.plateau), 0.05);
  EXPECT_LT(std::abs(b.plateau), std::abs(a.plateau));
  EXPECT_LT(b.checker, 0.03);
  EXPECT_LT(b.checker, a.checker);
  EXPECT_LT(std::abs(b.radius), 0.02);
  for (int s = 0; s < 6; ++s) EXPECT_GT(b.shell[s], 0.85 * 64) << "shell " << s;
}

// The third-order remap (numerics.advection: third) at 64^3 (h = 1/64 on the octant box, which
// gives the full box's numbers) against the default second order (issue #53;
// docs/studies/2026-12-06-third-order.md), both runs shared by the two tests below (label long).
// Observed (2026-12-06, the combined step, second / third): plateau -4.76 / -4.09 %,
// checkerboard 2.70 / 2.86 %, shock radius +0.75 / +0.75 %, inner shells 61.3 63.1 62.9 / 66.2
// 65.1 64.5. Under the default cloverleaf step (2026-12-07, 154 / 155 cycles): plateau -4.60 /
// -3.96 %, checkerboard 2.30 / 2.38 %, radius +0.75 / +0.75 %, shells 60.8 64.2 63.1 / 65.1
// 65.8 64.5.
namespace {
const std::pair<NohMeasure, NohMeasure>& noh_orders() {
  static const std::pair<NohMeasure, NohMeasure> r{noh_at(64, kBox),
                                                   noh_at(64, kBox, {"numerics.advection=third"})};
  return r;
}
}  // namespace

// The plateau and the shock radius: no more than 5 % worse with third order (the issue's bound).
TEST(NohLong, ThirdOrderPlateauAndRadiusNoWorseThanSecond) {
  const NohMeasure& s = noh_orders().first;
  const NohMeasure& t = noh_orders().second;
  ASSERT_GT(t.cells, 100);
  EXPECT_LE(std::abs(t.plateau), 1.05 * std::abs(s.plateau));
  EXPECT_LE(std::abs(t.radius), 1.05 * std::abs(s.radius));
  for (int q = 0; q < 6; ++q) EXPECT_GT(t.shell[q], 0.85 * 64) << "shell " << q;
}

// A regression pin, not a verification: the checkerboard is 1.03x second order's with third
// order (2.38 against 2.30 % under the default cloverleaf step; 2.86 against 2.70 % under the
// combined one; the issue's bound is 5 %), still within issue #16's 3 %. Bound: 1.1x the value
// observed under the combined step (1.32x today's).
TEST(NohLongPin, ThirdOrderCheckerboard) {
  EXPECT_LE(noh_orders().second.checker, 1.1 * 0.0286);
}
