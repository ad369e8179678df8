// Point functions of the staggered hydro scheme: they see a few numbers, never a view or a loop.
#pragma once
#include "core/math.hpp"

namespace mp::hydro {

// Artificial viscosity, quadratic (von Neumann–Richtmyer) plus linear (Landshoff), acting in
// compression only. `du` is the velocity jump across the cell (negative in compression).
KOKKOS_INLINE_FUNCTION Real viscosity(Real rho, Real c, Real du, Real c_quad, Real c_lin) {
  if (du >= 0) return 0;
  return rho * (c_quad * du * du - c_lin * c * du);
}

// A material's share of the cell's viscosity in a mixed cell: q is proportional to density, so
// each material sees q rho_m / rho (rho the cell's mean density). Under equal strain every
// material then receives the same viscous work per unit mass, -q dv / (rho V), and the sum over
// the materials, alpha_m rho_m V de_m, is the cell's -q dv exactly; the cell's q itself, built
// from the mean density, would charge a light material (air beside copper) rho / rho_m ~ 1e3
// times its share and drive its energy negative wherever q > 0 meets a net expansion. A pure
// cell gets q (rho_m == rho).
KOKKOS_INLINE_FUNCTION Real material_viscosity(Real q, Real rho_m, Real rho) {
  return q * (rho_m / rho);
}

// Christensen's monotonic limiter for the viscosity (Christensen, "Godunov methods on a
// staggered mesh: an improved artificial viscosity", UCRL-JC-105269, 1990): with the velocity
// jumps of the two neighbours along the same axis, returns the jump that the viscosity should
// see. A linear velocity field (smooth compression, r = 1) gives 0; a shock (r ~ 0) keeps all.
KOKKOS_INLINE_FUNCTION Real limited_jump(Real du_lo, Real du, Real du_hi) {
  if (du >= 0) return 0;
  const Real rl = du_lo / du, rr = du_hi / du;
  Real psi = Real(0.5) * (rl + rr);
  psi = psi < 2 * rl ? psi : 2 * rl;
  psi = psi < 2 * rr ? psi : 2 * rr;
  psi = psi < 1 ? psi : 1;
  psi = psi > 0 ? psi : 0;
  return du * (1 - psi);
}

// Value of a cell (or node) quantity on the face it flows through: donor value plus a
// van Leer-limited slope, time-centred by the Courant number `sigma` of the donor
// (second order; `order == 1` gives donor cell). up / donor / down are ordered along the wind.
KOKKOS_INLINE_FUNCTION Real face_value(Real up, Real donor, Real down, Real sigma, int order) {
  if (order == 1) return donor;
  const Real a = donor - up, b = down - donor;
  if (a * b <= 0) return donor;
  const Real slope = 2 * a * b / (a + b);  // van Leer's harmonic mean of the one-sided slopes
  return donor + Real(0.5) * (1 - sigma) * slope;
}

// Specific internal energy after the volume change dv of a cell (or material) of mass `mass`
// under pressure p and viscosity q: the Lagrangian p dV work, shared by the single- and
// multi-material predictor and corrector.
KOKKOS_INLINE_FUNCTION Real pdv_energy(Real e, Real p, Real q, Real dv, Real mass) {
  return e - (p + q) * dv / mass;
}

// The kinetic-energy fix (DeBar; Benson, Comput. Methods Appl. Mech. Eng. 99:235, 1992): a
// cell receives `de`, its share (per unit mass) of the kinetic energy the momentum remap took
// from its 8 nodes. The whole discrepancy is returned, both signs, so total energy is conserved
// to round-off; where the remap made kinetic energy (de < 0) a material gives at most half of
// its specific internal energy, which keeps near-vacuum cells positive (the 123 problem). Only
// that clamp, when it acts, leaves energy unconserved. Returns the least `de` a material of
// specific energy e may take.
KOKKOS_INLINE_FUNCTION Real ke_fix_floor(Real e) {
  return -Real(0.5) * e;
}

// Mass and internal-energy flux through a face with volume flux f (signed along the axis) out of
// a donor cell of volume `pre`, from van Leer face values of density (Courant number |f|/pre)
// and of specific energy (the mass Courant number). up / donor / down ordered along the wind.
KOKKOS_INLINE_FUNCTION void donor_flux(Real f, Real pre, Real rho_up, Real rho_d, Real rho_dn,
                                       Real e_up, Real e_d, Real e_dn, int order, Real& mass,
                                       Real& energy) {
  const Real sigma = mabs(f) / pre;
  const Real rf = face_value(rho_up, rho_d, rho_dn, sigma, order);
  mass = f * rf;
  const Real sm = mabs(mass) / (rho_d * pre);
  energy = mass * face_value(e_up, e_d, e_dn, sm, order);
}

}  // namespace mp::hydro
