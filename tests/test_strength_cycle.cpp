// Strength in the hydro cycle (kernels/strength/module.hpp): elastic wave speeds, the
// elastic-plastic piston against its exact solution, objectivity under rigid rotation, and total
// energy to round-off with the deviator's work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "exact/ep_piston.hpp"
#include "exact/norms.hpp"
#include "strength/module.hpp"
#include "support.hpp"

using namespace mp;

namespace {

// Aluminium 6061-T6 as configs/elastic_wave.yaml takes it: Steinberg's Mie-Grueneisen fit
// (rho0 2.703, c0 0.524, s 1.40, Gamma0 1.97) and G0 = 0.276 Mbar, Y0 = 0.0029 Mbar
// (UCRL-MA-106439; kernels/materials/library.cpp, kernels/strength/library.hpp).
constexpr double kRho0 = 2.703, kC0 = 0.524, kS = 1.40, kGamma0 = 1.97, kG = 0.276, kY = 0.0029;

struct Line {
  std::vector<double> x, rho, p, sxx, u;  // cells (x, rho, p, s_xx) and nodes (u) along j=k=0
  double dx = 0, t = 0;
};

Line line_x(const test::Ran& r) {
  const Mesh& m = r.sim->mesh();
  const auto& st = r.sim->hydro().state();
  const int nx = m.global_cells(0);
  const auto rho = test::gather(m, st.rho, Centering::Cell);
  const auto p = test::gather(m, st.p, Centering::Cell);
  const auto u = test::gather(m, st.u, Centering::Node);
  const auto sxx =
      test::gather(m, r.sim->hydro().module<strength::Strength>()->stress()[0], Centering::Cell);
  Line l;
  l.dx = m.dx(0);
  l.t = r.result.time;
  for (int i = 0; i < nx; ++i) {
    l.x.push_back((i + 0.5) * l.dx);
    l.rho.push_back(rho[i]);
    l.p.push_back(p[i]);
    l.sxx.push_back(sxx[i]);
  }
  for (int i = 0; i <= nx; ++i) l.u.push_back(u[i]);
  return l;
}

// First node from the wall where the velocity falls below `level` (moving away from the wall
// means more negative here), linearly interpolated.
// (tests/exact/norms.hpp, shared with the speed/accuracy harness perf/tradeoff.cpp)
double front(const Line& l, double level) {
  return exact::falling_front(l.u, l.dx, level);
}

// Speed of the elastic wave relative to the material, bar moving at -v0 onto the wall, and the
// relative speed error that half a cell of front position makes (0.5 dx / (c t)).
struct Wave {
  double c, half_cell;
};

Wave wave_speed(int cells, const std::vector<std::string>& extra) {
  std::vector<std::string> o = {"mesh.cells=[" + std::to_string(cells) + ",2,2]"};
  o.insert(o.end(), extra.begin(), extra.end());
  auto r = test::run_scene(test::load_scene("elastic_wave.yaml", o));
  EXPECT_TRUE(r.result.ok) << r.result.health.what;
  const Line l = line_x(r);
  const double v0 = 1e-4;
  const double c = front(l, -0.5 * v0) / l.t + v0;
  return {c, 0.5 * l.dx / (c * l.t)};
}

}  // namespace

