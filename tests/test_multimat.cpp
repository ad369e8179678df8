// Multi-material verification (issue: multi-material): the two-material shock tube against the
// exact two-gamma Riemann solution, interface advection error with Youngs vs SLIC, per-material
// mass conservation on the triple point, and dense == compact on every multi-material scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "config/deck.hpp"
#include "exact/isentrope_riemann.hpp"
#include "exact/norms.hpp"
#include "exact/riemann.hpp"
#include "materials/library.hpp"
#include "support.hpp"

using namespace mp;

namespace {

// Every cell field of a finished run (density, energy, pressure, fractions) and the node
// velocities, gathered globally.
struct Snapshot {
  std::vector<std::string> names;
  std::vector<std::vector<double>> fields;
  RunResult result;
};

Snapshot snapshot(const Scene& scene) {
  auto r = test::run_scene(scene);
  Snapshot s;
  s.result = r.result;
  const Mesh& m = r.sim->mesh();
  const auto& h = r.sim->hydro();
  for (const auto& f : h.output_fields()) {
    s.names.push_back(f.name);
    s.fields.push_back(test::gather(m, f.view, f.centering));
  }
  const mat::MaterialState* mm = h.materials();
  for (int q = 0; q < mm->nmat(); ++q) {
    s.names.push_back("fraction_" + scene.materials[q].name);
    s.fields.push_back(test::gather(m, mm->fraction(q), Centering::Cell));
  }
  return s;
}

// Largest difference, relative to the field's largest magnitude, between the two layouts.
void expect_layouts_agree(const std::string& deck, const std::vector<std::string>& overrides) {
  auto o = overrides;
  o.push_back("numerics.layout=compact");
  const Snapshot c = snapshot(test::load_scene(deck, o));
  o.back() = "numerics.layout=dense";
  const Snapshot d = snapshot(test::load_scene(deck, o));
  ASSERT_TRUE(c.result.ok && d.result.ok);
  EXPECT_EQ(c.result.cycles, d.result.cycles);
  ASSERT_EQ(c.names, d.names);
  double worst = 0;
  for (std::size_t f = 0; f < c.fields.size(); ++f) {
    double scale = 0, diff = 0;
    for (std::size_t i = 0; i < c.fields[f].size(); ++i) {
      scale = std::max(scale, std::abs(c.fields[f][i]));
      diff = std::max(diff, std::abs(c.fields[f][i] - d.fields[f][i]));
    }
    const double rel = scale > 0 ? diff / scale : diff;
    worst = std::max(worst, rel);
    // Both layouts run the same point functions in the same order on the same values, so they
    // agree bit for bit (observed 0 on every scene in double; docs/numerics.md records the same
    // in float). Was
    // 1e-13, which could not see a difference of round-off.
    EXPECT_EQ(rel, 0.0) << deck << ": field " << c.names[f];
  }
  std::printf(
      "%s: dense vs compact, %zu fields over %ld cycles, largest relative difference %.3e\n",
      deck.c_str(), c.fields.size(), c.result.cycles, worst);
}

}  // namespace

namespace {

// The two-material shock tube (configs/sod2.yaml) at n cells along x against the exact
// two-gamma Riemann solution: L1 of density and pressure (tests/exact/norms.hpp), the interface
// (the driver's volume per unit area) against the exact contact, the mixed-cell count.
struct Sod2 {
  double l1, l1p, interface, contact, dx, p_min;
  int mixed;
  long cycles;
};

Sod2 run_sod2(int n, const std::string& advection = "second") {
  auto r =
      test::run_scene(test::load_scene("sod2.yaml", {"mesh.cells=[" + std::to_string(n) + ",2,2]",
                                                     "numerics.advection=" + advection}));
  EXPECT_TRUE(r.result.ok) << r.result.health.what;
  const Mesh& m = r.sim->mesh();
  const auto rho = test::gather(m, r.sim->hydro().state().rho, Centering::Cell);
  const auto p = test::gather(m, r.sim->hydro().state().p, Centering::Cell);
  const auto frac = test::gather(m, r.sim->hydro().materials()->fraction(0), Centering::Cell);
  const exact::Riemann rs({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 1.667);
  const double dx = m.dx(0), t = 0.2, x0 = 0.5;
  Sod2 s{0, 0, 0, x0 + rs.u_star() * t, dx, 1e300, 0, r.result.cycles};
  std::vector<double> x(n), rho_x(n), p_x(n);
  for (int i = 0; i < n; ++i) {
    x[i] = (i + 0.5) * dx;
    rho_x[i] = rho[i];
    p_x[i] = p[i];
    s.interface += frac[i] * dx;  // the driver fills [0, interface)
    s.mixed += (frac[i] > 0 && frac[i] < 1) ? 1 : 0;
    s.p_min = std::min(s.p_min, p[i]);
  }
  s.l1 = exact::l1_density(x, rho_x, dx, rs, x0, t);
  s.l1p = exact::l1_pressure(x, p_x, dx, rs, x0, t);
  std::printf(
      "two-material Sod (gamma 1.4 | 1.667), %d cells, %ld cycles: L1(rho) %.4e, L1(p) %.4e; "
      "interface %.5f vs exact contact %.5f (%+.2f cells); %d mixed cells; min p %.4f; p* %.5f "
      "u* %.5f\n",
      n, s.cycles, s.l1, s.l1p, s.interface, s.contact, (s.interface - s.contact) / dx, s.mixed,
      s.p_min, rs.p_star(), rs.u_star());
  return s;
}

}  // namespace

// The two-material shock tube against its exact solution at 100, 200 and 400 cells: the L1
// errors fall at first order, the interface stays at the exact contact and sharp.
TEST(MultiMaterial, TwoMaterialSodConvergesToExactSolution) {
  const int sizes[3] = {100, 200, 400};
  Sod2 s[3];
  for (int k = 0; k < 3; ++k) s[k] = run_sod2(sizes[k]);
  double order[2][2];
  for (int k = 0; k < 2; ++k) {
    order[0][k] = std::log2(s[k].l1 / s[k + 1].l1);
    order[1][k] = std::log2(s[k].l1p / s[k + 1].l1p);
  }
  std::printf("two-material Sod observed orders: L1(rho) %.3f %.3f, L1(p) %.3f %.3f (floor 0.6)\n",
              order[0][0], order[0][1], order[1][0], order[1][1]);
  // Order. Both discontinuities are held to O(dx): the shock is captured in a fixed number of
  // cells and the interface reconstruction keeps the contact, a material interface here, to
  // one or two mixed cells, so the L1 errors are first order (observed 1.03, 0.96 for rho;
  // 1.01, 0.98 for p; 0.88 and 0.92 from 400 to 800 cells, not run here). The floor 0.6 is
  // Sod.ConvergesToExactSolution's, and lies above the 1/2 of a contact smeared by first-order
  // advection: an interface that began to smear would fail it.
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(order[0][k], 0.6) << sizes[k] << " -> " << sizes[k + 1];
    EXPECT_GT(order[1][k], 0.6) << sizes[k] << " -> " << sizes[k + 1];
  }
  // Accuracy at the finest resolution, against the single-material scheme on Sod's states at
  // 400 cells (sod_x.yaml, measured 2026-12-01: L1(rho) 1.53e-3, L1(p) 9.86e-4).
  // Density: no worse than the single fluid, whose error is mostly the smeared contact that a
  // material interface does not have; observed 9.71e-4 (1.55x below 1.5e-3). Pressure is
  // continuous across the contact, so both problems' L1(p) come from the same shock and
  // rarefaction: the bound is the single fluid's plus half (a mixed-cell closure adding a
  // pressure error of half the scheme's own fails); observed 1.04e-3 (1.44x below 1.5e-3).
  // Was one resolution (200 cells) with bounds 4e-3 and 3e-3 (2.1x, 1.46x).
  EXPECT_LT(s[2].l1, 1.5e-3);
  EXPECT_LT(s[2].l1p, 1.5e-3);
  for (const Sod2& r : s) {
    // Interface at the exact contact: observed -0.05 cells at 200. A quarter cell is a contact
    // speed error of 0.25 dx / t = 0.7 % of u* at 200 cells, the size of the star-state
    // bounds of the water-air test (and 1.4 % at 100, 0.35 % at 400).
    EXPECT_LT(std::abs(r.interface - r.contact), 0.25 * r.dx) << r.dx;
    // the interface stays sharp: a plane between two cells is at most one mixed cell, two
    // while it crosses a face in a step
    EXPECT_LE(r.mixed, 2) << r.dx;
    EXPECT_GT(r.p_min, 0) << r.dx;
  }
}

