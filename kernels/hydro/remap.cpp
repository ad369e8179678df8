// The remap phase: advection back to the fixed mesh. A step moves mass and internal energy
// through the faces normal to a set of axes with van Leer-limited face values, then moves
// momentum through the faces of the dual (node-centred) mesh with mass fluxes averaged from the
// cell faces, so mass and momentum are both conserved to round-off.
//   split (default): three steps of one axis each, order x,y,z / z,y,x alternating by cycle;
//   unsplit: one step over all three axes from the same Lagrangian state (symmetric under
//            permutations of the axes; stable for a Courant-number sum below one).
// Here the steps' driver (Hydro::remap_step) and the kernels it launches itself; a split sweep's
// kernels along its axis are in remap_sweep.cpp.
#include <mpi.h>

#include "core/axis.hpp"
#include "core/columns.hpp"
#include "core/error.hpp"
#include "core/math.hpp"
#include "core/profiling.hpp"
#include "hydro/hydro.hpp"
#include "hydro/point.hpp"
#include "hydro/remap_detail.hpp"

namespace mp::hydro {

namespace {

// The unsplit step's node update (remap::momentum): each node computes its own dual faces along
// the moved axes. `again`: the redo after a node was flagged (ke_redo, as the split sweep's
// remap::dual_face_redo): the faces of the nodes flagged in `flags` (a copy of the node losses,
// which this launch rewrites) with donor values.
struct UnsplitMomentum {
  Field3 u, v, w, nm, mfx, mfy, mfz, flags;
  Real ax, ay, az;
  int ord;
  bool weigh, again;
  MomentumFinish<Field3> finish;
  Kokkos::View<int, MemSpace> redo;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    const Real u0 = u(i, j, k), v0 = v(i, j, k), w0 = w(i, j, k), m0 = nm(i, j, k);
    DualUpdate du{m0, u0 * m0, v0 * m0, w0 * m0, 0};
    const bool me = again && ke_redo(flags(i, j, k));
    for (int d = 0; d < 3; ++d) {
      if (!(d == 0 ? ax > 0 : d == 1 ? ay > 0 : az > 0)) continue;
      const Field3& mf = d == 0 ? mfx : d == 1 ? mfy : mfz;
      const int sx = d == 0, sy = d == 1, sz = d == 2;
      const int li = i - sx, lj = j - sy, lk = k - sz;
      const int olo = again && (me || ke_redo(flags(li, lj, lk))) ? 1 : ord;
      const int ohi = again && (me || ke_redo(flags(i + sx, j + sy, k + sz))) ? 1 : ord;
      const DualFace lo = dual_face(mf, nm, u, v, w, li, lj, lk, d, olo, weigh);
      const DualFace hi = dual_face(mf, nm, u, v, w, i, j, k, d, ohi, weigh);
      du.add(lo.f, hi.f, lo.u, hi.u, lo.v, hi.v, lo.w, hi.w, lo.k, hi.k);
    }
    if (finish(i, j, k, m0, u0, v0, w0, du)) Kokkos::atomic_exchange(&redo(), 1);
  }
};

// A cell's new density and energy from its mass and energy gains dm, de through the step's
// faces (pre, post: its volume before and after the step). The volume before the step is read
// no more in it: the cell's internal energy takes its place, the KE fix's weight
// (ke_fix_share), and the next step recomputes it.
KOKKOS_INLINE_FUNCTION void update_cell(Real& rho, Real& e, Real& pre, Real post, Real dm,
                                        Real de) {
  const Real m0 = rho * pre;
  const Real m1 = m0 + dm;
  const Real e1 = (e * m0 + de) / m1;
  e = e1;
  rho = m1 / post;
  pre = m1 * mmax(e1, Real(0));
}

// The KE fix of cell k of a column (single-material scenes; item 6 of "One cycle"): the cell's
// density, energy and volume after the sweep as columns, and its 8 nodes' losses as the node
// columns (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1) at k and k + 1. Returns the energy
// the cell could not pay (its share below ke_fix_floor: m (floor - de), else 0), which the
// launch adds to State::ke_unpaid (Totals::ke_fix_unpaid). With the redo (ke_redo) no cell
// should reach the floor; without it (numerics.ke_fix_redo: false) a closed Noh box does.
template <class C, class K>
KOKKOS_INLINE_FUNCTION Real ke_fix_cell(const C& r, const C& en, const C& p1, const K& c00,
                                        const K& c10, const K& c01, const K& c11, int k) {
  const Real m = r[k] * p1[k];
  const Real x[8] = {c00[k],     c10[k],     c01[k],     c11[k],
                     c00[k + 1], c10[k + 1], c01[k + 1], c11[k + 1]};
  const Real de = ke_fix_share_of([&](int a, int b, int c) { return x[a + 2 * b + 4 * c]; }, m,
                                  m * mmax(en[k], Real(0)));
  const Real floor = ke_fix_floor(en[k]);
  en[k] += mmax(de, floor);
  return de < floor ? m * (floor - de) : Real(0);
}

// The KE fix over a box of owned cells as k-columns (core/columns.hpp).
struct KeFixColumns {
  Field3 rho, e, post, kel;
  Kokkos::View<double, MemSpace> unpaid;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    const auto r = column(rho, i, j), en = column(e, i, j), p1 = column(post, i, j);
    const auto c00 = column(kel, i, j), c10 = column(kel, i + 1, j), c01 = column(kel, i, j + 1),
               c11 = column(kel, i + 1, j + 1);
    Real u = 0;
#pragma omp simd reduction(+ : u)
    for (int k = k0; k < k1; ++k) u += ke_fix_cell(r, en, p1, c00, c10, c01, c11, k);
    add_unpaid(unpaid, u);
  }
};