// A small-amplitude pulse travels at the longitudinal speed sqrt((K + 4/3 G)/rho) with
// strength, and at the bulk speed with G = 0 (yield 0 here: the deviator is returned to zero).
// The front is where the velocity crosses half its jump. A small-amplitude wave's ramp is
// symmetric about that crossing, so it locates the front to half a cell: the bound is the
// speed error of half a cell of position, 0.5 dx / (c t) = 0.78 % (0.96 % bulk) at 200 cells
// and half that at 400. Observed (2026-12-06) -0.267 % and -0.123 % (2.9x, 3.2x below), bulk
// -0.212 % and -0.109 % (4.5x, 4.4x), Steinberg-Guinan at 200 cells -0.261 % (3.0x); the
// longitudinal error falls (ratio 0.46). Run at 200 and 400 cells since 2026-12-06 (400 and 800
// before, 4x the cost: -0.123 / -0.093 %, bulk -0.109 / -0.087 %, SG -0.117 % at 400). Was 1 %
// (the issue's) at both, 8x to 11x the observations.
TEST(StrengthCycle, ElasticWaveAtTheLongitudinalAndBulkSpeeds) {
  const double K = kRho0 * kC0 * kC0;
  const double c_long = std::sqrt((K + 4.0 / 3.0 * kG) / kRho0), c_bulk = kC0;
  const std::vector<std::string> plain = {"materials.0.strength.model=elastic_plastic",
                                          "materials.0.strength.yield=1",
                                          "materials.0.strength.shear_modulus=0.276"};
  const std::vector<std::string> no_g = {"materials.0.strength.model=elastic_plastic",
                                         "materials.0.strength.yield=0",
                                         "materials.0.strength.shear_modulus=0.276"};
  double err_prev = 1;
  for (int n : {200, 400}) {
    const Wave w = wave_speed(n, plain), wb = wave_speed(n, no_g);
    const double c = w.c, cb = wb.c;
    const double e = c / c_long - 1, eb = cb / c_bulk - 1;
    std::printf(
        "elastic wave, %d cells: %.6f vs longitudinal %.6f (%+.3f %%, bound %.3f %%); G = 0: "
        "%.6f vs bulk %.6f (%+.3f %%, bound %.3f %%)\n",
        n, c, c_long, 100 * e, 100 * w.half_cell, cb, c_bulk, 100 * eb, 100 * wb.half_cell);
    EXPECT_LT(std::abs(e), w.half_cell);
    EXPECT_LT(std::abs(eb), wb.half_cell);
    EXPECT_LT(std::abs(e), err_prev);
    err_prev = std::abs(e);
  }
  // Steinberg-Guinan (the deck's model): G(p, T) at the nearly undisturbed state is G0 within
  // 1e-3, so the same speed to the same half cell.
  const Wave sg = wave_speed(200, {});
  std::printf("elastic wave, Steinberg-Guinan: %.6f (%+.3f %%, bound %.3f %%)\n", sg.c,
              100 * (sg.c / c_long - 1), 100 * sg.half_cell);
  EXPECT_LT(std::abs(sg.c / c_long - 1), sg.half_cell);
}

