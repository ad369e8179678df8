// A split remap sweep's kernels along one axis D: mass and energy through the cell faces, the
// dual faces and the nodes' momentum from them (and the KE fix's redo), the free-expansion impulse.
#include <mpi.h>

#include <type_traits>

#include "core/axis.hpp"
#include "core/columns.hpp"
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/point.hpp"
#include "hydro/remap_detail.hpp"

namespace mp::hydro {

namespace {

// The kernels of a split sweep are instantiated per axis D, so that the neighbour offsets along
// the sweep are compile-time constants (the same point functions as the unsplit step, so the
// same bits).

// Mass and energy through the owned faces normal to D (single-material scenes). With Expand (the
// free-expansion rule acts: gm1 > 0, xw allocated), ef holds what the receiver takes and xw the
// rest of what the donor pays (expansion_share), and any_work is raised where a face did work.
// Ord, the advection order, is a template argument (as DualFaceColumns'): face_value's branches
// on it are then resolved at compile time, and a third order costs the default nothing (Ord 0:
// `ord` read at run time, the unlimited orders of Hydro::set_unlimited).
template <int D, bool Expand, int Ord>
void cell_flux_columns(const int lo[3], const int hi[3], const Field3& vf, const Field3& pre,
                       const Field3& rho, const Field3& e, const Field3& mf, const Field3& ef,
                       int ord, const Field3& xw, Real gm1, Real ratio, int wall_lo, int wall_hi,
                       const Kokkos::View<int, MemSpace>& any_work) {
  const int o = Ord != 0 ? Ord : ord;
  constexpr int sx = D == 0, sy = D == 1, sz = D == 2;
  // (k-columns, core/columns.hpp; the four cells along D around the face are loaded whatever
  // the wind, and the donor's stencil selected from them: fixed offsets, as dual_face_value)
  for_columns(
      "remap::cell_flux", lo, hi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
        // (captured here: nvcc allows an extended lambda no first capture in an if constexpr)
        (void)gm1, (void)ratio, (void)wall_lo, (void)wall_hi, (void)any_work, (void)o, (void)sx,
            (void)sy, (void)sz;
        const auto vfa = local(vf), pa = local(pre), ra = local(rho), ea = local(e);
        const auto mfa = local(mf), efa = local(ef), xwa = local(xw);
        if constexpr (!Expand) {
#pragma GCC ivdep
          for (int k = k0; k < k1; ++k) {
            const Real f = vfa(i, j, k);
            auto at = [&](const auto& a, int s) { return a(i + s * sx, j + s * sy, k + s * sz); };
            Real m, en;
            column_face_flux(f, at, ra, ea, pa, o, m, en);
            mfa(i, j, k) = m;
            efa(i, j, k) = en;
          }
        } else {
          // Chunks of the column: every face's fluxes and whether the rule acts there in one
          // vector loop, which stores the fluxes of a face where it does not (share 1: ef the
          // whole energy flux, xw |en| - |en| = 0); then the faces where it acts, one by one
          // (their power of the density ratio, expansion_share's, is no vector operation):
          // the same values as expansion_share per face, bit for bit. (The rule acts at a few
          // faces by a contact: a scalar loop over every face took 11 % of bm_short's cycle.)
          constexpr int kChunk = kWholeColumns ? 16 : 1;
          int any = 0;
          for (int kb = k0; kb < k1; kb += kChunk) {
            const int n = kb + kChunk < k1 ? kChunk : k1 - kb;
            // (every lane value a Real, the plane indices too: GCC 12 left the loop scalar where
            // it mixed int lanes with the doubles')
            Real base[kChunk], energy[kChunk], acts[kChunk];
            int some = 0;
#pragma GCC ivdep
            for (int l = 0; l < n; ++l) {
              const int k = kb + l;
              const Real f = vfa(i, j, k);
              auto at = [&](const auto& a, int s) { return a(i + s * sx, j + s * sy, k + s * sz); };
              Real m, en;
              column_face_flux(f, at, ra, ea, pa, o, m, en);
              mfa(i, j, k) = m;
              // the receiver: cell 0 when f > 0, else -1
              const Real vr = f > 0 ? at(pa, 0) : at(pa, -1);
              const Real rr = f > 0 ? at(ra, 0) : at(ra, -1);
              // (not where the node plane behind the face, whose nodes the work pushes back, is
              // a reflective wall: they cannot move)
              const Real c = Real(D == 0 ? i : D == 1 ? j : k);
              const Real behind = f > 0 ? c - 1 : c + 1;
              // a receiver compressed along the axis (its far face moving on slower than the
              // near one) may be a shock's: there only a density ratio no shock makes, beyond
              // (gamma - 1) / (gamma + 1), counts as free expansion
              const Real vfar = f > 0 ? at(vfa, 1) : at(vfa, -1);
              // (squeezed: vfar < f where f > 0, else vfar > f; as the sign of a difference of
              // finite values, which is exact: a select between two tests left the loop scalar)
              const Real closing = f > 0 ? f - vfar : vfar - f;
              const Real limit = closing > 0 ? gm1 / (gm1 + 2) : ratio;
              // (0 where behind is a wall's plane: the distance to the nearer one, exact)
              const Real wall = mmin(mabs(behind - Real(wall_lo)), mabs(behind - Real(wall_hi)));
              Real b;
              const Real a = expansion_acts(m, f, rr * vr, vr, limit, b);
              base[l] = b;
              energy[l] = en;
              acts[l] = wall != 0 ? a : Real(0);
              efa(i, j, k) = en * Real(1);
              xwa(i, j, k) = mabs(en) - mabs(en * Real(1));
            }
            // (apart: an int reduction in the loop above kept GCC 12 from vectorizing it)
            for (int l = 0; l < n; ++l) some |= acts[l] != 0 ? 1 : 0;
            if (!some) continue;
            for (int l = 0; l < n; ++l) {
              if (acts[l] == 0) continue;
              const int k = kb + l;
              const Real en = energy[l];
              const Real share = expansion_power(base[l], gm1);
              efa(i, j, k) = en * share;
              xwa(i, j, k) = mabs(en) - mabs(en * share);
              any |= int(share < 1);
            }
          }
          if (any) Kokkos::atomic_exchange(&any_work(), 1);
        }
      });
}

}  // namespace

