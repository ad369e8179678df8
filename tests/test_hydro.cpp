// Verification of the single-material hydro against exact solutions (issue: single-material
// hydro). Every test asserts numbers: error norms, observed orders, wave positions, plateaus.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "driver/wave.hpp"
#include "exact/norms.hpp"
#include "exact/riemann.hpp"
#include "support.hpp"

using namespace mp;

namespace {

struct Profile {
  std::vector<double> x, rho, e, u;
  double dx;
};

// Density, energy and x-velocity along x of a quasi-1-D run (row j = k = 0; cell-centred
// velocity as the mean of the node values on the cell's two faces).
Profile profile_x(const test::Ran& r) {
  const Mesh& m = r.sim->mesh();
  const auto& s = r.sim->hydro().state();
  const auto rho = test::gather(m, s.rho, Centering::Cell);
  const auto e = test::gather(m, s.e, Centering::Cell);
  const auto u = test::gather(m, s.u, Centering::Node);
  Profile p;
  const int nx = m.global_cells(0);
  p.dx = m.dx(0);
  for (int i = 0; i < nx; ++i) {
    p.x.push_back(m.spec().lo[0] + (i + 0.5) * p.dx);
    p.rho.push_back(rho[i]);
    p.e.push_back(e[i]);
    p.u.push_back(0.5 * (u[i] + u[i + 1]));
  }
  return p;
}

double l1_sod(const Profile& p, const exact::Riemann& rs, double x0, double t) {
  return exact::l1_density(p.x, p.rho, p.dx, rs, x0, t);
}

// First x, scanning from `from` in direction `dir`, where rho crosses `level`.
double crossing(const Profile& p, double level, int dir) {
  const int n = static_cast<int>(p.x.size());
  for (int step = 0; step < n - 1; ++step) {
    const int i = dir > 0 ? step : n - 1 - step;
    const int j = i + dir;
    if ((p.rho[i] - level) * (p.rho[j] - level) <= 0) {
      const double t = (level - p.rho[i]) / (p.rho[j] - p.rho[i]);
      return p.x[i] + t * (p.x[j] - p.x[i]);
    }
  }
  return NAN;
}

const exact::Riemann kSod({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 1.4);

}  // namespace

TEST(Sod, ConvergesToExactSolution) {
  const int sizes[3] = {100, 200, 400};
  double err[3];
  for (int n = 0; n < 3; ++n) {
    auto r = test::run_scene(
        test::load_scene("sod_x.yaml", {"mesh.cells=[" + std::to_string(sizes[n]) + ",2,2]"}));
    ASSERT_TRUE(r.result.ok);
    err[n] = l1_sod(profile_x(r), kSod, 0.5, 0.2);
  }
  const double o1 = std::log2(err[0] / err[1]), o2 = std::log2(err[1] / err[2]);
  std::printf("Sod L1(rho): %d %.4e  %d %.4e  %d %.4e  observed order %.3f %.3f\n", sizes[0],
              err[0], sizes[1], err[1], sizes[2], err[2], o1, o2);
  // The order is the verification (below); the absolute errors are guarded 30 % above this
  // scheme's own when the bounds were set (5.40e-3 at 100 cells, 1.53e-3 at 400; observed
  // 2026-12-07 under the default cloverleaf step 4.02e-3 / 2.05e-3 / 1.18e-3, orders 0.97,
  // 0.80; combined 4.02e-3 / 2.18e-3 / 1.27e-3): no external reference gives L1 for this
  // scheme, so these two bounds are regression margins, not accuracy claims.
  EXPECT_LT(err[0], 7.0e-3);
  EXPECT_LT(err[2], 2.0e-3);
  // Discontinuities cap the order near 1 for any scheme; below 0.6 would mean a first-order
  // error somewhere in the smooth parts.
  EXPECT_GT(o1, 0.6);
  EXPECT_GT(o2, 0.6);
}

TEST(Sod, WavePositions) {
  auto r = test::run_scene(test::load_scene("sod_x.yaml", {"mesh.cells=[400,2,2]"}));
  ASSERT_TRUE(r.result.ok);
  const Profile p = profile_x(r);
  const double t = 0.2, x0 = 0.5;
  const double shock = x0 + kSod.right_head_speed() * t;
  const double contact = x0 + kSod.u_star() * t;
  const double head = x0 + kSod.left_head_speed() * t;
  const double tail = x0 + kSod.left_tail_speed() * t;
  const double x_shock = crossing(p, 0.5 * (kSod.rho_star_right() + 0.125), -1);
  const double x_contact = crossing(p, 0.5 * (kSod.rho_star_left() + kSod.rho_star_right()), -1);
  const double x_head = crossing(p, 1.0 - 0.01, +1);
  std::printf(
      "Sod positions: shock %.4f (exact %.4f), contact %.4f (%.4f), rarefaction head "
      "%.4f (%.4f), tail exact %.4f, dx %.4f\n",
      x_shock, shock, x_contact, contact, x_head, head, tail, p.dx);
  // The rarefaction head is a kink: the exact profile reaches 0.99 a little behind it. That
  // exact crossing, found by bisection, is what the scheme's 0.99 crossing is compared with.
  double lo = head, hi = tail;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (kSod.sample((mid - x0) / t).rho > 0.99 ? lo : hi) = mid;
  }
  const double head_099 = 0.5 * (lo + hi);
  std::printf(
      "Sod position errors in cells: shock %+.3f, contact %+.3f, rho = 0.99 behind the "
      "head %+.3f (exact crossing %.4f)\n",
      (x_shock - shock) / p.dx, (x_contact - contact) / p.dx, (x_head - head_099) / p.dx, head_099);
  // A front smeared over a few cells is located by its mid-level crossing to within half a
  // cell; observed +0.09 dx (shock) and -0.15 dx (contact) (2026-12-07; the combined rule
  // +0.08, -0.06), so the bounds (0.5 dx) are 3-6x the errors, set by the resolution; a wave
  // speed 1 % wrong would put the shock 0.7 dx off.
  EXPECT_NEAR(x_shock, shock, 0.5 * p.dx);
  EXPECT_NEAR(x_contact, contact, 0.5 * p.dx);
  // The head is a kink, which the scheme spreads diffusively ahead of itself over several cells
  // (no steepening holds it): the 0.99 level is reached 1.0 dx before the exact one (1.1 dx
  // under the combined rule, 1.9 dx when this bound was set). 3 dx bounds the spreading at this
  // resolution.
  EXPECT_NEAR(x_head, head_099, 3 * p.dx);
  // The plateau between tail and contact holds the exact star density to 1 %.
  double worst = 0;
  int cells = 0;
  for (std::size_t i = 0; i < p.x.size(); ++i)
    if (p.x[i] > tail + 4 * p.dx && p.x[i] < contact - 6 * p.dx) {
      EXPECT_NEAR(p.rho[i], kSod.rho_star_left(), 0.01 * kSod.rho_star_left()) << p.x[i];
      worst = std::max(worst, std::abs(p.rho[i] / kSod.rho_star_left() - 1));
      ++cells;
    }
  std::printf(
      "Sod star plateau: %d cells, exact rho* %.5f, largest relative deviation %.3e "
      "(bound 1e-2)\n",
      cells, kSod.rho_star_left(), worst);
  EXPECT_GE(cells, 60);  // tail + 4 dx .. contact - 6 dx: 0.18 wide, 70 cells at 400
}