// The elastic-plastic piston (uniaxial strain, constant yield): the bar moves at -u_p onto a
// rigid wall, which is the exact solution's piston in the bar's frame. Elastic precursor and
// plastic shock speeds, the Hugoniot elastic limit and the plastic state against
// exact::EpPiston (hypoelastic law, this code's rho Gamma = rho0 Gamma0 form), at 400 and 800
// cells, every error falling.
TEST(StrengthCycle, ElasticPlasticPistonMatchesTheExactSolution) {
  exact::EpPistonMaterial mat{kRho0, kC0, kS, kGamma0, kG, kY};
  const double up = 0.01;  // 100 m/s, 3x the HEL particle speed
  const exact::EpPiston ex(mat, up);
  const exact::EpState& y = ex.yield_state();
  const exact::EpState& pl = ex.plastic_state();
  std::printf(
      "EP piston exact: U_e %.6f U_p %.6f (bar frame), HEL %.6e Mbar, yield rho %.6f "
      "u %.6f; plastic rho %.6f sigma %.6e\n",
      ex.elastic_speed(), ex.plastic_speed(), ex.hel(), y.rho, y.u, pl.rho, pl.sigma());
  double prev[4] = {1, 1, 1, 1};
  for (int n : {400, 800}) {
    auto r = test::run_scene(test::load_scene(
        "elastic_wave.yaml",
        {"mesh.cells=[" + std::to_string(n) + ",2,2]", "materials.0.strength.model=elastic_plastic",
         "materials.0.strength.yield=0.0029", "materials.0.strength.shear_modulus=0.276",
         "regions.0.velocity=[-0.01,0,0]", "regions.0.energy=1e-9", "time.end=5"}));
    ASSERT_TRUE(r.result.ok) << r.result.health.what;
    const Line l = line_x(r);
    const double t = l.t;
    // wall frame: the fronts run at U - u_p; the yield state moves at u_y - u_p
    const double x_e = front(l, 0.5 * (y.u - up) + 0.5 * (-up));
    const double x_p = front(l, 0.5 * (0 + (y.u - up)));
    const double ue = x_e / t + up, upl = x_p / t + up;
    // plateaus: the middle of each region, 10 % of its width from its ends
    auto mean = [&](const std::vector<double>& f, double a, double b) {
      double s = 0;
      int c = 0;
      for (std::size_t i = 0; i < l.x.size(); ++i)
        if (l.x[i] > a && l.x[i] < b) s += f[i], ++c;
      return s / c;
    };
    std::vector<double> sig(l.x.size());
    for (std::size_t i = 0; i < sig.size(); ++i) sig[i] = l.sxx[i] - l.p[i];
    const double w_y = x_e - x_p, w_p = x_p;
    const double hel = -mean(sig, x_p + 0.1 * w_y, x_e - 0.1 * w_y);
    const double rho2 = mean(l.rho, 0.1 * w_p, 0.9 * w_p);
    const double sig2 = mean(sig, 0.1 * w_p, 0.9 * w_p);
    const double err[4] = {ue / ex.elastic_speed() - 1, upl / ex.plastic_speed() - 1,
                           hel / ex.hel() - 1, sig2 / pl.sigma() - 1};
    const double err_rho = rho2 / pl.rho - 1;
    // the speed error that one cell of front position makes, dx / (U t), for each front
    const double cell_e = l.dx / (ex.elastic_speed() * t), cell_p = l.dx / (ex.plastic_speed() * t);
    std::printf(
        "EP piston, %d cells, t = %.2f: U_e %.6f (%+.3f %%, bound %.3f %%), U_p %.6f (%+.3f %%, "
        "bound %.3f %%), HEL %.6e (%+.3f %%), plastic rho %.6f (%+.2e), sigma %.6e (%+.2e)\n",
        n, t, ue, 100 * err[0], 100 * cell_e, upl, 100 * err[1], 100 * cell_p, hel, 100 * err[2],
        rho2, err_rho, sig2, err[3]);
    // Fronts: a captured shock's mid-level crossing locates it to a cell (the ramps of these
    // nonlinear waves are not symmetric about it, unlike the small-amplitude wave above): the
    // bound is the speed error of one cell of position, dx / (U t) = 0.31 % (precursor) and
    // 0.37 % (plastic shock) at 400 cells, half that at 800. Observed +0.090 % / +0.032 % (3.4x,
    // 4.8x below) and -0.154 % / -0.074 % (2.4x, 2.5x). Was 1 %.
    EXPECT_LT(std::abs(err[0]), cell_e);
    EXPECT_LT(std::abs(err[1]), cell_p);
    // The HEL is the plateau the precursor leaves and carries its start-up error: bounded by
    // the precursor's one-cell figure, observed +0.096 % / +0.013 % (3.2x, 12x below: it falls
    // faster than first order, asserted below). Was 1 %.
    EXPECT_LT(std::abs(err[2]), cell_e);
    // The plastic state behind the piston follows from the jump conditions, which the
    // conservative scheme keeps, so its plateau is exact but for the wall's start-up transient:
    // sigma within 1e-4 (observed -4.05e-5 / -9.8e-6); the density moves by sigma / K of that
    // (K = rho0 c0^2 = 0.742 Mbar, sigma = 0.0156 Mbar: 2.1e-6; bound 3e-6; observed -1.25e-6 /
    // -3.5e-7). Were 1 % and 0.1 %. Float: the plateau sits at a round-off floor that does not
    // fall (sigma -1.05e-4 / -1.22e-4, density -2.42e-6 / -2.38e-6 at 400 / 800 cells; a
    // relative rounding of 6e-8 in rho is K / sigma = 48 times that in sigma, per cycle, over
    // ~1000 cycles of mostly cancelling roundings): bounds 5e-4 and 1e-5, about 4x those.
    EXPECT_LT(std::abs(err[3]), test::by_precision(1e-4, 5e-4));
    EXPECT_LT(std::abs(err_rho), test::by_precision(3e-6, 1e-5));
    // every error falls with resolution (in float the plastic sigma is at its round-off floor)
    for (int k = 0; k < 4; ++k) {
      if (k < 3 || !test::kFloat) {
        EXPECT_LE(std::abs(err[k]), std::abs(prev[k])) << k;
      }
    }
    std::copy(err, err + 4, prev);
  }
}

