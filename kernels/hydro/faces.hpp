// The Lagrangian step's face geometry as point functions: the volume each face sweeps (the
// undeformed faces, and the mid-step geometry's corrections of the faces moved by dt/2), the
// cell volumes of a remap step, and the tensor viscosity's fields as one Sym6.
#pragma once

#include "core/columns.hpp"
#include "core/math.hpp"
#include "hydro/point.hpp"

namespace mp::hydro {

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

}  // namespace mp::hydro