TEST(Sod, SameAlongEveryAxis) {
  auto rx = test::run_scene(test::load_scene("sod_x.yaml", {"mesh.cells=[100,2,2]"}));
  auto ry = test::run_scene(test::load_scene("sod_y.yaml", {"mesh.cells=[2,100,2]"}));
  auto rz = test::run_scene(test::load_scene("sod_z.yaml", {"mesh.cells=[2,2,100]"}));
  ASSERT_TRUE(rx.result.ok && ry.result.ok && rz.result.ok);
  EXPECT_EQ(rx.result.cycles, ry.result.cycles);
  EXPECT_EQ(rx.result.cycles, rz.result.cycles);
  const auto& sx = rx.sim->hydro().state();
  const auto& sy = ry.sim->hydro().state();
  const auto& sz = rz.sim->hydro().state();
  const auto ax = test::gather(rx.sim->mesh(), sx.rho, Centering::Cell);
  const auto ay = test::gather(ry.sim->mesh(), sy.rho, Centering::Cell);
  const auto az = test::gather(rz.sim->mesh(), sz.rho, Centering::Cell);
  const auto ex = test::gather(rx.sim->mesh(), sx.e, Centering::Cell);
  const auto ey = test::gather(ry.sim->mesh(), sy.e, Centering::Cell);
  const auto ez = test::gather(rz.sim->mesh(), sz.e, Centering::Cell);
  double dmax = 0;
  for (int i = 0; i < 100; ++i)
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const double x = ax[i + 100 * (a + 2 * b)], xe = ex[i + 100 * (a + 2 * b)];
        const double y = ay[a + 2 * (i + 100 * b)], ye = ey[a + 2 * (i + 100 * b)];
        const double z = az[a + 2 * (b + 2 * i)], ze = ez[a + 2 * (b + 2 * i)];
        dmax = std::max(
            {dmax, std::abs(x - y), std::abs(x - z), std::abs(xe - ye), std::abs(xe - ze)});
      }
  // A planar flow keeps its transverse velocities exactly 0 (the node forces are sums of
  // differences across the node: a field uniform along an axis gives no force along it; the
  // cell-by-cell sum before left 1e-17 .. 2e-15, kernels/hydro/lagrange.cpp)
  auto transverse = [](const test::Ran& r, const Field3& a, const Field3& b) {
    double m = 0;
    for (const Field3& f : {a, b})
      for (double x : test::gather(r.sim->mesh(), f, Centering::Node)) m = std::max(m, std::abs(x));
    return m;
  };
  EXPECT_EQ(transverse(rx, sx.v, sx.w), 0.0);
  EXPECT_EQ(transverse(ry, sy.u, sy.w), 0.0);
  EXPECT_EQ(transverse(rz, sz.u, sz.v), 0.0);
  std::printf("Sod x/y/z max difference: %.3e over %ld cycles\n", dmax, rx.result.cycles);
  // Not bitwise: the sweep order (x,y,z then z,y,x) puts the active axis first, last or in the
  // middle, so the same operations round in a different order. Worst case a few ulps of the
  // O(1) fields per cycle: 4 eps x 126 cycles = 1.1e-13, the bound 1e-13 (observed 8.4e-15,
  // random-sign roundings cancelling).
  EXPECT_LE(dmax, test::roundoff(1e-13));
}

// L1 density error of the entropy wave after one period on nx x 2 x 2 cells, against the exact
// cell averages of the initial state.
double smooth_wave_error(int nx, const std::vector<std::string>& extra = {}) {
  const std::string h = std::to_string(2.0 / nx);
  std::vector<std::string> ov = {"mesh.cells=[" + std::to_string(nx) + ",2,2]",
                                 "mesh.hi=[1," + h + "," + h + "]"};
  ov.insert(ov.end(), extra.begin(), extra.end());
  auto r = test::run_scene(test::load_scene("smooth_wave.yaml", ov));
  EXPECT_TRUE(r.result.ok);
  const Profile p = profile_x(r);
  const double kw = 2 * M_PI;
  double e1 = 0;
  for (int i = 0; i < nx; ++i) {
    const double x0 = i * p.dx, x1 = x0 + p.dx;
    const double exact = 1 + 0.2 * (std::cos(kw * x0) - std::cos(kw * x1)) / (kw * p.dx);
    e1 += std::abs(p.rho[i] - exact) * p.dx;
  }
  return e1;
}

// Noh's inflow in a closed box (reflective outer faces too): the gas leaving the outer walls and
// the far corner is cold (e = 1.5e-6 against u^2 / 2 = 0.5) and drains towards vacuum, and there
// the momentum remap's limited face velocities make more kinetic energy than the cells around a
// node can pay without going below ke_fix_floor (the whole cold region holds some 400 times less
// internal energy than that). The split sweep redoes those nodes' dual faces with donor values,
// which make none (hydro.hpp, ke_redo): total energy is then kept to round-off. Before
// (2026-12-05) the box gained 1.487e-3 at 24^3 (1.2185e-3 at 32^3), exactly what the floor left
// unpaid. docs/numerics.md, "One cycle", item 6.
struct ClosedNoh {
  long cycles = 0, redone = 0;
  double de = 0, unpaid = 0;  // relative to the initial total energy
};
static ClosedNoh run_closed_noh(int n, const std::vector<std::string>& extra = {}) {
  const std::string c = std::to_string(n);
  std::vector<std::string> ov = {"mesh.cells=[" + c + "," + c + "," + c + "]",
                                 "boundaries.x=reflective", "boundaries.y=reflective",
                                 "boundaries.z=reflective"};
  ov.insert(ov.end(), extra.begin(), extra.end());
  auto r = test::run_scene(test::load_scene("noh.yaml", ov));
  EXPECT_TRUE(r.result.ok);
  const double e0 = r.result.start.total();
  ClosedNoh out;
  out.cycles = r.result.cycles;
  out.redone = r.result.ke_redone;
  out.de = (r.result.end.total() - e0) / e0;
  out.unpaid = (r.result.end.ke_fix_unpaid - r.result.start.ke_fix_unpaid) / e0;
  std::printf(
      "closed Noh box %d^3 %s: total energy change %.6e, KE fix unpaid %.6e (difference %.3e; "
      "round-off bound %.3e over %ld cycles), faces redone in %ld sweeps\n",
      n, extra.empty() ? "" : extra[0].c_str(), out.de, out.unpaid, out.de - out.unpaid,
      test::energy_roundoff(out.cycles), out.cycles, out.redone);
  return out;
}

TEST(Conservation, ClosedNohBoxKeepsItsEnergy) {
  // the split sweeps (the default) and the unsplit step (each node's own faces)
  for (const char* remap : {"numerics.remap=split", "numerics.remap=unsplit"}) {
    const ClosedNoh b = run_closed_noh(24, {remap});
    EXPECT_GT(b.redone, 0) << remap;  // the case arises here (observed 225 / 113 sweeps)
    EXPECT_EQ(b.unpaid, 0.0) << remap;
    EXPECT_LT(std::abs(b.de), test::energy_roundoff(b.cycles)) << remap;  // (3.7e-15 / 3.1e-15)
  }
}

// Without the redo (numerics.ke_fix_redo: false) the floor binds, and the run's energy change
// must be exactly what the KE fix reports it could not charge (Totals::ke_fix_unpaid), to
// round-off: the floor is the one place the fix leaves energy unconserved.
TEST(Conservation, WithoutTheRedoAClosedNohBoxGainsOnlyWhatTheKeFixCouldNotCharge) {
  const ClosedNoh b = run_closed_noh(24, {"numerics.ke_fix_redo=false"});
  EXPECT_EQ(b.redone, 0);
  EXPECT_GT(b.unpaid, 1e-4);  // the floor binds here (observed 1.487e-3)
  EXPECT_LT(std::abs(b.de - b.unpaid), test::energy_roundoff(b.cycles));
}

