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

// donor_flux of face k of a k-column (remap::cell_flux, the compact layout's material faces):
// at(a, o) reads field a o cells along the axis from the face's high cell (face k lies between
// cells -1 and 0). The four cells around the face are loaded whatever the wind and the donor's
// stencil selected from them (fixed offsets: no branch on the wind).
template <class At, class A>
KOKKOS_INLINE_FUNCTION void column_face_flux(Real f, const At& at, const A& rho, const A& e,
                                             const A& pre, int order, Real& mass, Real& energy) {
  // the donor is the cell the flow leaves (-1 when f > 0, up -2, down 0; else 0, up 1, down -1)
  const bool pos = f > 0;
  const Real rm2 = at(rho, -2), rm1 = at(rho, -1), r0 = at(rho, 0), r1 = at(rho, 1);
  const Real em2 = at(e, -2), em1 = at(e, -1), e0 = at(e, 0), e1 = at(e, 1);
  const Real pm1 = at(pre, -1), p0 = at(pre, 0);  // (both loaded: no branch)
  donor_flux(f, pos ? pm1 : p0, pos ? rm2 : r1, pos ? rm1 : r0, pos ? r0 : rm1, pos ? em2 : e1,
             pos ? em1 : e0, pos ? e0 : em1, order, mass, energy);
}

}  // namespace mp::hydro
