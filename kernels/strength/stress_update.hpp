// Stress-deviator update of one material point: the rate form of Hooke's law with the Jaumann
// rotation, then the von Mises radial return (DESIGN.md section 4 item 5). Point functions of
// plain numbers; the layouts and the cycle own the loops.
//
// Units: cm / g / us (kernels/materials/library.hpp): stresses and G in Mbar, velocity gradient
// in 1/us, dt in us, work per unit volume in Mbar (= Mbar cm^3 / cm^3).
//
// Constitutive law (hypoelastic, objective through the Jaumann rate):
//   ds/dt = 2 G (D - tr(D)/3 I) + W s - s W,      D = sym(L), W = skew(L),
// so that the Jaumann rate  ds/dt - W s + s W  equals 2 G D'. Two integrators over a step dt:
//  - elastic_trial_euler: the forward form s_n + dt [2 G D' + W s_n - s_n W] written in the
//    issue. First order in the rotation: under a pure spin |s| grows by a factor
//    (1 + O((|W| dt)^2)) per step, so J2 drifts by O(|W| dt) over a fixed angle.
//  - elastic_trial_rotated (what the cycle should use): s* = Q (s_n + G dt D') Q^T + G dt D',
//    with Q the Cayley (Hughes-Winget) rotation Q = (I - dt/2 W)^-1 (I + dt/2 W), orthogonal to
//    round-off, so a pure spin keeps every invariant of s exactly and turns it through
//    2 atan(|w| dt / 2) per step (|w| dt - (|w| dt)^3 / 12 + ...); splitting the elastic
//    increment around the rotation makes the whole update second order for constant L. With L
//    the velocity gradient at the middle of the step this is the time-centred update.
// Both keep s symmetric by construction (6 components) and remove the trace round-off leaves.
//
// Radial return (perfect plasticity within one step, associated flow):
//   J = sqrt(3/2 s*:s*);  if J > Y: s = (Y/J) s*,
//   plastic strain increment (equivalent, von Mises) d_eps_p = (J - Y) / (3 G),
//   plastic strain increment tensor  d_eps_p_ij = (s* - s)_ij / (2 G) = 3/2 d_eps_p s_ij / Y,
//   plastic work per unit volume  s : d_eps_p_ij = Y d_eps_p  (> 0 whenever J > Y).
// Y <= 0 (melt, or no strength) returns s = 0, d_eps_p = 0, work 0.
//
// Time centring proposed for the predictor-corrector (DESIGN.md section 4 item 4):
//  - predictor: s^{n+1/2} = return(elastic_trial_rotated(s^n, L^n, G^n, dt/2), Y^n), used only
//    in the half-step nodal forces (beside p^{n+1/2} + q); the equivalent plastic strain is not
//    advanced;
//  - corrector: s^{n+1} = return(elastic_trial_rotated(s^n, L^{n+1/2}, G, dt), Y), with
//    L^{n+1/2} the velocity gradient of the time-centred vertex velocities (u^n + u^{n+1})/2 on
//    the half-step geometry (the same velocities the corrector's volume change uses), G and Y at
//    the half-step state; eps_p += d_eps_p;
//  - energy: the deviatoric stress power enters e with the same centring as p dV,
//    de_dev = dt/rho * (s^n + s^{n+1})/2 : D^{n+1/2} (deviatoric_work below); it contains the
//    plastic work, and the elastic part is stored in e as in Wilkins' scheme. The plastic work
//    returned by the radial return is the dissipated part (heating, diagnostics).
#pragma once
#include "core/math.hpp"
#include "strength/tensor.hpp"