TEST(MultiMaterial, SphereAdvectionYoungsBeatsSlicAndConverges) {
  // One period of uniform diagonal flow returns the sphere to its start: the L1 volume-fraction
  // difference measures the shape error of the interface transport.
  auto shape_error = [](int n, const std::string& iface) {
    const std::string cells = "mesh.cells=[" + std::to_string(n) + "," + std::to_string(n) + "," +
                              std::to_string(n) + "]";
    const Scene scene =
        test::load_scene("sphere_advection.yaml", {cells, "numerics.interface=" + iface});
    auto r = test::run_scene(scene);
    EXPECT_TRUE(r.result.ok);
    // the initial fractions: the same scene painted, not run
    RunSettings settings;
    settings.quiet = true;
    Simulation start(scene, MPI_COMM_WORLD, settings);
    start.initialize();
    const Mesh& m = r.sim->mesh();
    const auto f1 = test::gather(m, r.sim->hydro().materials()->fraction(1), Centering::Cell);
    const auto f0 =
        test::gather(start.mesh(), start.hydro().materials()->fraction(1), Centering::Cell);
    double v0 = 0, v1 = 0;
    const double cell = 1.0 / (double(n) * n * n);
    for (std::size_t i = 0; i < f0.size(); ++i) {
      v0 += f0[i] * cell;
      v1 += f1[i] * cell;
    }
    const auto& mm0 = r.result.start.material_mass;
    const auto& mm1 = r.result.end.material_mass;
    std::printf("sphere advection %d^3 %s: ball volume change %.2e, material mass changes", n,
                iface.c_str(), v1 - v0);
    for (std::size_t q = 0; q < mm0.size(); ++q) std::printf(" %.2e", mm1[q] / mm0[q] - 1);
    std::printf("\n");
    // Volume and masses to round-off: the remap moves each material's volume between cells
    // and only rounds it. The ball's volume (0.03) is summed here over up to 32^3 cells:
    // N eps x 0.03 = 1.1e-13 at worst (observed up to 1.2e-15, roundings of mixed sign and
    // of a thread-count-dependent order). The masses change by up to 3.3e-14 (observed, with
    // fraction-weighted fluxes; 6e-15 with Youngs), 3x below the bound.
    EXPECT_NEAR(v1, v0, test::roundoff(1e-13)) << "ball volume conserved";
    for (std::size_t q = 0; q < mm0.size(); ++q)
      EXPECT_NEAR(mm1[q] / mm0[q], 1.0, test::roundoff(1e-13));
    // relative to the sphere's volume (tests/exact/norms.hpp, shared with perf/tradeoff.cpp)
    return exact::shape_error(f0, f1, cell);
  };
  const double y16 = shape_error(16, "youngs"), y32 = shape_error(32, "youngs");
  const double s16 = shape_error(16, "slic"), n16 = shape_error(16, "none");
  std::printf(
      "sphere advection, one period, L1 shape error / sphere volume: Youngs 16^3 %.4f, 32^3 "
      "%.4f (order %.2f); SLIC 16^3 %.4f; no reconstruction 16^3 %.4f\n",
      y16, y32, std::log2(y16 / y32), s16, n16);
  // Accuracy at 32^3 (observed 0.0089 under the default cloverleaf step, 2026-12-07, 2.2x
  // below; 0.0101 under the combined rule): the bound was the 16^3 error then, 0.0153 (0.0133
  // now), at the observed order 0.6 and then some; the verification is the trend below.
  EXPECT_LT(y32, 0.02);
  // Falls with resolution: observed ratio 0.67 (order 0.58; 0.66 under combined), within 16 % of
  // the bound 0.8 because the L1 shape error of a moving interface converges slowly at these
  // resolutions (the sphere is 5 to 10 cells across); 0.8 is order 0.32, the least that still says
  // the error falls by more than round-off or noise.
  EXPECT_LT(y32, 0.8 * y16);
  // Youngs (piecewise-planar, exact for a plane) against SLIC (axis-aligned planes, an O(1)
  // error in every interface cell): observed ratio 0.067; the bound 0.2 (3x) says Youngs is
  // several times better, as the plane-exact reconstruction should be; was 0.8 (12x).
  EXPECT_LT(y16, 0.2 * s16);
  // and SLIC better than fraction-weighted fluxes, which smear the interface every step
  // (observed ratio 0.28; the bound is only the ordering)
  EXPECT_LT(s16, n16);
}

TEST(MultiMaterial, TriplePointConservesEveryMaterialsMass) {
  const Scene scene = test::load_scene("triple_point.yaml");
  auto r = test::run_scene(scene);
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  // The step the end time limits sets t = t_end exactly (Simulation::run; observed 0); the
  // loop would also stop on a sum of steps within 1e-12 t_end (3e-12) of it, which this bound
  // (1e-12) would flag as the end step going missing.
  EXPECT_NEAR(r.result.time, 3.0, 1e-12);
  const auto& a = r.result.start.material_mass;
  const auto& b = r.result.end.material_mass;
  ASSERT_EQ(a.size(), 3u);
  std::printf("triple point: end time - 3 = %.2e; initial masses - exact: %.2e %.2e %.2e\n",
              r.result.time - 3.0, a[0] - 0.3, a[1] - 0.9, a[2] - 0.1125);
  // The initial masses are sums over 4200 cells: N eps = 4.7e-13 of the mass if every
  // rounding had one sign, sqrt(N) eps = 7e-15 for roundings of mixed sign. The reduction's
  // order depends on the thread count: observed 2e-16 to 5.6e-16 with one count, up to 4.4e-14
  // (heavy, 0.9) with another, so the bound, 1e-13 (2.3x), lies between the typical and the
  // worst case.
  // exact initial masses: driver 1 x 3 x 0.1 x 1.0, heavy 6 x 1.5 x 0.1 x 1.0, light 6 x 1.5 x 0.1
  // x 0.125
  EXPECT_NEAR(a[0], 0.3, test::roundoff(1e-13));
  EXPECT_NEAR(a[1], 0.9, test::roundoff(1e-13));
  EXPECT_NEAR(a[2], 0.1125, test::roundoff(1e-13));
  double worst = 0;
  for (int q = 0; q < 3; ++q) {
    const double rel = std::abs(b[q] - a[q]) / a[q];
    worst = std::max(worst, rel);
    // The fields do not depend on the thread count (checked bitwise), but the two mass sums
    // over 4200 cells do: each carries reduction round-off up to ~N eps = 4200 x 1.1e-16 =
    // 4.7e-13 in the worst case (observed 4e-15 to 5e-14 with 2 and 1 threads).
    EXPECT_LT(rel, test::roundoff(2e-13)) << scene.materials[q].name;
  }
  const double de = (r.result.end.total() - r.result.start.total()) / r.result.start.total();
  std::printf(
      "triple point: %ld cycles to t = %.2f; largest material mass change %.2e; total "
      "energy change %.2e\n",
      r.result.cycles, r.result.time, worst, de);
  // Closed box, KE fix returning the remap's whole discrepancy: round-off only
  // (test::energy_roundoff: 9.9e-13 for 186 cycles, the worst case of roundings of one sign;
  // observed -1.5e-14 to -4.6e-14, roundings of mixed sign cancel). Until 2026-11 the fix
  // returned only dissipation: +2.6e-4.
  EXPECT_LT(std::abs(de), test::energy_roundoff(r.result.cycles));
}

TEST(MultiMaterial, DenseAndCompactLayoutsAgree) {
  expect_layouts_agree("sod2.yaml", {"time.end=0.1"});
  expect_layouts_agree("triple_point.yaml", {"mesh.cells=[35,15,2]", "time.end=1.5"});
  expect_layouts_agree("sphere_advection.yaml", {"mesh.cells=[12,12,12]", "time.end=1.0"});
  expect_layouts_agree("sphere_advection.yaml",
                       {"mesh.cells=[12,12,12]", "time.end=1.0", "numerics.interface=slic"});
  // pressure relaxation rewrites the volume fractions of mixed cells: both layouts alike
  expect_layouts_agree("water_air.yaml", {"time.end=60", "numerics.closure=relaxation"});
  expect_layouts_agree("triple_point.yaml",
                       {"mesh.cells=[35,15,2]", "time.end=1.5", "numerics.closure=relaxation"});
  // strength and burn in mixed cells (4 materials; the deviator, plastic strain, burn
  // fraction and lighting times are among the output fields compared)
  expect_layouts_agree("charge_3d.yaml", {"time.end=1.5", "output.write=false"});
  // with no fraction floor asked for, the build's own floor keeps the layouts together
  expect_layouts_agree("sphere_advection.yaml",
                       {"mesh.cells=[12,12,12]", "time.end=1.0", "numerics.min_fraction=0"});
}

// The third-order remap (numerics.advection: third) in multi-material scenes: both layouts give
// the same fields (the pure donors' face values, the strength deviators, plastic strain and burn
// fraction of charge_3d, the sphere's interface transport), and on the two-material shock tube no
// error more than 5 % above second order's (issue #53).
TEST(MultiMaterial, ThirdOrderLayoutsAgreeAndSod2NoWorseThanSecond) {
  expect_layouts_agree("sod2.yaml", {"time.end=0.1", "numerics.advection=third"});
  expect_layouts_agree("triple_point.yaml",
                       {"mesh.cells=[35,15,2]", "time.end=1.5", "numerics.advection=third"});
  expect_layouts_agree("sphere_advection.yaml",
                       {"mesh.cells=[12,12,12]", "time.end=1.0", "numerics.advection=third"});
  expect_layouts_agree("charge_3d.yaml",
                       {"time.end=1.5", "output.write=false", "numerics.advection=third"});
  for (int n : {100, 200, 400}) {
    const Sod2 s = run_sod2(n), t = run_sod2(n, "third");
    std::printf(
        "two-material Sod %d cells, second / third: L1(rho) %.4e / %.4e, L1(p) %.4e / "
        "%.4e, interface %+.3f / %+.3f cells\n",
        n, s.l1, t.l1, s.l1p, t.l1p, (s.interface - s.contact) / s.dx,
        (t.interface - t.contact) / t.dx);
    EXPECT_LE(t.l1, 1.05 * s.l1) << n;
    EXPECT_LE(t.l1p, 1.05 * s.l1p) << n;
    EXPECT_LE(t.mixed, 2) << n;
  }
}

// min_fraction is at least 4 ulps of 1 in Real (a smaller sliver leaves 1 - f at exactly 1,
// pure to the dense layout and mixed to the compact one), and the run log says when it raised
// the deck's value.
TEST(MultiMaterial, MinFractionFloorIsAppliedAndLogged) {
  const double floor = 4 * double(std::numeric_limits<Real>::epsilon());
  EXPECT_EQ(hydro::kMinFractionFloor, floor);
  EXPECT_EQ(hydro::effective_min_fraction(0.0), floor);
  EXPECT_EQ(hydro::effective_min_fraction(1e-3), 1e-3);
  // (1 - floor < 1 in Real follows from floor = 4 ulps, pinned above; the two asserts that
  // restated it on the local `floor` could not fail and were dropped, issue #55)
  const auto line = [](const std::string& value) {
    RunSettings settings;
    settings.quiet = true;
    const Simulation sim(test::load_scene("sod2.yaml", {"numerics.min_fraction=" + value}),
                         MPI_COMM_WORLD, settings);
    for (const auto& m : sim.modules())
      if (m.find("min fraction") != std::string::npos) return m;
    return std::string();
  };
  const std::string raised = line("0"), kept = line("1e-5");
  std::printf("%s\n", raised.c_str());
  EXPECT_NE(raised.find("raised to 4 ulps of 1"), std::string::npos) << raised;
  EXPECT_NE(kept.find("min fraction 1e-05"), std::string::npos) << kept;
  EXPECT_EQ(kept.find("raised"), std::string::npos) << kept;
}

