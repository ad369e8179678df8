// Jones-Wilkins-Lee (JWL) equation of state for detonation products, as point functions, and the
// Chapman-Jouguet (CJ) state of a parameter set.
//
// Units: cm / g / us (kernels/materials/library.hpp): rho in g/cm^3, e in cm^2/us^2, A, B, p in
// Mbar; R1, R2, omega dimensionless.
//
//   p = A (1 - omega/(R1 V)) exp(-R1 V) + B (1 - omega/(R2 V)) exp(-R2 V) + omega rho e,
//   V = rho0 / rho  (relative volume, rho0 = unreacted explosive density).
// (Lee, Hornig & Kury, UCRL-50422, 1968; Dobratz & Crawford, LLNL Explosives Handbook,
// UCRL-52997, 1985, sec. 8.) The energy e is per mass and includes the chemical energy: the
// unreacted explosive at rest has e = e0 = E0 / rho0, E0 being the detonation energy per unit
// initial volume that the handbooks tabulate (Mbar cm^3/cm^3).
//
// Sound speed: c^2 = (dp/drho)_e + p/rho^2 (dp/de)_rho, with (dp/de)_rho = omega rho and
//   (dp/drho)_e = -(V/rho) sum_i A_i exp(-R_i V) [omega/(R_i V^2) - R_i + omega/V] + omega e.
// Validity: the fits are made to cylinder-test expansions from the CJ state, V ~ 0.7 .. 7; the
// form stays finite for any V > 0 (the exponentials underflow to 0 in strong expansion, where the
// products become an omega+1 ideal gas). c^2 <= 0 (e.g. e <= 0 in strong expansion) is clamped to
// c2_floor so p and c stay finite with c > 0 (the state is not physical).
#pragma once
#include "core/math.hpp"

namespace mp::eos {

struct Jwl {
  Real rho0;  // unreacted explosive density, g/cm^3
  Real a, b;  // Mbar
  Real r1, r2;
  Real omega;

  static constexpr Real c2_floor = Real(1e-24);

  // p and (dp/drho)_e together.
  KOKKOS_INLINE_FUNCTION void pressure_and_dp_drho(Real rho, Real e, Real& p, Real& dp) const {
    const Real v = rho0 / rho;
    const Real x1 = a * MP_KOKKOS_MATH::exp(-r1 * v);
    const Real x2 = b * MP_KOKKOS_MATH::exp(-r2 * v);
    p = x1 * (1 - omega / (r1 * v)) + x2 * (1 - omega / (r2 * v)) + omega * rho * e;
    const Real dp_dv =
        x1 * (omega / (r1 * v * v) - r1 + omega / v) + x2 * (omega / (r2 * v * v) - r2 + omega / v);
    dp = -dp_dv * v / rho + omega * e;
  }

  KOKKOS_INLINE_FUNCTION Real pressure(Real rho, Real e) const {
    Real p, dp;
    pressure_and_dp_drho(rho, e, p, dp);
    return p;
  }
  // Analytic c^2, unclamped (may be <= 0 outside the validity range).
  KOKKOS_INLINE_FUNCTION Real sound_speed2(Real rho, Real e) const {
    Real p, dp;
    pressure_and_dp_drho(rho, e, p, dp);
    return dp + p * omega / rho;
  }
  KOKKOS_INLINE_FUNCTION Real sound_speed(Real rho, Real e) const {
    return msqrt(mmax(sound_speed2(rho, e), c2_floor));
  }
};

// A CJ state: products density, energy per mass, pressure, particle velocity, detonation speed.
struct JwlCjState {
  Real rho, e, p, u, d;
};

// The CJ state as the handbooks document it: from the tabulated detonation speed D and CJ
// pressure p_cj (initial pressure neglected) the jump conditions give
//   u_cj = p_cj / (rho0 D),  rho_cj = rho0 D / (D - u_cj),
//   e_cj = e0 + p_cj / 2 (1/rho0 - 1/rho_cj),
// with e0 = E0 / rho0 the detonation energy per mass. A JWL fit reproduces this only to the
// accuracy of the fit: p(rho_cj, e_cj) ~ p_cj and c(rho_cj, e_cj) + u_cj ~ D within a few %.
KOKKOS_INLINE_FUNCTION JwlCjState jwl_cj_from_tabulated(const Jwl& j, Real e0, Real d, Real p_cj) {
  JwlCjState s;
  s.d = d;
  s.p = p_cj;
  s.u = p_cj / (j.rho0 * d);
  s.rho = j.rho0 * d / (d - s.u);
  s.e = e0 + Real(0.5) * p_cj * (1 / j.rho0 - 1 / s.rho);
  return s;
}

// The CJ state the parameters themselves imply: the point of the products Hugoniot from
// (rho0, e0, p = 0) where the Rayleigh line is tangent, i.e. the minimum detonation speed
//   D^2(v) = v0^2 p_H(v) / (v0 - v),  p_H(v) = (g(v) + omega e0 / v) / (1 - omega (v0 - v)/(2 v)),
// over specific volumes v in (omega v0 / (2 + omega), v0), g being the two exponential terms.
// Found by golden-section search; at the minimum the flow is sonic, c + u = D.
inline JwlCjState jwl_cj_state(const Jwl& j, Real e0) {
  const Real v0 = 1 / j.rho0;
  auto hugoniot_p = [&](Real v) {
    const Real rho = 1 / v;
    const Real p_cold = j.pressure(rho, Real(0));
    return (p_cold + j.omega * e0 / v) / (1 - j.omega * (v0 - v) / (2 * v));
  };
  auto d2 = [&](Real v) { return v0 * v0 * hugoniot_p(v) / (v0 - v); };
  Real lo = j.omega * v0 / (2 + j.omega) * (1 + Real(1e-6));
  Real hi = v0 * (1 - Real(1e-9));
  const Real phi = Real(0.6180339887498949);
  Real x1 = hi - phi * (hi - lo);
  Real x2 = lo + phi * (hi - lo);
  Real f1 = d2(x1);
  Real f2 = d2(x2);
  for (int it = 0; it < 200 && hi - lo > Real(1e-15) * v0; ++it) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - phi * (hi - lo);
      f1 = d2(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + phi * (hi - lo);
      f2 = d2(x2);
    }
  }
  const Real v = Real(0.5) * (lo + hi);
  JwlCjState s;
  s.rho = 1 / v;
  s.p = hugoniot_p(v);
  s.d = msqrt(d2(v));
  s.u = s.d * (1 - v / v0);
  s.e = e0 + Real(0.5) * s.p * (v0 - v);
  return s;
}

}  // namespace mp::eos