// A split sweep's cell update along axis D, as k-columns (a functor, not an extended lambda:
// nvcc allows none inside the generic lambda with_axis calls). mf, ef: the axis's fluxes.
template <int D>
struct AxisCellUpdate {
  Field3 rho, e, pre, post, mf, ef;
  // the free-expansion rule's work at each face, which the face's donor pays on top of ef
  // (State::expansion_work; unallocated where the rule does not act)
  Field3 xw;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    constexpr int sx = D == 0, sy = D == 1, sz = D == 2;
    const auto r = column(rho, i, j), en = column(e, i, j), p0 = column(pre, i, j),
               p1 = column(post, i, j);
    const auto ml = column(mf, i, j), mh = column(mf, i + sx, j + sy), el = column(ef, i, j),
               eh = column(ef, i + sx, j + sy);
    if (xw.data() != nullptr) {
      const auto wl = column(xw, i, j), wh = column(xw, i + sx, j + sy);
#pragma GCC ivdep
      for (int k = k0; k < k1; ++k) {
        // (the cell gives through its low face where the flux there is negative)
        const Real work = (ml[k] < 0 ? wl[k] : Real(0)) + (mh[k + sz] > 0 ? wh[k + sz] : Real(0));
        update_cell(r[k], en[k], p0[k], p1[k], Real(0) + (ml[k] - mh[k + sz]),
                    (el[k] - eh[k + sz]) - work);
      }
      return;
    }
#pragma GCC ivdep
    for (int k = k0; k < k1; ++k)
      update_cell(r[k], en[k], p0[k], p1[k], Real(0) + (ml[k] - mh[k + sz]),
                  Real(0) + (el[k] - eh[k + sz]));
  }
};

}  // namespace

std::vector<Hydro::RemapStep> Hydro::remap_steps(long cycle) const {
  if (opt_.unsplit) return {RemapStep{{true, true, true}, {true, true, true}}};
  // Alternate the sweep order every cycle (x,y,z then z,y,x) to cancel the splitting bias.
  const int order[2][3] = {{0, 1, 2}, {2, 1, 0}};
  std::vector<RemapStep> steps;
  std::array<bool, 3> pending{{true, true, true}};
  for (int s = 0; s < 3; ++s) {
    const int d = order[cycle % 2][s];
    std::array<bool, 3> axes{{false, false, false}};
    axes[d] = true;
    steps.push_back({axes, pending});
    pending[d] = false;
  }
  return steps;
}

