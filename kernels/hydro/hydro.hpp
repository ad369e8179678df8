// Single-material staggered-grid hydro: a predictor–corrector Lagrangian step followed by a
// directionally split remap back to the fixed mesh (DESIGN.md §4). Cell-averaged fields live
// here; per-material state plugs in beside them (the multi-material layouts).
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "burn/module.hpp"
#include "core/columns.hpp"
#include "eos/eos.hpp"
#include "hydro/numerics.hpp"
#include "hydro/point.hpp"
#include "materials/layout.hpp"
#include "mesh/field.hpp"
#include "mesh/halo.hpp"
#include "mesh/mesh.hpp"
#include "strength/module.hpp"

namespace mp::hydro {

// Most module carriers a scene can have: one per material with strength, and the explosive.
constexpr int kMaxCarriers = mat::kMaxMaterials + 1;

// Volume change of cell (i, j, k) in one step: the volumes swept by its six faces (face fluxes
// stored in node-extent views, face d at index i sitting at node coordinate i along d).
// (F: a view or a core/columns.hpp local accessor)
template <class F>
KOKKOS_INLINE_FUNCTION Real net_volume_flux(const F& fx, const F& fy, const F& fz, int i, int j,
                                            int k) {
  return fx(i + 1, j, k) - fx(i, j, k) + fy(i, j + 1, k) - fy(i, j, k) + fz(i, j, k + 1) -
         fz(i, j, k);
}

// The volume a face sweeps in one step, from its four node velocities along the face's normal
// (`a`: the step's dt times a quarter of the face's area): the x face at node coordinate i of
// cell (i, j, k), and the y and z ones. The corrector's launch stores them; a kernel that needs a
// cell's six faces can compute them here instead and gets the stored values' bits.
template <class F3>
KOKKOS_FORCEINLINE_FUNCTION Real face_flux_x(const F3& u, int i, int j, int k, Real a) {
  return a * (u(i, j, k) + u(i, j + 1, k) + u(i, j, k + 1) + u(i, j + 1, k + 1));
}
template <class F3>
KOKKOS_FORCEINLINE_FUNCTION Real face_flux_y(const F3& v, int i, int j, int k, Real a) {
  return a * (v(i, j, k) + v(i + 1, j, k) + v(i, j, k + 1) + v(i + 1, j, k + 1));
}
template <class F3>
KOKKOS_FORCEINLINE_FUNCTION Real face_flux_z(const F3& w, int i, int j, int k, Real a) {
  return a * (w(i, j, k) + w(i + 1, j, k) + w(i, j + 1, k) + w(i + 1, j + 1, k));
}

// ---- The mid-step geometry (Options::mid_geometry; docs/numerics.md, "Mid-step geometry") ----
// A face whose four nodes move along straight lines by displacements D, bilinear over the face,
// sweeps the volume
//   S(D) = h1 h2 <N> + 1/2 <h2 (N dT1/ds - T1 dN/ds) + h1 (N dT2/dt - T2 dN/dt)> + O(|D|^3),
// N the displacement along the face's normal, T1 and T2 along its two sides (lengths h1, h2;
// normal, side 1, side 2 right-handed), s and t the unit coordinates along the sides, <> the mean
// over the face. The first term is face_flux_*'s (the undeformed face); the second, quadratic in
// D, is what the face's tilting and stretching add: in a flow converging across the face (faces
// shrinking as they move) it is -dt u / r of the first, the first-order error of the undeformed
// geometry. For nodal values it is the sum over the nodes of N_n times the first component of
// face_gradient (the matrices M_A, M_B below are those of the two means).
//
// The face's nodes, (s, t) = (0, 0), (1, 0), (0, 1), (1, 1) at a + 2 b: N, T1, T2 from node fields
// (u, v, w) for the face normal to D at node coordinates (i, j, k) (the low D face of cell
// (i, j, k)): x faces have sides y, z; y faces z, x; z faces x, y. (face_nodes and
// face_gradient give the node forces face by face, the definition that mid_step_force sums
// plane by plane; tests/test_lagrange.cpp checks that the two agree.)
template <int D, class F3>
KOKKOS_FORCEINLINE_FUNCTION void face_nodes(const F3& u, const F3& v, const F3& w, int i, int j,
                                            int k, Real N[4], Real T1[4], Real T2[4]) {
  for (int b = 0; b < 2; ++b)
    for (int a = 0; a < 2; ++a) {
      const int n = a + 2 * b;
      if constexpr (D == 0) {
        N[n] = u(i, j + a, k + b);
        T1[n] = v(i, j + a, k + b);
        T2[n] = w(i, j + a, k + b);
      } else if constexpr (D == 1) {
        N[n] = v(i + b, j, k + a);
        T1[n] = w(i + b, j, k + a);
        T2[n] = u(i + b, j, k + a);
      } else {
        N[n] = w(i + a, j + b, k);
        T1[n] = u(i + a, j + b, k);
        T2[n] = v(i + a, j + b, k);
      }
    }
}
// Row n of M_A x and M_B x: <f dg/ds - g df/ds> = f.M_A g and <f dg/dt - g df/dt> = f.M_B g for
// bilinear f, g given at the nodes (both matrices antisymmetric); form_a, form_b: f.M_A g and
// f.M_B g.
template <int n>
KOKKOS_FORCEINLINE_FUNCTION Real ma_row(const Real x[4]) {
  const Real third = Real(1) / 3, sixth = Real(1) / 6;
  if constexpr (n == 0) return third * x[1] + sixth * x[3];
  if constexpr (n == 1) return -third * x[0] - sixth * x[2];
  if constexpr (n == 2) return sixth * x[1] + third * x[3];
  if constexpr (n == 3) return -sixth * x[0] - third * x[2];
}
template <int n>
KOKKOS_FORCEINLINE_FUNCTION Real mb_row(const Real x[4]) {
  const Real third = Real(1) / 3, sixth = Real(1) / 6;
  if constexpr (n == 0) return third * x[2] + sixth * x[3];
  if constexpr (n == 1) return sixth * x[2] + third * x[3];
  if constexpr (n == 2) return -third * x[0] - sixth * x[1];
  if constexpr (n == 3) return -sixth * x[0] - third * x[1];
}
KOKKOS_FORCEINLINE_FUNCTION Real form_a(const Real f[4], const Real g[4]) {
  return f[0] * ma_row<0>(g) + f[1] * ma_row<1>(g) + f[2] * ma_row<2>(g) + f[3] * ma_row<3>(g);
}
KOKKOS_FORCEINLINE_FUNCTION Real form_b(const Real f[4], const Real g[4]) {
  return f[0] * mb_row<0>(g) + f[1] * mb_row<1>(g) + f[2] * mb_row<2>(g) + f[3] * mb_row<3>(g);
}
// The gradient of S's quadratic part with respect to node n's displacements (N_n, T1_n, T2_n) at
// the displacements given, in the face's axes: the correction of node n's corner vector when
// the face is moved by them.
template <int n>
KOKKOS_FORCEINLINE_FUNCTION void face_gradient(const Real N[4], const Real T1[4], const Real T2[4],
                                               Real h1, Real h2, Real c[3]) {
  c[0] = Real(0.5) * (h2 * ma_row<n>(T1) + h1 * mb_row<n>(T2));
  c[1] = -Real(0.5) * h2 * ma_row<n>(N);
  c[2] = -Real(0.5) * h1 * mb_row<n>(N);
}
// The mid-step geometry's correction of node (i, j, k)'s force per unit dt / 2 (Options::
// mid_geometry; docs/numerics.md, "Mid-step geometry"), added to f: over the 12 faces that meet
// at the node (4 normal to each axis, between its 8 cells), the pressure jump across the face
// (low cell less high cell) times the correction of the node's corner vector when the face's
// nodes are moved by u0 (face_gradient), u0 the start-of-step velocities. The viscous stress
// keeps the undeformed faces.
//
// The four faces normal to axis D lie in the plane of the node's 8 neighbours across them (sides
// s, t: the face axes of face_nodes). The face in quadrant (a, b) = (+-1, +-1) of the plane has
// the node at its corner opposite (s + a, t + b), and face_gradient's rows there are
// a (x(s + a, t) / 3 + x(s + a, t + b) / 6) along s and b (x(s, t + b) / 3 + x(s + a, t + b) / 6)
// along t; summed over the quadrants with their pressure jumps d_ab, each neighbour is loaded
// once (20 loads a plane, against 48 face by face):
//   sum_ab d_ab a (...)_s = [(d++ + d+-) x(s+1, t) - (d-+ + d--) x(s-1, t)] / 3
//                           + [d++ x++ + d+- x+- - d-+ x-+ - d-- x--] / 6,
//   sum_ab d_ab b (...)_t = [(d++ + d-+) x(s, t+1) - (d+- + d--) x(s, t-1)] / 3
//                           + [d++ x++ - d+- x+- + d-+ x-+ - d-- x--] / 6.
// Then the normal component gains (h2 sum_s(T1) + h1 sum_t(T2)) / 2, side 1 -h2 sum_s(N) / 2 and
// side 2 -h1 sum_t(N) / 2 (h1, h2 the lengths of the face's sides along s and t).
template <int D, class F, class P>
KOKKOS_FORCEINLINE_FUNCTION void mid_step_plane(const F& u0, const F& v0, const F& w0, const P& ph,
                                                int i, int j, int k, Real h1, Real h2, Real& fn,
                                                Real& f1, Real& f2) {
  // node (s + ds, t + dt) of the plane, and the jump across the face of quadrant (a, b) (its
  // low-D cell less its high-D cell), as mesh indices
  const auto at = [&](const F& x, int ds, int dt) -> Real {
    if constexpr (D == 0) return x(i, j + ds, k + dt);
    if constexpr (D == 1) return x(i + dt, j, k + ds);
    if constexpr (D == 2) return x(i + ds, j + dt, k);
  };
  const auto jump = [&](int a, int b) -> Real {
    const int cs = (a - 1) / 2, ct = (b - 1) / 2;
    if constexpr (D == 0) return ph(i - 1, j + cs, k + ct) - ph(i, j + cs, k + ct);
    if constexpr (D == 1) return ph(i + ct, j - 1, k + cs) - ph(i + ct, j, k + cs);
    if constexpr (D == 2) return ph(i + cs, j + ct, k - 1) - ph(i + cs, j + ct, k);
  };
  const F& N = D == 0 ? u0 : D == 1 ? v0 : w0;
  const F& T1 = D == 0 ? v0 : D == 1 ? w0 : u0;
  const F& T2 = D == 0 ? w0 : D == 1 ? u0 : v0;
  const Real dpp = jump(1, 1), dpm = jump(1, -1), dmp = jump(-1, 1), dmm = jump(-1, -1);
  const Real third = Real(1) / 3, sixth = Real(1) / 6;
  const auto sum_s = [&](const F& x) {
    return third * ((dpp + dpm) * at(x, 1, 0) - (dmp + dmm) * at(x, -1, 0)) +
           sixth *
               (dpp * at(x, 1, 1) + dpm * at(x, 1, -1) - dmp * at(x, -1, 1) - dmm * at(x, -1, -1));
  };
  const auto sum_t = [&](const F& x) {
    return third * ((dpp + dmp) * at(x, 0, 1) - (dpm + dmm) * at(x, 0, -1)) +
           sixth *
               (dpp * at(x, 1, 1) - dpm * at(x, 1, -1) + dmp * at(x, -1, 1) - dmm * at(x, -1, -1));
  };
  const Real half = Real(0.5);
  fn += half * (h2 * sum_s(T1) + h1 * sum_t(T2));
  f1 -= half * h2 * sum_s(N);
  f2 -= half * h1 * sum_t(N);
}
template <class F, class P>
KOKKOS_FORCEINLINE_FUNCTION void mid_step_force(const F& u0, const F& v0, const F& w0, const P& ph,
                                                int i, int j, int k, Real hx, Real hy, Real hz,
                                                Real f[3]) {
  // x faces: sides y, z; y faces: z, x; z faces: x, y
  mid_step_plane<0>(u0, v0, w0, ph, i, j, k, hy, hz, f[0], f[1], f[2]);
  mid_step_plane<1>(u0, v0, w0, ph, i, j, k, hz, hx, f[1], f[2], f[0]);
  mid_step_plane<2>(u0, v0, w0, ph, i, j, k, hx, hy, f[2], f[0], f[1]);
}

// The step's factors of the mid-step geometry's face corrections: dt^2 and the spacings.
struct SweptFactors {
  Real dt2, hx, hy, hz;
};

// The tensor viscosity's six fields as one Sym6 (point.hpp): as views, or as core/columns.hpp
// local accessors (in a column's body).
template <class V>
KOKKOS_INLINE_FUNCTION Sym6At<V> sym6_view(const V& a, const V& b, const V& c, const V& d,
                                           const V& e, const V& f) {
  return {a, b, c, d, e, f};
}
template <class V>
KOKKOS_INLINE_FUNCTION auto sym6_local(const V& a, const V& b, const V& c, const V& d, const V& e,
                                       const V& f) {
  return Sym6At<decltype(local(a))>{local(a), local(b), local(c), local(d), local(e), local(f)};
}

// A cell's six face volume fluxes (low and high along each axis) from the node velocities.
struct CellFaceFluxes {
  Real xl, xh, yl, yh, zl, zh;
  // the cell's volume change, in net_volume_flux's order of operations
  KOKKOS_INLINE_FUNCTION Real net() const { return xh - xl + yh - yl + zh - zl; }
};
template <class F3>
KOKKOS_FORCEINLINE_FUNCTION CellFaceFluxes cell_face_fluxes(const F3& u, const F3& v, const F3& w,
                                                            int i, int j, int k, Real ax, Real ay,
                                                            Real az) {
  return {face_flux_x(u, i, j, k, ax), face_flux_x(u, i + 1, j, k, ax),
          face_flux_y(v, i, j, k, ay), face_flux_y(v, i, j + 1, k, ay),
          face_flux_z(w, i, j, k, az), face_flux_z(w, i, j, k + 1, az)};
}
// One face's B(u0, u) / (dt^2 / 4) for cell_mid_corrections, from the cell's corner values (face
// node a + 2 b at corner C_{a+2b}; n, t1, t2: the normal and the two sides' components).
template <int C0, int C1, int C2, int C3>
KOKKOS_FORCEINLINE_FUNCTION Real mid_face(const Real* n0, const Real* t10, const Real* t20,
                                          const Real* n1, const Real* t11, const Real* t21, Real h1,
                                          Real h2) {
  const Real N0[4] = {n0[C0], n0[C1], n0[C2], n0[C3]}, A0[4] = {t10[C0], t10[C1], t10[C2], t10[C3]},
             B0[4] = {t20[C0], t20[C1], t20[C2], t20[C3]}, N[4] = {n1[C0], n1[C1], n1[C2], n1[C3]},
             A[4] = {t11[C0], t11[C1], t11[C2], t11[C3]},
             B[4] = {t21[C0], t21[C1], t21[C2], t21[C3]};
  return h2 * (form_a(N0, A) + form_a(N, A0)) + h1 * (form_b(N0, B) + form_b(N, B0));
}
// The mid-step geometry's corrections of a cell's six face volume fluxes (cell_face_fluxes's
// order), added to cell_face_fluxes with the time-centred velocities u to give the corrector's
// fluxes there: dt^2 B(u0, u) per face, B the polar form of S's quadratic part (S(D) = ... +
// B(D, D)) and u0 the start-of-step velocities. The sum is the work volume of the node forces
// that mid_step_force corrects (their corner vectors taken on the faces moved by dt/2 u0:
// sum_n grad_n S(dt/2 u0) . dt u = dt^2 B(u0, u)), so p times it is the forces' work and total
// energy is kept to round-off; it differs from the face's swept volume S(dt u) by O(dt^3). The
// cell's 8 nodes are loaded once and each face built from them in its own node order
// (lagrange::mid_faces takes the three low faces, and the high ones at the block's high side;
// the unused ones are optimised away).
template <class F3>
KOKKOS_FORCEINLINE_FUNCTION CellFaceFluxes cell_mid_corrections(const F3& u0, const F3& v0,
                                                                const F3& w0, const F3& u,
                                                                const F3& v, const F3& w, int i,
                                                                int j, int k,
                                                                const SweptFactors& s) {
  // corner (a, b, c) at a + 2 b + 4 c
  // (written out: a loop over the corners, vectorized on its own, kept GCC from vectorizing the
  // caller's loop over k)
  const auto corners = [&](const F3& f, Real c[8]) {
    c[0] = f(i, j, k);
    c[1] = f(i + 1, j, k);
    c[2] = f(i, j + 1, k);
    c[3] = f(i + 1, j + 1, k);
    c[4] = f(i, j, k + 1);
    c[5] = f(i + 1, j, k + 1);
    c[6] = f(i, j + 1, k + 1);
    c[7] = f(i + 1, j + 1, k + 1);
  };
  Real cu0[8], cv0[8], cw0[8], cu[8], cv[8], cw[8];
  corners(u0, cu0);
  corners(v0, cv0);
  corners(w0, cw0);
  corners(u, cu);
  corners(v, cv);
  corners(w, cw);
  // x faces: nodes (i + x, j + a, k + b); y faces: (i + b, j + y, k + a); z faces:
  // (i + a, j + b, k + z)
  const Real f = Real(0.25) * s.dt2;
  return {f * mid_face<0, 2, 4, 6>(cu0, cv0, cw0, cu, cv, cw, s.hy, s.hz),
          f * mid_face<1, 3, 5, 7>(cu0, cv0, cw0, cu, cv, cw, s.hy, s.hz),
          f * mid_face<0, 4, 1, 5>(cv0, cw0, cu0, cv, cw, cu, s.hz, s.hx),
          f * mid_face<2, 6, 3, 7>(cv0, cw0, cu0, cv, cw, cu, s.hz, s.hx),
          f * mid_face<0, 1, 2, 3>(cw0, cu0, cv0, cw, cu, cv, s.hx, s.hy),
          f * mid_face<4, 5, 6, 7>(cw0, cu0, cv0, cw, cu, cv, s.hx, s.hy)};
}

// Which axes a remap step moves (`a*`) and which are still to be remapped, its own included
// (`p*`), as 0 / 1 weights; and a cell's volume before the step (the Lagrangian volume less the
// steps already done) and after it, from its volume changes along the three axes.
struct StepWeights {
  Real px, py, pz, ax, ay, az;
};
KOKKOS_INLINE_FUNCTION void step_volumes(Real vol, Real dvx, Real dvy, Real dvz,
                                         const StepWeights& s, Real& pre, Real& post) {
  const Real v0 = vol + s.px * dvx + s.py * dvy + s.pz * dvz;
  pre = v0;
  post = v0 - (s.ax * dvx + s.ay * dvy + s.az * dvz);
}
// The same for cell (i, j, k) from the stored face volume fluxes, into pre and post.
// (F: a view or a core/columns.hpp local accessor)
template <class F>
KOKKOS_INLINE_FUNCTION void stored_step_volumes(const F& fx, const F& fy, const F& fz, int i, int j,
                                                int k, Real vol, const StepWeights& s, const F& pre,
                                                const F& post) {
  step_volumes(vol, fx(i + 1, j, k) - fx(i, j, k), fy(i, j + 1, k) - fy(i, j, k),
               fz(i, j, k + 1) - fz(i, j, k), s, pre(i, j, k), post(i, j, k));
}

// Specific internal energy a cell of mass m and internal energy w = m max(e, 0) takes from the
// KE fix (issue #16; docs/numerics.md, "One cycle", item 6): each of its 8 nodes holds, in
// `kel`, either its kinetic-energy loss L >= 0, of which every cell takes 1/8, or, where the
// remap made kinetic energy (L < 0), L over the 8 cells' w summed, so that each cell pays the
// same fraction of its own internal energy — a cold cell beside hot ones pays little, and the
// 8 cells together pay L: total energy is kept.
template <class Corner>
KOKKOS_INLINE_FUNCTION Real ke_fix_share_of(const Corner& kel, Real m, Real w) {
  // separate sums, the two being in different units, over the corners in the order a, b, c; as
  // selects, not branches, so that a column loop vectorizes (adding +0 to the other sum leaves
  // it bit for bit)
  Real gain = 0, frac = 0;
  auto add = [&](Real x) {
    const bool pos = x >= 0;
    gain += pos ? x : Real(0);
    frac += pos ? Real(0) : x;
  };
  add(kel(0, 0, 0));
  add(kel(1, 0, 0));
  add(kel(0, 1, 0));
  add(kel(1, 1, 0));
  add(kel(0, 0, 1));
  add(kel(1, 0, 1));
  add(kel(0, 1, 1));
  add(kel(1, 1, 1));
  return (Real(0.125) * gain + frac * w) / m;
}
// (`kel(a, b, c)`: the loss at node (i + a, j + b, k + c))
KOKKOS_INLINE_FUNCTION Real ke_fix_share(const Field3& kel, int i, int j, int k, Real m, Real w) {
  return ke_fix_share_of([&](int a, int b, int c) { return kel(i + a, j + b, k + c); }, m, w);
}

// A node's kinetic-energy loss L as kel stores it (MomentumFinish, Hydro::expansion_impulse): L
// where L >= 0, else L per unit internal energy `content` of its 8 cells (0 where they have
// none; the quotient taken whatever the sign: a select, not a branch); and back.
KOKKOS_INLINE_FUNCTION Real ke_stored(Real loss, Real content) {
  const Real per_content = loss / content;
  return loss >= 0 ? loss : content > 0 ? per_content : Real(0);
}
KOKKOS_INLINE_FUNCTION Real ke_unstored(Real stored, Real content) {
  return stored >= 0 ? stored : stored * content;
}

// A node whose kinetic-energy discrepancy, as MomentumFinish stores it (kel: the loss L >= 0, or
// L per unit internal energy of its 8 cells where the remap made kinetic energy), says it made
// more than 1/16 of its cells' internal energy: its dual faces are redone with donor values
// (remap.cpp, Hydro::remap_step). At 1/16 a node, no cell of 8 such nodes pays more than half
// its own energy in a sweep, so ke_fix_floor does not bind.
inline constexpr Real kKeRedo = Real(1) / 16;
KOKKOS_INLINE_FUNCTION bool ke_redo(Real kel) {
  return kel < -kKeRedo;
}

// Energy the KE fix's floor left unpaid (a column's or a cell's) into the rank's sum, State::
// ke_unpaid (one atomic per column or cell, and only where the floor bound: nearly never).
KOKKOS_INLINE_FUNCTION void add_unpaid(const Kokkos::View<double, MemSpace>& unpaid, Real u) {
  if (u > 0) Kokkos::atomic_add(&unpaid(), double(u));
}

// Sum of a node field over the 8 corners of cell (i, j, k), x fastest.
template <class F3>
KOKKOS_INLINE_FUNCTION Real corner_sum(const F3& f, int i, int j, int k) {
  Real sum = 0;
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) sum += f(i + a, j + b, k + c);
  return sum;
}

