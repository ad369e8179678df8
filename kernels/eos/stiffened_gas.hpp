// Stiffened-gas equation of state, p = (gamma - 1) rho e - gamma p_inf, as point functions.
//
// Units: the project's cm / g / us system (kernels/materials/library.hpp): rho in g/cm^3, e in
// cm^2/us^2, p and p_inf in Mbar.
//
// Sound speed: c^2 = (dp/drho)_e + p/rho^2 (dp/de)_rho = (gamma - 1) e + (gamma - 1) p / rho
//            = gamma (p + p_inf) / rho.
// Validity: c^2 > 0 needs p + p_inf > 0, i.e. e > p_inf / rho. Outside (strong expansion of a
// liquid at low energy, where a real liquid would cavitate) c^2 is clamped to c2_floor, so p and
// c stay finite and c > 0, but the state is not physical.
#pragma once
#include "core/math.hpp"

namespace mp::eos {

struct StiffenedGas {
  Real gamma;
  Real p_inf;

  // Smallest c^2 handed out, (cm/us)^2: keeps c finite and positive outside the validity range.
  static constexpr Real c2_floor = Real(1e-24);

  KOKKOS_INLINE_FUNCTION Real pressure(Real rho, Real e) const {
    return (gamma - 1) * rho * e - gamma * p_inf;
  }
  // Analytic c^2, unclamped (may be <= 0 outside the validity range).
  KOKKOS_INLINE_FUNCTION Real sound_speed2(Real rho, Real e) const {
    return (gamma - 1) * (e + pressure(rho, e) / rho);
  }
  KOKKOS_INLINE_FUNCTION Real sound_speed(Real rho, Real e) const {
    return msqrt(mmax(sound_speed2(rho, e), c2_floor));
  }
  KOKKOS_INLINE_FUNCTION Real energy(Real rho, Real p) const {
    return (p + gamma * p_inf) / ((gamma - 1) * rho);
  }
};

}  // namespace mp::eos