TEST(SmoothWave, SecondOrder) {
  const int sizes[3] = {32, 64, 128};
  double err[3];
  for (int n = 0; n < 3; ++n) err[n] = smooth_wave_error(sizes[n]);
  const double o1 = std::log2(err[0] / err[1]), o2 = std::log2(err[1] / err[2]);
  std::printf("Smooth wave L1(rho): %d %.4e  %d %.4e  %d %.4e  observed order %.3f %.3f\n",
              sizes[0], err[0], sizes[1], err[1], sizes[2], err[2], o1, o2);
  EXPECT_GE(o2, 1.8);
  EXPECT_LT(err[2], 4e-4);
}

TEST(SmoothWave, FirstOrderOptionIsFirstOrder) {
  const double e64 = smooth_wave_error(64, {"numerics.advection=first"});
  const double e128 = smooth_wave_error(128, {"numerics.advection=first"});
  const double o = std::log2(e64 / e128);
  std::printf("Smooth wave, first order: L1 %.4e %.4e, order %.3f\n", e64, e128, o);
  EXPECT_GT(o, 0.8);
  EXPECT_LT(o, 1.3);
}

namespace {

// The entropy wave of configs/smooth_wave.yaml after one period with the wave's `shape` (sine or
// plateau, driver/wave.hpp) and the remap's `advection`: along x on n x 2 x 2 cells, or along
// the box diagonal on n^3 cells of the unit box with velocity (1, 1, 1) (one period is again
// t = 1). The error is the mean |rho - exact| over the cells, the exact value the cell mean of
// the initial profile (for the 1-D wave the L1 norm smooth_wave_error takes).
struct WaveRun {
  double l1 = NAN;
  long cycles = 0;
};
WaveRun wave_run(int n, bool diagonal, const std::string& shape, const std::string& advection,
                 bool unlimited) {
  const std::string c = std::to_string(n), h = std::to_string(2.0 / n);
  std::vector<std::string> ov = {"numerics.advection=" + advection,
                                 "regions.0.wave.shape=" + shape};
  if (diagonal) {
    for (const std::string& o :
         {"mesh.cells=[" + c + "," + c + "," + c + "]", std::string("mesh.hi=[1,1,1]"),
          std::string("regions.0.velocity=[1,1,1]"), std::string("regions.0.wave.axis=diagonal")})
      ov.push_back(o);
  } else {
    ov.push_back("mesh.cells=[" + c + ",2,2]");
    ov.push_back("mesh.hi=[1," + h + "," + h + "]");
  }
  test::Ran r;
  RunSettings settings;
  settings.quiet = true;
  r.sim = std::make_unique<Simulation>(test::load_scene("smooth_wave.yaml", ov), MPI_COMM_WORLD,
                                       settings);
  r.sim->initialize();
  if (unlimited) r.sim->hydro().set_unlimited();
  r.result = r.sim->run();
  EXPECT_TRUE(r.result.ok) << r.result.health.what;
  WaveRun out;
  out.cycles = r.result.cycles;
  const Mesh& m = r.sim->mesh();
  const auto rho = test::gather(m, r.sim->hydro().state().rho, Centering::Cell);
  const int nx = m.global_cells(0), ny = m.global_cells(1), nz = m.global_cells(2);
  const int kind = shape == "plateau" ? wave::kPlateau : wave::kSine;
  const double w = 1.0 / nx;
  double sum = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double s0 = diagonal ? (i + j + k) * w : i * w;
        const double exact = 1 + 0.2 * wave::cell_mean(kind, s0, w, diagonal ? 3 : 1);
        sum += std::abs(rho[i + nx * (j + long(ny) * k)] - exact);
      }
  out.l1 = sum / (double(nx) * ny * nz);
  return out;
}

// Observed orders of three runs at n, 2n, 4n cells per axis.
struct Orders {
  double e[3], o1, o2;
};
Orders wave_orders(const int (&n)[3], bool diagonal, const std::string& shape,
                   const std::string& advection, bool unlimited = false) {
  Orders r;
  long cycles[3];
  for (int q = 0; q < 3; ++q) {
    const WaveRun w = wave_run(n[q], diagonal, shape, advection, unlimited);
    r.e[q] = w.l1;
    cycles[q] = w.cycles;
  }
  r.o1 = std::log2(r.e[0] / r.e[1]);
  r.o2 = std::log2(r.e[1] / r.e[2]);
  std::printf(
      "%s wave, %s, %s%s: L1(rho) %d %.4e  %d %.4e  %d %.4e  (%ld/%ld/%ld cycles)  orders %.3f "
      "%.3f\n",
      shape.c_str(), diagonal ? "box diagonal" : "1-D", advection.c_str(),
      unlimited ? " (limiter off)" : "", n[0], r.e[0], n[1], r.e[1], n[2], r.e[2], cycles[0],
      cycles[1], cycles[2], r.o1, r.o2);
  return r;
}

}  // namespace

// The third-order remap (numerics.advection: third; remap/advect.hpp, docs/numerics.md
// "Third-order advection") where its limiter does not act. With a TVD bound every periodic
// profile is limited at its extrema (the slope is 0 where the differences change sign), so the
// unlimited regime is measured two ways:
// - in 1-D, the limited scheme on the plateau profile (driver/wave.hpp), whose extrema are flat
//   plateaus: the limiter acts only in the smoothstep's t^4 feet, at values that fall as h^4.
//   From 128 cells per period (observed 2.46 from 64 to 128, 1.97 from 32 to 64: the feet's
//   limited cells still carry error there); the second-order scheme beside it;
// - along the box diagonal in 3-D, the sine with the limiter switched off (Hydro::set_unlimited,
//   a verification switch): each split sweep advects along one axis, and with a uniform velocity
//   the three sweeps commute, so the splitting adds no error and the order is the 1-D scheme's.
// Bound: the 2.7 at three resolutions (the scheme's order is 3).
TEST(SmoothWave, ThirdOrderUnlimited) {
  const int n[3] = {128, 256, 512};
  const Orders t = wave_orders(n, false, "plateau", "third");
  const Orders s = wave_orders(n, false, "plateau", "second");
  EXPECT_GE(t.o1, 2.7);
  EXPECT_GE(t.o2, 2.7);
  EXPECT_LT(t.e[2], s.e[2]);
}

// The same plateau at 32, 64 and 128 cells, in the fast path (the cases above are `long`, and
// the fast path's other third-order check, two-material Sod within 5 % of second order, does
// not notice the slope's two weights swapped): the third-order error below the second-order
// one at every resolution, and third order's L1 falling at order >= 2.2 from 64 to 128 cells.
// Observed (double, 2026-12-07): third 9.43e-4, 2.45e-4, 4.26e-5 (orders 1.94, 2.53), second
// 1.57e-3, 2.89e-4, 4.82e-5 (ratios 0.60, 0.85, 0.88); with the weights swapped, third
// 1.39e-3, 3.95e-4, 8.17e-5: above second at 64 and 128 cells
// (docs/studies/2026-12-07-deliberate-breakages.md).
TEST(SmoothWave, CoarsePlateauThirdBelowSecond) {
  const int n[3] = {32, 64, 128};
  const Orders t = wave_orders(n, false, "plateau", "third");
  const Orders s = wave_orders(n, false, "plateau", "second");
  for (int q = 0; q < 3; ++q) {
    EXPECT_LT(t.e[q], s.e[q]) << n[q];
  }
  EXPECT_GE(t.o2, 2.2);
}

