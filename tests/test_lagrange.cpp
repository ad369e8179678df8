// The Lagrangian step alone conserves total energy to round-off (docs/numerics.md: "the work
// done on the nodes equals the p dV work taken from the cells"): a 3-D blast in a closed
// reflective box is run a few full cycles (so velocities, viscosity and the wall nodes are all
// busy), then one Hydro::lagrange(dt) is taken with no remap after it, and the internal energy
// of the cells plus the kinetic energy of the nodes, both with the masses of the step (the
// Lagrangian cells keep their mass; the nodes their 1/8 share of the cells around them inside
// the box), must be what it was before, to a round-off bound derived below.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "hydro/hydro.hpp"
#include "hydro/point.hpp"
#include "support.hpp"

using namespace mp;

namespace {

// Sums in long double (64-bit or more significand): the host's own rounding, 2^-64 or less per
// operation, stays far below the Real round-off the test bounds.
using Wide = long double;

struct Energies {
  Wide internal = 0, kinetic = 0;
  Wide abs_internal = 0;  // sum of m |e|
  Wide twice_kinetic = 0;
};

// Energies of the global arrays (x fastest): cells n[0] x n[1] x n[2], nodes one more per axis.
// A node's mass is 1/8 of each cell of the box around it: a wall node's dual cell is cut by the
// wall (the ghost cells beyond it are mirror images, not mass in the box).
Energies energies(const std::array<long, 3>& n, double vol, const std::vector<double>& rho,
                  const std::vector<double>& e, const std::vector<double>& u,
                  const std::vector<double>& v, const std::vector<double>& w) {
  Energies out;
  for (long c = 0; c < n[0] * n[1] * n[2]; ++c) {
    const Wide m = Wide(rho[c]) * vol;
    out.internal += m * e[c];
    out.abs_internal += m * std::abs(Wide(e[c]));
  }
  const long nx = n[0] + 1, ny = n[1] + 1, nz = n[2] + 1;
  for (long k = 0; k < nz; ++k)
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        Wide m = 0;
        for (long c = k - 1; c <= k; ++c)
          for (long b = j - 1; b <= j; ++b)
            for (long a = i - 1; a <= i; ++a)
              if (a >= 0 && a < n[0] && b >= 0 && b < n[1] && c >= 0 && c < n[2])
                m += rho[a + n[0] * (b + n[1] * c)];
        m *= 0.125 * vol;
        const long q = i + nx * (j + ny * k);
        const Wide v2 = Wide(u[q]) * u[q] + Wide(v[q]) * v[q] + Wide(w[q]) * w[q];
        out.kinetic += 0.5 * m * v2;
        out.twice_kinetic += m * v2;
      }
  return out;
}

