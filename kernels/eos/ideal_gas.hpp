// Ideal-gas equation of state, p = (gamma - 1) rho e, as point functions.
#pragma once
#include "core/math.hpp"

namespace mp::eos {

struct IdealGas {
  Real gamma;
  KOKKOS_INLINE_FUNCTION Real pressure(Real rho, Real e) const { return (gamma - 1) * rho * e; }
  // c^2 = (dp/drho)_e + p/rho^2 (dp/de)_rho = gamma p / rho
  KOKKOS_INLINE_FUNCTION Real sound_speed(Real /*rho*/, Real e) const {
    const Real c2 = gamma * (gamma - 1) * e;
    return c2 > 0 ? msqrt(c2) : Real(0);
  }
  KOKKOS_INLINE_FUNCTION Real energy(Real rho, Real p) const { return p / ((gamma - 1) * rho); }
};

}  // namespace mp::eos
