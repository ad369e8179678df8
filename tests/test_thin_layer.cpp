// Thin-layer interface transport (issue #53): a copper sheet 2, 3 or 4 cells thick in air,
// carried by a prescribed, divergence-free velocity field through the multi-material remap
// alone (no Lagrangian step: the face volume fluxes are written from the field and
// Hydro::remap moves the materials), and measured when the flow has brought it back to where it
// started: (a) a uniform diagonal flow (1, 1, 1) for one box length through a periodic box, (b) a
// rigid rotation for one turn, (c) the reversing single-vortex deformation
// psi = sin^2(pi x) sin^2(pi y) cos(pi t / T) / pi (LeVeque, SIAM J. Numer. Anal. 33:627, 1996;
// Rider & Kothe, J. Comput. Phys. 141:112, 1998), which stretches the sheet and brings it back
// at t = T. docs/numerics.md ("Thin layers") has the table these tests print.
//
// Metrics on the final copper fractions f (exact solution: the painted start):
//  - kept: the copper in the connected layer (the 26-connected set of cells with f >= 1 %
//    holding the most copper) over all the copper;
//  - stray: cells outside the layer with 0 < f < 1 % more than two cells (Chebyshev, periodic)
//    from it, counted, and the copper of all cells that far, over all the copper;
//  - thickness: T = sqrt(12 var) of the copper's coordinate along the sheet's normal (a slab of
//    thickness T has variance T^2 / 12); its error |T1 - T0| / T0 against the painted start;
//  - L1: sum |f1 - f0| over the copper volume.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <string>
#include <vector>

#include "core/math.hpp"
#include "support.hpp"

using namespace mp;

namespace {

enum class Flow { Diagonal, Rotation, Vortex };
const char* flow_name(Flow f) {
  return f == Flow::Diagonal ? "diagonal" : f == Flow::Rotation ? "rotation" : "vortex";
}

constexpr double kPi = 3.14159265358979323846;
constexpr double kVortexPeriod = 2.0;  // T of the single vortex
constexpr double kRigidRadius = 0.48;  // the rotation is rigid inside, at rest outside
constexpr double kCourant = 0.5;       // largest Courant number of a sweep

// The face volume fluxes of a step dt at mid-step time t (a functor: nvcc allows no extended
// lambda in a TEST body). The planar flows come from a stream function psi at the nodes: the
// x face at node i between nodes j, j + 1 carries dt dz (psi(i, j + 1) - psi(i, j)), the y face
// -dt dz (psi(i + 1, j) - psi(i, j)), so each cell's fluxes sum to zero (up to round-off) and
// the cells keep their volume. The rotation's psi = -omega min(r, R)^2 / 2 (rigid inside R,
// at rest outside, so periodic images agree).
struct PrescribedFluxes {
  Geometry g;
  int flow;
  Real dt, t, omega;
  Field3 fx, fy, fz;
  KOKKOS_INLINE_FUNCTION Real psi(Real x, Real y) const {
    if (flow == int(Flow::Rotation)) {
      const Real rx = x - Real(0.5), ry = y - Real(0.5);
      const Real r2 = mmin(rx * rx + ry * ry, Real(kRigidRadius * kRigidRadius));
      return -omega * r2 / 2;
    }
    const Real sx = MP_KOKKOS_MATH::sin(Real(kPi) * x), sy = MP_KOKKOS_MATH::sin(Real(kPi) * y);
    return sx * sx * sy * sy * MP_KOKKOS_MATH::cos(Real(kPi) * t / Real(kVortexPeriod)) / Real(kPi);
  }
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    if (flow == int(Flow::Diagonal)) {
      fx(i, j, k) = dt * g.dx[1] * g.dx[2];
      fy(i, j, k) = dt * g.dx[0] * g.dx[2];
      fz(i, j, k) = dt * g.dx[0] * g.dx[1];
      return;
    }
    const Real x0 = g.node_coord(0, i), x1 = g.node_coord(0, i + 1);
    const Real y0 = g.node_coord(1, j), y1 = g.node_coord(1, j + 1);
    const Real p00 = psi(x0, y0);
    fx(i, j, k) = dt * g.dx[2] * (psi(x0, y1) - p00);
    fy(i, j, k) = -dt * g.dx[2] * (psi(x1, y0) - p00);
    fz(i, j, k) = 0;
  }
};

struct Measure {
  double kept = 0;        // copper in the connected layer / all copper
  long stray_cells = 0;   // cells with 0 < f < 1 % more than two cells from the layer
  double stray = 0;       // copper more than two cells from the layer / all copper
  double t0 = 0, t1 = 0;  // thickness of the start and the end
  double l1 = 0;          // sum |f1 - f0| / copper volume
  long steps = 0;
  double seconds = 0;
  double thickness_error() const { return std::abs(t1 - t0) / t0; }
};