TEST(SmoothWave, ThirdOrderUnlimitedAlongTheDiagonal) {
  const int n[3] = {16, 32, 64};
  const Orders t = wave_orders(n, true, "sine", "third", true);
  EXPECT_GE(t.o1, 2.7);
  EXPECT_GE(t.o2, 2.7);
}

// Where the limiter acts, bound order >= 1.8 (the issue's): in 1-D the sine, whose extrema clip
// the slope to 0 (a b <= 0; observed 2.15, 2.31 from 32 cells under the default cloverleaf
// step, 2.16, 2.29 under the combined one); along the diagonal the plateau, whose feet's limited
// cells hold most of the error at 16 to 64 cells per period (observed 2.39, 2.01; combined 2.35,
// 2.05; the sine there gave 1.78, 2.24 under combined: from 16^3 its extrema are 16 cells
// apart).
TEST(SmoothWave, ThirdOrderLimited) {
  const int n1[3] = {32, 64, 128}, n3[3] = {16, 32, 64};
  const Orders a = wave_orders(n1, false, "sine", "third");
  EXPECT_GE(a.o1, 1.8);
  EXPECT_GE(a.o2, 1.8);
  const Orders b = wave_orders(n3, true, "plateau", "third");
  EXPECT_GE(b.o1, 1.8);
  EXPECT_GE(b.o2, 1.8);
}

TEST(Conservation, ClosedBoxMassToRoundOff) {
  // Sod with reflective walls on every face: nothing leaves the box.
  auto scene =
      test::load_scene("sod_x.yaml", {"boundaries.y=reflective", "boundaries.z=reflective"});
  auto r = test::run_scene(scene);
  ASSERT_TRUE(r.result.ok);
  const double dm = (r.result.end.mass - r.result.start.mass) / r.result.start.mass;
  const double de = (r.result.end.total() - r.result.start.total()) / r.result.start.total();
  // x-momentum: the box starts at rest, and until a wave reaches a wall (t = 0.2: rarefaction
  // head at 0.263, shock at 0.850) the only net force is the pressure of the two wall cells,
  // which keep their initial state: p_L on the wall at x = 0, p_R on the wall at x = 1. The
  // nodal forces of the Lagrangian step telescope to exactly that, and the remap moves momentum
  // between nodes without creating any, so P_x(t) = (p_L - p_R) A t, A = 0.01 x 0.01.
  const Mesh& m = r.sim->mesh();
  const auto p = test::gather(m, r.sim->hydro().state().p, Centering::Cell);
  const int nx = m.global_cells(0);
  const double p_left = p[0], p_right = p[nx - 1];
  const double area = 0.01 * 0.01;
  const double impulse = (p_left - p_right) * area * r.result.time;
  const double px = r.result.end.momentum[0];
  // Round-off: every cycle rounds each node's velocity a few times (acceleration, remap
  // quotient), each time by at most eps/2 of that node's momentum. Sod's flow is all in +x, so
  // sum |m u| = P_x <= the impulse; over N cycles |P_x - impulse| <= k eps N impulse, k = 8
  // roundings per node and cycle (4 in the acceleration, 4 in the remap's update). This is
  // the worst case, every rounding of one sign; roundings of random sign cancel, and the
  // observed difference is about 1/100 of it (2.4e-15 relative against 3.4e-13, 193 cycles).
  const double bound = 8 * test::kEps * double(r.result.cycles) * std::abs(impulse);
  std::printf(
      "closed box: relative mass change %.3e, total energy change %.3e\n"
      "  x-momentum %.17e, wall impulse (p_L %.17g - p_R %.17g) A t = %.17e\n"
      "  difference %.3e (relative %.3e), round-off bound %.3e over %ld cycles\n"
      "  y-momentum %.3e, z-momentum %.3e\n",
      dm, de, px, p_left, p_right, impulse, px - impulse, (px - impulse) / impulse, bound,
      r.result.cycles, r.result.end.momentum[1], r.result.end.momentum[2]);
  // Mass: the split remap's three sweeps round each cell's mass once each per cycle (eps/2
  // relative), 3 x 193 x eps/2 = 6.4e-14 if every rounding had one sign; bound 1e-13 (observed
  // 1.9e-14: signs mix).
  EXPECT_LT(std::abs(dm), test::roundoff(1e-13));
  // Total energy: the Lagrangian step conserves it to round-off and the KE fix returns the
  // remap's whole discrepancy (both signs), so only round-off remains: observed -1.2e-14 in
  // double, bound 8 eps x 3 sweeps x 193 cycles = 1.0e-12 (test::energy_roundoff, a worst case
  // of one-signed roundings). Until 2026-11 the fix returned only dissipation: +1.81e-5.
  std::printf("  total energy change %.3e, round-off bound %.3e\n", de,
              test::energy_roundoff(r.result.cycles));
  EXPECT_LT(std::abs(de), test::energy_roundoff(r.result.cycles));
  // and the KE fix's floor never bound (Totals::ke_fix_unpaid)
  EXPECT_EQ(r.result.end.ke_fix_unpaid, 0.0);
  // the wall cells hold the initial state: so do cells far from the waves (x = 0.1025, 0.94).
  // (Until 2026-12-06 the left probe was x = 0.125, cell 25: with free_expansion 0.7 the
  // rarefaction head's numerical tail reaches it at 4e-16 of the pressure, cell 26 at 6e-15;
  // the probe now stands 5 cells further off, where that tail is far below one ulp.)
  EXPECT_EQ(p_left, p[nx / 10]);
  EXPECT_EQ(p_right, p[nx - 1 - nx / 16]);
  EXPECT_LE(std::abs(px - impulse), bound);
}

TEST(Extremes, LeBlancStaysPositive) {
  auto r = test::run_scene(test::load_scene("leblanc.yaml"));
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  EXPECT_NEAR(r.result.time, 6.0, 1e-12);
  const Profile p = profile_x(r);
  const double rmin = *std::min_element(p.rho.begin(), p.rho.end());
  const double emin = *std::min_element(p.e.begin(), p.e.end());
  std::printf("LeBlanc: %ld cycles, min rho %.17g, min e %.17g\n", r.result.cycles, rmin, emin);
  // Positivity itself is the health check's (ASSERT_TRUE(ok) above). What it does not see: the
  // exact solution never goes below the undisturbed right state (rho = 1e-3, e = 1e-7; the
  // shock raises both, the rarefaction and the contact stay far above), so any undershoot of
  // the scheme, at the shock foot or in the near-vacuum right state, makes a new minimum. The
  // minima must be that state to round-off: the remap of the resting state rounds it by an ulp
  // or so per cycle (observed +7 ulps in rho, -1 ulp in e; bound 1e-15 relative, about 4.5 ulps
  // in double, 2^29 times that in float).
  const double tol = test::roundoff(1e-15);
  std::printf("LeBlanc minima relative to the right state: rho %+.2e, e %+.2e (bound -%.1e)\n",
              rmin / 1e-3 - 1, emin / 1e-7 - 1, tol);
  EXPECT_GE(rmin, 1e-3 * (1 - tol));
  EXPECT_GE(emin, 1e-7 * (1 - tol));
}