template <int D>
void cell_flux_sweep(const int lo[3], const int hi[3], const Field3& vf, const Field3& pre,
                     const Field3& rho, const Field3& e, const Field3& mf, const Field3& ef,
                     int ord, const Field3& xw, Real gm1, Real ratio, int wall_lo, int wall_hi,
                     const Kokkos::View<int, MemSpace>& any_work) {
  auto with_order = [&](auto o) {
    constexpr int Ord = decltype(o)::value;
    if (gm1 > 0)
      cell_flux_columns<D, true, Ord>(lo, hi, vf, pre, rho, e, mf, ef, ord, xw, gm1, ratio, wall_lo,
                                      wall_hi, any_work);
    else
      cell_flux_columns<D, false, Ord>(lo, hi, vf, pre, rho, e, mf, ef, ord, ef, gm1, ratio,
                                       wall_lo, wall_hi, any_work);
  };
  if (ord == 1)
    with_order(std::integral_constant<int, 1>{});
  else if (ord == 3)
    with_order(std::integral_constant<int, 3>{});
  else if (ord == 2)
    with_order(std::integral_constant<int, 2>{});
  else
    with_order(std::integral_constant<int, 0>{});
}

namespace {

// The dual faces (i, j, k0 .. k1 - 1) of a column, normal to D, into F, U, V, W, K. Ord and
// Weigh (the advection order and the KE fix's weighing) are template arguments: as loop-invariant
// values they were selects GCC does not vectorize.
template <int D, class A>
struct DualFaceColumns {
  A mf, nm, u, v, w, F, U, V, W, K;
  // (Ord 0: `ord` read at run time, the unlimited orders of Hydro::set_unlimited)
  template <int Ord, bool Weigh>
  KOKKOS_INLINE_FUNCTION void run(int i, int j, int k0, int k1, int ord = 0) const {
    const int o = Ord != 0 ? Ord : ord;
#pragma GCC ivdep
    for (int k = k0; k < k1; ++k) {
      const DualFace df = dual_face(mf, nm, u, v, w, i, j, k, D, o, Weigh);
      F(i, j, k) = df.f;
      U(i, j, k) = df.u;
      V(i, j, k) = df.v;
      W(i, j, k) = df.w;
      K(i, j, k) = df.k;
    }
  }
};

// The launch of one order and weighing (a function template, not a generic lambda around the
// kernel: nvcc allows no extended lambda inside one).
template <int D, int Ord, bool Weigh>
void dual_face_launch(const int lo[3], const int hi[3], const Field3& mf, const Field3& nm,
                      const Field3& u, const Field3& v, const Field3& w, const Field3& F,
                      const Field3& U, const Field3& V, const Field3& W, const Field3& K, int ord) {
  // (k-columns, core/columns.hpp)
  for_columns(
      "remap::dual_face", lo, hi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
        const auto mfa = local(mf);
        const DualFaceColumns<D, decltype(mfa)> c{mfa,      local(nm), local(u), local(v),
                                                  local(w), local(F),  local(U), local(V),
                                                  local(W), local(K)};
        c.template run<Ord, Weigh>(i, j, k0, k1, ord);
      });
}

}  // namespace

