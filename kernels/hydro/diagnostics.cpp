// Global reductions: the time step with its limiting cell, the health check that stops a
// non-physical run, and the conserved totals of the run summary.
#include <algorithm>
#include <cfloat>
#include <climits>
#include <limits>
#include <string>

#include "core/columns.hpp"
#include "core/math.hpp"
#include "core/reduce.hpp"
#include "hydro/hydro.hpp"

namespace mp::hydro {

namespace {

// The stable step of cells (i, j, kb .. ke - 1) of a column into dt[k - kb], with sum[k - kb]
// 1 where the unsplit remap's Courant-sum bound is the tighter one (else 0). The options are
// template arguments so that the loop has no branch and GCC vectorizes it (the square root and
// the divisions of every cell); the arithmetic is the per-point form's, bit for bit.
template <class A>
struct CflCells {
  A c, q, rho, u, v, w;
  Real dx[3];
  Real cfl, cfl_u;
  Real c_lin;  // the viscosity's linear coefficient (the viscous stability bound below)

  // the largest |velocity| over the cell's 8 nodes. fabs, not mabs: GCC threads mabs's branch
  // through the chain of maxima and leaves the loop branchy. The two differ only in the sign
  // of a zero (mabs(-0) = -0), which the step, a sum with the positive c_eff and 1e-30, drops.
  KOKKOS_INLINE_FUNCTION static Real corners(const A& f, int i, int j, int k) {
    using MP_KOKKOS_MATH::fabs;
    Real m = 0;
    m = mmax(m, fabs(f(i, j, k)));
    m = mmax(m, fabs(f(i + 1, j, k)));
    m = mmax(m, fabs(f(i, j + 1, k)));
    m = mmax(m, fabs(f(i + 1, j + 1, k)));
    m = mmax(m, fabs(f(i, j, k + 1)));
    m = mmax(m, fabs(f(i + 1, j, k + 1)));
    m = mmax(m, fabs(f(i, j + 1, k + 1)));
    return mmax(m, fabs(f(i + 1, j + 1, k + 1)));
  }

  // the mean of a node field over the 4 nodes of a cell face: the low face of cell (i, j, k)
  // normal to axis a (and its high face at i + 1, j + 1 or k + 1)
  KOKKOS_INLINE_FUNCTION static Real face_mean(const A& f, int a, int i, int j, int k) {
    if (a == 0)
      return Real(0.25) * (f(i, j, k) + f(i, j + 1, k) + f(i, j, k + 1) + f(i, j + 1, k + 1));
    if (a == 1)
      return Real(0.25) * (f(i, j, k) + f(i + 1, j, k) + f(i, j, k + 1) + f(i + 1, j, k + 1));
    return Real(0.25) * (f(i, j, k) + f(i + 1, j, k) + f(i, j + 1, k) + f(i + 1, j + 1, k));
  }