// LeBlanc at t = 6 against the exact solution (shock at x = 3 + 6 * 0.8291 = 7.975, shocked
// light gas e*R = 0.1933), at the 800 cells and at 400. Before the free-expansion rule
// (numerics.free_expansion, docs/numerics.md "Free expansion to the nodes") the heavy gas's
// start-up expansion into the light cells left an entropy spike on the light side of the
// contact that ran the shock +14.3 / +13.4 cells ahead and the contact energy +25.8 / +22.7 %
// high (a fixed 13 cells at 1600 and 3200 too: first order in position). With its first ratio
// 0.5 (2026-12-05): +5.5 / +5.1 cells, +12.1 / +9.0 %; with the default 0.7 (2026-12-06,
// double): +2.9 / +1.4 cells, +9.3 / +7.4 %; under the default cloverleaf step (2026-12-07):
// +3.1 / +1.7 cells, +9.8 / +7.5 % (tools/riemann_check.py gave the same under combined; -1.8, -2.1
// and +3.0 cells at 360, 720 and 1600: not monotone in N, which start-up faces cross the ratio
// depends on the mesh). Asserted: the bounds, the shock within 5 cells at both (observed
// +3.1 / +1.7) and the contact energy within 10 % at 800 (observed +7.5 %; 11 % at 400,
// observed +9.8 %, was 13 %), total energy to round-off.
// A pin, not a verification (issue #55): these are the meshes the free-expansion ratio 0.7 was
// chosen on, the errors are not monotone in N, and no convergence is shown (the convergence test
// this replaced stopped holding). Issue #16's target is what each message names.
TEST(ExtremesPin, LeBlancShockAndContactEnergyOnTheTuningMeshes) {
  const double g = 5.0 / 3.0;
  const exact::Riemann rs({1.0, 0.0, (g - 1) * 0.1}, {1e-3, 0.0, (g - 1) * 1e-10}, g, g);
  const double t = 6, exact_shock = 3 + t * rs.right_head_speed();
  const double e_star = rs.p_star() / ((g - 1) * rs.rho_star_right());
  const int cells[2] = {400, 800};
  const double contact_bound[2] = {0.11, 0.10};
  for (int n = 0; n < 2; ++n) {
    auto r = test::run_scene(
        test::load_scene("leblanc.yaml", {"mesh.cells=[" + std::to_string(cells[n]) + ",2,2]"}));
    ASSERT_TRUE(r.result.ok) << r.result.health.what;
    const Profile p = profile_x(r);
    const double x_shock = crossing(p, 0.5 * (1e-3 + rs.rho_star_right()), -1);
    const double shock_cells = (x_shock - exact_shock) / p.dx;
    // the internal-energy peak on the light side of the contact (from 0.5 behind the exact
    // contact to 0.2 short of the exact shock)
    const double x_contact = 3 + t * rs.u_star();
    double e_peak = 0;
    for (size_t i = 0; i < p.x.size(); ++i)
      if (p.x[i] > x_contact - 0.5 && p.x[i] < exact_shock - 0.2) e_peak = std::max(e_peak, p.e[i]);
    const double over = e_peak / e_star - 1;
    const double de = (r.result.end.total() - r.result.start.total()) / r.result.start.total();
    std::printf(
        "LeBlanc, %d cells: shock at %.4f (exact %.4f), %+.1f cells; contact e peak %.4f "
        "against e*R %.4f (%+.1f %%); total energy change %.2e\n",
        cells[n], x_shock, exact_shock, shock_cells, e_peak, e_star, 100 * over, de);
    EXPECT_LE(std::abs(shock_cells), 5.0) << "pin; issue #16's target: the shock within 5 cells";
    EXPECT_LE(over, contact_bound[n]) << "pin; issue #16's target: contact energy within 10 %";
    EXPECT_LT(std::abs(de), test::energy_roundoff(r.result.cycles));
  }
}

// Sod with a near-vacuum right state (rho 1e-8, p 1e-10; issue #16), t = 0.06: the left gas
// expands into the vacuum at up to its escape speed 2 c_L / (gamma - 1) = 5.92. Before the
// free-expansion rule (numerics.free_expansion, docs/numerics.md "Free expansion to the
// nodes") the remap's heating of gas entering much lighter cells ran the rho = 1e-4 crossing
// +23.6 / +47.9 cells ahead at 400 / 800 cells and the gas beside it 27 / 21 % above the exact
// star velocity (tools/riemann_check.py); with the ratio 0.5 +1.5 / +11.3 cells, +8.0 / +5.5 %;
// with the default 0.7 (2026-12-06) -3.3 / -0.8 cells, +3.9 / -0.2 % (cell-centred velocities
// here). Asserted: the bounds at 400 cells (5 cells, 10 %), the velocity's also at 800
// and the front there within 8 cells (was 15). Not a convergence measure at these meshes: the
// exact solution holds only 1.1e-6 of mass beyond rho = 1e-4, under 1/500 of one initial cell's
// mass even at 1600 cells, where the crossing is +37 cells (docs/numerics.md). Total energy to
// round-off.
// A pin, not a verification (issue #55): asserted on the meshes the free-expansion ratio was
// chosen on, and the front does not converge (+37 cells at 1600). Issue #16's target is what
// each message names.
TEST(ExtremesPin, NearVacuumFrontAndPeakVelocityOnTheTuningMeshes) {
  const double g = 1.4;
  const exact::Riemann rs({1.0, 0.0, 1.0}, {1e-8, 0.0, 1e-10}, g, g);
  // the exact position of rho = 1e-4 in the left fan (bisection in x / t on the sampled density)
  double lo = rs.left_head_speed(), hi = rs.u_star();
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (rs.sample(mid).rho > 1e-4 ? lo : hi) = mid;
  }
  const double t = 0.06, x_exact = 0.5 + t * 0.5 * (lo + hi);
  const int cells[2] = {400, 800};
  for (int n = 0; n < 2; ++n) {
    auto r = test::run_scene(test::load_scene(
        "sod_x.yaml", {"regions.0.density=1e-8", "regions.0.pressure=1e-10", "time.end=0.06",
                       "mesh.cells=[" + std::to_string(cells[n]) + ",2,2]"}));
    ASSERT_TRUE(r.result.ok) << r.result.health.what;
    const Profile p = profile_x(r);
    const double front = (crossing(p, 1e-4, -1) - x_exact) / p.dx;
    double peak = 0;
    for (size_t i = 0; i < p.x.size(); ++i)
      if (p.rho[i] > 1e-4) peak = std::max(peak, p.u[i]);
    const double du = peak / rs.u_star() - 1;
    const double de = (r.result.end.total() - r.result.start.total()) / r.result.start.total();
    std::printf(
        "near vacuum, %d cells: rho = 1e-4 at %+.1f cells from exact %.4f; peak u %.4f against "
        "u* %.4f (%+.1f %%); total energy change %.2e\n",
        cells[n], front, x_exact, peak, rs.u_star(), 100 * du, de);
    // observed -3.3 / -0.8 cells (bounds 5 / 8), u +3.9 / -0.2 % (bound 10 %)
    EXPECT_LE(std::abs(front), n == 0 ? 5.0 : 8.0)
        << "pin; issue #16's target: the rho = 1e-4 front within 5 cells";
    EXPECT_LE(std::abs(du), 0.10) << "pin; issue #16's target: the peak velocity within 10 % of u*";
    EXPECT_LT(std::abs(de), test::energy_roundoff(r.result.cycles));
  }
}

