// Mie-Grueneisen equation of state referenced to a linear Us-up shock Hugoniot, as point
// functions.
//
// Units: cm / g / us (kernels/materials/library.hpp): rho in g/cm^3, e in cm^2/us^2 (energy per
// mass, zero at the ambient reference state), c0 in cm/us, p in Mbar.
//
// Reference curve: the principal Hugoniot from (rho0, e = 0, p = 0) with Us = c0 + s up. With
// eta = 1 - rho0/rho the jump conditions give
//   p_H(eta) = rho0 c0^2 eta / (1 - s eta)^2,   e_H(eta) = p_H eta / (2 rho0).
// Grueneisen coefficient: rho Gamma = rho0 Gamma0 (Gamma / V constant; Steinberg's first-order
// volume correction b is NOT used), so
//   compression (mu = rho/rho0 - 1 >= 0):  p = p_H + Gamma0 rho0 (e - e_H),
//   tension     (mu < 0):                  p = rho0 c0^2 mu + Gamma0 rho0 e.
// Both branches agree to first order at mu = 0 (same p and same (dp/drho)_e = c0^2 there), so p
// and c are continuous across rho0 for any e.
//
// Sound speed: c^2 = (dp/drho)_e + p/rho^2 (dp/de)_rho with (dp/de)_rho = Gamma0 rho0, derivatives
// analytic (below).
//
// Validity range and guards:
//  - p_H is singular at eta = 1/s (rho/rho0 = s/(s-1), e.g. 3.0 for copper, 2.1 for water). The
//    Us-up data behind the fits stop far below that, so beyond eta_l = 0.9/s the reference curve is
//    continued by its tangent at eta_l (p_H linear in eta): finite and monotone at any compression,
//    but not data. Every state on the Us-up line has eta = up/Us < 1/s; those with
//    up < 9 c0 / s (tens of km/s for metals) lie below eta_l and are reproduced exactly.
//  - In tension, c^2 = c0^2 + p Gamma0 rho0/rho^2 falls to zero near rho/rho0 ~ 0.73 for
//    Gamma0 ~ 2 at e = 0 (the root of x^2 + Gamma0 (x - 1) = 0). Real solids spall well before
//    that; this linear form is meant for rho/rho0 >~ 0.8. Below it (and at any extreme expansion)
//    c^2 is clamped to c2_floor: p and c stay finite, c > 0, the state is not physical.
#pragma once
#include "core/math.hpp"

namespace mp::eos {

struct MieGruneisen {
  Real rho0;    // reference density, g/cm^3
  Real c0;      // Us intercept, cm/us
  Real s;       // Us-up slope, dimensionless
  Real gamma0;  // Grueneisen coefficient at rho0, dimensionless

  static constexpr Real c2_floor = Real(1e-24);

  // Compression at which the tangent continuation of the Hugoniot takes over.
  KOKKOS_INLINE_FUNCTION Real eta_limit() const { return Real(0.9) / mmax(s, Real(1)); }

  // Reference Hugoniot pressure and d p_H / d eta, with the tangent continuation past eta_limit.
  KOKKOS_INLINE_FUNCTION void hugoniot(Real eta, Real& ph, Real& dph) const {
    const Real k = rho0 * c0 * c0;
    const Real eta_l = eta_limit();
    const Real x = mmin(eta, eta_l);
    const Real d = 1 - s * x;
    const Real ph_x = k * x / (d * d);
    const Real dph_x = k * (1 + s * x) / (d * d * d);
    ph = ph_x + (eta > eta_l ? dph_x * (eta - eta_l) : Real(0));
    dph = dph_x;
  }

  // p and (dp/drho)_e together; (dp/de)_rho = gamma0 rho0 everywhere.
  KOKKOS_INLINE_FUNCTION void pressure_and_dp_drho(Real rho, Real e, Real& p, Real& dp) const {
    const Real g = gamma0 * rho0;
    if (rho < rho0) {  // tension / expansion branch, mu < 0
      p = rho0 * c0 * c0 * (rho / rho0 - 1) + g * e;
      dp = c0 * c0;
      return;
    }
    const Real eta = 1 - rho0 / rho;
    Real ph, dph;
    hugoniot(eta, ph, dph);
    const Real eh = ph * eta / (2 * rho0);
    const Real deh = (dph * eta + ph) / (2 * rho0);
    p = ph + g * (e - eh);
    dp = (dph - g * deh) * rho0 / (rho * rho);
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
    return dp + p * gamma0 * rho0 / (rho * rho);
  }
  KOKKOS_INLINE_FUNCTION Real sound_speed(Real rho, Real e) const {
    return msqrt(mmax(sound_speed2(rho, e), c2_floor));
  }
};

}  // namespace mp::eos