  template <StepRule Rule, bool Unsplit>
  KOKKOS_INLINE_FUNCTION void chunk(int i, int j, int kb, int ke, Real* dt_out,
                                    Real* sum_out) const {
#pragma GCC ivdep
    for (int k = kb; k < ke; ++k) {
      // sound speed with the viscous pressure added: c_eff^2 = c^2 + 2 q / rho
      const Real ceff = msqrt(c(i, j, k) * c(i, j, k) + 2 * q(i, j, k) / rho(i, j, k));
      const Real vx = corners(u, i, j, k), vy = corners(v, i, j, k), vz = corners(w, i, j, k);
      Real dt = FLT_MAX, sum = 0;
      if constexpr (Rule == StepRule::CloverLeaf) {
        // CloverLeaf3D_ref's rule (UK-MAC, calc_dt_kernel.f90, subroutine calc_dt_kernel; its
        // dtc_safe is cfl here, its dtu/dtv/dtw/dtdiv_safe are cfl_transport): the sound limit
        // over the smallest edge, each axis's transport limit from the larger |velocity| of the
        // cell's two faces normal to it (face means of 4 nodes), and a limit on the volume
        // change rate |div u| from the same face means. (fabs, not mabs, as in corners().)
        using MP_KOKKOS_MATH::fabs;
        const Real ul = face_mean(u, 0, i, j, k), ur = face_mean(u, 0, i + 1, j, k);
        const Real vl = face_mean(v, 1, i, j, k), vr = face_mean(v, 1, i, j + 1, k);
        const Real wl = face_mean(w, 2, i, j, k), wr = face_mean(w, 2, i, j, k + 1);
        const Real dmin = mmin(dx[0], mmin(dx[1], dx[2]));
        dt = cfl * dmin / (ceff + Real(1e-30));
        dt = mmin(dt, cfl_u * dx[0] / (mmax(fabs(ul), fabs(ur)) + Real(1e-30)));
        dt = mmin(dt, cfl_u * dx[1] / (mmax(fabs(vl), fabs(vr)) + Real(1e-30)));
        dt = mmin(dt, cfl_u * dx[2] / (mmax(fabs(wl), fabs(wr)) + Real(1e-30)));
        const Real div = (ur - ul) / dx[0] + (vr - vl) / dx[1] + (wr - wl) / dx[2];
        dt = mmin(dt, cfl_u / (fabs(div) + Real(1e-30)));
      } else if constexpr (Rule == StepRule::Separate) {
        // each limit with its own safety factor, applied here
        dt = mmin(dt, mmin(cfl * dx[0] / (ceff + Real(1e-30)), cfl_u * dx[0] / (vx + Real(1e-30))));
        dt = mmin(dt, mmin(cfl * dx[1] / (ceff + Real(1e-30)), cfl_u * dx[1] / (vy + Real(1e-30))));
        dt = mmin(dt, mmin(cfl * dx[2] / (ceff + Real(1e-30)), cfl_u * dx[2] / (vz + Real(1e-30))));
      } else {
        dt = mmin(dt, dx[0] / (ceff + vx + Real(1e-30)));
        dt = mmin(dt, dx[1] / (ceff + vy + Real(1e-30)));
        dt = mmin(dt, dx[2] / (ceff + vz + Real(1e-30)));
        // an unsplit remap moves material across all faces at once: bound the Courant sum
        if constexpr (Unsplit) {
          const Real dt_sum = 1 / (vx / dx[0] + vy / dx[1] + vz / dx[2] + Real(1e-30));
          sum = dt_sum < dt ? Real(1) : Real(0);
          dt = dt_sum < dt ? dt_sum : dt;
        }
        dt *= cfl;
        // The linear viscosity q = c_L rho c |du| is a diffusion of coefficient ~ c_L c dx with
        // an explicit limit of its own that c_eff (second order in a small wave's amplitude)
        // does not see: where the viscosity acts, the step is also bounded by the combined
        // acoustic-viscous limit dx / (b + sqrt(b^2 + c_eff^2) + |u|), b = c_L c (docs/numerics.md,
        // "Time step"). Without it an undamped acoustic wave grew 9-84x at cfl 0.95-1.0. At
        // b = 0.2 c it binds only above cfl ~0.8 (1 / (0.2 + sqrt(1.04)) = 0.82): the decks'
        // cfl 0.3-0.5 get their steps bit for bit.
        const Real b = q(i, j, k) > 0 ? c_lin * c(i, j, k) : Real(0);
        const Real cv = b + msqrt(b * b + ceff * ceff);
        Real dv = dx[0] / (cv + vx + Real(1e-30));
        dv = mmin(dv, dx[1] / (cv + vy + Real(1e-30)));
        dv = mmin(dv, dx[2] / (cv + vz + Real(1e-30)));
        dt = mmin(dt, dv);
      }
      if constexpr (Unsplit && Rule != StepRule::Combined) {
        // the unsplit remap's Courant sum under the transport factor (named courant_sum when
        // it sets the step, as the combined rule's own above)
        const Real dt_sum = cfl_u / (vx / dx[0] + vy / dx[1] + vz / dx[2] + Real(1e-30));
        sum = dt_sum < dt ? Real(1) : Real(0);
        dt = dt_sum < dt ? dt_sum : dt;
      }
      dt_out[k - kb] = dt;
      sum_out[k - kb] = sum;
    }
  }
};

}  // namespace

TimeStep Hydro::time_step(Real dt_old, double t, double t_end) const {
  const Geometry g = mesh_.geometry();
  auto c = s_.c, q = s_.q, rho = s_.rho, u = s_.u, v = s_.v, w = s_.w;
  const Real cfl = opt_.cfl;
  const bool unsplit = opt_.unsplit;
  const StepRule rule = opt_.rule;
  const Real cfl_u = opt_.cfl_transport;
  const Real c_lin = opt_.q_linear;
  const int nlx = g.nl[0], nly = g.nl[1], ng = g.ng;
  using MinLoc = Kokkos::MinLoc<Real, long>;
  typename MinLoc::value_type best;
  int lo[3], hi[3];
  mesh_.box(Centering::Cell, Region::Owned, lo, hi);
  // k-columns (core/columns.hpp): a chunk of a column's steps in one loop GCC vectorizes
  // (CflCells), then the chunk's least step found in order.
  const Real dx[3] = {g.dx[0], g.dx[1], g.dx[2]};
  reduce_columns_with(
      "timestep::cfl", lo, hi,
      KOKKOS_LAMBDA(int i, int j, int k0, int k1, typename MinLoc::value_type& acc) {
        const auto ca = local(c);
        const CflCells<decltype(ca)> cells{
            ca,  local(q), local(rho), local(u), local(v), local(w), {dx[0], dx[1], dx[2]},
            cfl, cfl_u,    c_lin};
        constexpr int kChunk = 32;
        Real dts[kChunk], sums[kChunk];
        for (int kb = k0; kb < k1; kb += kChunk) {
          const int ke = kb + kChunk < k1 ? kb + kChunk : k1;
          if (rule == StepRule::Separate) {
            if (unsplit)
              cells.template chunk<StepRule::Separate, true>(i, j, kb, ke, dts, sums);
            else
              cells.template chunk<StepRule::Separate, false>(i, j, kb, ke, dts, sums);
          } else if (rule == StepRule::CloverLeaf) {
            if (unsplit)
              cells.template chunk<StepRule::CloverLeaf, true>(i, j, kb, ke, dts, sums);
            else
              cells.template chunk<StepRule::CloverLeaf, false>(i, j, kb, ke, dts, sums);
          } else {
            if (unsplit)
              cells.template chunk<StepRule::Combined, true>(i, j, kb, ke, dts, sums);
            else
              cells.template chunk<StepRule::Combined, false>(i, j, kb, ke, dts, sums);
          }
          for (int k = kb; k < ke; ++k)
            if (dts[k - kb] < acc.val) {
              acc.val = dts[k - kb];
              acc.loc = 2 * ((i - ng) + long(nlx) * ((j - ng) + long(nly) * (k - ng))) +
                        (sums[k - kb] > 0 ? 1 : 0);
            }
        }
      },
      MinLoc(best));
  // Global minimum: the winning rank tells where its cell is.
  struct {
    double dt;
    int rank;
  } mine{double(best.val), mesh_.rank()}, global{};
  MPI_Allreduce(&mine, &global, 1, MPI_DOUBLE_INT, MPI_MINLOC, mesh_.comm());
  int cell[4] = {0, 0, 0, 0};
  if (mesh_.rank() == global.rank) {
    const long at = best.loc / 2;
    cell[0] = int(at % nlx) + g.offset[0];
    cell[1] = int((at / nlx) % nly) + g.offset[1];
    cell[2] = int(at / (long(nlx) * nly)) + g.offset[2];
    cell[3] = int(best.loc % 2);
  }
  MPI_Bcast(cell, 4, MPI_INT, global.rank, mesh_.comm());

  TimeStep ts;
  ts.dt = Real(global.dt);
  ts.cell = {cell[0], cell[1], cell[2]};
  ts.limit = cell[3] ? DtLimit::CourantSum : DtLimit::Cfl;
  if (dt_old > 0 && ts.dt > opt_.growth * dt_old) {
    ts.dt = opt_.growth * dt_old;
    ts.limit = DtLimit::Growth;
  }
  if (ts.dt > opt_.dt_max) {
    ts.dt = opt_.dt_max;
    ts.limit = DtLimit::Max;
  }
  // The clock is double whatever Real is: in a float build, rounding t to float could make
  // the remaining time zero (or negative) and stall the run one step short of the end.
  if (t + double(ts.dt) > t_end) {
    ts.dt = Real(t_end - t);
    ts.limit = DtLimit::End;
  }
  return ts;
}

// What the health check found wrong, in the order a cell's quantities are tested; the report
// names the lowest bad cell and, in it, the first bad quantity.
constexpr long kBadDensity = 0, kBadEnergy = 1, kBadPressure = 2, kBadVelocityX = 3,
               kBadVelocityY = 4, kBadVelocityZ = 5, kBadKinds = 6, kNotBad = -1;

Health Hydro::check() const {
  const Geometry g = mesh_.geometry();
  auto rho = s_.rho, e = s_.e, p = s_.p, u = s_.u, v = s_.v, w = s_.w;
  const long nx = mesh_.global_cells(0), ny = mesh_.global_cells(1);
  // key = ((cell * kBadKinds + quantity) * 8 + top): lowest cell first, then its first bad
  // quantity; `top` marks a node of the last node layer (bit d: along axis d), which belongs to
  // no owned cell and is reported with the owned cell below it.
  // Every owned cell and every owned node, the last node layer [ng + nl] included, in one
  // launch over the owned nodes (the owned cells are the nodes below the last layer).
  const int tx = Mesh::ng + mesh_.owned_cells(0), ty = Mesh::ng + mesh_.owned_cells(1),
            tz = Mesh::ng + mesh_.owned_cells(2);
  const bool several = mm_ != nullptr;
  // A single material's floor: 0, or a Mie-Grueneisen solid's -c0^2 / 100 (its e is measured
  // from the ambient state; the floor of its materials in a mixed cell, eos.hpp energy_floor).
  // A cold solid at e = 0 ahead of a shock went to -7e-36 by the round-off of p dV (steel
  // against a rigid wall, tests/test_materials.cpp, once the viscosity's round-off stress was
  // dropped: docs/numerics.md, "Tensor viscosity").
  const Real efloor = several ? Real(0) : eos_.energy_floor();
  long first = LONG_MAX;
  // (k-columns: a column is screened in chunks by a vector loop, each point's tests as a 0/1
  // value, and only a chunk with a bad point is walked again by the per-point key below)
  auto point = KOKKOS_LAMBDA(int i, int j, int k, long& acc) {
    if (i < tx && j < ty && k < tz) {
      const Real r = rho(i, j, k), en = e(i, j, k), pr = p(i, j, k);
      // (a multi-material scene's energies are checked per material, against each
      // material's floor: MaterialState::first_bad)
      const long what = !(r > 0) || !misfinite(r)                         ? kBadDensity
                        : (!(en >= efloor) && !several) || !misfinite(en) ? kBadEnergy
                        : !misfinite(pr)                                  ? kBadPressure
                                                                          : kNotBad;
      if (what >= 0) {
        const long key = (g.global_cell(i, j, k, nx, ny) * kBadKinds + what) * 8;
        if (key < acc) acc = key;
      }
    }
    const long what = !misfinite(u(i, j, k))   ? kBadVelocityX
                      : !misfinite(v(i, j, k)) ? kBadVelocityY
                      : !misfinite(w(i, j, k)) ? kBadVelocityZ
                                               : kNotBad;
    if (what < 0) return;
    const int top = (i == tx ? 1 : 0) + (j == ty ? 2 : 0) + (k == tz ? 4 : 0);
    const long cell =
        g.global_cell(i == tx ? i - 1 : i, j == ty ? j - 1 : j, k == tz ? k - 1 : k, nx, ny);
    const long key = (cell * kBadKinds + what) * 8 + top;
    if (key < acc) acc = key;
  };
  int lo[3], hi[3];
  mesh_.box(Centering::Node, Region::Owned, lo, hi);
  reduce_columns_with(
      "health::check", lo, hi,
      KOKKOS_LAMBDA(int i, int j, int k0, int k1, long& acc) {
        const auto ra = local(rho), ea = local(e), pa = local(p), ua = local(u), va = local(v),
                   wa = local(w);
        const bool cells = i < tx && j < ty;
        constexpr Real big = kRealMax;
        // (en >= efloor || several) for every finite en: a NaN fails the finite test anyway
        const Real emin = several ? -kRealInfinity : efloor;
        constexpr int kChunk = 32;
        Real bad[kChunk];
        for (int kb = k0; kb < k1; kb += kChunk) {
          const int ke = kb + kChunk < k1 ? kb + kChunk : k1;
          // the last node layer along k is no cell's: its cell values are not read
          const int kc = cells ? (ke < tz ? ke : tz > kb ? tz : kb) : kb;
          using MP_KOKKOS_MATH::fabs;
#pragma GCC ivdep
          for (int k = kb; k < kc; ++k) {
            const Real r = ra(i, j, k), en = ea(i, j, k), pr = pa(i, j, k);
            // misfinite(x) is fabs(x) <= max (false for an infinity and a NaN); the tests
            // combined with &, not &&, so that no load is conditional
            const bool ok =
                (r > 0) & (fabs(r) <= big) & (en >= emin) & (fabs(en) <= big) & (fabs(pr) <= big);
            bad[k - kb] = ok ? Real(0) : Real(1);
          }
          for (int k = kc; k < ke; ++k) bad[k - kb] = 0;
#pragma GCC ivdep
          for (int k = kb; k < ke; ++k) {
            const bool ok = (fabs(ua(i, j, k)) <= big) & (fabs(va(i, j, k)) <= big) &
                            (fabs(wa(i, j, k)) <= big);
            bad[k - kb] += ok ? Real(0) : Real(1);
          }
          bool any = false;
          for (int k = kb; k < ke; ++k) any = any || bad[k - kb] > 0;
          if (any)
            for (int k = kb; k < ke; ++k) point(i, j, k, acc);
        }
      },
      Kokkos::Min<long>(first));
  long global_key = LONG_MAX;
  MPI_Allreduce(&first, &global_key, 1, MPI_LONG, MPI_MIN, mesh_.comm());
  long global_first = global_key == LONG_MAX ? LONG_MAX : global_key / (8 * kBadKinds);
  int bad_material = -1, material_what = 0;
  if (mm_) {
    // a material inside a mixed cell can go bad while the cell average still looks fine
    const long mfirst = mm_->first_bad(bad_material, material_what);
    if (mfirst < global_first) {
      global_first = mfirst;
    } else {
      bad_material = -1;
    }
  }
  Health h;
  if (global_first == LONG_MAX) return h;
  h.ok = false;
  h.cell = {int(global_first % nx), int((global_first / nx) % ny), int(global_first / (nx * ny))};
  // The owner reads the cell's values and shares them.
  double vals[6] = {0, 0, 0, 0, 0, 0};
  bool mine = true;
  int loc[3];
  for (int d = 0; d < 3; ++d) {
    loc[d] = h.cell[d] - mesh_.offset(d) + Mesh::ng;
    if (loc[d] < Mesh::ng || loc[d] >= Mesh::ng + mesh_.owned_cells(d)) mine = false;
  }
  auto read = [&](const Field3& f) {
    Real x = 0;
    Kokkos::deep_copy(x, Kokkos::subview(f, loc[0], loc[1], loc[2]));
    return double(x);
  };
  if (mine) {
    vals[0] = read(rho);
    vals[1] = read(e);
    vals[2] = read(p);
  }
  // a bad material's own fraction, density and energy in that cell (every rank fills the
  // fields, a collective-free kernel; only the owner reads them)
  if (bad_material >= 0)
    for (int which = 0; which < 3; ++which) {
      const Field3 f = mm_->material_field(bad_material, which);
      if (mine) vals[3 + which] = read(f);
    }
  double all[6];
  MPI_Allreduce(vals, all, 6, MPI_DOUBLE, MPI_SUM, mesh_.comm());
  h.rho = all[0];
  h.e = all[1];
  h.p = all[2];
  if (bad_material >= 0) {
    h.material = bad_material;
    h.m_fraction = all[3];
    h.m_rho = all[4];
    h.m_e = all[5];
  }
  h.volume = g.cell_volume();
  // The message names the quantity as the dumps do (density, energy, pressure, velocity_x ...).
  if (bad_material >= 0) {
    static const char* kWhat[4] = {"density not positive", "density NaN or infinite",
                                   "energy negative", "energy NaN or infinite"};
    h.what = "material " + std::to_string(bad_material) + " " + kWhat[material_what] +
             (h.m_fraction < 1 ? " in a mixed cell" : "");
    return h;
  }
  const long what = (global_key / 8) % kBadKinds;
  const int top = int(global_key % 8);
  switch (what) {
    case kBadDensity:
      h.what = misfinite(Real(h.rho)) ? "density not positive" : "density NaN or infinite";
      break;
    case kBadEnergy:
      h.what = misfinite(Real(h.e)) ? "energy negative" : "energy NaN or infinite";
      break;
    case kBadPressure:
      h.what = "pressure NaN or infinite";
      break;
    default: {
      const int node[3] = {h.cell[0] + (top & 1), h.cell[1] + (top >> 1 & 1),
                           h.cell[2] + (top >> 2 & 1)};
      h.what = std::string("velocity_") + "xyz"[what - kBadVelocityX] +
               " NaN or infinite at node (" + std::to_string(node[0]) + ", " +
               std::to_string(node[1]) + ", " + std::to_string(node[2]) + ")";
    }
  }
  return h;
}

Totals Hydro::totals() const {
  const Geometry g = mesh_.geometry();
  const Real vol = g.cell_volume();
  auto rho = s_.rho, e = s_.e, u = s_.u, v = s_.v, w = s_.w;
  // (compensated sums, core/reduce.hpp: the totals' changes are asserted to round-off)
  CompensatedSumN<2> cells;
  Kokkos::parallel_reduce(
      "totals::cells", mesh_.cells(Region::Owned),
      KOKKOS_LAMBDA(int i, int j, int k, CompensatedSumN<2>& acc) {
        const double mc = double(rho(i, j, k)) * vol;
        acc.add(0, mc);
        acc.add(1, mc * double(e(i, j, k)));
      },
      Kokkos::Sum<CompensatedSumN<2>>(cells));
  // Each node once: [ng, ng+nl) on every rank, plus the last node at a physical high face.
  // A node on a physical face carries half a dual cell per such face.
  int hi[3];
  bool lo_wall[3], hi_wall[3];
  for (int d = 0; d < 3; ++d) {
    hi_wall[d] = mesh_.physical_boundary(d, 1);
    lo_wall[d] = mesh_.physical_boundary(d, 0);
    hi[d] = Mesh::ng + mesh_.owned_cells(d) + (hi_wall[d] ? 1 : 0);
  }
  const int ng = Mesh::ng;
  const int lx = ng, ly = ng, lz = ng;
  const int hx = ng + mesh_.owned_cells(0), hy = ng + mesh_.owned_cells(1),
            hz = ng + mesh_.owned_cells(2);
  const bool lw0 = lo_wall[0], lw1 = lo_wall[1], lw2 = lo_wall[2];
  const bool hw0 = hi_wall[0], hw1 = hi_wall[1], hw2 = hi_wall[2];
  CompensatedSumN<4> nodes;
  Kokkos::parallel_reduce(
      "totals::nodes", Policy3({ng, ng, ng}, {hi[0], hi[1], hi[2]}),
      KOKKOS_LAMBDA(int i, int j, int k, CompensatedSumN<4>& acc) {
        double m = 0;
        for (int c = 0; c < 2; ++c)
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) m += rho(i - 1 + a, j - 1 + b, k - 1 + c);
        m *= 0.125 * vol;
        if ((lw0 && i == lx) || (hw0 && i == hx)) m *= 0.5;
        if ((lw1 && j == ly) || (hw1 && j == hy)) m *= 0.5;
        if ((lw2 && k == lz) || (hw2 && k == hz)) m *= 0.5;
        const double uu = u(i, j, k), vv = v(i, j, k), ww = w(i, j, k);
        acc.add(0, m * uu);
        acc.add(1, m * vv);
        acc.add(2, m * ww);
        acc.add(3, 0.5 * m * (uu * uu + vv * vv + ww * ww));
      },
      Kokkos::Sum<CompensatedSumN<4>>(nodes));
  double unpaid = 0;
  Kokkos::deep_copy(unpaid, s_.ke_unpaid);
  double local[7] = {cells.value(0), cells.value(1), nodes.value(0), nodes.value(1),
                     nodes.value(2), nodes.value(3), unpaid};
  double global[7];
  MPI_Allreduce(local, global, 7, MPI_DOUBLE, MPI_SUM, mesh_.comm());
  Totals t;
  t.mass = global[0];
  t.internal = global[1];
  t.momentum = {global[2], global[3], global[4]};
  t.kinetic = global[5];
  t.ke_fix_unpaid = global[6];
  if (mm_) t.material_mass = mm_->material_masses();
  return t;
}

std::vector<OutputField> Hydro::output_fields() const {
  std::vector<OutputField> f{
      {"density", Centering::Cell, s_.rho},  {"energy", Centering::Cell, s_.e},
      {"pressure", Centering::Cell, s_.p},   {"sound_speed", Centering::Cell, s_.c},
      {"viscosity", Centering::Cell, s_.q},  {"velocity_x", Centering::Node, s_.u},
      {"velocity_y", Centering::Node, s_.v}, {"velocity_z", Centering::Node, s_.w}};
  for (const OutputField& o : dump_fields(module_fields(kDump))) f.push_back(o);
  return f;
}

std::vector<Module*> Hydro::modules() const {
  std::vector<Module*> m;
  for (const auto& p : modules_) m.push_back(p.get());
  return m;
}

std::vector<FieldSpec> Hydro::module_fields(unsigned use) const {
  std::vector<FieldSpec> f;
  for (const Module* m : modules())
    for (const FieldSpec& s : m->fields(use))
      if (s.use & use) f.push_back(s);
  return f;
}

}  // namespace mp::hydro