// The smallest volume fraction a material may hold beside others: 4 ulps of 1 in Real. Below
// it the largest material's fraction 1 - f rounds to 1 (in float from f < 2^-25 = 3e-8), so a cell
// would read as pure in the dense layout (alpha == 1) and mixed in the compact one, and its
// volume would not sum to the cell's. 8.9e-16 in double builds (below the 1e-14 default), 4.8e-7
// in float builds.
constexpr double kMinFractionFloor = 4.0 * double(std::numeric_limits<Real>::epsilon());

// The min_fraction a run uses: the deck's, raised to the floor above.
inline double effective_min_fraction(double requested) {
  return std::max(requested, kMinFractionFloor);
}

struct Options {
  // The deck's numerics (numerics.hpp holds their one set of defaults; Options() takes them).
  Options() : Options(Numerics{}, StepControl{}) {}
  Options(const Numerics& n, const StepControl& t);

  int order;  // advection order: 2 van Leer, 1 donor cell (numerics.advection)
  Real q_linear;
  Real q_quadratic;
  // the viscous stress Q = q ((1 - b) S + b I), b = q_isotropic (point.hpp): 0 the tensor, 1 the
  // scalar q of a pressure
  Real q_isotropic;
  // Noh's artificial heat flux (conduction.cpp): the coefficient h of the conduction of
  // internal energy between face neighbours that the viscosity compresses; 0 turns it off.
  // Single-material scenes (a multi-material scene ignores it).
  Real heat_flux;
  // The Lagrangian step's pressure forces on the mid-step geometry (docs/numerics.md, "Mid-step
  // geometry"): each face's corner vectors at its nodes moved by dt/2 u^n, the cell's work the
  // forces' work (total energy kept to round-off), its volume change the matching second-order
  // face volumes. Off: the undeformed cube's faces (first order in dt where flow converges or
  // diverges across a face). Single-material scenes without strength; the others ignore it.
  bool mid_geometry;  // (the scene key numerics.geometry)
  // The free-expansion rule (point.hpp expansion_share; docs/numerics.md, "Free expansion to
  // the nodes"): a face whose gas enters a cell that would hold less than this fraction of the
  // face's density gives the receiver the isentropically expanded energy and its nodes the
  // rest as kinetic energy of the node pairs it pushes apart; 0 turns it off. Single-material
  // ideal-gas scenes on split sweeps with the KE fix (the others ignore it).
  Real free_expansion;
  Real cfl;
  // Time-step rule. Combined (default): dt = cfl min_d dx_d / (c_eff + |u_d|). Separate: the
  // sound speed and the transport speed limit the step each on its own, with its own safety
  // factor: dt = min_d min(cfl dx_d / c_eff, cfl_transport dx_d / |u_d|) (perf/timestep_study.cpp
  // measures it on the verification scenes; docs/numerics.md says why it is not the default).
  bool separate_limits = false;
  Real cfl_transport = 0.5;
  Real growth;
  Real dt_max;
  // Give the kinetic energy that the momentum remap dissipates back to the cells as internal
  // energy (DeBar's correction, see Benson, Comput. Methods Appl. Mech. Eng. 99:235, 1992),
  // so total energy is conserved to round-off.
  bool ke_fix;
  // Multi-material scenes: a node's loss goes to its 8 cells in proportion to their mass (every
  // cell takes the same specific energy; numerics.ke_fix_share: mass, the default) or an eighth
  // to each (equal, the rule before 2026-12-03). Single-material scenes have their own budget
  // (ke_fix_share() above) and ignore it.
  bool ke_fix_by_mass;
  // Single-material scenes: where a node made more kinetic energy than its cells can pay
  // (ke_redo), redo its dual faces with donor values (numerics.ke_fix_redo; remap.cpp).
  bool ke_fix_redo;
  // One remap step over all axes instead of three split sweeps (symmetric under permutations
  // of the axes; the time step then keeps the sum of the axes' Courant numbers below cfl).
  bool unsplit;
  // Multi-material scenes (two or more EOS): storage of the per-material state, interface
  // reconstruction of the material fluxes (Youngs PLIC, SLIC, or none: fraction-weighted),
  // and the volume fraction below which a material leaves a cell (its mass and energy go to
  // the largest material of the cell).
  mat::LayoutKind layout;
  Interface interface;
  Real min_fraction;  // the deck's, raised to kMinFractionFloor
  // Mixed-cell closure of the Lagrangian step: equal strain (false), or equal strain followed
  // by pressure relaxation (true, kernels/hydro/relax.hpp) with at most relax_iterations
  // Newton updates per cycle, stopping once the pressures agree to relax_tol (relative).
  bool relax;
  int relax_iterations;
  // Solid floor (docs/numerics.md, "Stretched solids in mixed cells"): a Mie-Grueneisen
  // material of a mixed cell below solid_floor x rho0 after the corrector is put back at that
  // density, its volume going to the cell's other materials without work (free expansion into
  // the void a failing solid opens); 0 leaves equal strain alone.
  Real solid_floor;
  // (1e-10, or 64 ulps where Real cannot hold that: 7.6e-6 in float)
  Real relax_tol = Real(std::max(1e-10, 64.0 * double(std::numeric_limits<Real>::epsilon())));
  // Strength of a single-material scene's material (kernels/strength/module.hpp): the
  // flow-stress model and the reference density; kind kNoStrength leaves the module out.
  strength::FlowStress strength;
  Real strength_rho0 = 1;
  // Strength of a multi-material scene: one model per material (n == 0, or every kind
  // kNoStrength, leaves the module out), and the materials' names (the dumps' field suffixes).
  strength::MaterialModels material_strength;
  std::vector<std::string> material_names;
  // Burn of the explosive (kernels/burn/module.hpp); off unless burn.on. A multi-material scene
  // names the explosive's material id in burn.material.
  burn::BurnSetup burn;
};