// geometry: numerics.geometry (the mid-step geometry's forces and fluxes keep the balance too)
void step_alone_conserves_total_energy(const std::string& geometry) {
  // Sedov's blast on 16^3 cells, every face reflective: nothing enters or leaves.
  auto scene =
      test::load_scene("sedov.yaml", {"mesh.cells=[16,16,16]", "boundaries.x=reflective",
                                      "boundaries.y=reflective", "boundaries.z=reflective",
                                      "time.max_cycles=25", "numerics.geometry=" + geometry});
  auto r = test::run_scene(scene);
  ASSERT_TRUE(r.result.ok) << r.result.health.what;
  ASSERT_EQ(r.result.cycles, 25);
  auto& hy = r.sim->hydro();
  const auto& s = hy.state();
  const Mesh& m = r.sim->mesh();
  const std::array<long, 3> n{m.global_cells(0), m.global_cells(1), m.global_cells(2)};
  const double vol = double(m.geometry().cell_volume());
  const auto C = Centering::Cell, N = Centering::Node;

  const auto rho0 = test::gather(m, s.rho, C);
  const Energies before = energies(n, vol, rho0, test::gather(m, s.e, C), test::gather(m, s.u, N),
                                   test::gather(m, s.v, N), test::gather(m, s.w, N));
  const hydro::TimeStep ts = hy.time_step(0, 0, 1e30);
  const hydro::Health h = hy.lagrange(ts.dt);
  ASSERT_TRUE(h.ok) << h.what;
  const auto u1 = test::gather(m, s.u, N), v1 = test::gather(m, s.v, N),
             w1 = test::gather(m, s.w, N);
  // the masses of the step: the cells' (rho0 vol) and the nodes' from them
  const Energies after = energies(n, vol, rho0, test::gather(m, s.e, C), u1, v1, w1);

  // Scale of the p dV terms: per cell (|p_half| + q) times the sum of |volume flux| over its six
  // faces (the corrector's fluxes, left in vol_flux by the step).
  const auto ph = test::gather(m, s.p_half, C), q = test::gather(m, s.q, C);
  const auto fx = test::gather(m, s.vol_flux[0], N), fy = test::gather(m, s.vol_flux[1], N),
             fz = test::gather(m, s.vol_flux[2], N);
  Wide work_scale = 0, volume_change = 0;
  const long nx = n[0] + 1, ny = n[1] + 1;
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        auto at = [&](long a, long b, long c) { return a + nx * (b + ny * c); };
        const Wide sum = std::abs(fx[at(i, j, k)]) + std::abs(fx[at(i + 1, j, k)]) +
                         std::abs(fy[at(i, j, k)]) + std::abs(fy[at(i, j + 1, k)]) +
                         std::abs(fz[at(i, j, k)]) + std::abs(fz[at(i, j, k + 1)]);
        const long c = i + n[0] * (j + n[1] * k);
        work_scale += (std::abs(Wide(ph[c])) + q[c]) * sum;
        volume_change += sum;
      }

  // Round-off bound. In exact arithmetic the step conserves total energy: the node work
  // F . ub dt equals the cells' (p_half + q) dV, the same faces and the same time-centred
  // velocities ub = (u0 + u1) / 2 on both sides. Rounding breaks it by at most (eps = machine
  // epsilon of Real):
  //  - each cell's new e is rounded once, eps/2 of m |e|: 2 eps sum m|e| covers it with the
  //    rounding of e0 and of the masses;
  //  - each node's velocity components and the nodal mass of the acceleration (1/8 sum of 8
  //    densities in Real) are rounded a few times, up to 4 eps of m |u|^2 each: 8 eps sum m|u|^2;
  //  - the p dV work is formed from sums with cancellation: a face flux from 4 node velocities
  //    (4 roundings), a cell's dV from 6 fluxes (5), a node's force from 8 pressures (7), each
  //    rounding eps/2 of the largest term, so 16 eps sum (|p_half| + q) sum |flux| bounds both
  //    sides' error.
  // This is the worst case, every rounding of one sign; roundings of random sign cancel, and the
  // observed change is about 1/70 of it (1.1e-18 against 7.8e-17 in double). A slip in the
  // scheme's balance (the corrector's p dV with p instead of p_half, a wall node's mass or force
  // counted twice) moves the total by a fraction of the work done, 4.3e-3 here: ten orders
  // of magnitude above the bound.
  const double eps = test::kEps;
  const double bound =
      double(eps * (2 * before.abs_internal +
                    8 * std::max(before.twice_kinetic, after.twice_kinetic) + 16 * work_scale));
  const Wide e0 = before.internal + before.kinetic, e1 = after.internal + after.kinetic;
  const double change = double(e1 - e0);
  std::printf(
      "Lagrangian step alone (%s geometry, dt %.4e, %s): internal %.17e -> %.17e, kinetic %.17e "
      "-> %.17e\n"
      "  total %.17e -> %.17e, change %.3e (relative %.3e, %.2f eps of the total)\n"
      "  bound %.3e: eps x (2 x %.3e + 8 x %.3e + 16 x %.3e); work done %.3e\n",
      geometry.c_str(), ts.dt, mp::hydro::dt_limit_name(ts.limit), double(before.internal),
      double(after.internal), double(before.kinetic), double(after.kinetic), double(e0), double(e1),
      change, change / double(e0), std::abs(change) / double(e0) / eps, bound,
      double(before.abs_internal), double(std::max(before.twice_kinetic, after.twice_kinetic)),
      double(work_scale), double(after.kinetic - before.kinetic));
  // the step did move energy between the cells and the nodes (far above the bound), else the
  // check would be empty
  EXPECT_GT(double(after.kinetic - before.kinetic), 100 * bound);
  EXPECT_GT(double(volume_change), 0.0);
  EXPECT_LE(std::abs(change), bound);
}

}  // namespace