namespace {

// A shock tube along x run to its end, with the global fields the comparisons read (x fastest):
// cell rho, e, p, the fraction of material 0, and node u.
struct Tube {
  test::Ran run;
  std::vector<double> rho, e, p, u, f0;
};

Tube run_tube(const std::string& deck, const std::vector<std::string>& overrides) {
  Tube t{test::run_scene(test::load_scene(deck, overrides)), {}, {}, {}, {}, {}};
  EXPECT_TRUE(t.run.result.ok);
  const Mesh& m = t.run.sim->mesh();
  const auto& s = t.run.sim->hydro().state();
  t.rho = test::gather(m, s.rho, Centering::Cell);
  t.e = test::gather(m, s.e, Centering::Cell);
  t.p = test::gather(m, s.p, Centering::Cell);
  t.u = test::gather(m, s.u, Centering::Node);
  t.f0 = test::gather(m, t.run.sim->hydro().materials()->fraction(0), Centering::Cell);
  return t;
}

// The water-air tube (configs/water_air.yaml) with one mixed-cell closure, against the exact
// stiffened-gas / ideal-gas Riemann solution.
struct WaterAir {
  double p_star, u_star;      // exact
  double p_air, u_mean;       // computed: mean p of the shocked air, mean u of the star region
  double e_air_err;           // largest |e - e*| / e* in the shocked air (wall heating)
  double interface, contact;  // computed water extent vs exact contact
  double shock, shock_exact;  // where p crosses (p* + p_R) / 2
  double l1u;                 // L1(u) / (u* length)
  double dx, p_air_min, p_water_min, p_mixed_min, rho_min, e_min;
  int mixed;
  long cycles;
  bool finite;
};

WaterAir run_water_air(const std::vector<std::string>& overrides) {
  const Tube tube = run_tube("water_air.yaml", overrides);
  const auto& r = tube.run;
  const Mesh& m = r.sim->mesh();
  const auto &rho = tube.rho, &e = tube.e, &p = tube.p, &u = tube.u, &water = tube.f0;
  // water: stiffened gas gamma 4.4, p_inf 6e-3 Mbar (library 'water_stiffened'); air: 1.4
  const double pl = 1e-2, pr = 1e-6;
  const exact::Riemann rs({1.0, 0.0, pl}, {1e-3, 0.0, pr}, 4.4, 1.4, 6e-3, 0.0);
  const int nx = m.global_cells(0);
  const double dx = m.dx(0), t = 240.0, x0 = 70.0, len = nx * dx;
  WaterAir w{};
  w.p_star = rs.p_star();
  w.u_star = rs.u_star();
  w.dx = dx;
  w.cycles = r.result.cycles;
  w.contact = x0 + rs.u_star() * t;
  w.shock_exact = x0 + rs.right_head_speed() * t;
  w.p_air_min = w.p_water_min = w.p_mixed_min = w.rho_min = w.e_min = 1e300;
  w.finite = true;
  // Star region: from the rarefaction tail to the shock, 4 cells clear of each wave; the
  // shocked air from 1 cell past the contact (its first cells show the wall heating).
  const double lo = x0 + rs.left_tail_speed() * t + 4 * dx;
  const double hi = w.shock_exact - 4 * dx;
  const double e_air = rs.p_star() / (0.4 * rs.rho_star_right());
  const double p_half = 0.5 * (rs.p_star() + pr);
  double psum = 0, usum = 0;
  int pn = 0, un = 0;
  for (int i = 0; i < nx; ++i) {
    const double x = (i + 0.5) * dx;
    w.interface += water[i] * dx;
    w.rho_min = std::min(w.rho_min, rho[i]);
    w.e_min = std::min(w.e_min, e[i]);
    w.finite = w.finite && std::isfinite(p[i]) && std::isfinite(rho[i]) && std::isfinite(e[i]);
    if (water[i] == 1)
      w.p_water_min = std::min(w.p_water_min, p[i]);
    else if (water[i] == 0)
      w.p_air_min = std::min(w.p_air_min, p[i]);
    else {
      w.p_mixed_min = std::min(w.p_mixed_min, p[i]);
      ++w.mixed;
    }
    if (water[i] == 0 && x > w.contact + dx && x < hi) {
      psum += p[i];
      ++pn;
      w.e_air_err = std::max(w.e_air_err, std::abs(e[i] / e_air - 1));
    }
    if (i > 0 && p[i - 1] >= p_half && p[i] < p_half && x > w.contact)
      w.shock = x - dx + dx * (p[i - 1] - p_half) / (p[i - 1] - p[i]);
  }
  std::vector<double> xn(nx + 1);
  for (int i = 0; i <= nx; ++i) {
    const double x = i * dx;
    xn[i] = x;
    w.finite = w.finite && std::isfinite(u[i]);
    if (x > lo && x < hi) {
      usum += u[i];
      ++un;
    }
  }
  w.p_air = psum / pn;
  w.u_mean = usum / un;
  // L1(u) / (u* L) (tests/exact/norms.hpp, shared with perf/tradeoff.cpp)
  w.l1u = exact::l1_velocity(xn, u, dx, rs, x0, t) / (rs.u_star() * len);
  std::printf(
      "water-air, %d cells, %ld cycles: shocked-air p %.5e vs exact %.5e (%+.2f %%), star u "
      "%.5e vs %.5e (%+.2f %%), L1(u)/(u* L) %.2e; shocked-air e error up to %.1f %%; interface "
      "%.3f vs contact %.3f (%+.2f cells); shock %.2f vs %.2f (%+.2f cells); %d mixed; min p: "
      "air %.3e, mixed %.3e, water %.3e; min rho %.3e, min e %.3e\n",
      nx, w.cycles, w.p_air, w.p_star, 100 * (w.p_air / w.p_star - 1), w.u_mean, w.u_star,
      100 * (w.u_mean / w.u_star - 1), w.l1u, 100 * w.e_air_err, w.interface, w.contact,
      (w.interface - w.contact) / dx, w.shock, w.shock_exact, (w.shock - w.shock_exact) / dx,
      w.mixed, w.p_air_min, w.p_mixed_min, w.p_water_min, w.rho_min, w.e_min);
  return w;
}

}  // namespace

// Water pulled apart: the two halves of a 1 cm water column (stiffened gas, library
// 'water_stiffened') start at +-0.01 cm/us, so the middle goes into tension of about
// rho c du = 1.6e-3 Mbar. `air` names a second material (a 0.1 cm slab at the right wall) so
// that a multi-material scene runs the mixed-cell kernels; `single` drops it.
struct Spall {
  double p_min, rho_min, dm, de;
  long at_cutoff, cycles;
};

Spall run_spall(bool single, const std::string& p_min) {
  std::string text =
      "scene: spall\n"
      "mesh: {cells: [100, 2, 2], lo: [0, 0, 0], hi: [1, 0.02, 0.02]}\n"
      "boundaries: {x: reflective, y: periodic, z: periodic}\n"
      "time: {end: 2.0, cfl: 0.5}\n"
      "materials:\n"
      "  - name: water\n"
      "    library: water_stiffened\n" +
      (p_min.empty() ? std::string() : "    p_min: " + p_min + "\n") +
      (single ? "" : "  - name: air\n    library: air\n") +
      "regions:\n"
      "  - {material: water, shape: all, density: 1.0, pressure: 1.0e-6, velocity: [-0.01, 0, 0]}\n"
      "  - {material: water, shape: box, lo: [0.5, -1, -1], hi: [2, 1, 1], density: 1.0,\n"
      "     pressure: 1.0e-6, velocity: [0.01, 0, 0]}\n" +
      (single ? ""
              : "  - {material: air, shape: box, lo: [0.9, -1, -1], hi: [2, 1, 1], "
                "density: 1.0e-3, pressure: 1.0e-6}\n") +
      "output: {write: false}\n";
  const Scene scene = read_scene(Deck::parse(text, "spall.yaml"));
  auto r = test::run_scene(scene);
  EXPECT_TRUE(r.result.ok);
  const Mesh& m = r.sim->mesh();
  const auto p = test::gather(m, r.sim->hydro().state().p, Centering::Cell);
  const auto rho = test::gather(m, r.sim->hydro().state().rho, Centering::Cell);
  Spall sp{1e300, 1e300, 0, 0, 0, r.result.cycles};
  // the cutoff as the fields hold it (-5e-4 is -5.00000024e-4 in float)
  const double cut = p_min.empty() ? -1e300 : double(Real(std::stod(p_min)));
  for (std::size_t i = 0; i < p.size(); ++i) {
    sp.p_min = std::min(sp.p_min, p[i]);
    if (rho[i] > 0.5) sp.rho_min = std::min(sp.rho_min, rho[i]);  // water cells
    if (p[i] == cut) ++sp.at_cutoff;
  }
  sp.dm = (r.result.end.mass - r.result.start.mass) / r.result.start.mass;
  sp.de = (r.result.end.total() - r.result.start.total()) / r.result.start.total();
  std::printf(
      "spall (%s, p_min %s): %ld cycles, min p %.4e, min water rho %.6f, %ld cells at "
      "the cutoff, mass change %.2e, energy change %.2e\n",
      single ? "single material" : "water + air", p_min.empty() ? "none" : p_min.c_str(),
      r.result.cycles, sp.p_min, sp.rho_min, sp.at_cutoff, sp.dm, sp.de);
  return sp;
}