// The unsplit remap step (numerics.remap: unsplit) carries the free-expansion rule as the split
// sweeps do (each axis's faces' work kept apart, paid in its one cell update and given to the
// node pairs along that axis). In a flow along x alone the two steps do the same arithmetic but
// for zeros added in other orders, so they must agree to round-off on the two decks the rule was
// made for. Without the rule in the unsplit step (until 2026-12-07) they did not: LeBlanc at
// 360 cells had its shock +13.2 cells ahead unsplit against -1.8 split, and the near-vacuum front
// left the box. Observed at 400 cells: 1e-14 of each field's largest value; total energy of the
// unsplit runs to round-off.
TEST(UnsplitRemap, OneDimensionalExpansionsAreTheSplitSweepsToRoundOff) {
  const std::vector<std::vector<std::string>> cases = {
      {"leblanc.yaml", "mesh.cells=[400,2,2]"},
      {"sod_x.yaml", "regions.0.density=1e-8", "regions.0.pressure=1e-10", "time.end=0.06",
       "mesh.cells=[400,2,2]"}};
  for (const auto& c : cases) {
    std::vector<std::string> split(c.begin() + 1, c.end()), unsplit = split;
    split.push_back("numerics.remap=split");
    unsplit.push_back("numerics.remap=unsplit");
    auto a = test::run_scene(test::load_scene(c[0], split));
    auto b = test::run_scene(test::load_scene(c[0], unsplit));
    ASSERT_TRUE(a.result.ok && b.result.ok) << c[0];
    ASSERT_TRUE(b.sim->hydro().free_expansion_acts()) << c[0];
    const Profile pa = profile_x(a), pb = profile_x(b);
    const auto worst = [](const std::vector<double>& x, const std::vector<double>& y) {
      double d = 0, m = 0;
      for (size_t i = 0; i < x.size(); ++i) {
        d = std::max(d, std::abs(x[i] - y[i]));
        m = std::max(m, std::abs(x[i]));
      }
      return d / m;
    };
    const double drho = worst(pa.rho, pb.rho), de = worst(pa.e, pb.e), du = worst(pa.u, pb.u);
    const double energy = (b.result.end.total() - b.result.start.total()) / b.result.start.total();
    std::printf(
        "%s unsplit against split: %ld / %ld cycles; largest difference over largest "
        "value: rho %.2e, e %.2e, u %.2e; unsplit total energy change %.2e\n",
        c[0].c_str(), b.result.cycles, a.result.cycles, drho, de, du, energy);
    EXPECT_EQ(a.result.cycles, b.result.cycles) << c[0];
    const double tol = test::roundoff(1e-12);
    EXPECT_LT(drho, tol) << c[0];
    EXPECT_LT(de, tol) << c[0];
    EXPECT_LT(du, tol) << c[0];
    EXPECT_LT(std::abs(energy), test::energy_roundoff(b.result.cycles)) << c[0];
  }
}

TEST(Extremes, Problem123StaysPositive) {
  auto r = test::run_scene(test::load_scene("test123.yaml"));
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  const Profile p = profile_x(r);
  const double rmin = *std::min_element(p.rho.begin(), p.rho.end());
  const double emin = *std::min_element(p.e.begin(), p.e.end());
  const exact::Riemann rs({1.0, -2.0, 0.4}, {1.0, 2.0, 0.4}, 1.4, 1.4);
  std::printf("123: %ld cycles, min rho %.3e (exact centre %.3e), min e %.3e\n", r.result.cycles,
              rmin, rs.rho_star_left(), emin);
  // Positivity itself is the health check's (ASSERT_TRUE(ok) above). The exact solution has
  // its minimum density and internal energy in the star state between the two rarefactions'
  // tails, x in 0.5 -+ c* t: the scheme's minima must lie there too, not at a spurious
  // undershoot elsewhere; and its lowest internal energy near the exact e*, converging: -12.4 %
  // at 200 cells, -8.3 % at 400 (measured 2026-12-02; bound 20 % at 200 cells and 10 % at 400,
  // with the error falling). The centre itself converges (Problem123CentreConverges below).
  const auto at_min = [&](const std::vector<double>& f) {
    return p.x[std::min_element(f.begin(), f.end()) - f.begin()];
  };
  const double x_rho = at_min(p.rho), x_e = at_min(p.e);
  const double c_star = std::sqrt(1.4 * rs.p_star() / rs.rho_star_left());
  const double tail = c_star * 0.15;  // star region: |x - 0.5| <= tail
  const double e_exact = rs.p_star() / (0.4 * rs.rho_star_left());
  std::printf(
      "123: min rho at x = %.4f, min e at x = %.4f, exact star region %.4f..%.4f; min e %.4e "
      "vs exact e* %.4e (%+.1f %%)\n",
      x_rho, x_e, 0.5 - tail, 0.5 + tail, emin, e_exact, 100 * (emin / e_exact - 1));
  EXPECT_NEAR(x_rho, 0.5, tail);
  EXPECT_NEAR(x_e, 0.5, tail);
  EXPECT_NEAR(emin / e_exact, 1.0, 0.20);
  {
    auto r400 = test::run_scene(test::load_scene("test123.yaml", {"mesh.cells=[400,2,2]"}));
    ASSERT_TRUE(r400.result.ok) << r400.result.health.what;
    const Profile p400 = profile_x(r400);
    const double emin400 = *std::min_element(p400.e.begin(), p400.e.end());
    std::printf("123: 400 cells, min e %.4e vs exact e* %.4e (%+.1f %%)\n", emin400, e_exact,
                100 * (emin400 / e_exact - 1));
    EXPECT_NEAR(emin400 / e_exact, 1.0, 0.10);
    EXPECT_LT(std::abs(emin400 / e_exact - 1), std::abs(emin / e_exact - 1));
  }
  // L1 of the density against the exact solution, the near-vacuum centre's deficit most of it:
  // observed 6.4e-3 at 200 cells; the bound 1e-2 (1.6x) is a margin over this scheme's own
  // error, as for Sod's absolute L1 (was 0.05, 7.8x).
  const double l1 = l1_sod(p, rs, 0.5, 0.15);
  std::printf("123: L1(rho) %.4e (bound 1e-2)\n", l1);
  EXPECT_LT(l1, 1e-2);
}