struct Grid {
  int nx, ny, nz;
  long at(int i, int j, int k) const {
    i = (i % nx + nx) % nx;
    j = (j % ny + ny) % ny;
    k = (k % nz + nz) % nz;
    return i + long(nx) * (j + long(ny) * k);
  }
};

// The layer: the 26-connected component (periodic) of cells with f >= 1 % holding the most
// copper; its mask.
std::vector<char> layer_of(const Grid& g, const std::vector<double>& f) {
  const double tau = 0.01;
  std::vector<int> comp(f.size(), -1);
  std::vector<double> mass;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const long c = g.at(i, j, k);
        if (f[c] < tau || comp[c] >= 0) continue;
        const int id = int(mass.size());
        mass.push_back(0);
        std::deque<std::array<int, 3>> q{{i, j, k}};
        comp[c] = id;
        while (!q.empty()) {
          const auto p = q.front();
          q.pop_front();
          mass[id] += f[g.at(p[0], p[1], p[2])];
          for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di) {
                const long n = g.at(p[0] + di, p[1] + dj, p[2] + dk);
                if (f[n] >= tau && comp[n] < 0) {
                  comp[n] = id;
                  q.push_back({(p[0] + di + g.nx) % g.nx, (p[1] + dj + g.ny) % g.ny,
                               (p[2] + dk + g.nz) % g.nz});
                }
              }
        }
      }
  int best = 0;
  for (int id = 1; id < int(mass.size()); ++id)
    if (mass[id] > mass[best]) best = id;
  std::vector<char> layer(f.size(), 0);
  for (std::size_t c = 0; c < f.size(); ++c) layer[c] = comp[c] == best && !mass.empty();
  return layer;
}

// Thickness sqrt(12 var) of the copper's signed distance along `n` from `c` (periodic
// minimum image in a box of size `box`).
double thickness(const Grid& g, const std::vector<double>& f, const double lo[3], const double h[3],
                 const double box[3], const double c[3], const double n[3]) {
  double m = 0, s1 = 0, s2 = 0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const double w = f[g.at(i, j, k)];
        if (!(w > 0)) continue;
        const int idx[3] = {i, j, k};
        double s = 0;
        for (int d = 0; d < 3; ++d) {
          double x = lo[d] + (idx[d] + 0.5) * h[d] - c[d];
          x -= box[d] * std::round(x / box[d]);
          s += n[d] * x;
        }
        m += w;
        s1 += w * s;
        s2 += w * s * s;
      }
  const double mean = s1 / m;
  return std::sqrt(12 * (s2 / m - mean * mean));
}