namespace {

// The test::rotation kernel of RigidRotationTurnsTheStressAndKeepsItsInvariants (a functor:
// nvcc allows no extended lambda in a TEST body, a private member function): node velocities
// of a rigid rotation about z at rate omega.
struct RigidRotation {
  Geometry g;
  double omega;
  Field3 u, v;

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    (void)k;
    const Real x = g.node_coord(0, i), yy = g.node_coord(1, j);
    u(i, j, k) = Real(-omega) * yy;
    v(i, j, k) = Real(omega) * x;
  }
};

}  // namespace

// Objectivity: a uniform deviator in a rigid rotation about z (node velocities u = -w y,
// v = w x, the cell gradient exactly the spin) for a quarter turn through the module's own
// corrector kernel: the von Mises stress stays to round-off and the tensor turns with the body,
// diag(S, -S, 0) -> diag(-S, S, 0), with an error that falls as dt^2 (Hughes-Winget). Without
// the Jaumann term nothing would turn s (D = 0), so s_xx would stay +S: the assertion on s_xx
// below is what fails.
TEST(StrengthCycle, RigidRotationTurnsTheStressAndKeepsItsInvariants) {
  MeshSpec ms;
  ms.cells = {8, 8, 2};
  ms.lo = {-1, -1, 0};
  ms.hi = {1, 1, 0.5};
  Mesh mesh(ms, MPI_COMM_SELF);
  strength::FlowStress f;
  f.kind = strength::kConstantYield;
  f.constant = {Real(kG), Real(1)};  // yield far above the stress: elastic
  const double S = 1e-3, omega = 0.1;
  double prev_err = 1;
  for (int steps : {16, 32, 64}) {
    strength::Strength st(mesh, f, Real(kRho0));
    Kokkos::deep_copy(st.stress()[0], Real(S));
    Kokkos::deep_copy(st.stress()[1], Real(-S));
    auto u = mesh.new_field("u", Centering::Node), v = mesh.new_field("v", Centering::Node),
         w = mesh.new_field("w", Centering::Node);
    auto rho = mesh.new_field("rho", Centering::Cell), e = mesh.new_field("e", Centering::Cell),
         ph = mesh.new_field("ph", Centering::Cell);
    Kokkos::deep_copy(rho, Real(kRho0));
    Kokkos::deep_copy(e, Real(1e-3));
    const Geometry g = mesh.geometry();
    Kokkos::parallel_for("test::rotation", mesh.nodes(Region::All), RigidRotation{g, omega, u, v});
    const double dt = (M_PI / 2) / omega / steps;
    for (int s = 0; s < steps; ++s) st.corrector(u, v, w, rho, e, ph, Real(dt));
    const auto sxx = test::gather(mesh, st.stress()[0], Centering::Cell);
    const auto syy = test::gather(mesh, st.stress()[1], Centering::Cell);
    const auto sxy = test::gather(mesh, st.stress()[3], Centering::Cell);
    double err = 0, vm_err = 0;
    for (std::size_t c = 0; c < sxx.size(); ++c) {
      err = std::max({err, std::abs(sxx[c] + S), std::abs(syy[c] - S), std::abs(sxy[c])});
      const double j2 = sxx[c] * sxx[c] + syy[c] * syy[c] + (sxx[c] + syy[c]) * (sxx[c] + syy[c]) +
                        2 * sxy[c] * sxy[c];
      vm_err = std::max(vm_err, std::abs(std::sqrt(1.5 * j2) / (std::sqrt(3.0) * S) - 1));
    }
    std::printf(
        "rigid rotation, %d steps: |s - R s0 R^T| / S = %.3e, von Mises change %.3e, "
        "s_xx / S = %.6f\n",
        steps, err / S, vm_err, sxx[0] / S);
    // the rotation angle per step is 2 atan(w dt / 2): error (w dt)^2 / 12 per radian turned
    EXPECT_LT(err / S, std::pow(omega * dt, 2));
    EXPECT_LT(vm_err, test::roundoff(1e-13) * steps);
    EXPECT_LT(sxx[0] / S, -0.99);
    EXPECT_LT(err, prev_err);
    prev_err = err;
  }
}