struct State {
  // cells
  Field3 rho, e, p, c, q;
  // the tensor viscosity Q = q S (point.hpp, compression_direction): xx, yy, zz, xy, xz, yz
  std::array<Field3, 6> qt;
  // per cell column (i, j): 1 where some cell of it has a viscous stress (the Lagrangian
  // kernels skip the stress of the columns without)
  Kokkos::View<int**, MemSpace> qcol;
  // Noh's heat flux (conduction.cpp; single-material scenes with numerics.heat_flux > 0): each
  // cell's compressive velocity jump where it converges (0 elsewhere), and a flag the
  // viscosity raises where any cell of the rank converges
  Field3 cjump;
  Kokkos::View<int, MemSpace> converging;
  // the energy the KE fix's floor left uncharged on this rank's owned cells since the start
  // (remap.cpp ke_fix_cell, mixed_ke_fix.cpp MixedKeFix / PureKeFix; reported by totals())
  Kokkos::View<double, MemSpace> ke_unpaid;
  // raised by remap::momentum where a node made kinetic energy its cells cannot pay (ke_redo)
  Kokkos::View<int, MemSpace> ke_redo;
  Field3 qw;  // a multi-material step's viscous work per cell (the corrector's, for its materials)
  Field3 p_half;             // pressure at the half step (predictor)
  Field3 pre_vol, post_vol;  // cell volumes before / after one remap sweep
  // nodes
  Field3 u, v, w;     // velocity
  Field3 ub, vb, wb;  // time-centred velocity of the Lagrangian step
  Field3 node_mass;   // remap scratch: nodal (dual-cell) mass before a sweep
  Field3 ke_loss;     // remap scratch: kinetic energy the momentum remap took from a node
                      // (multi-material, shares by mass: over 8 times the node's mass)
  // remap scratch of a split sweep: mass flux and upwind velocities of the dual face above
  // each node along the sweep's axis
  Field3 dual_flux, dual_u, dual_v, dual_w, dual_k;  // dual_k: kinetic energy carried per unit mass
  // faces, stored in node-extent views: face d at index i sits at node coordinate i along d
  std::array<Field3, 3> vol_flux;
  std::array<Field3, 3> mass_flux, energy_flux;  // through faces normal to x, y, z
  // the free-expansion rule (Options::free_expansion): the internal energy a face's donor pays
  // beyond what its receiver takes, given to the face's node pairs as kinetic energy (split
  // sweeps; allocated only where the rule can act)
  Field3 expansion_work;
  Kokkos::View<int, MemSpace> expansion_any;  // set where a sweep's faces did that work
};

