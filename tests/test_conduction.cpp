// Noh's artificial heat flux (kernels/hydro/conduction.cpp, numerics.heat_flux): on a 3-D Noh
// implosion, one application of the flux conserves the internal energy to round-off, keeps
// every cell's energy within the range of the old energies as many faces around it as the flux
// took sub-steps (each sub-step a convex combination of a cell's and its six neighbours'),
// changes only cells that converge, changes some; it does nothing on a
// planar shock (Sod) or with h = 0. Run at 1 and 2 ranks (tests/test_decomp.cpp compares Noh
// field by field at 1 and 4 ranks, the flux on).
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "support.hpp"

using namespace mp;

namespace {

struct Applied {
  bool acted = false;
  int substeps = 0;                       // the flux's explicit sub-steps
  std::vector<double> e0, e1, rho, jump;  // global, x fastest
  double energy0 = 0, energy1 = 0;        // sum rho e V over the mesh
  int n = 0;
};

// Runs `cycles` cycles of `deck` at 24^3, then applies the flux once over the next step.
Applied apply_once(const std::string& deck, const std::vector<std::string>& extra, int cycles) {
  const auto run = test::started(deck, 24, extra);
  Simulation& sim = *run;
  auto& h = sim.hydro();
  Real dt_old = 0;
  double t = 0;
  for (long cycle = 0; cycle < cycles; ++cycle) {
    const auto ts = h.time_step(dt_old, t, 1e9);
    const hydro::Health health = h.step(ts.dt, cycle);
    EXPECT_TRUE(health.ok) << health.what;
    t += ts.dt;
    dt_old = ts.dt;
  }
  const auto& m = sim.mesh();
  const auto& s = h.state();
  Applied a;
  a.e0 = test::gather(m, s.e, Centering::Cell);
  a.rho = test::gather(m, s.rho, Centering::Cell);
  const auto ts = h.time_step(dt_old, t, 1e9);
  a.substeps = h.heat_flux(ts.dt);
  a.acted = a.substeps > 0;
  a.e1 = test::gather(m, s.e, Centering::Cell);
  if (h.conducts()) a.jump = test::gather(m, s.cjump, Centering::Cell);
  a.n = 24;
  const double vol = m.dx(0) * m.dx(1) * m.dx(2);
  for (size_t c = 0; c < a.e0.size(); ++c) {
    a.energy0 += a.rho[c] * a.e0[c] * vol;
    a.energy1 += a.rho[c] * a.e1[c] * vol;
  }
  return a;
}

}  // namespace

TEST(HeatFlux, ConservesAndKeepsTheMaximumPrincipleInAnImplosion) {
  const Applied a = apply_once("noh.yaml", {}, 30);
  ASSERT_TRUE(a.acted);
  const int n = a.n;
  const auto at = [&](const std::vector<double>& f, int i, int j, int k) {
    return f[i + n * (j + n * k)];
  };
  // the old energies' range over each cell's neighbourhood of `substeps` faces (dilations)
  std::vector<double> range_lo = a.e0, range_hi = a.e0;
  for (int s = 0; s < a.substeps; ++s) {
    const std::vector<double> lo0 = range_lo, hi0 = range_hi;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k},
                                {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
          double& l = range_lo[i + n * (j + n * k)];
          double& u = range_hi[i + n * (j + n * k)];
          for (const auto& b : nb) {
            if (b[0] < 0 || b[1] < 0 || b[2] < 0 || b[0] >= n || b[1] >= n || b[2] >= n) continue;
            l = std::min(l, at(lo0, b[0], b[1], b[2]));
            u = std::max(u, at(hi0, b[0], b[1], b[2]));
          }
        }
  }
  long changed = 0, converging = 0, outside = 0, stray = 0;
  double largest = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double e0 = at(a.e0, i, j, k), e1 = at(a.e1, i, j, k);
        if (at(a.jump, i, j, k) > 0) ++converging;
        if (e1 == e0) continue;
        ++changed;
        largest = std::max(largest, std::abs(e1 - e0) / std::max(e0, 1e-300));
        if (!(at(a.jump, i, j, k) > 0)) ++stray;
        // the range of the old energies within `substeps` faces of the cell inside the mesh
        // (each sub-step a convex combination of a cell's and its face neighbours' energies; a
        // symmetry plane's ghost mirrors the cell: no flux through it)
        const double lo = at(range_lo, i, j, k), hi = at(range_hi, i, j, k);
        const double slack = 1e-12 * std::max(std::abs(lo), std::abs(hi));
        if (e1 < lo - slack || e1 > hi + slack) ++outside;
      }
  const double de = (a.energy1 - a.energy0) / a.energy0;
  std::printf(
      "Noh 24^3 after 30 cycles: %ld converging cells, %ld changed (largest relative "
      "change %.3e) in %d sub-steps, internal energy change %.3e\n",
      converging, changed, largest, a.substeps, de);
  EXPECT_GT(changed, 10);    // it acts (observed: see the printout)
  EXPECT_GT(largest, 1e-4);  // and not by round-off alone
  EXPECT_EQ(stray, 0);       // only converging cells
  EXPECT_EQ(outside, 0);     // each new energy within its neighbourhood's old range
  // (a.substeps >= 1 is what ASSERT_TRUE(a.acted) above says; the restatement that stood here
  // could not fail and was dropped, issue #55)
  EXPECT_LT(std::abs(de), 64 * std::numeric_limits<Real>::epsilon());  // conserved
}

TEST(HeatFlux, NothingOnAPlanarShockOrWhenOff) {
  // Sod along x: a planar shock, nothing converges (the middle eigenvalue is exactly 0)
  const Applied sod = apply_once("sod_x.yaml", {}, 20);
  EXPECT_FALSE(sod.acted);
  EXPECT_EQ(sod.e0, sod.e1);
  // the implosion with h = 0: the option is off
  const Applied off = apply_once("noh.yaml", {"numerics.heat_flux=0"}, 30);
  EXPECT_FALSE(off.acted);
  EXPECT_EQ(off.e0, off.e1);
}