// The sheet: thickness `thick` (box units), normal `n` through `c`. Diagonal: a disk of radius
// 0.3 in the unit cube, n = (1, 2, 3) / sqrt(14). Rotation and vortex: a strip in the x-y plane
// (2 cells along z), n = (cos 60, sin 60, 0), cut to 0.33 <= x < 0.67 (0.39 long).
Measure run_sheet(Flow flow, int n, double thick, const std::string& iface) {
  const bool planar = flow != Flow::Diagonal;
  const double nz = planar ? 2 : n;
  double nrm[3], c[3];
  if (planar) {
    nrm[0] = 0.5;
    nrm[1] = std::sqrt(0.75);
    nrm[2] = 0;
    c[0] = 0.5;
    c[1] = flow == Flow::Rotation ? 0.62 : 0.72;
    c[2] = 1.0 / n;
  } else {
    const double s = std::sqrt(14.0);
    nrm[0] = 1 / s;
    nrm[1] = 2 / s;
    nrm[2] = 3 / s;
    c[0] = c[1] = c[2] = 0.5;
  }
  char buf[1024];
  auto vec = [&](const double* v, double t) {
    char b[128];
    std::snprintf(b, sizeof b, "[%.17g, %.17g, %.17g]", c[0] + t * v[0], c[1] + t * v[1],
                  c[2] + t * v[2]);
    return std::string(b);
  };
  std::string sheet = "{material: cu, shape: cylinder, base: " + vec(nrm, -thick / 2) +
                      ", top: " + vec(nrm, thick / 2);
  if (planar) {
    sheet +=
        ", radius: 1.0, minus: [{shape: box, lo: [-1, -1, -1], hi: [0.33, 2, 2]}, "
        "{shape: box, lo: [0.67, -1, -1], hi: [2, 2, 2]}]";
  } else {
    sheet += ", radius: 0.3";
  }
  sheet += ", density: 8.93, energy: 1.0e-6}";
  std::snprintf(buf, sizeof buf, "mesh.cells=[%d,%d,%d]", n, n, int(nz));
  const std::vector<std::string> ov = {
      buf,
      "mesh.hi=[1, 1, " + std::to_string(nz / n) + "]",
      "time.end=1e9",
      "numerics.samples=8",
      "numerics.interface=" + iface,
      "materials=[{name: air, eos: ideal_gas, gamma: 1.4}, {name: cu, library: copper}]",
      "regions=[{material: air, shape: all, density: 1.225e-3, pressure: 1.0e-6}, " + sheet + "]"};
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(test::load_scene("sphere_advection.yaml", ov), MPI_COMM_WORLD, settings);
  sim.initialize();
  hydro::Hydro& h = sim.hydro();
  const Mesh& mesh = sim.mesh();
  const auto f0 = test::gather(mesh, h.materials()->fraction(1), Centering::Cell);

  // one box length along the diagonal, one turn, or the vortex's period, at Courant kCourant
  const double dx = 1.0 / n;
  const double omega = 2 * kPi;  // (one turn in unit time)
  const double speed = flow == Flow::Diagonal   ? 1
                       : flow == Flow::Rotation ? omega * kRigidRadius
                                                : 1;
  const double span = flow == Flow::Vortex ? kVortexPeriod : 1;
  const long steps = long(std::ceil(span * speed / (kCourant * dx)));
  const double dt = span / steps;
  auto& s = h.state();
  const auto t_start = std::chrono::steady_clock::now();
  for (long q = 0; q < steps; ++q) {
    PrescribedFluxes pf{mesh.geometry(), int(flow),     Real(dt),      Real((q + 0.5) * dt),
                        Real(omega),     s.vol_flux[0], s.vol_flux[1], s.vol_flux[2]};
    Kokkos::parallel_for("test::fluxes", mesh.nodes(Region::All), pf);
    h.remap(q);
  }
  Kokkos::fence();
  Measure r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  r.steps = steps;
  const auto f1 = test::gather(mesh, h.materials()->fraction(1), Centering::Cell);

  const Grid g{n, n, int(nz)};
  double v0 = 0, v1 = 0;
  for (std::size_t i = 0; i < f0.size(); ++i) {
    v0 += f0[i];
    v1 += f1[i];
    r.l1 += std::abs(f1[i] - f0[i]);
  }
  r.l1 /= v0;
  EXPECT_NEAR(v1, v0, test::roundoff(1e-10) * v0) << "copper volume conserved";
  const auto layer = layer_of(g, f1);
  // the layer dilated by two cells
  std::vector<char> near(f1.size(), 0);
  const int reach_z = planar ? 0 : 2;  // (the planar cases' two z cells are one column)
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        if (!layer[g.at(i, j, k)]) continue;
        for (int dk = -reach_z; dk <= reach_z; ++dk)
          for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di) near[g.at(i + di, j + dj, k + dk)] = 1;
      }
  double kept = 0, far = 0;
  for (std::size_t i = 0; i < f1.size(); ++i) {
    if (layer[i]) kept += f1[i];
    if (!near[i] && f1[i] > 0) {
      far += f1[i];
      if (f1[i] < 0.01) ++r.stray_cells;
    }
  }
  r.kept = kept / v1;
  r.stray = far / v1;
  const double lo[3] = {0, 0, 0}, hh[3] = {dx, dx, dx}, box[3] = {1, 1, nz * dx};
  r.t0 = thickness(g, f0, lo, hh, box, c, nrm);
  r.t1 = thickness(g, f1, lo, hh, box, c, nrm);
  std::printf(
      "thin layer %-8s %-7s %3d cells, sheet %.2f cells: kept %.4f, stray cells %ld (copper "
      "%.2e), thickness %.4f -> %.4f cells (error %.4f), L1 %.4f, %ld steps, %.1f s\n",
      flow_name(flow), iface.c_str(), n, thick * n, r.kept, r.stray_cells, r.stray, r.t0 / dx,
      r.t1 / dx, r.thickness_error(), r.l1, steps, r.seconds);
  return r;
}

}  // namespace

// Issue #53's must-show: a copper sheet 3 cells thick (at 24^3; a disk of radius 0.3, normal
// (1, 2, 3) / sqrt(14)) carried one box length along the diagonal with the default normal
// (Youngs') keeps >= 95 % of its copper in the connected layer, leaves no cell below 1 % more
// than two cells from it, and its thickness error falls when the same sheet is resolved twice
// as finely (6 cells at 48^3).
TEST(ThinLayer, DiagonalThreeCellSheetStaysConnectedAndItsThicknessConverges) {
  const Measure c = run_sheet(Flow::Diagonal, 24, 3.0 / 24, "youngs");
  const Measure f = run_sheet(Flow::Diagonal, 48, 3.0 / 24, "youngs");
  // the 95 %: observed 0.9994 at 24^3, 0.9998 at 48^3
  EXPECT_GE(c.kept, 0.95);
  EXPECT_GE(f.kept, 0.95);
  // no stray copper below 1 % more than two cells from the layer: observed none (0 cells, 0
  // copper) at either resolution
  EXPECT_EQ(c.stray_cells, 0);
  EXPECT_EQ(f.stray_cells, 0);
  EXPECT_EQ(c.stray, 0);
  EXPECT_EQ(f.stray, 0);
  // Thickness error 0.0652 at 24^3 (3.13 -> 3.34 cells), 0.0069 at 48^3 (6.06 -> 6.02): ratio
  // 0.106; the bound 0.5 is first order, the least that says the error falls with resolution.
  EXPECT_LT(f.thickness_error(), 0.5 * c.thickness_error());
  // and the L1 shape error: 0.1615 -> 0.0842 (order 0.94); bound 0.7 (order 0.5)
  EXPECT_LT(f.l1, 0.7 * c.l1);
}