TEST(Lagrange, StepAloneConservesTotalEnergyMidStepGeometry) {
  step_alone_conserves_total_energy("midstep");
}
TEST(Lagrange, StepAloneConservesTotalEnergyFixedGeometry) {
  step_alone_conserves_total_energy("fixed");
}

// ---- The mid-step geometry's point functions (kernels/hydro/hydro.hpp; docs/numerics.md,
// "Mid-step geometry") on small host blocks with random velocities and pressures ----
namespace {

// A node or cell array of n^3 on the host, (i, j, k) from 0, x fastest: the accessor the
// hydro.hpp point functions take.
struct Grid {
  int n;
  std::vector<Real> a;
  explicit Grid(int n_) : n(n_), a(size_t(n_) * n_ * n_, Real(0)) {}
  Real& operator()(int i, int j, int k) { return a[i + n * (j + n * k)]; }
  Real operator()(int i, int j, int k) const { return a[i + n * (j + n * k)]; }
};

// Uniform in [-1, 1) on every point (interior_only: zero on the outer layer).
void fill(Grid& g, std::mt19937& rng, bool interior_only = false) {
  std::uniform_real_distribution<double> d(-1, 1);
  for (int k = 0; k < g.n; ++k)
    for (int j = 0; j < g.n; ++j)
      for (int i = 0; i < g.n; ++i) {
        const bool edge =
            i == 0 || j == 0 || k == 0 || i == g.n - 1 || j == g.n - 1 || k == g.n - 1;
        g(i, j, k) = interior_only && edge ? Real(0) : Real(d(rng));
      }
}

// face_gradient<n> for a run-time n
void gradient(int n, const Real N[4], const Real T1[4], const Real T2[4], Real h1, Real h2,
              Real c[3]) {
  switch (n) {
    case 0:
      hydro::face_gradient<0>(N, T1, T2, h1, h2, c);
      break;
    case 1:
      hydro::face_gradient<1>(N, T1, T2, h1, h2, c);
      break;
    case 2:
      hydro::face_gradient<2>(N, T1, T2, h1, h2, c);
      break;
    default:
      hydro::face_gradient<3>(N, T1, T2, h1, h2, c);
      break;
  }
}

// The node's force correction face by face, from its definition: over the 12 faces at node
// (i, j, k), the pressure jump across the face (low cell less high cell) times face_gradient at
// the node's corner of the face, in the mesh's axes. Also the sum of |jump| |c|, the scale of
// its round-off.
void force_by_faces(const Grid& u, const Grid& v, const Grid& w, const Grid& p, int i, int j, int k,
                    Real hx, Real hy, Real hz, double f[3], double* scale) {
  Real N[4], T1[4], T2[4], c[3];
  *scale = 0;
  const auto add = [&](double dp, int a, int b, int d) {  // c in the face's axes to a, b, d
    f[a] += dp * c[0];
    f[b] += dp * c[1];
    f[d] += dp * c[2];
    *scale += std::abs(dp) * (std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]));
  };
  for (int e1 = 0; e1 < 2; ++e1)
    for (int e0 = 0; e0 < 2; ++e0) {
      const int n = (1 - e0) + 2 * (1 - e1);  // the node's corner of each of the three faces
      {  // x face of cells (i - 1, jp, kp) | (i, jp, kp): sides y, z
        const int jp = j - 1 + e0, kp = k - 1 + e1;
        hydro::face_nodes<0>(u, v, w, i, jp, kp, N, T1, T2);
        gradient(n, N, T1, T2, hy, hz, c);
        add(double(p(i - 1, jp, kp)) - p(i, jp, kp), 0, 1, 2);
      }
      {  // y face of cells (ip, j - 1, kp) | (ip, j, kp): sides z, x
        const int ip = i - 1 + e1, kp = k - 1 + e0;
        hydro::face_nodes<1>(u, v, w, ip, j, kp, N, T1, T2);
        gradient(n, N, T1, T2, hz, hx, c);
        add(double(p(ip, j - 1, kp)) - p(ip, j, kp), 1, 2, 0);
      }
      {  // z face of cells (ip, jp, k - 1) | (ip, jp, k): sides x, y
        const int ip = i - 1 + e0, jp = j - 1 + e1;
        hydro::face_nodes<2>(u, v, w, ip, jp, k, N, T1, T2);
        gradient(n, N, T1, T2, hx, hy, c);
        add(double(p(ip, jp, k - 1)) - p(ip, jp, k), 2, 0, 1);
      }
    }
}