// What limited a time step: the CFL condition per axis, the unsplit remap's sum of the axes'
// Courant numbers, the growth factor, dt_max, the end time; the driver's first step held at
// time.dt_initial. dt_limit_name gives the run log's word for each.
enum class DtLimit { Cfl, CourantSum, Growth, Max, End, Initial };
inline const char* dt_limit_name(DtLimit l) {
  switch (l) {
    case DtLimit::Cfl:
      return "cfl";
    case DtLimit::CourantSum:
      return "courant_sum";
    case DtLimit::Growth:
      return "growth";
    case DtLimit::Max:
      return "max";
    case DtLimit::End:
      return "end";
    case DtLimit::Initial:
      return "initial";
  }
  return "?";
}

struct TimeStep {
  Real dt = 0;
  std::array<int, 3> cell{{-1, -1, -1}};  // global index of the limiting cell
  DtLimit limit = DtLimit::Cfl;
};

struct Totals {
  double mass = 0, internal = 0, kinetic = 0;
  std::array<double, 3> momentum{};
  // the energy the KE fix could not charge since the run began: where the remap made kinetic
  // energy its cells could not pay without falling below ke_fix_floor (point.hpp), the total
  // energy gains this much (0 in every shipped deck)
  double ke_fix_unpaid = 0;
  std::vector<double> material_mass;  // per material (multi-material scenes)
  double total() const { return internal + kinetic; }
};