template <int D>
void dual_face_sweep(const int lo[3], const int hi[3], const Field3& mf, const Field3& nm,
                     const Field3& u, const Field3& v, const Field3& w, const Field3& F,
                     const Field3& U, const Field3& V, const Field3& W, const Field3& K, int ord,
                     bool weigh) {
  // (one launch per order and weighing, chosen here: the choice per column inside the kernel,
  // over four orders, took 6 % more instructions, callgrind)
  auto with_weigh = [&](auto o) {
    constexpr int Ord = decltype(o)::value;
    if (weigh)
      dual_face_launch<D, Ord, true>(lo, hi, mf, nm, u, v, w, F, U, V, W, K, ord);
    else
      dual_face_launch<D, Ord, false>(lo, hi, mf, nm, u, v, w, F, U, V, W, K, ord);
  };
  if (ord == 1)
    with_weigh(std::integral_constant<int, 1>{});
  else if (ord == 3)
    with_weigh(std::integral_constant<int, 3>{});
  else if (ord == 2)
    with_weigh(std::integral_constant<int, 2>{});
  else
    with_weigh(std::integral_constant<int, 0>{});
}

// The owned nodes from their two dual faces normal to D ("remap::momentum"; `finish` stores the
// new velocities and the node's kinetic-energy discrepancy, and raises `redo` where a node made
// more kinetic energy than its cells can safely pay, MomentumFinish).
template <int D>
void momentum_nodes(const int nlo[3], const int nhi[3], const Field3& nm, const Field3& u,
                    const Field3& v, const Field3& w, const Field3& F, const Field3& U,
                    const Field3& V, const Field3& W, const Field3& K,
                    const MomentumFinish<Field3>& finish, const Kokkos::View<int, MemSpace>& redo) {
  constexpr int sx = D == 0, sy = D == 1, sz = D == 2;
  for_columns(
      "remap::momentum", nlo, nhi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
        const auto ua = local(u), va = local(v), wa = local(w), nma = local(nm);
        const auto Fa = local(F), Ua = local(U), Va = local(V), Wa = local(W), Ka = local(K);
        const auto fin = finish.at(ua);
        // the finish's options as template arguments (loop-invariant selects stay scalar)
        auto run = [&](auto by_mass, auto weighs) {
          int any = 0;
#pragma omp simd reduction(| : any)
          for (int k = k0; k < k1; ++k) {
            const Real u0 = ua(i, j, k), v0 = va(i, j, k), w0 = wa(i, j, k), m0 = nma(i, j, k);
            DualUpdate du{m0, u0 * m0, v0 * m0, w0 * m0, 0};
            const int li = i - sx, lj = j - sy, lk = k - sz;
            du.add(Fa(li, lj, lk), Fa(i, j, k), Ua(li, lj, lk), Ua(i, j, k), Va(li, lj, lk),
                   Va(i, j, k), Wa(li, lj, lk), Wa(i, j, k), Ka(li, lj, lk), Ka(i, j, k));
            any |= int(fin.template apply<decltype(by_mass)::value, decltype(weighs)::value>(
                i, j, k, m0, u0, v0, w0, du));
          }
          if (any) Kokkos::atomic_exchange(&redo(), 1);
        };
        if (finish.by_mass)
          run(std::true_type{}, std::false_type{});
        else if (finish.weigh)
          run(std::false_type{}, std::true_type{});
        else
          run(std::false_type{}, std::false_type{});
      });
}