// The 2- and 4-cell sheets on the same path at 24^3, with Youngs' normal and the ELVIRA-type
// one (numerics.interface: elvira): all stay in one layer with no stray copper, and ELVIRA's
// L1 shape error is below Youngs' on each (observed 0.3315 / 0.3517, 0.1466 / 0.1615,
// 0.1220 / 0.1264 for 2, 3, 4 cells: 3.5 to 9 % lower).
TEST(ThinLayer, DiagonalSheetsWithBothNormals) {
  for (double cells : {2.0, 3.0, 4.0}) {
    const Measure y = run_sheet(Flow::Diagonal, 24, cells / 24, "youngs");
    const Measure e = run_sheet(Flow::Diagonal, 24, cells / 24, "elvira");
    for (const Measure* m : {&y, &e}) {
      // observed >= 0.9993 (the 2-cell sheet) for both normals
      EXPECT_GE(m->kept, 0.95) << cells;
      EXPECT_EQ(m->stray_cells, 0) << cells;
    }
    EXPECT_LT(e.l1, y.l1) << cells;
  }
}

// The planar flows (a strip in the x-y plane, 2 cells along z), labelled long: the rotation
// takes 387 steps at 64^2 and 773 at 128^2 (about a minute on one core). A 3-cell sheet at 64^2
// and the same sheet at 128^2 (6 cells), one turn and one vortex period, with both normals:
// kept in one layer, no stray copper, thickness and L1 errors falling with resolution.
// Observed (kept >= 0.9998 and no stray copper everywhere):
//   rotation youngs: thickness error 0.0768 -> 0.0009, L1 0.1425 -> 0.0524
//   rotation elvira:                 0.0732 -> 0.0002,    0.1346 -> 0.0481
//   vortex   youngs:                 0.0565 -> 0.0066,    0.1365 -> 0.0539
//   vortex   elvira:                 0.0482 -> 0.0035,    0.1303 -> 0.0493
// The bounds are the diagonal test's: ratio 0.5 for the thickness error (first order), 0.7 for
// L1 (order 0.5); observed ratios at most 0.12 and 0.39.
TEST(ThinLayerLong, RotationAndVortexThreeCellSheetsConverge) {
  for (Flow flow : {Flow::Rotation, Flow::Vortex})
    for (const char* iface : {"youngs", "elvira"}) {
      const Measure c = run_sheet(flow, 64, 3.0 / 64, iface);
      const Measure f = run_sheet(flow, 128, 3.0 / 64, iface);
      for (const Measure* m : {&c, &f}) {
        EXPECT_GE(m->kept, 0.95) << flow_name(flow) << " " << iface;
        EXPECT_EQ(m->stray_cells, 0) << flow_name(flow) << " " << iface;
      }
      EXPECT_LT(f.thickness_error(), 0.5 * c.thickness_error()) << flow_name(flow) << " " << iface;
      EXPECT_LT(f.l1, 0.7 * c.l1) << flow_name(flow) << " " << iface;
    }
}

// The 2- and 4-cell strips at 64^2 with both normals stay in one layer with no stray copper
// (observed kept >= 0.9995). Thickness errors, for the table in docs/numerics.md: rotation 2
// cells 0.2089 (youngs) / 0.1926 (elvira), 4 cells 0.0258 / 0.0227; vortex 2 cells 0.1341 /
// 0.1275, 4 cells 0.0157 / 0.0153.
TEST(ThinLayerLong, RotationAndVortexTwoAndFourCellSheetsStayConnected) {
  for (Flow flow : {Flow::Rotation, Flow::Vortex})
    for (double cells : {2.0, 4.0})
      for (const char* iface : {"youngs", "elvira"}) {
        const Measure m = run_sheet(flow, 64, cells / 64, iface);
        EXPECT_GE(m.kept, 0.95) << flow_name(flow) << " " << cells << " " << iface;
        EXPECT_EQ(m.stray_cells, 0) << flow_name(flow) << " " << cells << " " << iface;
      }
}