TEST(MultiMaterial, TensionCutoffHoldsPressureAtPmin) {
  for (bool single : {true, false}) {
    const Spall raw = run_spall(single, "");
    const Spall cut = run_spall(single, "-5.0e-4");
    // Without a cutoff the EOS carries the tension: acoustic estimate rho c du = 1.6e-3 Mbar
    // (observed -1.49e-3 single, -1.62e-3 with air); the bound asks for 2/3 of it.
    EXPECT_LT(raw.p_min, -1e-3);
    // With one, no cell goes below p_min and the middle sits at it (4 cells across y, z at
    // least), so the cutoff is what holds the pressure there.
    EXPECT_GE(cut.p_min, double(Real(-5e-4)));
    EXPECT_GE(cut.at_cutoff, 4);
    // The water that cannot carry the tension opens up (cavitates) in the middle: the cutoff
    // changes the motion, not only the pressure written out. Without it the water stretches
    // elastically by |p| / (rho c^2) = 1.6e-3 / 2.64e-2 = 6 %, rho = 0.94 (observed 0.931 to
    // 0.936); with it, it opens (observed 0.779). The two bounds separate the outcomes and lie
    // within 15 % of the observations because they sit between them: 0.9 allows for the
    // stiffened gas's nonlinearity below the acoustic 0.94; 0.85 is 10 % below it, more than
    // elastic stretching alone can reach.
    EXPECT_LT(cut.rho_min, 0.85);
    EXPECT_GT(raw.rho_min, 0.9);
    // Mass to round-off: a rounding per cell in each of 3 remap sweeps of 122 cycles, 3 x 122
    // x 2.2e-16 = 8e-14 if all of one sign (observed 2.4e-15 to 8.7e-15). The cutoff pressure
    // does the p dV work, and the KE fix returns the remap's discrepancy, so total energy is
    // conserved to round-off in this closed box (test::energy_roundoff, 6.5e-13 for 122
    // cycles; observed 1.7e-15 to 6.8e-15). Was 1e-5, from before the KE fix returned the
    // whole discrepancy (then 2e-7 to 1.4e-6).
    for (const Spall* s : {&raw, &cut}) {
      EXPECT_LT(std::abs(s->dm), test::roundoff(1e-13));
      EXPECT_LT(std::abs(s->de), test::energy_roundoff(s->cycles));
    }
  }
}

// One water-air run per closure and resolution, shared by the two tests below.
const WaterAir& water_air(const std::string& closure, int cells) {
  static std::map<std::pair<std::string, int>, WaterAir> runs;
  const auto key = std::make_pair(closure, cells);
  auto it = runs.find(key);
  if (it == runs.end())
    it = runs.emplace(key, run_water_air({"numerics.closure=" + closure,
                                          "mesh.cells=[" + std::to_string(cells) + ",2,2]"}))
             .first;
  return it->second;
}

// The water-air criterion as issue #16 restates it: the star state and the interface against
// the exact solution, no negative pressure in the air and the interface cells, and pure-water
// tension bounded by 5 % of the initial water pressure at 200 cells (the exact solution has
// none; the bound is the criterion, not this scheme's observation of 2.3 %).
TEST(MultiMaterial, WaterAirShockTubeStarStateAndBoundedTension) {
  // Observed at 200 / 400 cells (2026-12-06, double): equal strain p +0.17 / -0.01 %, u +0.13 /
  // +0.08 %, air e error 2.8 / 2.1 %, shock -0.00 / +0.02 cells, interface +0.02 / +0.02 cells;
  // relaxation p +0.19 / -0.01 %, u +0.10 / +0.06 %, air e error 0.9 / 0.6 %, shock -0.09 /
  // -0.07 cells, interface +0.03 / +0.03 cells; 1 mixed cell each. The star-state bounds here
  // are the accuracy issue #16 records for this problem (p*, u* within 0.3 %), with margin, at
  // both resolutions; WaterAirStarStateConverges shows the star velocity's error falling.
  for (const int cells : {200, 400}) {
    const WaterAir& es = water_air("equal_strain", cells);
    const WaterAir& rx = water_air("relaxation", cells);
    for (const WaterAir* w : {&es, &rx}) {
      const std::string name =
          std::string(w == &es ? "equal strain, " : "relaxation, ") + std::to_string(cells);
      EXPECT_TRUE(w->finite) << name;
      EXPECT_GT(w->rho_min, 0) << name;
      EXPECT_GT(w->e_min, 0) << name;
      // the air and the interface cells never go below zero pressure
      EXPECT_GT(w->p_air_min, 0) << name;
      EXPECT_GT(w->p_mixed_min, 0) << name;
      EXPECT_GE(w->mixed, 1) << name;
      EXPECT_LE(w->mixed, 2) << name;
      // Pure water: the start-up error of the sharp diaphragm rides the u - c characteristic
      // that coincides with the rarefaction tail (single-material Sod has the same -0.9 % density
      // dip there; docs/numerics.md); water's stiffness turns it into a tension: observed
      // -2.3e-4 / -1.8e-4 Mbar with equal strain, -1.9e-4 / -1.5e-4 with relaxation at 200 / 400
      // cells (2.3 % of the initial pressure at most). Bound: 5 % of the initial water pressure,
      // -5e-4 (2.2x the largest), well inside the stiffened-gas validity limit p > -p_inf =
      // -6e-3 Mbar. Reference Lagrangian Godunov schemes undershoot here too, by less
      // (tools/water_air_godunov.py: -2.3e-5 first order, -7.1e-6 MUSCL-Hancock at 200 cells,
      // against p* = 4.8e-6).
      EXPECT_GT(w->p_water_min, -0.05 * 1e-2) << name;
      // Interface at the exact contact: 0.15 cells (5x the largest observation, 0.03) is a
      // contact speed error of 0.15 dx / (u* t) = 0.64 % at 200 cells, within the star-speed
      // bound; was 2 cells.
      EXPECT_LT(std::abs(w->interface - w->contact), 0.15 * w->dx) << name;
      // Star velocity: 0.4 % (#16's 0.3 % with a third for margin; observed at most +0.13 %).
      EXPECT_LT(std::abs(w->u_mean / w->u_star - 1), 0.004) << name;
      // Shocked-air pressure: 0.4 % as for u (observed at most 0.19 %).
      EXPECT_LT(std::abs(w->p_air / w->p_star - 1), 0.004) << name;
      // The shocked air's energy (the wall heating beside the interface): within 5 % (observed
      // 2.8 / 2.1 % with equal strain, 0.9 / 0.6 % with relaxation; 56 % with equal strain
      // before the closure's fixes of 2026-12, when a pin held it) and the air shock within
      // one cell of the exact one (observed at most 0.09 cells; +2.13 before).
      EXPECT_LT(w->e_air_err, 0.05) << name;
      EXPECT_LT(std::abs(w->shock - w->shock_exact), 1 * w->dx) << name;
    }
    // the wall heating falls with the mesh (2.8 -> 2.1 %, 0.9 -> 0.6 %)
    if (cells == 400) {
      EXPECT_LT(es.e_air_err, water_air("equal_strain", 200).e_air_err);
      EXPECT_LT(rx.e_air_err, water_air("relaxation", 200).e_air_err);
    }
  }
}

// The water-air star state against the exact solution at 200 and 400 cells, both closures:
// the errors of the star velocity (mean over the star region) and the star pressure (mean of
// the shocked air) printed at each; the velocity's falling, both bounded at 400 cells.
TEST(MultiMaterial, WaterAirStarStateConverges) {
  for (const std::string closure : {"equal_strain", "relaxation"}) {
    const WaterAir& c = water_air(closure, 200);
    const WaterAir& f = water_air(closure, 400);
    const double uc = std::abs(c.u_mean / c.u_star - 1), uf = std::abs(f.u_mean / f.u_star - 1);
    const double pc = std::abs(c.p_air / c.p_star - 1), pf = std::abs(f.p_air / f.p_star - 1);
    std::printf(
        "water-air %s, 200 -> 400 cells: |u/u* - 1| %.4f %% -> %.4f %% (ratio %.3f), "
        "|p/p* - 1| %.4f %% -> %.4f %% (ratio %.3f)\n",
        closure.c_str(), 100 * uc, 100 * uf, uf / uc, 100 * pc, 100 * pf, pf / pc);
    // Falling. The star velocity converges at order 0.6 to 0.9 from 200 cells, 0.2 to 0.4 from
    // 100 to 200 (measured 2026-12-02 at 100, 200, 400, 800 cells: equal strain +0.157,
    // +0.116, +0.076, +0.041 %; relaxation +0.106, +0.092, +0.060, +0.032 %): the plateau mean
    // carries the start-up error of the sharp diaphragm, which decays slowly. Observed ratios
    // 0.60 and 0.62 (2026-12-06); the bound 0.8 (order 0.32), 1.3x above them, says the error
    // falls by more than the plateau's noise, not at a rate.
    EXPECT_LT(uf, 0.8 * uc) << closure;
    // The shocked-air pressure error drops to the plateau mean's noise by 400 cells (equal
    // strain -0.81 % at 100 -> -0.17 % -> +0.011 % -> +0.011 % at 800; relaxation +0.028 % ->
    // +0.11 % -> +0.0008 % -> -0.005 %, crossing zero): its ratio is not a rate and is not
    // asserted (issue #55; it was, at 0.8). At 400 cells both are bounded by #16's 0.3 % at 200
    // cells carried to 400 at first order, 0.15 %. Observed u 0.078 %, 0.062 % (1.9x, 2.4x
    // below); p 0.0075 %, 0.0061 % (the plateau mean's noise: a bound near them would pin this
    // code's noise, not its accuracy).
    EXPECT_LT(uf, 0.0015) << closure;
    EXPECT_LT(pf, 0.0015) << closure;
  }
}