void Hydro::remap(long cycle) {
  const auto steps = remap_steps(cycle);
  for (size_t s = 0; s < steps.size(); ++s)
    remap_step(steps[s], s + 1 < steps.size() ? &steps[s + 1] : nullptr);
}

bool Hydro::ke_redo_begin() {
  if (!opt_.ke_fix_redo) return false;
  int mine = 0, any = 0;
  Kokkos::deep_copy(mine, s_.ke_redo);
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, mesh_.comm());
  if (!any) return false;
  // a face by a rank boundary is computed on both sides: the ghost nodes need their owners'
  // flags (the node losses), and those at a reflective wall their mirror images' (without it
  // the closed 24^3 Noh box on one rank lost 4.8e-7 of its energy and the 12x10x10 box with
  // the ranks along x differed in 6305 values between 1 and 4 ranks: Conservation.
  // ClosedNohBoxKeepsItsEnergy, Decomposition.ClosedNohBoxRanksAlongTheSweep...)
  halo_.exchange({{s_.ke_loss, Centering::Node, {1, 1, 1}}});
  ++ke_redone_;
  return true;
}

// (after the redo's own remap::momentum, which may raise the flag again: a node whose faces
// changed can still be flagged, and its cells then pay by the floor)
void Hydro::ke_redo_end() {
  Kokkos::deep_copy(s_.ke_redo, 0);
}

void Hydro::remap_step(const std::array<bool, 3>& axes, const std::array<bool, 3>& pending) {
  remap_step(RemapStep{axes, pending}, nullptr);
}