// The first cell (lowest global index) that went non-physical, if any.
struct Health {
  bool ok = true;
  std::array<int, 3> cell{};
  double rho = 0, e = 0, p = 0, volume = 0;
  std::string what;
  // A bad material of a mixed cell (what names it): its id (-1: none) and its own state there.
  int material = -1;
  double m_fraction = 0, m_rho = 0, m_e = 0;
};

class Hydro {
 public:
  Hydro(const Mesh& mesh, Halo& halo, const Options& opt, eos::Eos eos);
  // One EOS per material; two or more switch the multi-material path on.
  Hydro(const Mesh& mesh, Halo& halo, const Options& opt, const std::vector<eos::Eos>& eos);

  State& state() { return s_; }
  const State& state() const { return s_; }
  const Options& options() const { return opt_; }
  // whether this step runs the mid-step geometry (Options::mid_geometry, where it applies)
  bool mid_geometry() const { return mid_geometry_; }
  // Switches the time-step rule (the scene reader does not set it; perf/timestep_study.cpp).
  void set_time_limits(bool separate, Real cfl_transport) {
    opt_.separate_limits = separate;
    opt_.cfl_transport = cfl_transport;
  }
  // The per-material state of a multi-material scene, or nullptr.
  mat::MaterialState* materials() { return mm_.get(); }
  const mat::MaterialState* materials() const { return mm_.get(); }
  // The strength module, or nullptr when no material has strength.
  strength::Strength* strength() { return strength_.get(); }
  const strength::Strength* strength() const { return strength_.get(); }
  // The burn module, or nullptr when no material is an explosive.
  burn::Burn* burn() { return burn_.get(); }
  const burn::Burn* burn() const { return burn_.get(); }