// Unequal spacings, so that a side length taken along the wrong axis shows.
constexpr Real kHx = Real(0.7), kHy = Real(1.1), kHz = Real(1.3);

}  // namespace

// In a planar flow every mid-step correction cancels across a node's faces (the faces normal to
// the flow keep their shape; the others have no flow across them): Sod along x, y and z, on a
// 4 x 4 cross-section so that every face orientation has interior nodes, gives the fixed
// geometry's fields bit for bit (observed max |difference| 0 in rho, e and the velocity along
// the flow; a correction that does not cancel moves them by O(dt u h) at the waves).
TEST(MidStepGeometry, PlanarFlowIsTheFixedGeometrysBitForBit) {
  const char* decks[3] = {"sod_x.yaml", "sod_y.yaml", "sod_z.yaml"};
  const char* meshes[3] = {"mesh.cells=[100,4,4]", "mesh.cells=[4,100,4]", "mesh.cells=[4,4,100]"};
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> f[2][3];
    long cycles[2] = {0, 0};
    for (int g = 0; g < 2; ++g) {
      auto r = test::run_scene(test::load_scene(
          decks[axis],
          {meshes[axis], g == 0 ? "numerics.geometry=midstep" : "numerics.geometry=fixed"}));
      ASSERT_TRUE(r.result.ok) << r.result.health.what;
      const Mesh& m = r.sim->mesh();
      const auto& st = r.sim->hydro().state();
      EXPECT_EQ(r.sim->hydro().mid_geometry(), g == 0);
      const Field3 vel[3] = {st.u, st.v, st.w};
      f[g][0] = test::gather(m, st.rho, Centering::Cell);
      f[g][1] = test::gather(m, st.e, Centering::Cell);
      f[g][2] = test::gather(m, vel[axis], Centering::Node);
      cycles[g] = r.result.cycles;
    }
    EXPECT_EQ(cycles[0], cycles[1]);
    double worst = 0;
    for (int q = 0; q < 3; ++q) {
      ASSERT_EQ(f[0][q].size(), f[1][q].size());
      for (std::size_t n = 0; n < f[0][q].size(); ++n)
        worst = std::max(worst, std::abs(f[0][q][n] - f[1][q][n]));
    }
    std::printf(
        "Sod along axis %d, %ld cycles: mid-step against fixed geometry, max |difference| "
        "%.3e\n",
        axis, cycles[0], worst);
    EXPECT_EQ(worst, 0.0);
  }
}

// mid_step_force sums the 12 faces' gradients plane by plane (each neighbour node loaded once):
// it must be the face-by-face sum of their definition, at every interior node of a random block,
// to round-off (observed 0.5-2 eps of the scale; a neighbour, sign or spacing taken wrong
// moves it by O(1) of it).
TEST(MidStepGeometry, NodeForceIsItsFacesGradients) {
  std::mt19937 rng(7);
  Grid u(6), v(6), w(6), p(6);  // nodes 0..5, cells 0..4 (the last layer unused)
  fill(u, rng);
  fill(v, rng);
  fill(w, rng);
  fill(p, rng);
  double worst = 0;
  for (int k = 1; k < 5; ++k)
    for (int j = 1; j < 5; ++j)
      for (int i = 1; i < 5; ++i) {
        Real f[3] = {0, 0, 0};
        hydro::mid_step_force(u, v, w, p, i, j, k, kHx, kHy, kHz, f);
        double ref[3] = {0, 0, 0}, scale = 0;
        force_by_faces(u, v, w, p, i, j, k, kHx, kHy, kHz, ref, &scale);
        for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(f[d] - ref[d]) / scale);
      }
  std::printf(
      "mid-step node force against its faces' gradients: largest |difference| %.2f eps "
      "of the scale\n",
      worst / test::kEps);
  EXPECT_LT(worst, 16 * test::kEps);
}