// The 123 problem's centre (issue #16): the star state between the two rarefactions, rho* =
// 0.02185, e* = 0.2167, must be approached as the mesh is refined. Two defects kept it away
// (docs/numerics.md, the 123 section): the node on the velocity jump started at the left
// state's -2 instead of the painted momentum's 0, so the solution was not symmetric about
// x = 0.5 (1.5e-2 of the density) and the measured centre sat between two different cells;
// and the KE fix charged the near-vacuum centre's cells for kinetic energy the remap's limited
// slopes carried out of the draining centre nodes but that no node held (the centre's entropy
// p / rho^gamma fell from 0.400 to 0.285 by t = 0.01). Measured 2026-12-02, the mean of the two
// cells beside x = 0.5: rho -0.99 % / -0.55 %, e -1.52 % / -1.32 % at 400 / 800 cells (+0.7 % /
// -0.8 % at 1600); 2026-12-07 under the default cloverleaf step rho -0.41 % / -0.23 %, e
// -1.35 % / -1.26 %; before, rho -7.0 / -14.0 / -20.8 % and e +26.5 / +26.9 / +31.4 % at 400 /
// 800 / 1600. Bounds: symmetric to round-off, each error within 3 %, smaller at 800 than 400.
TEST(Extremes, Problem123CentreConverges) {
  const exact::Riemann rs({1.0, -2.0, 0.4}, {1.0, 2.0, 0.4}, 1.4, 1.4);
  const double e_star = rs.p_star() / (0.4 * rs.rho_star_left());
  double err_rho[2], err_e[2];
  const int cells[2] = {400, 800};
  for (int n = 0; n < 2; ++n) {
    auto r = test::run_scene(
        test::load_scene("test123.yaml", {"mesh.cells=[" + std::to_string(cells[n]) + ",2,2]"}));
    ASSERT_TRUE(r.result.ok) << r.result.health.what;
    const Profile p = profile_x(r);
    const int nx = static_cast<int>(p.rho.size());
    double asym = 0, peak = 0;
    for (int i = 0; i < nx; ++i) {
      asym = std::max(asym, std::abs(p.rho[i] - p.rho[nx - 1 - i]));
      peak = std::max(peak, p.rho[i]);
    }
    const double rho_c = 0.5 * (p.rho[nx / 2 - 1] + p.rho[nx / 2]);
    const double e_c = 0.5 * (p.e[nx / 2 - 1] + p.e[nx / 2]);
    err_rho[n] = rho_c / rs.rho_star_left() - 1;
    err_e[n] = e_c / e_star - 1;
    std::printf("123, %d cells: centre rho %.5f (%+.2f %%), e %.4f (%+.2f %%), asymmetry %.2e\n",
                cells[n], rho_c, 100 * err_rho[n], e_c, 100 * err_e[n], asym / peak);
    EXPECT_LT(asym / peak, test::roundoff(1e-12));
    EXPECT_LT(std::abs(err_rho[n]), 0.03);
    EXPECT_LT(std::abs(err_e[n]), 0.03);
  }
  EXPECT_LT(std::abs(err_rho[1]), std::abs(err_rho[0]));
  EXPECT_LT(std::abs(err_e[1]), std::abs(err_e[0]));
}

// Noh's planar implosion onto a wall (configs/noh_planar.yaml): the exact shock runs out at
// t/3 and leaves gas at rest with rho = 4, e = 1/2. On the fixed mesh every shocked parcel
// reaches the plateau through the remap, whose momentum advection dissipates kinetic energy
// at the shock; the KE fix returns it, so the Rankine-Hugoniot jump (a statement of mass,
// momentum and total-energy conservation) holds and the shock speed converges. Without the fix
// the shock lags by a fixed distance at every resolution (measured 2026-12-01: 2.25, 4.84, 9.90
// cells behind at 100, 200, 400 cells, plateau e 0.437, 0.413, 0.365): the fix is what makes
// the scheme converge on a strong shock, and this test guards it.
TEST(Noh, PlanarShockSpeedAndPlateau) {
  const double t = 0.6, r_exact = t / 3;
  struct Measure {
    double shock, plateau_rho, plateau_e, wall_rho, dx, l1;
  };
  const auto measure = [&](int n, bool ke_fix) {
    auto r = test::run_scene(test::load_scene(
        "noh_planar.yaml", {"mesh.cells=[" + std::to_string(n) + ",2,2]",
                            std::string("numerics.ke_fix=") + (ke_fix ? "true" : "false")}));
    EXPECT_TRUE(r.result.ok) << r.result.health.what;
    EXPECT_NEAR(r.result.time, t, 1e-12);
    const Profile p = profile_x(r);
    Measure m{crossing(p, 2.5, -1), 0, 0, p.rho[0], p.dx, 0};  // 2.5: halfway between 1 and 4
    // the plateau away from the wall's heating and the shock's ramp: 0.5 R < x < R - 4 dx
    int count = 0;
    for (std::size_t i = 0; i < p.x.size(); ++i)
      if (p.x[i] > 0.5 * r_exact && p.x[i] < r_exact - 4 * p.dx) {
        m.plateau_rho += p.rho[i];
        m.plateau_e += p.e[i];
        ++count;
      }
    EXPECT_GE(count, 5);
    m.plateau_rho /= count;
    m.plateau_e /= count;
    // L1(rho) against the exact profile (tests/exact/norms.hpp), the measure the
    // speed/accuracy harness (perf/tradeoff.cpp) reports for this scene
    const double l1 = exact::l1_density(p.x, p.rho, p.dx, exact::Noh(1, 5.0 / 3.0), t);
    m.l1 = l1;
    std::printf(
        "Noh planar, %d cells, ke_fix %d: shock %.5f (exact %.5f, %+.2f cells), plateau rho "
        "%.5f (%+.3f %%), e %.5f (%+.3f %%), wall cell rho %.3f, L1(rho) %.4e\n",
        n, int(ke_fix), m.shock, r_exact, (m.shock - r_exact) / m.dx, m.plateau_rho,
        100 * (m.plateau_rho / 4 - 1), m.plateau_e, 100 * (m.plateau_e / 0.5 - 1), m.wall_rho, l1);
    return m;
  };
  const Measure a = measure(100, true), b = measure(200, true);
  // Observed (2026-12-01) +0.14 cells at both resolutions, plateau rho +0.148 % / -0.032 %,
  // e -0.14 % / +0.01 %. Bounds: the shock's mid-level crossing within half a cell of the exact
  // front (the resolution of a captured shock); the plateau within 0.5 %, about 3x the coarser
  // run's error, and the error falling with resolution.
  for (const Measure& m : {a, b}) {
    EXPECT_LT(std::abs(m.shock - r_exact), 0.5 * m.dx);
    EXPECT_LT(std::abs(m.plateau_rho / 4 - 1), 5e-3);
    EXPECT_LT(std::abs(m.plateau_e / 0.5 - 1), 5e-3);
  }
  EXPECT_LT(std::abs(b.plateau_rho / 4 - 1), std::abs(a.plateau_rho / 4 - 1));
  EXPECT_LT(std::abs(b.shock - r_exact), std::abs(a.shock - r_exact));
  // L1(rho): observed 2.18e-2 / 1.11e-2 at 100 / 200 cells (the sweep: 5.6e-3, 2.9e-3 at 400,
  // 800), first order as a captured shock allows; bounds: the coarse one 1.5x observed, and
  // halving the cells takes at least 40 % off.
  EXPECT_LT(a.l1, 3.3e-2);
  EXPECT_LT(b.l1, 0.6 * a.l1);
  // Without the fix the same test fails: the shock lags by more than a cell (observed 2.25).
  const Measure off = measure(100, false);
  EXPECT_GT((r_exact - off.shock) / off.dx, 1.0);
}