// The exact solver for an arbitrary-EOS left state (tests/exact/isentrope_riemann.hpp) against
// the closed-form stiffened-gas one where both apply, and against itself at half the steps.
TEST(ExactSolution, IsentropeRiemannMatchesClosedForm) {
  // The isentrope solver evaluates the EOS in Real: a float build reaches about 1e-7 (observed
  // up to 5e-8 on Sod, 1.7e-7 on 123) and, for water, the float resolution of its pressure,
  // 3e-9 Mbar against p* = 4.8e-6 (observed 2.6e-4).
  // In double the solver's error is that of interpolating its table linearly between nodes
  // h = ln(1e-4) / 200000 = 4.6e-5 apart (RK4's own, h^4, is 1e-17): h^2 / 8 = 2.7e-10 times
  // the curvature of e(s), u(s), O(1) for these gases. The bound 1e-9 is that estimate with a
  // curvature up to 4; the observed differences, printed at the end, are 3e-12 to 3e-11 (the
  // star state rarely sits mid-interval, where the estimate is reached). Was 1e-8.
  const double tol = test::by_precision(1e-9, 2e-7);
  // Every comparison goes through `near`, which keeps each block's largest difference and its
  // bound; all are printed at the end.
  std::vector<std::pair<std::string, std::pair<double, double>>> seen;
  const auto near = [&](double a, double b, double bound, const char* what) {
    EXPECT_NEAR(a, b, bound) << what;
    if (seen.empty() || seen.back().first != what) seen.push_back({what, {0.0, bound}});
    seen.back().second.first = std::max(seen.back().second.first, std::abs(a - b));
  };
  const eos::Eos gas = eos::make_eos(eos::IdealGas{1.4});
  const exact::IsentropeRiemann a(gas, 1.0, 0.0, 1.0 / 0.4, 0.125, 0.0, 0.1, 1.4);
  const exact::Riemann b({1, 0, 1}, {0.125, 0, 0.1}, 1.4, 1.4);
  near(a.p_star() / b.p_star(), 1.0, tol, "Sod p*");
  near(a.u_star() / b.u_star(), 1.0, tol, "Sod u*");
  for (double xi : {-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.7, 2.0}) {
    const auto s = a.sample(xi);
    const auto t = b.sample(xi);
    near(s.rho, t.rho, tol, "Sod profile");
    near(s.u, t.u, tol, "Sod profile");
    near(s.p, t.p, tol, "Sod profile");
  }
  // Toro's 123 problem: two rarefactions, so the right-rarefaction branch is sampled too
  const exact::IsentropeRiemann e123(gas, 1.0, -2.0, 0.4 / 0.4, 1.0, 2.0, 0.4, 1.4);
  const exact::Riemann t123({1, -2, 0.4}, {1, 2, 0.4}, 1.4, 1.4);
  near(e123.p_star() / t123.p_star(), 1.0, test::by_precision(1e-9, 1e-6), "123 p*");
  near(e123.u_star(), t123.u_star(), tol, "123 u*");
  for (double xi : {-3.0, -2.0, -1.0, -0.2, 0.0, 0.2, 1.0, 2.0, 3.0}) {
    const auto s = e123.sample(xi);
    const auto t = t123.sample(xi);
    near(s.rho, t.rho, tol, "123 profile");
    near(s.u, t.u, tol, "123 profile");
    near(s.p, t.p, tol, "123 profile");
  }
  // water (stiffened gas) into air: the isentrope stops before p = 0, p* = 4.8e-6 Mbar
  const eos::Eos water = eos::make_eos(eos::StiffenedGas{4.4, 6e-3});
  const double ew = (1e-2 + 4.4 * 6e-3) / 3.4;
  const exact::IsentropeRiemann c(water, 1.0, 0.0, ew, 1e-3, 0.0, 1e-6, 1.4);
  const exact::Riemann d({1, 0, 1e-2}, {1e-3, 0, 1e-6}, 4.4, 1.4, 6e-3, 0);
  // (double: water expands from 1e-2 to 4.8e-6 Mbar, far down the table where the curvature
  // of u(s) is larger: observed 2.0e-9 (p*), 1.6e-9 (u*); bound 1e-8, 5x; was 1e-7)
  near(c.p_star() / d.p_star(), 1.0, test::by_precision(1e-8, 1e-3), "water p*");
  near(c.u_star() / d.u_star(), 1.0, test::by_precision(1e-8, 1e-5), "water u*");
  // JWL products: the table at half the number of steps gives the same star state, to the
  // interpolation estimate at the doubled step, (2h)^2 / 8 = 1.1e-9 (observed 6e-12 to 1.3e-11)
  const auto* m = materials::find_material("pbx9404_products");
  const eos::Eos jwl = materials::make_eos(*m);
  const double e0 = m->param("E0") / m->rho0;
  const exact::IsentropeRiemann fine(jwl, m->rho0, 0.0, e0, 1.225e-3, 0.0, 1e-6, 1.4);
  const exact::IsentropeRiemann half(jwl, m->rho0, 0.0, e0, 1.225e-3, 0.0, 1e-6, 1.4, 100000);
  near(half.p_star() / fine.p_star(), 1.0, test::by_precision(1e-9, 1e-6), "JWL half-steps p*");
  near(half.u_star() / fine.u_star(), 1.0, test::by_precision(1e-9, 1e-6), "JWL half-steps u*");
  // ... and lies on the closed-form JWL isentrope through the left state,
  // p_s(V) = A exp(-R1 V) + B exp(-R2 V) + C V^-(1 + omega), V = rho0 / rho
  const auto j = jwl.jwl();
  const double pl = jwl.pressure(m->rho0, e0);
  const double cc = pl - j.a * std::exp(-j.r1) - j.b * std::exp(-j.r2);  // V_L = 1
  const double vs = m->rho0 / fine.rho_star_left();
  const double ps =
      j.a * std::exp(-j.r1 * vs) + j.b * std::exp(-j.r2 * vs) + cc * std::pow(vs, -(1 + j.omega));
  // the same interpolation estimate as above in double (observed 3.6e-11; was 1e-6); float
  // evaluates the EOS in Real, as for the gases
  near(fine.p_star() / ps, 1.0, test::by_precision(1e-9, 1e-6), "JWL closed-form isentrope");
  for (const auto& [what, v] : seen)
    std::printf("isentrope solver vs reference, %-26s largest difference %.2e (bound %.0e)\n",
                what.c_str(), v.first, v.second);
}

namespace {

// PBX 9404 products (JWL) expanding into air, configs/products_air.yaml, against the exact
// solution: 1.5e5 pressure ratio, the products expand 16-fold.
struct ProductsAir {
  double p_star, u_star, rho_star, contact, shock_exact;
  double p_air, u_mean, rho_products, interface, dx, p_min, rho_min, e_min;
  double dm_products, dm_air;
  bool finite;
};

ProductsAir run_products_air(const std::vector<std::string>& overrides) {
  const Tube tube = run_tube("products_air.yaml", overrides);
  const auto& r = tube.run;
  const Mesh& m = r.sim->mesh();
  const auto &rho = tube.rho, &e = tube.e, &p = tube.p, &u = tube.u, &f = tube.f0;
  const auto* lib = materials::find_material("pbx9404_products");
  const exact::IsentropeRiemann rs(materials::make_eos(*lib), lib->rho0, 0.0,
                                   lib->param("E0") / lib->rho0, 1.225e-3, 0.0, 1e-6, 1.4);
  const int nx = m.global_cells(0);
  const double dx = m.dx(0), t = 10.0, x0 = 6.0;
  ProductsAir w{};
  w.p_star = rs.p_star();
  w.u_star = rs.u_star();
  w.rho_star = rs.rho_star_left();
  w.contact = x0 + rs.u_star() * t;
  w.shock_exact = x0 + rs.right_head_speed() * t;
  w.dx = dx;
  w.p_min = w.rho_min = w.e_min = 1e300;
  w.finite = true;
  const double tail = x0 + rs.left_tail_speed() * t;
  double psum = 0, usum = 0, rsum = 0;
  int pn = 0, un = 0, rn = 0;
  for (int i = 0; i < nx; ++i) {
    const double x = (i + 0.5) * dx;
    w.interface += f[i] * dx;
    // minima over the cells holding products (the untouched air would set them otherwise)
    if (f[i] > 0) {
      w.p_min = std::min(w.p_min, p[i]);
      w.rho_min = std::min(w.rho_min, rho[i]);
      w.e_min = std::min(w.e_min, e[i]);
    }
    w.finite = w.finite && std::isfinite(p[i]) && std::isfinite(rho[i]) && std::isfinite(e[i]);
    // shocked air: from 2 cells past the contact to 4 cells before the shock
    if (f[i] == 0 && x > w.contact + 2 * dx && x < w.shock_exact - 4 * dx) {
      psum += p[i];
      ++pn;
    }
    // expanded products: from the fan tail to 2 cells before the contact
    if (f[i] == 1 && x > tail && x < w.contact - 2 * dx) {
      rsum += rho[i];
      ++rn;
    }
  }
  for (int i = 0; i <= nx; ++i) {
    const double x = i * dx;
    w.finite = w.finite && std::isfinite(u[i]);
    if (x > tail + 2 * dx && x < w.shock_exact - 4 * dx) {
      usum += u[i];
      ++un;
    }
  }
  w.p_air = psum / pn;
  w.u_mean = usum / un;
  w.rho_products = rsum / rn;
  const auto& m0 = r.result.start.material_mass;
  const auto& m1 = r.result.end.material_mass;
  w.dm_products = (m1[0] - m0[0]) / m0[0];
  w.dm_air = (m1[1] - m0[1]) / m0[1];
  std::printf(
      "products-air, %d cells, %ld cycles: shocked-air p %.4e vs exact %.4e (%+.1f %%), star u "
      "%.4f vs %.4f (%+.1f %%), expanded products rho %.4f vs %.4f (%+.1f %%); interface %.3f vs "
      "contact %.3f (%+.1f cells); products cells: min p %.2e, min rho %.2e, min e %.2e; mass "
      "change "
      "%.1e / %.1e\n",
      nx, r.result.cycles, w.p_air, w.p_star, 100 * (w.p_air / w.p_star - 1), w.u_mean, w.u_star,
      100 * (w.u_mean / w.u_star - 1), w.rho_products, w.rho_star,
      100 * (w.rho_products / w.rho_star - 1), w.interface, w.contact,
      (w.interface - w.contact) / dx, w.p_min, w.rho_min, w.e_min, w.dm_products, w.dm_air);
  return w;
}

// |a / b - 1|: a computed value's relative error against the exact b.
double rel(double a, double b) {
  return std::abs(a / b - 1);
}

}  // namespace

