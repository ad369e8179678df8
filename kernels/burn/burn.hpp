// High-explosive burn as point functions: the programmed-burn ramp, the CJ volume burn, the burn
// fraction update, and the pressure and sound speed of a partly burnt explosive.
// docs/numerics.md, "Burn", says what each choice is and where it comes from.
//
// Units: cm / g / us (kernels/materials/library.hpp): t in us, D in cm/us, lengths in cm,
// specific volumes in cm^3/g, p in Mbar.
//
// Model (the traditional hydrocode "program burn" that Bdzil, Stewart & Jackson, J. Comput.
// Phys. 174 (2001) 870, set out to improve; the FLAC3D JWL model documents the same
// p = lambda P_JWL): the explosive cell holds ONE material whose
// pressure is the products EOS scaled by its burn fraction F in [0, 1],
//   p = F P_products(rho, e),
// e being the specific internal energy including the chemical energy (e = e0 = E0 / rho0 for
// unreacted explosive at rest, kernels/eos/jwl.hpp). F rises from the lighting time on (the
// programmed ramp) or from compression toward the CJ volume (the CJ volume burn), whichever is
// larger, and never falls (the reaction is irreversible).
#pragma once
#include "core/math.hpp"
#include "eos/eos.hpp"

namespace mp::burn {

// Cells over which the programmed burn fraction ramps from 0 to 1 as the front passes
// (ramp length = kDefaultRampCells x the largest cell edge). A numerical choice, not physics:
// at the hydro's CFL 0.5 a cell takes about 2 n_ramp time steps to burn, which keeps the
// energy release from arriving as a one-step jump.
inline constexpr Real kDefaultRampCells = Real(2);

// Lighting time of a cell no detonator reaches (inert cells, or explosive cut off from every
// detonator): finite, so that health checks looking for non-finite values stay quiet, and far
// beyond any run.
inline constexpr Real kNeverLit = Real(1e30);

// 0 <= x <= 1.
KOKKOS_INLINE_FUNCTION Real clamp01(Real x) {
  return x < 0 ? Real(0) : (x > 1 ? Real(1) : x);
}

// Programmed-burn fraction at time t of a cell lit at t_light by a front of speed d_cj:
//   F = clamp((t - t_light) D / ramp_length, 0, 1),
// ramp_length = n_ramp x cell size (kDefaultRampCells). Zero before t_light, one once the front
// has travelled ramp_length past the cell centre.
KOKKOS_INLINE_FUNCTION Real programmed_burn_fraction(Real t, Real t_light, Real d_cj,
                                                     Real ramp_length) {
  if (t_light >= kNeverLit) return Real(0);
  return clamp01((t - t_light) * d_cj / ramp_length);
}

// CJ specific volume from the tabulated detonation speed D and CJ pressure (initial pressure
// neglected; Rayleigh line p = rho0^2 D^2 (v0 - v)): u_cj = p_cj / (rho0 D) and
//   v_cj / v0 = 1 - u_cj / D = 1 - p_cj / (rho0 D^2).
// Same jump conditions as eos::jwl_cj_from_tabulated (which returns rho_cj = 1 / v_cj).
KOKKOS_INLINE_FUNCTION Real cj_relative_volume(Real rho0, Real d_cj, Real p_cj) {
  return 1 - p_cj / (rho0 * d_cj * d_cj);
}
KOKKOS_INLINE_FUNCTION Real cj_specific_volume(Real rho0, Real d_cj, Real p_cj) {
  return cj_relative_volume(rho0, d_cj, p_cj) / rho0;
}

// CJ volume burn fraction: the cell burns as it is compressed from its initial specific volume
// v0 = 1/rho0 toward v_cj (the "beta burn" of Mader's Numerical Modeling of Explosives and
// Propellants; not read here, the formula is the definition):
//   F = clamp((v0 - v) / (v0 - v_cj), 0, 1).
KOKKOS_INLINE_FUNCTION Real volume_burn_fraction(Real v, Real v0, Real v_cj) {
  return clamp01((v0 - v) / (v0 - v_cj));
}

// What an explosive material needs to update its burn fraction; built once per material on the
// host from the library entry (rho0, D, p_cj) and the mesh (ramp length).
struct BurnParams {
  Real d_cj;         // detonation speed, cm/us
  Real ramp_length;  // n_ramp x cell size, cm
  Real v0;           // initial specific volume 1/rho0, cm^3/g
  Real v_cj;         // CJ specific volume, cm^3/g
  bool volume_burn;  // also burn on compression (CJ volume burn)
  bool programmed;   // burn from lighting times (programmed burn)
};

inline BurnParams make_burn_params(Real rho0, Real d_cj, Real p_cj, Real cell_size, bool programmed,
                                   bool volume_burn, Real ramp_cells = kDefaultRampCells) {
  BurnParams b;
  b.d_cj = d_cj;
  b.ramp_length = ramp_cells * cell_size;
  b.v0 = 1 / rho0;
  b.v_cj = cj_specific_volume(rho0, d_cj, p_cj);
  b.volume_burn = volume_burn;
  b.programmed = programmed;
  return b;
}

// The burn fraction after a step: the larger of the programmed and volume fractions (the
// combination production codes use, e.g. Radioss /MAT/LAW5 "IBFRAC = 0: volumetric compression
// + burning time"), and never below the old value (burning is irreversible).
// rho: the material's density at the end of the Lagrangian step; t: the time at its end.
KOKKOS_INLINE_FUNCTION Real update_burn_fraction(const BurnParams& b, Real f_old, Real t,
                                                 Real t_light, Real rho) {
  Real f = f_old;
  if (b.programmed) f = mmax(f, programmed_burn_fraction(t, t_light, b.d_cj, b.ramp_length));
  if (b.volume_burn) f = mmax(f, volume_burn_fraction(1 / rho, b.v0, b.v_cj));
  return f;
}

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

}  // namespace mp::burn