// The dual faces normal to D (box lo/hi, as dual_face_sweep) of which a node is flagged by
// ke_redo (its kel after remap::momentum, ghosts exchanged), again with donor values: order 1.
template <int D>
void dual_face_redo(const int lo[3], const int hi[3], const Field3& mf, const Field3& nm,
                    const Field3& u, const Field3& v, const Field3& w, const Field3& kel,
                    const Field3& F, const Field3& U, const Field3& V, const Field3& W,
                    const Field3& K) {
  constexpr int sx = D == 0, sy = D == 1, sz = D == 2;
  Kokkos::parallel_for(
      "remap::dual_face_redo", Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}),
      KOKKOS_LAMBDA(int i, int j, int k) {
        if (!(ke_redo(kel(i, j, k)) || ke_redo(kel(i + sx, j + sy, k + sz)))) return;
        const DualFace df = dual_face(mf, nm, u, v, w, i, j, k, D, 1, true);
        F(i, j, k) = df.f;
        U(i, j, k) = df.u;
        V(i, j, k) = df.v;
        W(i, j, k) = df.w;
        K(i, j, k) = df.k;
      });
}

// The launchers for the three axes (declared in remap_detail.hpp).
#define MP_REMAP_SWEEP_AXIS(D)                                                                 \
  template void cell_flux_sweep<D>(const int[3], const int[3], const Field3&, const Field3&,   \
                                   const Field3&, const Field3&, const Field3&, const Field3&, \
                                   int, const Field3&, Real, Real, int, int,                   \
                                   const Kokkos::View<int, MemSpace>&);                        \
  template void dual_face_sweep<D>(const int[3], const int[3], const Field3&, const Field3&,   \
                                   const Field3&, const Field3&, const Field3&, const Field3&, \
                                   const Field3&, const Field3&, const Field3&, const Field3&, \
                                   int, bool);                                                 \
  template void momentum_nodes<D>(                                                             \
      const int[3], const int[3], const Field3&, const Field3&, const Field3&, const Field3&,  \
      const Field3&, const Field3&, const Field3&, const Field3&, const Field3&,               \
      const MomentumFinish<Field3>&, const Kokkos::View<int, MemSpace>&);                      \
  template void dual_face_redo<D>(const int[3], const int[3], const Field3&, const Field3&,    \
                                  const Field3&, const Field3&, const Field3&, const Field3&,  \
                                  const Field3&, const Field3&, const Field3&, const Field3&,  \
                                  const Field3&);
MP_REMAP_SWEEP_AXIS(0)
MP_REMAP_SWEEP_AXIS(1)
MP_REMAP_SWEEP_AXIS(2)
#undef MP_REMAP_SWEEP_AXIS

