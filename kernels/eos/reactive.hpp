// A partly burnt explosive as an EOS closure of its burn fraction F, the products' EOS and,
// optionally, the unreacted solid's: p = F P_products(rho, e), or p = (1 - F) P_u(rho, e - e0) +
// F P_products(rho, e), with the sound speeds of the same definitions (docs/numerics.md, "Burn").
// The hydro's EOS kernels evaluate it where a module burns an explosive (Reactive, below); the
// burn module (kernels/burn/) updates F.
#pragma once
#include "core/math.hpp"
#include "core/types.hpp"
#include "eos/eos.hpp"

namespace mp::eos {

// (dP/de)_rho of an EOS record: every EOS of eos.hpp is linear in e at fixed rho.
KOKKOS_INLINE_FUNCTION Real eos_dp_de(const eos::Eos& m, Real rho) {
  switch (m.kind) {
    case eos::kStiffenedGas:
      return (m.params[0] - 1) * rho;  // (gamma - 1) rho
    case eos::kMieGruneisen:
      return m.params[3] * m.params[0];  // gamma0 rho0 (eos/mie_gruneisen.hpp)
    case eos::kPolynomial: {
      Real p, dpr, dpe;
      m.polynomial().evaluate(rho, Real(0), p, dpr, dpe);
      return dpe;
    }
    case eos::kJwl:
      return m.params[5] * rho;  // omega rho
    default:
      return (m.params[0] - 1) * rho;  // ideal gas: (gamma - 1) rho
  }
}

// Pressure of an explosive with burn fraction f: p = f P_products(rho, e).
KOKKOS_INLINE_FUNCTION Real he_pressure(const eos::Eos& products, Real f, Real rho, Real e) {
  return f * products.pressure(rho, e);
}

// Sound speed squared of p = f P(rho, e) at frozen f, from the same definition the EOS use,
// c^2 = (dp/drho)_e + p / rho^2 (dp/de)_rho, with (dp/drho)_e = f P_rho, (dp/de)_rho = f P_e:
//   c^2 = f c_P^2 - f (1 - f) P P_e / rho^2,
// c_P^2 = P_rho + P P_e / rho^2 being the products' own. Unclamped (0 at f = 0: unreacted
// explosive carries no pressure in this model). For the time step the products' c_P (the
// larger, f <= 1 and P >= 0) is the safe choice once f > 0, since f itself grows at a rate
// D / ramp_length the frozen c does not see.
KOKKOS_INLINE_FUNCTION Real he_sound_speed2(const eos::Eos& products, Real f, Real rho, Real e) {
  const Real p = products.pressure(rho, e);
  return f * products.sound_speed2(rho, e) -
         f * (1 - f) * p * eos_dp_de(products, rho) / (rho * rho);
}
KOKKOS_INLINE_FUNCTION Real he_sound_speed(const eos::Eos& products, Real f, Real rho, Real e) {
  return msqrt(mmax(he_sound_speed2(products, f, rho, e), eos::kSoundSpeed2Floor));
}

// The alternative closure, for an explosive whose unreacted solid has an EOS of its own: the
// two phases share (rho, e), the unreacted one measuring its energy from the unburnt state,
//   p = (1 - f) P_u(rho, e - e0) + f P_p(rho, e),
// so unburnt explosive (f = 0) carries the shocks its solid EOS gives it (e = e0 at rest:
// P_u(rho0, 0) = 0 for a solid referenced at rho0). No pressure equilibrium between the phases
// (a simplification). c^2 at frozen f from the same definition, with p_rho = sum w_i P_i,rho
// and p_e = sum w_i P_i,e:
//   c^2 = sum_i w_i (c_i^2 - P_i P_i,e / rho^2) + p p_e / rho^2.
KOKKOS_INLINE_FUNCTION Real he_pressure_mixed(const eos::Eos& unreacted, const eos::Eos& products,
                                              Real e0, Real f, Real rho, Real e) {
  return (1 - f) * unreacted.pressure(rho, e - e0) + f * products.pressure(rho, e);
}
KOKKOS_INLINE_FUNCTION Real he_sound_speed2_mixed(const eos::Eos& unreacted,
                                                  const eos::Eos& products, Real e0, Real f,
                                                  Real rho, Real e) {
  const Real pu = unreacted.pressure(rho, e - e0), pp = products.pressure(rho, e);
  const Real eu = eos_dp_de(unreacted, rho), ep = eos_dp_de(products, rho);
  const Real r2 = rho * rho;
  const Real p = (1 - f) * pu + f * pp, pe = (1 - f) * eu + f * ep;
  return (1 - f) * (unreacted.sound_speed2(rho, e - e0) - pu * eu / r2) +
         f * (products.sound_speed2(rho, e) - pp * ep / r2) + p * pe / r2;
}

// What the cycle uses (module.hpp mixed()): he_pressure_mixed with each phase's tension cutoff
// (eos.hpp pressure_cut; equal to he_pressure_mixed where neither phase has one), and the
// frozen-F sound speed floored as the EOS module floors its own. Below the void density
// (numerics.void_density, carried by the products' EOS, the explosive material's own) the
// explosive has no pressure and the floor's sound speed whatever its burn fraction, as every
// other material (eos.hpp pressure_cut, sound_speed_cut).
KOKKOS_INLINE_FUNCTION Real he_pressure_mixed_cut(const eos::Eos& unreacted,
                                                  const eos::Eos& products, Real e0, Real f,
                                                  Real rho, Real e) {
  if (products.is_void(rho)) return 0;
  return (1 - f) * unreacted.pressure_cut(rho, e - e0) + f * products.pressure_cut(rho, e);
}
KOKKOS_INLINE_FUNCTION Real he_sound_speed_mixed(const eos::Eos& unreacted,
                                                 const eos::Eos& products, Real e0, Real f,
                                                 Real rho, Real e) {
  if (products.is_void(rho)) return msqrt(eos::kSoundSpeed2Floor);
  return msqrt(
      mmax(he_sound_speed2_mixed(unreacted, products, e0, f, rho, e), eos::kSoundSpeed2Floor));
}

// What the hydro's EOS kernels need of a burning explosive (hydro::Module::reactive): its
// material (-1: the scene's one material), its burn fraction per cell, the CJ detonation speed
// (the sound speed's floor where F < 1), and the unreacted closure where there is one.
struct Reactive {
  int material = -1;
  Field3 fraction;
  Real d_cj = 0;
  bool mixed = false;  // p = (1 - F) P_u(rho, e - e0) + F P(rho, e); else p = F P(rho, e)
  Eos unreacted;
  Real e0 = 0;
};

}  // namespace mp::eos