namespace mp::strength {

// Deviatoric part of the strain rate, D - tr(D)/3 I.
KOKKOS_INLINE_FUNCTION Sym strain_rate_deviator(const Mat3& L) {
  return deviator(strain_rate(L));
}

// W s - s W for a spin W and a symmetric s (symmetric and traceless).
KOKKOS_INLINE_FUNCTION Sym spin_term(const Mat3& w, const Sym& s) {
  const Mat3 ws = matmul(w, to_mat(s));
  // s W = (W^T s)^T = -(W s)^T, so W s - s W = W s + (W s)^T = 2 sym(W s)
  return scaled(sym_part(ws), Real(2));
}

// The rate ds/dt = 2 G D' + W s - s W.
KOKKOS_INLINE_FUNCTION Sym jaumann_rate(const Sym& s, const Mat3& L, Real G) {
  const Sym d = strain_rate_deviator(L);
  const Sym r = spin_term(spin(L), s);
  const Real g2 = 2 * G;
  return {g2 * d.xx + r.xx, g2 * d.yy + r.yy, g2 * d.zz + r.zz,
          g2 * d.xy + r.xy, g2 * d.yz + r.yz, g2 * d.zx + r.zx};
}

// Forward step s_n + dt ds/dt, deviator re-projected (trace round-off removed).
KOKKOS_INLINE_FUNCTION Sym elastic_trial_euler(const Sym& s, const Mat3& L, Real G, Real dt) {
  const Sym r = jaumann_rate(s, L, G);
  return deviator({s.xx + dt * r.xx, s.yy + dt * r.yy, s.zz + dt * r.zz, s.xy + dt * r.xy,
                   s.yz + dt * r.yz, s.zx + dt * r.zx});
}

// The Cayley rotation (I - K)^-1 (I + K), K = dt/2 W, in closed form:
//   Q = I + 2 / (1 + |k|^2) (K + K^2),  k the axial vector of K.
KOKKOS_INLINE_FUNCTION Mat3 cayley_rotation(const Mat3& w, Real dt) {
  Mat3 k;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) k.a[i][j] = Real(0.5) * dt * w(i, j);
  const Real k1 = k(2, 1), k2 = k(0, 2), k3 = k(1, 0);
  const Real f = 2 / (1 + k1 * k1 + k2 * k2 + k3 * k3);
  const Mat3 k_sq = matmul(k, k);
  Mat3 q;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      q.a[i][j] = (i == j ? Real(1) : Real(0)) + f * (k(i, j) + k_sq(i, j));
  return q;
}

// Objective, time-centred trial deviator: half the elastic increment G dt D' before the Cayley
// rotation of the step's spin, half after (a symmetric splitting):
//   s* = Q (s_n + G dt D') Q^T + G dt D'.
// Against the exact flow of ds/dt = 2 G D' + W s - s W with constant L this agrees to O(dt^3)
// per step (rotating the whole increment after the rotation, or not at all, leaves an
// O(dt^2) error dt^2/2 [W, 2 G D'] per step: first order). A pure spin keeps s's invariants.
KOKKOS_INLINE_FUNCTION Sym elastic_trial_rotated(const Sym& s, const Mat3& L, Real G, Real dt) {
  const Sym d = strain_rate_deviator(L);
  const Real gdt = G * dt;
  const Sym half{s.xx + gdt * d.xx, s.yy + gdt * d.yy, s.zz + gdt * d.zz,
                 s.xy + gdt * d.xy, s.yz + gdt * d.yz, s.zx + gdt * d.zx};
  const Sym r = rotate(half, cayley_rotation(spin(L), dt));
  return deviator({r.xx + gdt * d.xx, r.yy + gdt * d.yy, r.zz + gdt * d.zz, r.xy + gdt * d.xy,
                   r.yz + gdt * d.yz, r.zx + gdt * d.zx});
}

struct ReturnResult {
  Real d_eps_p = 0;  // equivalent plastic strain increment, dimensionless
  Real work = 0;     // plastic work per unit volume, Mbar (divide by rho for per unit mass)
  bool yielded = false;
};

// Von Mises radial return of the trial deviator s (modified in place) to the yield surface of
// flow stress Y (Mbar), shear modulus G (Mbar).
KOKKOS_INLINE_FUNCTION ReturnResult radial_return(Sym& s, Real Y, Real G) {
  ReturnResult r;
  if (!(Y > 0)) {  // melted or no strength: no deviator survives
    s = Sym{};
    return r;
  }
  const Real j = von_mises(s);
  if (j <= Y) return r;
  s = scaled(s, Y / j);
  r.yielded = true;
  if (G > 0) {
    r.d_eps_p = (j - Y) / (3 * G);
    r.work = Y * r.d_eps_p;
  }
  return r;
}

// Deviatoric stress power over a step, per unit volume (Mbar): dt * s : D (only D' contributes
// since s is traceless). Pass the time-centred deviator (s^n + s^{n+1})/2.
KOKKOS_INLINE_FUNCTION Real deviatoric_work(const Sym& s, const Mat3& L, Real dt) {
  return dt * ddot(s, strain_rate(L));
}

}  // namespace mp::strength
