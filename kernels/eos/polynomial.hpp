// Polynomial equation of state in the compression mu = rho/rho0 - 1, as point functions.
//
// Units: cm / g / us (kernels/materials/library.hpp): rho in g/cm^3, e in cm^2/us^2, the A
// coefficients in Mbar, the B coefficients dimensionless.
//
//   compression (mu >= 0): p = A1 mu + A2 mu^2 + A3 mu^3 + (B0 + B1 mu) rho0 e
//   tension     (mu < 0):  p = A1 mu + B0 rho0 e
// The tension form is the usual one of hydrocodes (AUTODYN's polynomial EOS with its default
// tension coefficients T1 = A1, T2 = 0): the quadratic and cubic stiffening and the B1 term act in
// compression only. p and (dp/drho)_e are continuous at mu = 0.
//
// Sound speed: c^2 = (dp/drho)_e + p/rho^2 (dp/de)_rho with (dp/drho)_e = dp/dmu / rho0 and
// (dp/de)_rho = (B0 + B1 mu) rho0 (B0 rho0 in tension), analytic.
// Validity: a fit is valid over the compressions it was fitted on (typically mu <~ 1); the cubic
// keeps p finite at any compression. In tension c^2 = A1/rho0 + p B0 rho0/rho^2 drops to zero in
// strong expansion at low e; there, and wherever else c^2 <= 0, c^2 is clamped to c2_floor so p
// and c stay finite and c > 0 (the state is not physical).
#pragma once
#include "core/math.hpp"

namespace mp::eos {

struct Polynomial {
  Real rho0;        // reference density, g/cm^3
  Real a1, a2, a3;  // Mbar
  Real b0, b1;      // dimensionless

  static constexpr Real c2_floor = Real(1e-24);

  // p, (dp/drho)_e and (dp/de)_rho together.
  KOKKOS_INLINE_FUNCTION void evaluate(Real rho, Real e, Real& p, Real& dp_drho,
                                       Real& dp_de) const {
    const Real mu = rho / rho0 - 1;
    if (mu < 0) {
      p = a1 * mu + b0 * rho0 * e;
      dp_drho = a1 / rho0;
      dp_de = b0 * rho0;
      return;
    }
    p = mu * (a1 + mu * (a2 + mu * a3)) + (b0 + b1 * mu) * rho0 * e;
    dp_drho = (a1 + mu * (2 * a2 + 3 * a3 * mu) + b1 * rho0 * e) / rho0;
    dp_de = (b0 + b1 * mu) * rho0;
  }

  KOKKOS_INLINE_FUNCTION Real pressure(Real rho, Real e) const {
    Real p, dpr, dpe;
    evaluate(rho, e, p, dpr, dpe);
    return p;
  }
  // Analytic c^2, unclamped (may be <= 0 outside the validity range).
  KOKKOS_INLINE_FUNCTION Real sound_speed2(Real rho, Real e) const {
    Real p, dpr, dpe;
    evaluate(rho, e, p, dpr, dpe);
    return dpr + p * dpe / (rho * rho);
  }
  KOKKOS_INLINE_FUNCTION Real sound_speed(Real rho, Real e) const {
    return msqrt(mmax(sound_speed2(rho, e), c2_floor));
  }
};

}  // namespace mp::eos