void Hydro::remap_step(const RemapStep& step, const RemapStep* next) {
  const auto& axes = step.axes;
  ProfileRegion region(axes[0] && axes[1] && axes[2] ? "remap::unsplit"
                       : axes[0]                     ? "remap::sweep_x"
                       : axes[1]                     ? "remap::sweep_y"
                                                     : "remap::sweep_z");
  const Geometry g = mesh_.geometry();
  const Real vol = g.cell_volume();
  const int ord = opt_.order;
  auto rho = s_.rho, e = s_.e, pre = s_.pre_vol, post = s_.post_vol;
  auto fx = s_.vol_flux[0], fy = s_.vol_flux[1], fz = s_.vol_flux[2];
  auto mfx = s_.mass_flux[0], mfy = s_.mass_flux[1], mfz = s_.mass_flux[2];
  auto efx = s_.energy_flux[0], efy = s_.energy_flux[1], efz = s_.energy_flux[2];
  auto nm = s_.node_mass;
  const int ex = mesh_.extent(Centering::Cell, 0), ey = mesh_.extent(Centering::Cell, 1),
            ez = mesh_.extent(Centering::Cell, 2);
  const StepWeights sw = step.weights();
  const Real ax = sw.ax, ay = sw.ay, az = sw.az;
  const bool one_axis = int(ax + ay + az) == 1;  // a split sweep (else the unsplit step)

  // Cell volume before this step (the Lagrangian volume less the steps already done) and
  // after it; written ahead by the launch before when it could (the corrector for a cycle's
  // first step, the last step's KE fix for the next one: tests/test_launches.cpp).
  // (Fused with the node masses below, each node recomputing its eight cells' volumes, this
  // took 3.4x the two launches' time: 11.2 against 3.3 ms per cycle at 64^3, 2 threads; the
  // launch saved is worth microseconds. Kept apart, as are the cell update and dual faces.)
  // (k-columns, core/columns.hpp)
  if (!(volumes_ready_ && volumes_for_ == step)) {
    const int lo[3] = {0, 0, 0}, hi[3] = {ex, ey, ez};
    for_columns(
        "remap::volumes", lo, hi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
          const auto a = local(fx), b = local(fy), c = local(fz), p0 = local(pre), p1 = local(post);
#pragma GCC ivdep
          for (int k = k0; k < k1; ++k) stored_step_volumes(a, b, c, i, j, k, vol, sw, p0, p1);
        });
  }
  volumes_ready_ = false;

  // Dual-cell (node) mass before the step.
  // (k-columns: the node's 8 cells are the columns (i - 1, j - 1), (i, j - 1), (i - 1, j),
  // (i, j) at k - 1 and k, summed in the order a, b, c)
  {
    const int lo[3] = {1, 1, 1}, hi[3] = {ex, ey, ez};
    for_columns(
        "remap::node_mass", lo, hi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
          const auto r00 = column(rho, i - 1, j - 1), r10 = column(rho, i, j - 1),
                     r01 = column(rho, i - 1, j), r11 = column(rho, i, j);
          const auto v00 = column(pre, i - 1, j - 1), v10 = column(pre, i, j - 1),
                     v01 = column(pre, i - 1, j), v11 = column(pre, i, j);
          const auto out = column(nm, i, j);
#pragma GCC ivdep
          for (int k = k0; k < k1; ++k) {
            Real m = 0;
            for (int c = 0; c < 2; ++c) {
              const int kc = k - 1 + c;
              m += r00[kc] * v00[kc];
              m += r10[kc] * v10[kc];
              m += r01[kc] * v01[kc];
              m += r11[kc] * v11[kc];
            }
            out[k] = Real(0.125) * m;
          }
        });
  }

  // Mass and energy through the owned faces normal to each axis of the step (all rows across),
  // then the ghost faces from the neighbours.
  for (int d = 0; d < 3; ++d) {
    if (!axes[d]) continue;
    auto vf = s_.vol_flux[d];
    auto mf = s_.mass_flux[d], ef = s_.energy_flux[d];
    const auto fr = mesh_.range(Centering::Node, Region::Owned, d);
    int lo[3] = {0, 0, 0}, hi[3] = {ex, ey, ez};
    lo[d] = fr[0];
    hi[d] = fr[1];
    // (the unsplit step keeps each axis's free-expansion work apart: one cell update pays all)
    const Field3 xw = one_axis ? s_.expansion_work : s_.expansion_work_axis[d];
    if (mm_)
      mm_remap_faces(d);
    else
      with_axis(d, [&](auto a) {
        cell_flux_sweep<decltype(a)::value>(
            lo, hi, vf, pre, rho, e, mf, ef, ord, xw, expansion_gm1_, opt_.free_expansion,
            reflective_face(d, 0), reflective_face(d, 1), s_.expansion_any);
      });
    ledger_sweep(d);
    HaloField mfh{mf, Centering::Cell, {1, 1, 1}};
    HaloField efh{ef, Centering::Cell, {1, 1, 1}};
    mfh.face_axis = efh.face_axis = d;
    mfh.parity[d] = efh.parity[d] = -1;  // a flux normal to a wall changes sign in the mirror
    // (the free-expansion work is exchanged, paid and given to the nodes only in sweeps where
    // some rank's faces did any: none in most sweeps of most scenes; the unsplit step decides
    // once its three axes' faces are done, below)
    expanded_ = one_axis && expansion_gm1_ > 0 && expansion_worked();
    if (expanded_) {
      // (an amount, not a flux: its mirror keeps the sign, and the mirrored flux its donor)
      HaloField xwh{s_.expansion_work, Centering::Cell, {1, 1, 1}};
      xwh.face_axis = d;
      halo_.exchange({mfh, efh, xwh});
    } else {
      halo_.exchange({mfh, efh});
    }
  }
  if (!one_axis && expansion_gm1_ > 0) {
    expanded_ = expansion_worked();
    if (expanded_)
      for (int d = 0; d < 3; ++d) {
        HaloField xwh{s_.expansion_work_axis[d], Centering::Cell, {1, 1, 1}};
        xwh.face_axis = d;
        halo_.exchange({xwh});
      }
  }

  // Cells: new mass and energy; one ghost layer is updated too, for the dual-mesh masses.
  // (Multi-material: owned cells, then the material exchange; the scene reader keeps
  // multi-material runs on split sweeps, one axis per step.)
  // the strength module's quantities ride on the same mass fluxes (before rho changes)
  // (a multi-material scene's on its carriers' mass fluxes and densities)
  if (mm_ && !modules_.empty()) mm_carriers();
  for (std::size_t i = 0; i < modules_.size(); ++i)
    modules_[i]->remap(carriers_of(i), axes, pre, ord);
  // (the unsplit step's free-expansion work, where its faces did any: each face's donor pays
  // it on top of ef, as AxisCellUpdate)
  const bool pay = !one_axis && expanded_;
  const auto xwx = s_.expansion_work_axis[0], xwy = s_.expansion_work_axis[1],
             xwz = s_.expansion_work_axis[2];
  auto cell_update = [=] KOKKOS_FUNCTION(int i, int j, int k) {
    Real dm = 0, de = 0;
    if (ax > 0) {
      dm += mfx(i, j, k) - mfx(i + 1, j, k);
      de += efx(i, j, k) - efx(i + 1, j, k);
      if (pay)
        de -= (mfx(i, j, k) < 0 ? xwx(i, j, k) : Real(0)) +
              (mfx(i + 1, j, k) > 0 ? xwx(i + 1, j, k) : Real(0));
    }
    if (ay > 0) {
      dm += mfy(i, j, k) - mfy(i, j + 1, k);
      de += efy(i, j, k) - efy(i, j + 1, k);
      if (pay)
        de -= (mfy(i, j, k) < 0 ? xwy(i, j, k) : Real(0)) +
              (mfy(i, j + 1, k) > 0 ? xwy(i, j + 1, k) : Real(0));
    }
    if (az > 0) {
      dm += mfz(i, j, k) - mfz(i, j, k + 1);
      de += efz(i, j, k) - efz(i, j, k + 1);
      if (pay)
        de -= (mfz(i, j, k) < 0 ? xwz(i, j, k) : Real(0)) +
              (mfz(i, j, k + 1) > 0 ? xwz(i, j, k + 1) : Real(0));
    }
    update_cell(rho(i, j, k), e(i, j, k), pre(i, j, k), post(i, j, k), dm, de);
  };
  if (mm_) {
    for (int d = 0; d < 3; ++d)
      if (axes[d]) mm_remap_cells(d);
    // what the modules keep in the pool: from the pool before the update into the pool after
    // it (the strength module's pooled stress sets)
    for (std::size_t i = 0; i < modules_.size(); ++i)
      modules_[i]->remap_materials(carriers_of(i), axes, pre, ord);
    if (!modules_.empty()) mm_clear_absent();
  } else {
    // (one axis, its flux faces' offsets constants: a column loop GCC vectorizes; the same
    // update_cell as the unsplit step's, bit for bit: 0 + x is x for the one axis's terms)
    const int lo[3] = {Mesh::ng - 1, Mesh::ng - 1, Mesh::ng - 1};
    const int hi[3] = {Mesh::ng + mesh_.owned_cells(0) + 1, Mesh::ng + mesh_.owned_cells(1) + 1,
                       Mesh::ng + mesh_.owned_cells(2) + 1};
    if (int(ax + ay + az) == 1) {
      with_axis(ax > 0   ? 0
                : ay > 0 ? 1
                         : 2,
                [&](auto a) {
                  constexpr int D = decltype(a)::value;
                  const Field3 mf = D == 0 ? mfx : D == 1 ? mfy : mfz;
                  const Field3 ef = D == 0 ? efx : D == 1 ? efy : efz;
                  for_columns("remap::cell_update", lo, hi,
                              AxisCellUpdate<D>{rho, e, pre, post, mf, ef,
                                                expanded_ ? s_.expansion_work : Field3()});
                });
    } else {
      Kokkos::parallel_for(
          "remap::cell_update", mesh_.cells_padded(1),
          KOKKOS_LAMBDA(int i, int j, int k) { cell_update(i, j, k); });
    }
  }

  // Momentum through the dual faces normal to each moved axis. A split sweep (one axis) first
  // computes every dual face's mass flux and upwind velocities once ("remap::dual_face"), then
  // updates the nodes from their two faces; the unsplit step does both per node. Both run the
  // same point functions in the same order, so the fields do not depend on the path.
  auto u = s_.u, v = s_.v, w = s_.w, un = s_.ub, vn = s_.vb, wn = s_.wb, kel = s_.ke_loss;
  // The KE fix's budget in a single-material scene (docs/numerics.md, "One cycle", item 6): an
  // expanding face carries no slope spread (ke_carried), and a node that made kinetic energy
  // charges its cells by their internal energy (ke_fix_share). Not yet in multi-material
  // scenes: their sweep brings the ghost cells' averages up to date only in the exchange after
  // it, so a node by a rank boundary would weigh stale ghosts (1/2/4 ranks would differ); they
  // keep the full form and the equal shares.
  const bool weigh = opt_.ke_fix && !mm_;
  // Multi-material scenes share a node's loss among its 8 cells by their mass (the default,
  // numerics.ke_fix_share: mass; else an eighth each, kel holding the loss): kel holds the
  // loss per unit mass of the node's cells, L / (8 m_node), and every cell around the node takes
  // that specific energy (mm_ke_fix), so a light cell beside heavy moving ones (air at a copper
  // jet) is not handed an eighth of the heavy nodes' loss. The 8 cells' masses sum to 8 m_node
  // to round-off (the dual-face fluxes are the cells' own), so total energy is kept.
  const bool by_mass = opt_.ke_fix && mm_ && opt_.ke_fix_by_mass;
  const MomentumFinish<Field3> finish{un, vn, wn, kel, pre, by_mass, weigh};
  if (int(ax + ay + az) == 1) {
    const int d = ax > 0 ? 0 : ay > 0 ? 1 : 2;
    const Field3 mf = d == 0 ? mfx : d == 1 ? mfy : mfz;
    auto F = s_.dual_flux, U = s_.dual_u, V = s_.dual_v, W = s_.dual_w, K = s_.dual_k;
    // the faces between nodes c and c + 1 along d: both faces of every owned node
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const auto r = mesh_.range(Centering::Node, Region::Owned, a);
      lo[a] = r[0] - (a == d);
      hi[a] = r[1];
    }
    int nlo[3], nhi[3];  // the owned nodes
    mesh_.box(Centering::Node, Region::Owned, nlo, nhi);
    // (one launch with the cell update took 10.5 against 8.3 ms per cycle for the two at
    // 64^3, 2 threads: the branch per point costs more than the launch)
    const auto redo = s_.ke_redo;
    with_axis(d, [&](auto a) {
      constexpr int D = decltype(a)::value;
      dual_face_sweep<D>(lo, hi, mf, nm, u, v, w, F, U, V, W, K, ord, weigh);
      momentum_nodes<D>(nlo, nhi, nm, u, v, w, F, U, V, W, K, finish, redo);
    });
    // Where a node made more kinetic energy than kKeRedo of its cells' internal energy (cold,
    // fast gas draining towards vacuum: the KE fix's floor would bind), the faces of such nodes
    // are redone with donor values, which make none, and the nodes updated again (docs/
    // numerics.md, "One cycle", item 6). Nothing is launched where no node is flagged: every
    // shipped deck.
    if (weigh && ke_redo_begin()) {
      with_axis(d, [&](auto a) {
        constexpr int D = decltype(a)::value;
        dual_face_redo<D>(lo, hi, mf, nm, u, v, w, kel, F, U, V, W, K);
        momentum_nodes<D>(nlo, nhi, nm, u, v, w, F, U, V, W, K, finish, redo);
      });
      ke_redo_end();
    }
    if (expanded_) expansion_impulse(d);
  } else {
    // The unsplit step computes each node's faces itself; the redo (as in the split sweep
    // above) runs the launch again with donor values on the faces of the flagged nodes, whose
    // flags it reads from a copy of the node losses (`flags`: the launch rewrites kel).
    const auto redo = s_.ke_redo;
    UnsplitMomentum op{u,  v,  w,  nm,  mfx,   mfy,   mfz,    kel,
                       ax, ay, az, ord, weigh, false, finish, redo};
    Kokkos::parallel_for("remap::momentum", mesh_.nodes(Region::Owned), op);
    if (weigh && ke_redo_begin()) {
      const Field3 flags = s_.dual_k;  // (scratch: the split sweep's, unused here)
      Kokkos::deep_copy(flags, kel);
      op.flags = flags;
      op.again = true;
      Kokkos::parallel_for("remap::momentum_redo", mesh_.nodes(Region::Owned), op);
      ke_redo_end();
    }
    // each axis's work to its node pairs along it (each impulse changes that axis's velocity
    // component only)
    if (expanded_)
      for (int d = 0; d < 3; ++d) expansion_impulse(d, s_.expansion_work_axis[d]);
  }
  if (opt_.ke_fix && mm_) {
    mm_ke_fix(next);
  } else if (opt_.ke_fix) {
    // Owned cells read owned nodes only.
    // a column's cells (k-columns, core/columns.hpp): each cell's 8 nodes are the columns
    // (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1) at k and k + 1
    const auto unpaid = s_.ke_unpaid;
    const KeFixColumns fix{rho, e, post, kel, unpaid};
    if (next) {
      // Every cell, ghosts included, then gets the next step's volumes (from the volume fluxes
      // alone) in the same launch. The ghost cells take a fix too (finite: a ghost node's loss
      // is never written, 0), which the cell exchange that ends the step overwrites: without a
      // branch to the owned cells the launch took 2.7 ms per cycle at 64^3 (2 threads), with
      // one 3.4 (a masked store, 2.9); as k-columns, 1.2.
      const StepWeights nw = next->weights();
      int lo[3], hi[3], olo[3], ohi[3];
      mesh_.box(Centering::Cell, Region::All, lo, hi);
      mesh_.box(Centering::Cell, Region::Owned, olo, ohi);
      const int oi0 = olo[0], oi1 = ohi[0], oj0 = olo[1], oj1 = ohi[1], ok0 = olo[2], ok1 = ohi[2];
      for_columns(
          "remap::ke_fix", lo, hi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
            const auto r = column(rho, i, j), en = column(e, i, j), p0 = column(pre, i, j),
                       p1 = column(post, i, j);
            const auto c00 = column(kel, i, j), c10 = column(kel, i + 1, j),
                       c01 = column(kel, i, j + 1), c11 = column(kel, i + 1, j + 1);
            const auto xl = column(fx, i, j), xh = column(fx, i + 1, j), yl = column(fy, i, j),
                       yh = column(fy, i, j + 1), zc = column(fz, i, j);
            // the unpaid energy of the owned cells only (a ghost's is its owner's)
            Real owed = 0;
#pragma omp simd reduction(+ : owed)
            for (int k = k0; k < k1; ++k) {
              const Real left = ke_fix_cell(r, en, p1, c00, c10, c01, c11, k);
              owed += k >= ok0 && k < ok1 ? left : Real(0);
              step_volumes(vol, xh[k] - xl[k], yh[k] - yl[k], zc[k + 1] - zc[k], nw, p0[k], p1[k]);
            }
            if (i >= oi0 && i < oi1 && j >= oj0 && j < oj1) add_unpaid(unpaid, owed);
          });
      volumes_ready_ = true;
      volumes_for_ = *next;
    } else {
      int lo[3], hi[3];
      mesh_.box(Centering::Cell, Region::Owned, lo, hi);
      for_columns("remap::ke_fix", lo, hi, fix);
    }
  }
  std::swap(s_.u, s_.ub);
  std::swap(s_.v, s_.vb);
  std::swap(s_.w, s_.wb);
  exchange_cells();
  exchange_nodes(s_.u, s_.v, s_.w);
}

}  // namespace mp::hydro