// One run of each products-air variant, shared by the verification and the pin below: the
// deck's 400 cells with the KE fix on and off, and 800 and 1600 cells with it on.
const ProductsAir& products_air(bool ke_fix, int cells = 400) {
  static std::map<std::pair<bool, int>, ProductsAir> runs;
  const auto key = std::make_pair(ke_fix, cells);
  auto it = runs.find(key);
  if (it == runs.end())
    it = runs.emplace(key, run_products_air(
                               {"numerics.closure=equal_strain",
                                std::string("numerics.ke_fix=") + (ke_fix ? "true" : "false"),
                                "mesh.cells=[" + std::to_string(cells) + ",2,2]"}))
             .first;
  return it->second;
}

// What every products-air run must show, whatever its accuracy: finite, positive density,
// energy and pressure in the products' cells, each material's mass to round-off. Masses: a
// rounding per cell in each of 3 remap sweeps, 3 x 535 x 2.2e-16 = 3.5e-13 at 400 cells (6.5e-13
// for the 970 cycles at 800; the default cloverleaf step takes 363 and 649) if all of one sign;
// observed (2026-12-06) 2.8e-15 to 8.3e-15 at 400 cells (2026-12-07: 6.9e-15, 7.1e-15),
// 1.1e-14 and 1.3e-14 at 800 (2.0e-14, 1.1e-14), 2.0e-14 and 1.6e-14 at 1600 (mixed signs cancel,
// the sum grows as the square root of the roundings); bound 1e-13. Checked by the tests that use
// each run (until 2026-12-06 a test of its own, ProductsIntoAirAtTheExtremes).
void expect_products_air_sane(const ProductsAir& w, const std::string& name) {
  EXPECT_TRUE(w.finite) << name;
  EXPECT_GT(w.rho_min, 0) << name;
  EXPECT_GT(w.e_min, 0) << name;
  EXPECT_GT(w.p_min, 0) << name;
  EXPECT_LT(std::abs(w.dm_products), test::roundoff(1e-13)) << name;
  EXPECT_LT(std::abs(w.dm_air), test::roundoff(1e-13)) << name;
}

// The products-air star state against the exact solution at 400 and 800 cells (KE fix on, the
// default numerics): the star velocity (mean over the star region) and pressure (mean of the
// shocked air), the expanded products' density and the interface offset, each printed at both
// resolutions and falling. Measured (2026-12-01) at 200, 400, 800, 1600 cells: u +4.7, +2.2,
// +0.6, +0.1 %; p +2.6, +3.0, -0.7, -0.4 %; products density -34.1, -29.5, -16.2, -7.4 %;
// interface +0.34, +0.245, +0.129, +0.062 cm. With the KE fix's shares by mass (2026-12-03) at
// 400 / 800 cells: u +2.4 / +0.7 %, p +3.7 / -0.6 %, density -31.0 / -17.3 %, interface +0.262 /
// +0.138 cm (ratios 0.27, 0.16, 0.56, 0.53; the same on 2026-12-06).
TEST(MultiMaterial, ProductsIntoAirStarStateConverges) {
  const ProductsAir& c = products_air(true, 400);
  const ProductsAir& f = products_air(true, 800);
  expect_products_air_sane(c, "KE fix on, 400 cells");
  expect_products_air_sane(f, "KE fix on, 800 cells");
  const double uc = rel(c.u_mean, c.u_star), uf = rel(f.u_mean, f.u_star);
  const double pc = rel(c.p_air, c.p_star), pf = rel(f.p_air, f.p_star);
  const double rc = rel(c.rho_products, c.rho_star), rf = rel(f.rho_products, f.rho_star);
  const double ic = std::abs(c.interface - c.contact), iff = std::abs(f.interface - f.contact);
  std::printf(
      "products-air, 400 -> 800 cells: |u/u* - 1| %.2f %% -> %.2f %% (ratio %.2f), |p/p* - 1| "
      "%.2f %% -> %.2f %% (ratio %.2f), |rho/rho* - 1| %.1f %% -> %.1f %% (ratio %.2f), "
      "interface offset %.3f -> %.3f cm (ratio %.2f)\n",
      100 * uc, 100 * uf, uf / uc, 100 * pc, 100 * pf, pf / pc, 100 * rc, 100 * rf, rf / rc, ic,
      iff, iff / ic);
  // Star velocity: first order would halve it; the bound 0.7 (order 1/2) allows the slower
  // start of the 200 -> 400 step (ratio 0.47). Observed 0.27. The pressure's error changes sign
  // from 400 to 800 (+3.7 -> -0.6 %, then -0.5 % at 1600): its ratio (0.16) is not a rate and
  // is not asserted (issue #55; it was, at 0.7); its size at 800 cells is, below.
  EXPECT_LT(uf, 0.7 * uc);
  // At 800 cells: the 400-cell margins of this test before it ran two resolutions (5 % for p,
  // 4 % for u) carried to 800 at first order, 2.5 % and 2 %. Observed p 0.65 %, u 0.64 %
  // under the default cloverleaf step (2026-12-07; 0.59 %, 0.66 % under the combined one),
  // 3.8x and 3.1x below each.
  EXPECT_LT(pf, 0.025);
  EXPECT_LT(uf, 0.02);
  // The products' over-expansion (MultiMaterialRegressionPin.ProductsIntoAirOverExpansion) is
  // an error that converges: density and interface offset fall at order 0.86 and 0.93 from 400
  // to 800 (ratios 0.55, 0.53), more slowly from 200 to 400 (0.87, 0.72). The bound 0.75
  // (order 0.42) says they fall; it is not met from 200 to 400 for the density, which is why
  // this runs 400 and 800. The density error at 800 cells, 16 %, is still above issue #16's
  // 10 % (met at 1600 cells: 7.4 % then, 7.9 % with the shares by mass; the next test).
  EXPECT_LT(rf, 0.75 * rc);
  EXPECT_LT(iff, 0.75 * ic);
}

// Issue #16's products-into-air criterion, the expanded products' density within 10 % of the
// exact star density, with the default numerics (KE fix on, its shares by mass): not met at 400
// or 800 cells (above), so it is asserted where the converging error gets there, 1600 cells,
// and the error must keep falling from 800 to 1600 at the 400 -> 800 order's pace (bound 0.75,
// as above). Measured 2026-12-03 (double, 1 thread): density -17.3 % at 800 and -7.9 % at 1600
// cells (ratio 0.46, order 1.1), interface +0.138 and +0.067 cm (0.49), star p -0.5 %, u +0.1 %
// at 1600, 1,860 cycles (docs/numerics.md, "Products into air").
// Labelled long (the 1600-cell run is the suite's second-longest; ci/long.sh runs it in the
// double build; suite MultiMaterialLong, tests/CMakeLists.txt).
TEST(MultiMaterialLong, ProductsIntoAirDensityWithinTenPercentAt1600Cells) {
  const ProductsAir& f = products_air(true, 800);
  const ProductsAir& ff = products_air(true, 1600);
  expect_products_air_sane(ff, "KE fix on, 1600 cells");
  const double rf = rel(f.rho_products, f.rho_star), rff = rel(ff.rho_products, ff.rho_star);
  const double iff = std::abs(f.interface - f.contact), ifff = std::abs(ff.interface - ff.contact);
  std::printf(
      "products-air, 800 -> 1600 cells: |rho/rho* - 1| %.1f %% -> %.1f %% (ratio %.2f), "
      "interface offset %.3f -> %.3f cm (ratio %.2f)\n",
      100 * rf, 100 * rff, rff / rf, iff, ifff, ifff / iff);
  EXPECT_LT(rff, 0.10);
  EXPECT_LT(rff, 0.75 * rf);
  EXPECT_LT(ifff, 0.75 * iff);
  // the star state stays within the 800-cell bounds of the test above
  EXPECT_LT(rel(ff.p_air, ff.p_star), 0.025);
  EXPECT_LT(rel(ff.u_mean, ff.u_star), 0.02);
}

namespace {

// Products into air started from the exact solution at t0 instead of from the membrane at t = 0
// (docs/studies/2026-12-07-products-air-start-up.md): the deck's regions replaced by the
// self-similar state at t0, painted cell by cell (the fan's cells at their centre's similarity
// coordinate, the products cut at the exact contact, the shocked air one box up to the exact
// shock), run to t = 10 us, so the exact solution of run_products_air applies unchanged (x0 + s
// t with t = t0 + 10 - t0). What it separates: the start-up, while the fan spans a few cells,
// from how the scheme carries a resolved JWL fan, contact and strong air shock.
std::string self_similar_regions(double t0, int cells) {
  const auto* lib = materials::find_material("pbx9404_products");
  const exact::IsentropeRiemann rs(materials::make_eos(*lib), lib->rho0, 0.0,
                                   lib->param("E0") / lib->rho0, 1.225e-3, 0.0, 1e-6, 1.4);
  const double x0 = 6.0, dx = 14.0 / cells;
  const double head = x0 + rs.left_head_speed() * t0, contact = x0 + rs.u_star() * t0;
  const double shock = x0 + rs.right_head_speed() * t0;
  auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", v);
    return std::string(b);
  };
  auto box = [&](const char* material, double lo, double hi, const exact::EosState& q) {
    return std::string("{material: ") + material + ", shape: box, lo: [" + num(lo) +
           ", -1, -1], hi: [" + num(hi) + ", 1, 1], density: " + num(q.rho) +
           ", energy: " + num(q.e) + ", velocity: [" + num(q.u) + ", 0, 0]}";
  };
  std::string r = "regions=[{material: air, shape: all, density: 1.225e-3, pressure: 1.0e-6}, ";
  r += box("products", -1, head, rs.sample(-1e30));
  for (int i = 0; i < cells; ++i) {
    const double lo = std::max(i * dx, head), hi = std::min((i + 1) * dx, contact);
    if (!(hi > lo)) continue;
    r += ", " + box("products", lo, hi, rs.sample((0.5 * (lo + hi) - x0) / t0));
  }
  r += ", " + box("air", contact, shock, rs.sample(0.5 * (rs.u_star() + rs.right_head_speed())));
  return r + "]";
}