// The third-order remap on the shock problems verified above, at their resolutions: each error
// measure with `third` against the same measure with today's default `second`. (The issue's
// claim: no error above second order's by more than 5 %.) Errors are magnitudes: L1 norms,
// distances from the exact front in cells, relative errors of plateaus and centres.
namespace {

void add_profile_rows(std::vector<std::pair<std::string, double>>& out, const std::string& deck,
                      int n, const std::string& advection) {
  const std::string cells = "mesh.cells=[" + std::to_string(n) + ",2,2]";
  auto r = test::run_scene(test::load_scene(deck, {cells, "numerics.advection=" + advection}));
  EXPECT_TRUE(r.result.ok) << deck << " " << advection << ": " << r.result.health.what;
  if (!r.result.ok) return;
  const Profile p = profile_x(r);
  const std::string at = " " + std::to_string(n);
  if (deck == "sod_x.yaml") {
    out.push_back({"Sod L1(rho)" + at, l1_sod(p, kSod, 0.5, 0.2)});
  } else if (deck == "leblanc.yaml") {
    const double g = 5.0 / 3.0;
    const exact::Riemann rs({1.0, 0.0, (g - 1) * 0.1}, {1e-3, 0.0, (g - 1) * 1e-10}, g, g);
    const double t = 6, shock = 3 + t * rs.right_head_speed(), contact = 3 + t * rs.u_star();
    const double e_star = rs.p_star() / ((g - 1) * rs.rho_star_right());
    double e_peak = 0;
    for (size_t i = 0; i < p.x.size(); ++i)
      if (p.x[i] > contact - 0.5 && p.x[i] < shock - 0.2) e_peak = std::max(e_peak, p.e[i]);
    out.push_back({"LeBlanc L1(rho)" + at, exact::l1_density(p.x, p.rho, p.dx, rs, 3, t)});
    out.push_back({"LeBlanc |shock - exact| (cells)" + at,
                   std::abs(crossing(p, 0.5 * (1e-3 + rs.rho_star_right()), -1) - shock) / p.dx});
    out.push_back({"LeBlanc |contact e peak / e* - 1|" + at, std::abs(e_peak / e_star - 1)});
  } else if (deck == "test123.yaml") {
    const exact::Riemann rs({1.0, -2.0, 0.4}, {1.0, 2.0, 0.4}, 1.4, 1.4);
    const int nx = static_cast<int>(p.rho.size());
    const double rho_c = 0.5 * (p.rho[nx / 2 - 1] + p.rho[nx / 2]);
    const double e_c = 0.5 * (p.e[nx / 2 - 1] + p.e[nx / 2]);
    out.push_back({"123 L1(rho)" + at, l1_sod(p, rs, 0.5, 0.15)});
    out.push_back({"123 |centre rho / rho* - 1|" + at, std::abs(rho_c / rs.rho_star_left() - 1)});
    out.push_back({"123 |centre e / e* - 1|" + at,
                   std::abs(e_c / (rs.p_star() / (0.4 * rs.rho_star_left())) - 1)});
  } else {  // noh_planar.yaml
    const double t = 0.6;
    out.push_back({"planar Noh L1(rho)" + at,
                   exact::l1_density(p.x, p.rho, p.dx, exact::Noh(1, 5.0 / 3.0), t)});
    out.push_back(
        {"planar Noh |shock - exact| (cells)" + at, std::abs(crossing(p, 2.5, -1) - t / 3) / p.dx});
  }
}

std::vector<std::pair<std::string, double>> shock_measures(const std::string& advection) {
  std::vector<std::pair<std::string, double>> out;
  for (int n : {100, 200, 400}) add_profile_rows(out, "sod_x.yaml", n, advection);
  for (int n : {400, 800}) add_profile_rows(out, "leblanc.yaml", n, advection);
  for (int n : {200, 400, 800}) add_profile_rows(out, "test123.yaml", n, advection);
  for (int n : {100, 200}) add_profile_rows(out, "noh_planar.yaml", n, advection);
  return out;
}

// Both schemes' measures, run once for the two tests below.
struct ShockTable {
  std::vector<std::pair<std::string, double>> second, third;
};
const ShockTable& shock_table() {
  static const ShockTable t = [] {
    ShockTable r{shock_measures("second"), shock_measures("third")};
    std::printf("%-44s %12s %12s %8s\n", "measure (resolution)", "second", "third", "ratio");
    for (std::size_t q = 0; q < r.second.size() && q < r.third.size(); ++q)
      std::printf("%-44s %12.4e %12.4e %8.3f\n", r.second[q].first.c_str(), r.second[q].second,
                  r.third[q].second, r.third[q].second / r.second[q].second);
    return r;
  }();
  return t;
}

// The measures where third order misses the bound (ThirdOrderRegressionPin below): the
// expansions' measures, LeBlanc's shock position and contact energy and the 123 problem's
// near-vacuum centre, which the free-expansion rule and the KE fix's donor-value redo were tuned
// on with second-order slopes.
bool expansion_measure(const std::string& what) {
  return what.rfind("LeBlanc |", 0) == 0 || what.rfind("123 |centre", 0) == 0;
}

}  // namespace

// The L1 norms of Sod, LeBlanc and 123 and planar Noh's L1 and shock position: third order no
// more than 5 % above second (the bound). Observed (2026-12-06): 0.78 .. 0.98 of second
// order's (docs/studies/2026-12-06-third-order.md has the table).
TEST(ThirdOrder, ShockTubesNoWorseThanSecond) {
  const ShockTable& t = shock_table();
  ASSERT_EQ(t.second.size(), t.third.size());
  int checked = 0;
  for (std::size_t q = 0; q < t.second.size(); ++q) {
    if (expansion_measure(t.second[q].first)) continue;
    EXPECT_LE(t.third[q].second, 1.05 * t.second[q].second) << t.second[q].first;
    ++checked;
  }
  EXPECT_EQ(checked, 12);
}

// A regression pin, not a verification: where third order is worse than second (observed
// 2026-12-07 under the default cloverleaf step, second / third): LeBlanc's shock 3.14 / 3.88
// cells from exact at 400 cells and 1.65 / 2.77 at 800, its contact energy peak +9.8 / +16.4 %
// and +7.5 / +12.3 %; the 123 problem's centre density -27.0 / -27.7 %, -0.41 / -4.15 %, -0.23 /
// -2.54 % and energy 12.9 / 13.4 %, 1.35 / 3.00 %, 1.26 / 2.35 % at 200 / 400 / 800 cells.
// (Under the combined step, 2026-12-06: 2.86 / 3.78 and 1.44 / 2.61 cells, +9.3 / +15.6 % and
// +7.4 / +11.2 %; -26.2 / -27.3 %, -0.99 / -4.43 %, -0.55 / -2.78 %; 12.4 / 13.1 %, 1.52 /
// 3.05 %, 1.32 / 2.38 %: the third-order values moved by 0.91-1.11x, the pinned ones below are
// today's.) Why the default stays second order (docs/numerics.md, "Third-order advection").
// Bounds: each third-order value at most 1.2x its observed value (a change of the scheme that
// moves them shows here).
TEST(ThirdOrderRegressionPin, ExpansionMeasuresWorseThanSecond) {
  const ShockTable& t = shock_table();
  const std::vector<std::pair<std::string, double>> observed = {
      {"LeBlanc |shock - exact| (cells) 400", 3.8818},
      {"LeBlanc |contact e peak / e* - 1| 400", 0.16432},
      {"LeBlanc |shock - exact| (cells) 800", 2.7724},
      {"LeBlanc |contact e peak / e* - 1| 800", 0.12339},
      {"123 |centre rho / rho* - 1| 200", 0.27748},
      {"123 |centre e / e* - 1| 200", 0.13380},
      {"123 |centre rho / rho* - 1| 400", 0.041493},
      {"123 |centre e / e* - 1| 400", 0.029972},
      {"123 |centre rho / rho* - 1| 800", 0.025372},
      {"123 |centre e / e* - 1| 800", 0.023490}};
  int found = 0;
  for (const auto& [what, value] : t.third)
    for (const auto& [name, seen] : observed)
      if (what == name) {
        EXPECT_LE(value, 1.2 * seen) << what;
        ++found;
      }
  EXPECT_EQ(found, int(observed.size()));
}
