// The remap's dual-face point functions and node finish, shared by its driver (remap.cpp,
// Hydro::remap_step: the unsplit step) and a split sweep's kernels (remap_sweep.cpp).
#pragma once

#include "core/columns.hpp"
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/point.hpp"

namespace mp::hydro {

// Mass flux through the dual face between node c = (ci, cj, ck) and node c + e_d: the average
// of the mass fluxes through the two cell faces bounding cell c along d, over the four cells
// around the node line.
template <class F3>
KOKKOS_INLINE_FUNCTION Real dual_mass_flux(const F3& mf, int ci, int cj, int ck, int d) {
  const int sx = d == 0, sy = d == 1, sz = d == 2;
  // unit steps along the two transverse axes
  const int tx1 = d == 0 ? 0 : 1, ty1 = d == 0 ? 1 : 0, tz1 = 0;
  const int tx2 = 0, ty2 = d == 2 ? 1 : 0, tz2 = d == 2 ? 0 : 1;
  Real f = 0;
  for (int b = 0; b < 2; ++b)
    for (int a = 0; a < 2; ++a) {
      const int oi = ci - a * tx1 - b * tx2, oj = cj - a * ty1 - b * ty2,
                ok = ck - a * tz1 - b * tz2;
      f += mf(oi, oj, ok) + mf(oi + sx, oj + sy, ok + sz);
    }
  return Real(0.125) * f;
}

// The wind through the dual face above node c along d (mass flux f): the donor node (c when f > 0,
// else c + e_d) and its Courant number |f| / m_donor, found once for the face's three velocity
// components.
struct DualWind {
  bool pos;  // f > 0: node c gives
  Real sigma;
};
template <class F3>
KOKKOS_INLINE_FUNCTION DualWind dual_wind(const F3& nm, int ci, int cj, int ck, int d, Real f) {
  const int sx = d == 0, sy = d == 1, sz = d == 2;
  const Real m1 = nm(ci, cj, ck), m2 = nm(ci + sx, cj + sy, ck + sz);
  return {f > 0, mabs(f) / (f > 0 ? m1 : m2)};
}

// Node value on the upwind side of the dual face above node c along d, with a limited slope. The
// four nodes along d around the face are loaded whatever the wind and the donor's stencil is
// selected from them (a sweep's loads are then fixed offsets: remap::dual_face took 0.69x the
// time of the branch on the wind, 48^3, 1 thread). `donor` and `receiver` get the values of the
// two nodes of the face.
template <class F3>
KOKKOS_INLINE_FUNCTION Real dual_face_value(const F3& phi, const DualWind& wd, int ci, int cj,
                                            int ck, int d, int ord, Real& donor, Real& receiver) {
  const int sx = d == 0, sy = d == 1, sz = d == 2;
  const Real p0 = phi(ci - sx, cj - sy, ck - sz), p1 = phi(ci, cj, ck),
             p2 = phi(ci + sx, cj + sy, ck + sz), p3 = phi(ci + 2 * sx, cj + 2 * sy, ck + 2 * sz);
  donor = wd.pos ? p1 : p2;
  receiver = wd.pos ? p2 : p1;
  return face_value(wd.pos ? p0 : p3, donor, receiver, wd.sigma, ord);
}

// Kinetic energy per unit mass carried through a dual face with face velocity (uf, vf, wf) out
// of a donor node of velocity (ud, vd, wd): |u_f|^2 / 2, or, where `linear` (a single-material
// scene's expanding face), the donor's kinetic energy plus the work of the face velocity's
// departure from it, u_d . u_f - |u_d|^2 / 2 — the expansion of |u_f|^2 / 2 about the donor's
// velocity to first order. The second-order rest, |u_f - u_d|^2 / 2, is the spread of the
// limited slope inside the donor's dual cell, kinetic energy that no node holds; counted as
// carried it made every draining node (the near-vacuum centre of Toro's 123 problem) export
// kinetic energy it never had, which the KE fix took from its cells' internal energy (the
// centre's entropy fell from 0.400 to 0.285 by t = 0.01; docs/numerics.md, "One cycle", item 6).
// One value per face, so the remap's kinetic energy budget still closes to round-off.
KOKKOS_INLINE_FUNCTION Real ke_carried(Real uf, Real vf, Real wf, const Real dn[3], bool linear) {
  if (linear)
    return (dn[0] * uf + dn[1] * vf + dn[2] * wf) -
           Real(0.5) * (dn[0] * dn[0] + dn[1] * dn[1] + dn[2] * dn[2]);
  return Real(0.5) * (uf * uf + vf * vf + wf * wf);
}

// A node's mass, momentum and carried kinetic energy, gaining the flux through its low dual
// face and losing the flux through its high one (kl, kh: kinetic energy per unit mass carried).
struct DualUpdate {
  Real m1, pu, pv, pw, ke_flux;
  KOKKOS_INLINE_FUNCTION void add(Real f_lo, Real f_hi, Real ul, Real uh, Real vl, Real vh, Real wl,
                                  Real wh, Real kl, Real kh) {
    m1 += f_lo - f_hi;
    pu += f_lo * ul - f_hi * uh;
    pv += f_lo * vl - f_hi * vh;
    pw += f_lo * wl - f_hi * wh;
    // kinetic energy carried by the same face values, to measure the remap's loss
    ke_flux += f_lo * kl - f_hi * kh;
  }
};

// The kinetic energy per unit mass carried through the dual face above node c along d (mass
// flux f, face velocity uf, vf, wf; dn the donor node's velocity): ke_carried, linear where
// `linear` and the flow expands across the face (the receiving node runs ahead of the donor
// along d; nd, nr: the donor's and the receiver's velocity component along d).
KOKKOS_INLINE_FUNCTION Real dual_face_ke(Real f, Real uf, Real vf, Real wf, const Real dn[3],
                                         Real nd, Real nr, bool linear) {
  if (!linear) return Real(0.5) * (uf * uf + vf * vf + wf * wf);  // the full form, no donor
  return ke_carried(uf, vf, wf, dn, (nr - nd) * f > 0);
}

// The mass flux, face velocities and carried kinetic energy of the dual face above node c
// along d (one point function for the split sweep's face pass and the unsplit node update).
struct DualFace {
  Real f, u, v, w, k;
};
template <class F3>
KOKKOS_INLINE_FUNCTION DualFace dual_face(const F3& mf, const F3& nm, const F3& u, const F3& v,
                                          const F3& w, int ci, int cj, int ck, int d, int ord,
                                          bool weigh) {
  DualFace r;
  r.f = dual_mass_flux(mf, ci, cj, ck, d);
  const DualWind wd = dual_wind(nm, ci, cj, ck, d, r.f);
  Real dn[3], rv[3];
  r.u = dual_face_value(u, wd, ci, cj, ck, d, ord, dn[0], rv[0]);
  r.v = dual_face_value(v, wd, ci, cj, ck, d, ord, dn[1], rv[1]);
  r.w = dual_face_value(w, wd, ci, cj, ck, d, ord, dn[2], rv[2]);
  r.k = dual_face_ke(r.f, r.u, r.v, r.w, dn, dn[d], rv[d], weigh);
  return r;
}

// A node's new velocities (un, vn, wn) and its kinetic-energy discrepancy (kel) from its remapped
// mass and momentum (DualUpdate). Multi-material scenes share a node's loss among its 8 cells by
// their mass (by_mass: kel holds the loss per unit mass of the node's cells, L / (8 m_node));
// else kel holds the loss, and where the KE fix weighs its shares (weigh) a node that made
// kinetic energy stores it per unit internal energy of its 8 cells (ke_fix_share; the cell
// update left each cell's internal energy in `pre`). A is the field type (views, or local()
// accessors made by at() inside a column); apply's options are template arguments.
// Returns whether the node made more kinetic energy than kKeRedo of its cells' internal energy
// (Weigh only; the sweep then redoes its faces with donor values, Hydro::remap_step).
template <class A>
struct MomentumFinish {
  A un, vn, wn, kel, pre;
  bool by_mass, weigh;
  template <class B>
  KOKKOS_INLINE_FUNCTION MomentumFinish<B> at(const B&) const {
    return {local(un), local(vn), local(wn), local(kel), local(pre), by_mass, weigh};
  }
  template <bool ByMass, bool Weigh>
  KOKKOS_INLINE_FUNCTION bool apply(int i, int j, int k, Real m0, Real u0, Real v0, Real w0,
                                    const DualUpdate& du) const {
    const Real u1 = du.pu / du.m1, v1 = du.pv / du.m1, w1 = du.pw / du.m1;
    un(i, j, k) = u1;
    vn(i, j, k) = v1;
    wn(i, j, k) = w1;
    const Real ke0 = Real(0.5) * m0 * (u0 * u0 + v0 * v0 + w0 * w0);
    const Real ke1 = Real(0.5) * du.m1 * (u1 * u1 + v1 * v1 + w1 * w1);
    const Real loss = ke0 + du.ke_flux - ke1;
    if constexpr (ByMass) {
      const Real per_mass = loss / (8 * du.m1);
      kel(i, j, k) = du.m1 > 0 ? per_mass : Real(0);
      return false;
    } else if constexpr (!Weigh) {
      kel(i, j, k) = loss;
      return false;
    } else {
      // (the 8 loads whatever the sign: a select, not a branch)
      const Real stored = ke_stored(loss, corner_sum(pre, i - 1, j - 1, k - 1));
      kel(i, j, k) = stored;
      return ke_redo(stored);
    }
  }
  KOKKOS_INLINE_FUNCTION bool operator()(int i, int j, int k, Real m0, Real u0, Real v0, Real w0,
                                         const DualUpdate& du) const {
    if (by_mass) return apply<true, false>(i, j, k, m0, u0, v0, w0, du);
    if (weigh) return apply<false, true>(i, j, k, m0, u0, v0, w0, du);
    return apply<false, false>(i, j, k, m0, u0, v0, w0, du);
  }
};

// A split sweep's launchers along axis D (remap_sweep.cpp, which instantiates them for D = 0, 1
// and 2; Hydro::remap_step picks D with with_axis).
template <int D>
void cell_flux_sweep(const int lo[3], const int hi[3], const Field3& vf, const Field3& pre,
                     const Field3& rho, const Field3& e, const Field3& mf, const Field3& ef,
                     int ord, const Field3& xw, Real gm1, Real ratio, int wall_lo, int wall_hi,
                     const Kokkos::View<int, MemSpace>& any_work);
template <int D>
void dual_face_sweep(const int lo[3], const int hi[3], const Field3& mf, const Field3& nm,
                     const Field3& u, const Field3& v, const Field3& w, const Field3& F,
                     const Field3& U, const Field3& V, const Field3& W, const Field3& K, int ord,
                     bool weigh);
template <int D>
void momentum_nodes(const int nlo[3], const int nhi[3], const Field3& nm, const Field3& u,
                    const Field3& v, const Field3& w, const Field3& F, const Field3& U,
                    const Field3& V, const Field3& W, const Field3& K,
                    const MomentumFinish<Field3>& finish, const Kokkos::View<int, MemSpace>& redo);
template <int D>
void dual_face_redo(const int lo[3], const int hi[3], const Field3& mf, const Field3& nm,
                    const Field3& u, const Field3& v, const Field3& w, const Field3& kel,
                    const Field3& F, const Field3& U, const Field3& V, const Field3& W,
                    const Field3& K);

}  // namespace mp::hydro