// One run from the self-similar start at t0 = 0.3 us (the fan 0.28 cm wide: 8 cells at 400).
const ProductsAir& products_air_self_similar(int cells) {
  static std::map<int, ProductsAir> runs;
  auto it = runs.find(cells);
  if (it == runs.end()) {
    const double t0 = 0.3;
    char end[32];
    std::snprintf(end, sizeof end, "time.end=%.17g", 10.0 - t0);
    it = runs.emplace(cells,
                      run_products_air({"numerics.closure=equal_strain", "numerics.ke_fix=true",
                                        "mesh.cells=[" + std::to_string(cells) + ",2,2]", end,
                                        self_similar_regions(t0, cells)}))
             .first;
  }
  return it->second;
}

}  // namespace

// Issue #53's products-into-air criterion, the expanded products' density within 10 % of exact
// at 400 cells and falling at 800, from the self-similar start at t0 = 0.3 us (above), with the
// default numerics. From the membrane the same runs are -30.9 / -17.2 % (the tests above):
// that error is made in the start-up, while the fan spans fewer than about five cells, and the
// start from the exact state at 0.3 us leaves almost none of it. This verifies the propagation,
// not the start from the membrane (the deck), which still misses 10 % at 400 cells.
// Observed (2026-12-07, double, 1 thread): density -1.0 % at 400 and -0.1 % at 800 cells (bound
// 10 %, and falling), shocked-air p +0.7 / +0.1 % (bound 2.5 %), star u +0.2 / +0.0 % (bound
// 2 %), interface -0.1 / -0.2 cells (bound 2 cells); at 200 cells -10.7 %, p +1.3 %, u +1.1 %
// (not asserted: the fan spans 4 cells at t0 there).
TEST(MultiMaterial, ProductsIntoAirFromSelfSimilarStart) {
  const ProductsAir& c = products_air_self_similar(400);
  const ProductsAir& f = products_air_self_similar(800);
  expect_products_air_sane(c, "self-similar start, 400 cells");
  expect_products_air_sane(f, "self-similar start, 800 cells");
  const double rc = rel(c.rho_products, c.rho_star), rf = rel(f.rho_products, f.rho_star);
  std::printf(
      "products-air from the self-similar state at 0.3 us, 400 -> 800 cells: |rho/rho* - 1| "
      "%.2f %% -> %.2f %%\n",
      100 * rc, 100 * rf);
  EXPECT_LT(rc, 0.10);
  EXPECT_LT(rf, rc);
  for (const ProductsAir* w : {&c, &f}) {
    EXPECT_LT(rel(w->p_air, w->p_star), 0.025);
    EXPECT_LT(rel(w->u_mean, w->u_star), 0.02);
    EXPECT_LT(std::abs(w->interface - w->contact), 2 * w->dx);
  }
}

// A regression pin of a known defect, not a verification (issue #16 open; docs/numerics.md,
// "Products into air"): the start-up overshoot of the velocity at the rarefaction tail is
// damped by the remap, and the KE fix returns that loss as heat to the expanded products, which
// over-expand: with the KE fix the interface runs 7.0 cells ahead and the products' star
// density is 29.5 % low at 400 cells (7.5 cells and 31.0 % with its shares by mass, 2026-12-03)
// (exact solution: 0; it falls with resolution, see ProductsIntoAirStarStateConverges); without
// it 1.7 cells and 11.5 % (1.8 cells, 11.7 % under the default cloverleaf step, 2026-12-07, with
// the KE fix 7.5 cells, 30.9 %) (but energy is not conserved). The bounds hold these near their
// present values so that a change shows. The KE-fix-off star state is pinned here too, not
// verified: observed at 400 cells p -5.1 %, u +0.7 % (its shocked air short of the plateau for the
// energy it lost), but it does not converge: at 200 / 400 / 800 cells p -5.4 / -5.1 / -16.3 %, u
// +1.2 / +0.7 / -5.9 % (measured 2026-12-01). Its bounds (7 %, 2 %) were in the verification test
// before.
TEST(MultiMaterialRegressionPin, ProductsIntoAirOverExpansion) {
  const ProductsAir& es = products_air(true);
  const ProductsAir& nk = products_air(false);
  expect_products_air_sane(es, "KE fix on, 400 cells");
  expect_products_air_sane(nk, "KE fix off, 400 cells");
  // observed (2026-12-06) interface +7.5 / +1.7 cells (bounds 9, 3), density -31.0 / -11.5 %
  // (bounds 35 %, 15 %), KE fix off p -5.1 % (7 %), u +0.7 % (2 %); exact solution: 0 each
  EXPECT_LT(std::abs(es.interface - es.contact), 9 * es.dx);
  EXPECT_LT(std::abs(nk.interface - nk.contact), 3 * nk.dx);
  EXPECT_LT(std::abs(es.rho_products / es.rho_star - 1), 0.35);
  EXPECT_LT(std::abs(nk.rho_products / nk.rho_star - 1), 0.15);
  EXPECT_LT(std::abs(nk.p_air / nk.p_star - 1), 0.07);
  EXPECT_LT(std::abs(nk.u_mean / nk.u_star - 1), 0.02);
}

namespace {

// A water|air cell at the scene's initial densities (material 0 water, 1 air).
KOKKOS_INLINE_FUNCTION int water_air_content(Real water, Real e_water, Real e_air, Real* a, Real* r,
                                             Real* en) {
  a[0] = water;
  a[1] = 1 - water;
  r[0] = 1.0;
  r[1] = 1e-3;
  en[0] = e_water;
  en[1] = e_air;
  return 2;
}

// Replaces the content of the owned cells within 10 cm of the water-air interface by a sliver
// of the other material: air at fraction f in the water (60 < x < 70 cm), water at fraction f
// in the air (70 < x < 80 cm), f = 1e-12, 1e-11, ..., 1e-6 cycling with the cell index. Each
// material keeps its own initial state (water 1e-2 Mbar, air 1e-6 Mbar), so the slivers start
// out of pressure equilibrium by four orders of magnitude.
struct SliverSource {
  Geometry g;
  int lo[3], hi[3];
  Real e_water, e_air;

  KOKKOS_INLINE_FUNCTION bool changed(int i, int j, int k) const {
    if (i < lo[0] || i >= hi[0] || j < lo[1] || j >= hi[1] || k < lo[2] || k >= hi[2]) return false;
    const double x = g.node_coord(0, i) + 0.5 * g.dx[0];
    return x > 60 && x < 80;
  }
  KOKKOS_INLINE_FUNCTION int content(int i, int, int, Real* a, Real* r, Real* en) const {
    const double x = g.node_coord(0, i) + 0.5 * g.dx[0];
    // a float build holds no fraction below hydro::kMinFractionFloor (4.8e-7) beside another
    // material, so its slivers start at twice that (9.5e-7) instead of 1e-12
    const Real f = mmax(MP_KOKKOS_MATH::pow(Real(10), Real(-12 + (i % 7))),
                        Real(2 * hydro::kMinFractionFloor));
    return water_air_content(x < 70 ? 1 - f : f, e_water, e_air, a, r, en);
  }
};

struct SliverRun {
  RunResult result;
  long bad;
  double smallest, water_mass_change, air_mass_change;
  int slivers_start, slivers_end;
};

SliverRun run_slivers(const std::vector<std::string>& overrides) {
  const Scene scene = test::load_scene("water_air.yaml", overrides);
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(scene, MPI_COMM_WORLD, settings);
  sim.initialize();
  const Mesh& m = sim.mesh();
  const int ng = Mesh::ng;
  // water: stiffened gas e = (p + gamma p_inf) / ((gamma - 1) rho); air: p / ((gamma - 1) rho)
  const SliverSource src{m.geometry(),
                         {ng, ng, ng},
                         {ng + m.owned_cells(0), ng + m.owned_cells(1), ng + m.owned_cells(2)},
                         Real((1e-2 + 4.4 * 6e-3) / 3.4),
                         Real(1e-6 / (0.4 * 1e-3))};
  mat::MaterialState* mm = sim.hydro().materials();
  mm->assign("test::slivers", src);
  sim.hydro().prepare();
  const auto count = [&](double* smallest) {
    int n = 0;
    *smallest = 1;
    for (int q = 0; q < 2; ++q)
      for (double a : test::gather(m, mm->fraction(q), Centering::Cell))
        if (a > 0 && a <= 1.5e-6) {
          ++n;
          *smallest = std::min(*smallest, a);
        }
    return n;
  };
  SliverRun s{};
  s.slivers_start = count(&s.smallest);
  const auto m0 = mm->material_masses();
  s.result = sim.run();
  const auto m1 = mm->material_masses();
  s.slivers_end = count(&s.smallest);
  double vals[3];
  s.bad = mm->first_bad(vals);
  s.water_mass_change = (m1[0] - m0[0]) / m0[0];
  s.air_mass_change = (m1[1] - m0[1]) / m0[1];
  return s;
}

}  // namespace