// Total energy with strength: two aluminium blocks collide at 2 x 100 m/s (plastic) in a closed
// box; the deviator's nodal forces and its work in the cells use the same stress and the same
// gradient, so, with the KE fix, total energy changes by round-off only.
TEST(StrengthCycle, CollisionConservesTotalEnergyToRoundOff) {
  auto r = test::run_scene(test::load_scene(
      "elastic_wave.yaml",
      {"mesh.cells=[200,2,2]", "boundaries.x=reflective",
       "materials.0.strength.model=elastic_plastic", "materials.0.strength.yield=0.0029",
       "materials.0.strength.shear_modulus=0.276",
       "regions=[{material: al, shape: all, density: 2.703, energy: 1.0e-9, velocity: [-0.01, 0, "
       "0]}, {material: al, shape: box, lo: [0, -1, -1], hi: [2, 1, 1], density: 2.703, energy: "
       "1.0e-9, velocity: [0.01, 0, 0]}]",
       "time.end=3"}));
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  const double de = (r.result.end.total() - r.result.start.total()) / r.result.start.total();
  const double bound = test::energy_roundoff(r.result.cycles);
  const auto eps =
      test::gather(r.sim->mesh(), r.sim->hydro().module<strength::Strength>()->plastic_strain(),
                   Centering::Cell);
  const double eps_max = *std::max_element(eps.begin(), eps.end());
  std::printf(
      "collision: %ld cycles, total energy change %.3e (round-off bound %.3e), largest "
      "plastic strain %.3e\n",
      r.result.cycles, de, bound, eps_max);
  EXPECT_LT(std::abs(de), bound);
  EXPECT_GT(eps_max, 1e-3);  // the collision is plastic
}

// The strength block is read strictly: each bad input names its key.
TEST(StrengthCycle, DeckErrorsNameTheKey) {
  const struct {
    std::vector<std::string> set;
    const char* expect;
  } cases[] = {
      {{"materials.0.strength.model=plastic"}, "materials.0.strength.model"},
      {{"materials.0.strength.model=elastic_plastic"}, "yield"},
      {{"materials.0.strength.yield=0.1"}, "'yield' belongs to model elastic_plastic"},
      {{"materials.0.strength.library=unobtainium"}, "no strength data for 'unobtainium'"},
      {{"materials.0.strength.shear_modulus=-1"}, "materials.0.strength.shear_modulus"},
      {{"materials.0.strength.colour=red"}, "colour"},
      // Zerilli-Armstrong is cited for copper only
      {{"materials=[{name: al, library: aluminium_6061, strength: {model: zerilli_armstrong}}]"},
       "'aluminium_6061' has no Zerilli-Armstrong set in the library"},
      // a multi-material scene reads each material's block (and names the second's key)
      {{"materials=[{name: al, library: aluminium_6061, strength: {model: steinberg_guinan}}, "
        "{name: air, library: air, strength: {model: johnson_cook}}]"},
       "key 'materials.1.strength': model johnson_cook takes its parameters"},
  };
  for (const auto& c : cases) {
    const std::string msg = test::input_error("elastic_wave.yaml", c.set);
    std::printf("%s -> %s\n", c.set[0].c_str(), msg.c_str());
    EXPECT_NE(msg.find(c.expect), std::string::npos) << c.set[0] << ": " << msg;
  }
}