  // Fills ghosts of the primary fields and derives p, c, q (call after setting rho, e, u, v, w).
  void prepare();
  // p and c from the EOS, then q (a plain single-material scene does both in one launch).
  void eos_viscosity();
  TimeStep time_step(Real dt_old, double t, double t_end) const;
  // One full cycle: Lagrangian step then remap; `cycle` sets the sweep order. Returns the
  // health of the Lagrangian volumes (a run stops when they collapse).
  Health step(Real dt, long cycle);
  Health check() const;
  Totals totals() const;
  std::vector<OutputField> output_fields() const;

  // Exposed for tests.
  void equation_of_state(const Field3& rho, const Field3& e, const Field3& p,
                         const Field3& c) const;
  void viscosity();
  // The Lagrangian step; `cycle`, the cycle whose remap follows, lets the corrector write the
  // first remap step's cell volumes (any other remap recomputes them).
  Health lagrange(Real dt, long cycle = 0);
  void remap(long cycle);
  // sweeps whose dual faces the KE fix redid with donor values so far (ke_redo; the same on
  // every rank)
  long ke_redone() const { return ke_redone_; }
  // One remap step over the faces normal to `axes`; `pending` marks the axes whose volume
  // change is not yet remapped (the step's own included).
  void remap_step(const std::array<bool, 3>& axes, const std::array<bool, 3>& pending);
  struct RemapStep {
    std::array<bool, 3> axes, pending;
    bool operator==(const RemapStep& o) const { return axes == o.axes && pending == o.pending; }
    StepWeights weights() const {
      return {Real(pending[0]), Real(pending[1]), Real(pending[2]),
              Real(axes[0]),    Real(axes[1]),    Real(axes[2])};
    }
  };
  // The remap steps of a cycle, in order: x, y, z on even cycles and z, y, x on odd ones, or
  // the one unsplit step.
  std::vector<RemapStep> remap_steps(long cycle) const;