// Compatibility, the reason total energy is kept: the corrected node forces' work over a step,
// sum_n (dt/2 f_n) . (dt u_n), is the cells' pressures times the corrected part of their volume
// changes, sum_c p_c (net of cell_mid_corrections with u0 and u), for any u0, u and p (velocities
// zero on the block's outer nodes, so that every face that moves lies between two cells of the
// block). dt = 1.
TEST(MidStepGeometry, ForcesDoTheFluxesWork) {
  std::mt19937 rng(11);
  const int nn = 7;  // nodes 0..6, cells 0..5
  Grid u0(nn), v0(nn), w0(nn), u(nn), v(nn), w(nn), p(nn);
  for (Grid* g : {&u0, &v0, &w0, &u, &v, &w}) fill(*g, rng, true);
  fill(p, rng);
  double work = 0, work_scale = 0;
  for (int k = 1; k < nn - 1; ++k)
    for (int j = 1; j < nn - 1; ++j)
      for (int i = 1; i < nn - 1; ++i) {
        Real f[3] = {0, 0, 0};
        hydro::mid_step_force(u0, v0, w0, p, i, j, k, kHx, kHy, kHz, f);
        const double t[3] = {0.5 * f[0] * u(i, j, k), 0.5 * f[1] * v(i, j, k),
                             0.5 * f[2] * w(i, j, k)};
        work += t[0] + t[1] + t[2];
        work_scale += std::abs(t[0]) + std::abs(t[1]) + std::abs(t[2]);
      }
  const hydro::SweptFactors sf{1, kHx, kHy, kHz};
  double pdv = 0, pdv_scale = 0;
  for (int k = 0; k < nn - 1; ++k)
    for (int j = 0; j < nn - 1; ++j)
      for (int i = 0; i < nn - 1; ++i) {
        const hydro::CellFaceFluxes c =
            hydro::cell_mid_corrections(u0, v0, w0, u, v, w, i, j, k, sf);
        pdv += double(p(i, j, k)) * c.net();
        pdv_scale +=
            std::abs(double(p(i, j, k))) * (std::abs(c.xl) + std::abs(c.xh) + std::abs(c.yl) +
                                            std::abs(c.yh) + std::abs(c.zl) + std::abs(c.zh));
      }
  const double scale = work_scale + pdv_scale;
  std::printf(
      "mid-step forces' work %.12e, p times the corrected volumes %.12e: difference %.2f "
      "eps of the scale %.3e\n",
      work, pdv, std::abs(work - pdv) / scale / test::kEps, scale);
  EXPECT_GT(std::abs(work), 1e-3 * scale);  // not a balance of zeros
  EXPECT_LT(std::abs(work - pdv), 32 * test::kEps * scale);
}