// The free-expansion rule's second half (split sweeps, before the KE fix; docs/numerics.md
// "Free expansion to the nodes"): the work W of a face at node plane p with flow direction s
// (State::expansion_work) pushes apart the node pair (p - s, p), the node behind the face and
// the one on it, a quarter of W for each of the face's four node columns. A node so has at most
// two pairs along d, (n - 1, n) and (n, n + 1), each with the summed work w of its faces, and
// takes equal and opposite impulses +-P, P chosen so that the pair's kinetic energy grows by w
// (Delta its separation speed, mu its reduced mass):
//   P Delta + P^2 / (2 mu) = w,
// from the velocities and node masses before the sweep (ghosts included, so every rank finds
// the same P). Momentum is kept exactly; the node's kinetic energy then changes by J u + J^2 /
// (2 m) with its impulses' sum J on its remapped velocity and mass, and the difference from what
// its pairs meant it to take joins its loss for the KE fix (kel, as MomentumFinish stores it),
// so total energy is kept to round-off. (Its two impulses have opposite signs: the overlap is a
// gain for the cells, not a charge on cold ones.)
namespace {
KOKKOS_INLINE_FUNCTION Real pair_impulse(Real w, Real delta, Real mu) {
  const Real root = msqrt(delta * delta + 2 * w / mu);
  return delta >= 0 ? 2 * w / (delta + root) : mu * (root - delta);
}
}  // namespace

// The local index along d of the face on the rank's reflective wall at side s (0 low, 1 high),
// or a value no face has.
int Hydro::reflective_face(int d, int s) const {
  if (!mesh_.physical_boundary(d, s) || mesh_.boundary(d, s) != BoundaryKind::Reflective)
    return -1000000;
  return s == 0 ? Mesh::ng : Mesh::ng + mesh_.owned_cells(d);
}

// Whether any face of any rank did free-expansion work in this sweep (State::expansion_any, set
// by the face-flux kernel; cleared here for the next sweep).
bool Hydro::expansion_worked() {
  int mine = 0, any = 0;
  Kokkos::deep_copy(mine, s_.expansion_any);
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, mesh_.comm());
  // (cleared by expansion_impulse, which runs wherever a flag was set: no fill launch here)
  return any != 0;
}