  // Kernel launchers (public: nvcc requires the function enclosing an extended
  // __host__ __device__ lambda to be public).
  void exchange_cells();
  // Noh's heat flux over a step dt (conduction.cpp), before the Lagrangian step: the number of
  // explicit sub-steps it took, 0 where it did nothing (off, a multi-material scene, no
  // converging cell).
  int heat_flux(Real dt);
  // whether the scene conducts (Noh's heat flux on, a single material)
  bool conducts() const { return opt_.heat_flux > 0 && !mm_; }
  // whether the free-expansion rule acts (Options::free_expansion; single-material ideal gas,
  // split sweeps, no modules)
  bool free_expansion_acts() const { return expansion_gm1_ > 0; }
  void exchange_nodes(const Field3& u, const Field3& v, const Field3& w);
  // After remap::momentum: whether a node on any rank raised State::ke_redo (with the option
  // on); if so the node losses are exchanged (their ghosts hold their owners' flags) and the
  // sweep counted, the caller redoes the flagged nodes' faces, then ke_redo_end lowers the flag.
  bool ke_redo_begin();
  void ke_redo_end();
  // `next`: the step after this one (nullptr for the last), whose cell volumes the KE fix's
  // launch writes.
  void remap_step(const RemapStep& step, const RemapStep* next);
  // A single-material scene without strength or burn, whose EOS and viscosity are one launch
  // (the modules adjust p and c between the two).
  bool plain() const { return !mm_ && !strength_ && !burn_; }
  void viscosity_with(bool with_eos);
  // Multi-material pieces (mixed_lagrange.cpp, mixed_remap_faces.cpp, mixed_remap_cells.cpp,
  // mixed_ke_fix.cpp).
  void mm_equation_of_state() const;
  // (`f`: the half step's face factors, dt/2 times a quarter of each axis's face area)
  void mm_predictor(Real vol, const std::array<Real, 3>& f);
  void mm_corrector(Real vol);
  template <class Dev>
  void mm_face_fluxes(const Dev& dev, int d);
  template <class Dev>
  void mm_cell_update(const Dev& dev, int d);
  void mm_remap_faces(int d);
  void mm_remap_cells(int d);
  // (`next`: as remap_step's; the compact layout's pure launch then writes its volumes)
  void mm_ke_fix(const RemapStep* next);
  // The carriers' densities of a remap step (before the cell update).
  void mm_carriers();
  // After the cell update: a cell its carrier left (through a face, or as a sliver below
  // min_fraction) holds none of the module's quantities.
  void mm_clear_absent();
  // The mass fluxes (face field of the sweep's axis) and densities the module quantities ride
  // on: a single-material scene's cell ones, or a multi-material scene's carriers.
  struct Carrier {
    std::array<Field3, 3> flux;
    Field3 rho;
  };
  Carrier carrier(int slot) const;