// The face fluxes' claim: the undeformed face's flux plus cell_mid_corrections's correction (with
// u0 = u = D) is the volume the face sweeps when its nodes move by D along straight lines, to
// third order in |D|. The swept volume itself, the integral of the Jacobian of the trilinear map
// X(s, t, tau) = x(s, t) + tau D(s, t) over the unit cube, by 2-point Gauss quadrature (exact: the
// Jacobian is of degree 2 in each variable). The swept volume is a cubic in D, so the error is
// its cubic term alone: halving D must cut it by 8 (observed 8.00 for the three orientations;
// a correction with a wrong coefficient leaves a second-order error, ratio 4).
TEST(MidStepGeometry, FaceFluxIsTheSweptVolumeToThirdOrder) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1, 1);
  double dsp[4][3];  // the face's node displacements, node a + 2 b, mesh axes
  const double h[3] = {kHx, kHy, kHz};
  for (int axis = 0; axis < 3; ++axis) {
    const int s = (axis + 1) % 3, t = (axis + 2) % 3;  // the face's sides
    for (auto& n : dsp)
      for (double& c : n) c = d(rng);
    double err[2];
    for (int level = 0; level < 2; ++level) {
      const double eps = level == 0 ? 0.2 : 0.1;
      // swept volume: det [dX/ds, dX/dt, dX/dtau] at the 8 Gauss points
      const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
      double exact = 0;
      for (double gs : g)
        for (double gt : g)
          for (double gtau : g) {
            const double phi[4] = {(1 - gs) * (1 - gt), gs * (1 - gt), (1 - gs) * gt, gs * gt},
                         ps[4] = {-(1 - gt), 1 - gt, -gt, gt}, pt[4] = {-(1 - gs), -gs, 1 - gs, gs};
            double xs[3] = {0, 0, 0}, xt[3] = {0, 0, 0}, xtau[3] = {0, 0, 0};
            xs[s] = h[s];
            xt[t] = h[t];
            for (int n = 0; n < 4; ++n)
              for (int c = 0; c < 3; ++c) {
                xs[c] += gtau * eps * ps[n] * dsp[n][c];
                xt[c] += gtau * eps * pt[n] * dsp[n][c];
                xtau[c] += eps * phi[n] * dsp[n][c];
              }
            exact += 0.125 * (xs[0] * (xt[1] * xtau[2] - xt[2] * xtau[1]) -
                              xs[1] * (xt[0] * xtau[2] - xt[2] * xtau[0]) +
                              xs[2] * (xt[0] * xtau[1] - xt[1] * xtau[0]));
          }
      // the same face as the low `axis` face of cell (0, 0, 0) of a 2^3 node block
      Grid f[3] = {Grid(2), Grid(2), Grid(2)};
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          int idx[3] = {0, 0, 0};
          idx[s] = a;
          idx[t] = b;
          for (int c = 0; c < 3; ++c) f[c](idx[0], idx[1], idx[2]) = Real(eps * dsp[a + 2 * b][c]);
        }
      const hydro::SweptFactors sf{1, kHx, kHy, kHz};
      const hydro::CellFaceFluxes c =
          hydro::cell_mid_corrections(f[0], f[1], f[2], f[0], f[1], f[2], 0, 0, 0, sf);
      const Real a = Real(0.25) * Real(h[s] * h[t]);
      const double approx = axis == 0   ? double(hydro::face_flux_x(f[0], 0, 0, 0, a)) + c.xl
                            : axis == 1 ? double(hydro::face_flux_y(f[1], 0, 0, 0, a)) + c.yl
                                        : double(hydro::face_flux_z(f[2], 0, 0, 0, a)) + c.zl;
      err[level] = std::abs(exact - approx);
    }
    std::printf(
        "face normal to axis %d: swept-volume error %.3e at |D| ~ 0.2, %.3e at 0.1, "
        "ratio %.2f\n",
        axis, err[0], err[1], err[0] / err[1]);
    EXPECT_GT(err[0] / err[1], 7.5);
    EXPECT_LT(err[0] / err[1], 8.5);
  }
}

// The tensor viscosity's direction tensor (kernels/hydro/point.hpp, compression_direction;
// docs/numerics.md, "Tensor viscosity").
namespace {

using hydro::Sym6;

// R D R^T for a rotation R (rows r[0..2])
Sym6 rotate(const Sym6& d, const double r[3][3]) {
  const double a[3][3] = {{d.xx, d.xy, d.xz}, {d.xy, d.yy, d.yz}, {d.xz, d.yz, d.zz}};
  double b[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) b[i][j] += r[i][k] * a[k][l] * r[j][l];
  return {Real(b[0][0]), Real(b[1][1]), Real(b[2][2]), Real(b[0][1]), Real(b[0][2]), Real(b[1][2])};
}
double contract(const Sym6& s, const Sym6& d) {
  return double(s.xx) * d.xx + double(s.yy) * d.yy + double(s.zz) * d.zz +
         2 * (double(s.xy) * d.xy + double(s.xz) * d.xz + double(s.yz) * d.yz);
}
double max_diff(const Sym6& a, const Sym6& b) {
  return std::max({std::abs(double(a.xx) - b.xx), std::abs(double(a.yy) - b.yy),
                   std::abs(double(a.zz) - b.zz), std::abs(double(a.xy) - b.xy),
                   std::abs(double(a.xz) - b.xz), std::abs(double(a.yz) - b.yz)});
}

}  // namespace