namespace {

// The impulse along D as k-columns (core/columns.hpp): a node none of whose 12 faces did work
// (most nodes of a sweep that did any: the work sits at an expanding contact) is passed over by
// a vector test of the faces' work first (the same nodes the per-node test below returns at,
// so the same bits; the kernel took 12 % of bm_short's cycle testing every node one by one,
// docs/studies/2026-12-07-bm-short-profile.md).
template <int D>
void impulse_columns(const Field3& rho, const Field3& pre, const Field3& post, const Field3& nm,
                     const Field3& xw, const Field3& mf, const Field3& kel, const Field3& u0,
                     const Field3& u1, const Kokkos::View<int, MemSpace>& flag, const int olo[3],
                     const int ohi[3]) {
  constexpr int d = D;
  constexpr int sx = d == 0, sy = d == 1, sz = d == 2;
  // the two axes across d
  constexpr int t1 = d == 0 ? 1 : 0, t2 = d == 2 ? 1 : 2;
  const int i0 = olo[0], j0 = olo[1], kz0 = olo[2];
  auto node = KOKKOS_LAMBDA(int i, int j, int k) {
    // the work of the node's two pairs along d: (n - 1, n) below, (n, n + 1) above; a face
    // at plane p with flow s (+-1) pushes apart its nodes p - s (behind) and p (on it)
    Real w_lo = 0, w_hi = 0;
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a)
        for (int p = -1; p <= 1; ++p) {
          int o[3] = {i + p * sx, j + p * sy, k + p * sz};
          o[t1] -= a;
          o[t2] -= b;
          const Real work = Real(0.25) * xw(o[0], o[1], o[2]);
          const bool pos = mf(o[0], o[1], o[2]) > 0;
          // plane n: the pair below if the flow is +, above if -; plane n - 1 (flow -): below;
          // plane n + 1 (flow +): above
          if (p == 0) (pos ? w_lo : w_hi) += work;
          if (p == -1 && !pos) w_lo += work;
          if (p == 1 && pos) w_hi += work;
        }
    if (!(w_lo > 0) && !(w_hi > 0)) return;
    const Real un = u0(i, j, k), mn = nm(i, j, k);
    Real J = 0, meant = 0;
    if (w_lo > 0) {
      const Real ul = u0(i - sx, j - sy, k - sz), ml = nm(i - sx, j - sy, k - sz);
      const Real P = pair_impulse(w_lo, un - ul, ml * mn / (ml + mn));
      J += P;
      meant += P * un + P * P / (2 * mn);
    }
    if (w_hi > 0) {
      const Real uh = u0(i + sx, j + sy, k + sz), mh = nm(i + sx, j + sy, k + sz);
      const Real P = pair_impulse(w_hi, uh - un, mh * mn / (mh + mn));
      J -= P;
      meant += -P * un + P * P / (2 * mn);
    }
    // the node's remapped mass (an eighth of its 8 cells' after the sweep: the totals' mass)
    const Real m =
        Real(0.125) *
        corner_sum([&](int ci, int cj, int ck) { return rho(ci, cj, ck) * post(ci, cj, ck); },
                   i - 1, j - 1, k - 1);
    const Real v = u1(i, j, k);
    const Real dv = J / m;
    u1(i, j, k) = v + dv;
    // energy meant for the node that it did not take: to its cells (as a loss)
    const Real left = meant - (m * v * dv + Real(0.5) * m * dv * dv);
    // kel as MomentumFinish stores it: the loss L >= 0, or L over the cells' content
    const Real content = corner_sum(pre, i - 1, j - 1, k - 1);
    kel(i, j, k) = ke_stored(ke_unstored(kel(i, j, k), content) + left, content);
  };
  for_columns(
      "remap::expansion_impulse", olo, ohi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
        if (i == i0 && j == j0 && k0 <= kz0 && kz0 < k1) flag() = 0;  // (read already)
        const auto xa = local(xw);
        constexpr int kChunk = 16;
        for (int kb = k0; kb < k1; kb += kChunk) {
          const int ke = kb + kChunk < k1 ? kb + kChunk : k1;
          // whether any of the node's faces (as `node` walks them) did work
          bool work[kChunk];
#pragma GCC ivdep
          for (int k = kb; k < ke; ++k) {
            Real most = 0;
            for (int b = 0; b < 2; ++b)
              for (int a = 0; a < 2; ++a)
                for (int p = -1; p <= 1; ++p) {
                  const int oi = i + p * sx - (t1 == 0 ? a : 0) - (t2 == 0 ? b : 0);
                  const int oj = j + p * sy - (t1 == 1 ? a : 0) - (t2 == 1 ? b : 0);
                  const int ok = k + p * sz - (t1 == 2 ? a : 0) - (t2 == 2 ? b : 0);
                  most = mmax(most, xa(oi, oj, ok));
                }
            work[k - kb] = most > 0;
          }
          for (int k = kb; k < ke; ++k)
            if (work[k - kb]) node(i, j, k);
        }
      });
}

}  // namespace

void Hydro::expansion_impulse(int d) {
  expansion_impulse(d, s_.expansion_work);
}

void Hydro::expansion_impulse(int d, const Field3& xw) {
  int olo[3], ohi[3];
  mesh_.box(Centering::Node, Region::Owned, olo, ohi);
  const Field3 u0 = d == 0 ? s_.u : d == 1 ? s_.v : s_.w;
  const Field3 u1 = d == 0 ? s_.ub : d == 1 ? s_.vb : s_.wb;
  with_axis(d, [&](auto a) {
    impulse_columns<decltype(a)::value>(s_.rho, s_.pre_vol, s_.post_vol, s_.node_mass, xw,
                                        s_.mass_flux[d], s_.ke_loss, u0, u1, s_.expansion_any, olo,
                                        ohi);
  });
}

}  // namespace mp::hydro