 private:
  const Mesh& mesh_;
  Halo& halo_;
  Options opt_;
  eos::Eos eos_;
  mat::MaterialSet mats_;
  std::unique_ptr<mat::MaterialState> mm_;
  std::unique_ptr<strength::Strength> strength_;
  std::unique_ptr<burn::Burn> burn_;
  // Multi-material scenes with modules: the materials whose mass carries each module's cell
  // quantities (slots 0 .. sets - 1: the strength module's stress sets, each its own material;
  // then the burn module's explosive), their mass flux through the faces of the sweep (written
  // by the material flux kernel) and their density (sum alpha_m rho_m over them).
  int ncarrier_ = 0, burn_carrier_ = -1;
  unsigned carrier_mask_[kMaxCarriers] = {};
  Field3 carrier_flux_[kMaxCarriers], carrier_rho_[kMaxCarriers];
  State s_;
  // the mid-step geometry (Options::mid_geometry): the nodes' start-of-step velocities
  Field3 u0_, v0_, w0_;
  bool mid_geometry_ = false;
  // The remap step whose cell volumes (pre_vol, post_vol) a fused launch has written ahead (the
  // corrector the first step's, a step's KE fix the next one's), if any.
  bool volumes_ready_ = false;
  RemapStep volumes_for_{};
  long ke_redone_ = 0;  // sweeps whose dual faces were redone (ke_redo)
  // gamma - 1 of the scene's ideal gas where the free-expansion rule acts (else 0)
  Real expansion_gm1_ = 0;
  bool expanded_ = false;  // whether the current sweep's faces did free-expansion work
  void expansion_impulse(int d);
  bool expansion_worked();
  int reflective_face(int d, int s) const;
};

}  // namespace mp::hydro