TEST(TensorViscosity, PlanarFlowsGetTheirAxisExactly) {
  // a compression along one axis alone: Q acts along it alone, exactly, whatever its size (a
  // flow along one axis keeps the scalar viscosity's forces and work)
  for (const double a : {-2.5, -49.0, -1e-7, -3.3e5, -0.1})
    for (int d = 0; d < 3; ++d) {
      const Sym6 s = hydro::compression_direction(
          {d == 0 ? Real(a) : 0, d == 1 ? Real(a) : 0, d == 2 ? Real(a) : 0, 0, 0, 0});
      EXPECT_EQ(d == 0 ? s.xx : d == 1 ? s.yy : s.zz, 1) << a << " along " << d;
      EXPECT_EQ(s.xx + s.yy + s.zz, 1) << a << " along " << d;
      EXPECT_EQ(s.xy, 0);
    }
  // with a transverse expansion the neutral axis takes a share (below), the expanding one none
  const Sym6 x = hydro::compression_direction({-2.5, 0, 0, 0, 0, 0});
  const Sym6 y = hydro::compression_direction({0, -0.3, 0.1, 0, 0, 0});
  const Sym6 z = hydro::compression_direction({0.2, 0, -7, 0, 0, 0});
  EXPECT_EQ(x.xx, 1);
  EXPECT_EQ(x.yy, 0);
  EXPECT_EQ(x.zz, 0);
  EXPECT_EQ(x.xy, 0);
  // y: lambda_max 0.1 (the expanding z), tr D = -0.2, so S = diag(0.1, 0.4, 0) / 0.5: the
  // neutral x takes a share, the expanding z none
  EXPECT_NEAR(y.yy, 0.8, test::roundoff(1e-15));
  EXPECT_NEAR(y.xx, 0.2, test::roundoff(1e-15));
  EXPECT_EQ(y.zz, 0);
  EXPECT_EQ(y.xy, 0);
  EXPECT_NEAR(z.zz, 7.2 / 7.4, test::roundoff(1e-15));
  EXPECT_NEAR(z.yy, 0.2 / 7.4, test::roundoff(1e-15));
  EXPECT_EQ(z.xx, 0);
}

TEST(TensorViscosity, RotatesWithTheFlowAndDissipates) {
  // a planar compression along a unit normal n (D = d n n): S = n n, for any n; a spherical
  // shock's strain (radial d_r, tangential d_t = 0.1 d_r twice): S is the radial n n
  const double n[3] = {0.36, 0.48, 0.8};
  for (const double dt : {0.0, 0.1, 0.25}) {
    // D = d_r n n + d_t (I - n n), d_r = -4
    const double dr = -4, dtan = dt * dr;
    Sym6 d;
    double m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = (dr - dtan) * n[i] * n[j] + (i == j ? dtan : 0);
    d = {Real(m[0][0]), Real(m[1][1]), Real(m[2][2]), Real(m[0][1]), Real(m[0][2]), Real(m[1][2])};
    const Sym6 s = hydro::compression_direction(d);
    const Sym6 nn{Real(n[0] * n[0]), Real(n[1] * n[1]), Real(n[2] * n[2]),
                  Real(n[0] * n[1]), Real(n[0] * n[2]), Real(n[1] * n[2])};
    std::printf("d_t / d_r = %.2f: |S - n n| = %.2e, S:D = %.6f (d_r %.1f)\n", dt, max_diff(s, nn),
                contract(s, d), dr);
    EXPECT_LT(max_diff(s, nn), test::roundoff(1e-14));
    EXPECT_NEAR(contract(s, d), dr, test::roundoff(1e-13));
  }
  // a general strain rate and its rotations: S(R D R^T) = R S(D) R^T, trace 1, S:D <= 0 when
  // tr D < 0 (the viscous work is dissipative), and S = I / 3 where D is isotropic
  const double c = std::cos(0.7), sn = std::sin(0.7);
  const double r1[3][3] = {{c, -sn, 0}, {sn, c, 0}, {0, 0, 1}};
  const double r2[3][3] = {{1, 0, 0}, {0, c, sn}, {0, -sn, c}};
  const Sym6 samples[] = {{-3, 1, 0.5, 0.7, -0.2, 0.4},
                          {-1, -1, 1.9, 0.01, 0.02, -0.03},
                          {0.3, -2, -0.1, 1.1, 0.5, -0.6},
                          {-1, -1.2, -0.9, 0.3, 0.2, 0.1}};
  for (const Sym6& d : samples) {
    const Sym6 s = hydro::compression_direction(d);
    EXPECT_NEAR(double(s.xx) + s.yy + s.zz, 1.0, test::roundoff(1e-14));
    if (d.xx + d.yy + d.zz < 0) {
      EXPECT_LE(contract(s, d), 0.0);
    }
    const Sym6 rs = hydro::compression_direction(rotate(d, r1));
    const Sym6 rrs = hydro::compression_direction(rotate(d, r2));
    EXPECT_LT(max_diff(rs, rotate(s, r1)), test::roundoff(1e-13));
    EXPECT_LT(max_diff(rrs, rotate(s, r2)), test::roundoff(1e-13));
  }
  const Sym6 iso = hydro::compression_direction({-2, -2, -2, 0, 0, 0});
  EXPECT_EQ(iso.xx, Real(1) / 3);
  EXPECT_EQ(iso.xy, 0);
}