// Slivers (issue: real materials): volume fractions 1e-12 to 1e-6 four orders of magnitude out
// of pressure equilibrium with their cell, through the whole water-air run, in both layouts and
// both closures: no NaN, no negative density or energy (the run's health check stops on any),
// and every material's mass kept.
TEST(MultiMaterial, SliversStayFiniteAndPositive) {
  for (const std::string layout : {"compact", "dense"})
    for (const std::string closure : {"equal_strain", "relaxation"}) {
      const std::string name = layout + "/" + closure;
      const SliverRun s = run_slivers({"numerics.layout=" + layout, "numerics.closure=" + closure});
      std::printf(
          "slivers %-24s %ld cycles: %d sliver cells (fraction <= 1.5e-6) at the start, %d at "
          "the end (smallest %.2e); mass change water %.2e, air %.2e; first bad cell %ld\n",
          name.c_str(), s.result.cycles, s.slivers_start, s.slivers_end, s.smallest,
          s.water_mass_change, s.air_mass_change, s.bad == LONG_MAX ? -1L : s.bad);
      EXPECT_TRUE(s.result.ok) << name;
      EXPECT_NEAR(s.result.time, 240.0, 1e-9) << name;
      // the slivers are there while the waves run through them: after 3 cycles most remain
      const SliverRun early = run_slivers(
          {"numerics.layout=" + layout, "numerics.closure=" + closure, "time.max_cycles=3"});
      std::printf("slivers %-24s after 3 cycles: %d sliver cells (smallest %.2e)\n", name.c_str(),
                  early.slivers_end, early.smallest);
      // (float: the relaxation squeezes the air slivers in the water below the 4.8e-7 floor
      // within 3 cycles; 76 of 160 remain there, the smallest 1.3e-6)
      // (double: 140 of the 160 remain, 1.4x the bound; the bound asks that most of them do)
      EXPECT_GE(early.slivers_end, test::kFloat ? 60 : 100) << name;
      // the smallest painted slivers (1e-12) are still there: observed 1.0e-12 and 1.4e-12;
      // the bound 1e-11 is the next painted fraction, which would show they had all gone
      EXPECT_LE(early.smallest, test::by_precision(1e-11, 1.5e-6)) << name;
      EXPECT_EQ(early.bad, LONG_MAX) << name;
      EXPECT_EQ(s.bad, LONG_MAX) << name;
      EXPECT_EQ(s.slivers_start, 40 * 4) << name;  // 40 cells x 4 (2x2 in y, z)
      // slivers leave only below min_fraction (1e-14 of a cell), handing their mass to the
      // cell's largest material: at most 40 x 4 x 1e-14 x 0.125 cm^3 x 1 g/cm^3 of water.
      // In float the floor is 4.8e-7 and the slivers 1e-6: the water slivers in the air,
      // 80 x 1e-6 x 0.125 g = 1e-5 g, may all go to the air (0.03 g), 3.3e-4 of it (observed
      // 2.9e-4); the water's own change is float round-off (observed 1.4e-6).
      // In double the handed-over mass is 40 x 4 x 1e-14 x 0.125 x 1 = 2e-14 g: 3e-16 of the
      // water (70 g) and 7e-13 of the air (0.03 g); the remap's round-off adds 3 sweeps x
      // 293 cycles x 2.2e-16 = 1.9e-13 at worst. Observed: water 3.3e-15 to 4.3e-15 (bound
      // 2e-13, was 1e-12), air 1.1e-13 with equal strain, 4e-15 with relaxation (bound 1e-12,
      // the handed-over mass plus round-off; was 1e-9).
      EXPECT_LT(std::abs(s.water_mass_change), test::by_precision(2e-13, 1e-5)) << name;
      EXPECT_LT(std::abs(s.air_mass_change), test::by_precision(1e-12, 4e-4)) << name;
    }
}

namespace {

// Every cell half water (1e-2 Mbar) and half air (1e-6 Mbar), at rest: the Lagrangian step
// moves nothing, so one cycle shows the mixed-cell closure alone.
struct HalfHalfSource {
  Real e_water, e_air;
  KOKKOS_INLINE_FUNCTION bool changed(int, int, int) const { return true; }
  KOKKOS_INLINE_FUNCTION int content(int, int, int, Real* a, Real* r, Real* en) const {
    return water_air_content(0.5, e_water, e_air, a, r, en);
  }
};

struct Closure {
  double spread;                // largest |p_water - p_air| / p_water over the owned cells
  double alpha_min, alpha_max;  // water fraction over the owned cells
  double mass_change, energy_change;
};

// The test::pressures kernel, a for_cells body (a functor at namespace scope, not a generic
// extended lambda, which nvcc rejects inside for_cells' own lambdas): the relative spread of a
// cell's water and air pressures, and its water fraction.
struct CellPressures {
  eos::Eos water, air;
  Field3 spread, alpha;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    Real pw = 0, pa = 0, aw = 0;
    for (int s = 0; s < cell.count(); ++s) {
      const mat::MatRef q = cell.get(s);
      if (!(q.alpha > 0)) continue;
      if (q.m == 0) {
        pw = water.pressure(*q.rho, *q.e);
        aw = q.alpha;
      } else {
        pa = air.pressure(*q.rho, *q.e);
      }
    }
    spread(i, j, k) = mabs(pw - pa) / pw;
    alpha(i, j, k) = aw;
  }
};

Closure one_cycle_closure(const std::string& layout, const std::string& closure) {
  const Scene scene = test::load_scene("water_air.yaml",
                                       {"numerics.layout=" + layout, "numerics.closure=" + closure,
                                        "time.max_cycles=1", "mesh.cells=[20,2,2]"});
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(scene, MPI_COMM_WORLD, settings);
  sim.initialize();
  mat::MaterialState* mm = sim.hydro().materials();
  mm->assign("test::half_half",
             HalfHalfSource{Real((1e-2 + 4.4 * 6e-3) / 3.4), Real(1e-6 / (0.4 * 1e-3))});
  sim.hydro().prepare();
  const RunResult r = sim.run();
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.cycles, 1);
  const Mesh& m = sim.mesh();
  const eos::Eos water = eos::make_eos(eos::StiffenedGas{4.4, 6e-3});
  const eos::Eos air = eos::make_eos(eos::IdealGas{1.4});
  Field3 spread = m.new_field("spread", Centering::Cell);
  Field3 alpha = m.new_field("alpha", Centering::Cell);
  const int ng = Mesh::ng;
  mm->for_cells("test::pressures", {ng, ng, ng}, m.owned_end(),
                CellPressures{water, air, spread, alpha});
  Closure c{};
  for (double v : test::gather(m, spread, Centering::Cell)) c.spread = std::max(c.spread, v);
  const auto a = test::gather(m, alpha, Centering::Cell);
  c.alpha_min = *std::min_element(a.begin(), a.end());
  c.alpha_max = *std::max_element(a.begin(), a.end());
  c.mass_change = (r.end.mass - r.start.mass) / r.start.mass;
  c.energy_change = (r.end.total() - r.start.total()) / r.start.total();
  std::printf(
      "one cycle, %s layout, %s: pressure spread %.2e, water fraction %.6f..%.6f, mass change "
      "%.1e, energy change %.1e\n",
      layout.c_str(), closure.c_str(), c.spread, c.alpha_min, c.alpha_max, c.mass_change,
      c.energy_change);
  return c;
}

}  // namespace

// The closure wired into the cycle, both layouts: equal strain leaves the four orders of
// magnitude between the materials' pressures; relaxation brings them to one pressure in one
// cycle (the water expands from half the cell to 0.689 of it, as the point test found) with
// mass and energy kept.
TEST(MultiMaterial, RelaxationEqualisesMixedCellPressuresInOneCycle) {
  for (const std::string layout : {"compact", "dense"}) {
    const Closure es = one_cycle_closure(layout, "equal_strain");
    // the initial spread is 1 - 1e-6 / 1e-2 = 0.9999 by construction; equal strain keeps it
    // (observed 1.00): 0.99 is within 1 % of it because it is the initial state's own value
    EXPECT_GT(es.spread, 0.99) << layout;
    EXPECT_EQ(es.alpha_min, 0.5) << layout;
    EXPECT_EQ(es.alpha_max, 0.5) << layout;
    const Closure rx = one_cycle_closure(layout, "relaxation");
    // Water's pressure resolution, eps rho c^2 (rho c^2 = 2.6e-2 Mbar), against P* = 2e-6
    // Mbar: 2.9e-12 in double (observed 1.5e-13; was 1e-9, 6700x), 1.6e-3 in float (observed
    // 3.9e-4)
    EXPECT_LT(rx.spread, test::by_precision(3e-12, 2e-3)) << layout;
    EXPECT_EQ(rx.alpha_min, rx.alpha_max) << layout;  // every cell alike
    // Nothing moves in one cycle at rest and the closure changes volumes, not masses or
    // energies: round-off of the cell sums (80 cells), observed exactly 0 in double.
    EXPECT_LT(std::abs(rx.mass_change), test::roundoff(1e-14)) << layout;
    EXPECT_LT(std::abs(rx.energy_change), test::roundoff(1e-13)) << layout;
  }
}

// A regression pin, not a verification: the end state of the relaxation depends on its path
// (the work is charged at P*, a dissipative closure; docs/numerics.md), so the water fraction
// after one cycle, 0.6893, is this code's own number (the point test of relax.hpp lands on the
// same value); a change of the closure moves it.
TEST(MultiMaterialRegressionPin, RelaxationEndStateAfterOneCycle) {
  for (const std::string layout : {"compact", "dense"}) {
    const Closure rx = one_cycle_closure(layout, "relaxation");
    std::printf("relaxation end state, %s: water fraction %.6f\n", layout.c_str(), rx.alpha_min);
    EXPECT_NEAR(rx.alpha_min, 0.6893, 1e-3) << layout;
  }
}
