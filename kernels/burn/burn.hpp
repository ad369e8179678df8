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
#include "eos/reactive.hpp"

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

// The partly burnt explosive's EOS closure (he_pressure, he_sound_speed, their unreacted +
// products forms) is an EOS: kernels/eos/reactive.hpp; the burn module's code names it here.
using eos::eos_dp_de;
using eos::he_pressure;
using eos::he_pressure_mixed;
using eos::he_pressure_mixed_cut;
using eos::he_sound_speed;
using eos::he_sound_speed2;
using eos::he_sound_speed2_mixed;
using eos::he_sound_speed_mixed;

}  // namespace mp::burn