// The column kernel's eigenvalues (eigenvalues_lanes, 16 tensors at once as vector loops) are
// the per-tensor Jacobi's bit for bit, and so the direction tensors: random tensors over 30
// decades, diagonal ones, a zero or a 1e-200 off-diagonal, a double eigenvalue, lanes left out.
TEST(TensorViscosity, LanesGiveThePerTensorEigenvaluesBitForBit) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(-1, 1);
  long differ = 0, compared = 0;
  for (int it = 0; it < 20000; ++it) {
    constexpr int N = 16;
    Real a00[N], a11[N], a22[N], a01[N], a02[N], a12[N];
    int done[N];
    Sym6 d[N];
    const int n = 1 + it % N;
    for (int l = 0; l < n; ++l) {
      const double s = std::pow(10.0, 15 * u(gen));  // (squares within a float's range)
      d[l] = {Real(u(gen) * s), Real(u(gen) * s), Real(u(gen) * s),
              Real(u(gen) * s), Real(u(gen) * s), Real(u(gen) * s)};
      const int kind = (it + l) % 6;
      if (kind == 1) d[l].xy = d[l].xz = d[l].yz = 0;
      if (kind == 2) d[l].xy = 0;
      if (kind == 3) d[l] = {d[l].xx, d[l].zz, d[l].zz, d[l].xy, 0, 0};
      if (kind == 4) d[l].xy = Real(1e-200);
      if (kind == 5) d[l] = {1, 1, 1, 0, 0, Real(1e-17)};
      a00[l] = d[l].xx, a11[l] = d[l].yy, a22[l] = d[l].zz;
      a01[l] = d[l].xy, a02[l] = d[l].xz, a12[l] = d[l].yz;
      done[l] = l % 5 == 4 || (d[l].xy == 0 && d[l].xz == 0 && d[l].yz == 0) ? 1 : 0;
    }
    hydro::eigenvalues_lanes(n, a00, a11, a22, a01, a02, a12, done);
    for (int l = 0; l < n; ++l) {
      if (l % 5 == 4) continue;  // (left out)
      Real ev[3];
      const Sym6 s = hydro::compression_direction(d[l], ev);
      const Real lanes[3] = {a00[l], a11[l], a22[l]};
      const Sym6 sl = hydro::compression_direction_of(d[l], lanes);
      ++compared;
      const bool same = ev[0] == lanes[0] && ev[1] == lanes[1] && ev[2] == lanes[2] &&
                        s.xx == sl.xx && s.yy == sl.yy && s.zz == sl.zz && s.xy == sl.xy &&
                        s.xz == sl.xz && s.yz == sl.yz;
      differ += same ? 0 : 1;
    }
  }
  std::printf("%ld of %ld tensors differ\n", differ, compared);
  EXPECT_EQ(differ, 0);  // observed 0 of 143,750 (and of 1.4 million in a longer trial)
}
