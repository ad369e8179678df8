// The remap's advection as point functions: a quantity's van Leer face value time-centred by
// the donor's Courant number, and the mass and energy fluxes of a face from them. The hydro's
// sweeps (kernels/hydro/), the multi-material faces and the modules' per-mass quantities
// (per_mass.hpp) all advect through these.
#pragma once

#include "core/math.hpp"

namespace mp::remap {

// Value of a cell (or node) quantity on the face it flows through: the donor value plus a
// limited slope S times (1 - sigma) / 2, time-centred by the Courant number `sigma` of the
// donor. up / donor / down are ordered along the wind; a = donor - up, b = down - donor.
//   order 1: donor cell (S = 0).
//   order 2: van Leer's harmonic mean of the one-sided slopes, S = 2ab / (a + b) (second order).
//   order 3: the Courant-weighted 3-point slope S3 = ((1 + sigma) a + (2 - sigma) b) / 3, bounded
//            by van Leer's monotonicity constraint |S| <= 2 min(|a|, |b|) (docs/numerics.md,
//            "Third-order advection"). S3 makes the face value the exact mean, over the slab
//            of width sigma the face takes from the donor, of the parabola with the three cells'
//            averages: third order in space and time on a uniform mesh where the bound does not
//            bind (Leonard's QUICKEST, Comput. Methods Appl. Mech. Eng. 19 (1979) 59; the
//            3-point gradient in a second-order Taylor expansion of the PAGOSA paper's "variant
//            of van Leer's monotonic upwind scheme discussed by Youngs", Youngs 1982).
//   order -2, -3 (verification only, Hydro::set_unlimited): the unbounded slopes, Fromm's
//            (a + b) / 2 and S3, also at extrema; they oscillate at a discontinuity.
// Both limited slopes lie inside the TVD region 0 <= S / a <= 2 min(1, b / a) (S3 is a weighted
// mean of a and b, so the bound binds only where one difference exceeds about twice the other),
// and both are 0 at an extremum (a b <= 0).
KOKKOS_INLINE_FUNCTION Real face_value(Real up, Real donor, Real down, Real sigma, int order) {
  if (order == 1) return donor;
  const Real a = donor - up, b = down - donor;
  if (order < 0)
    return donor + Real(0.5) * (1 - sigma) *
                       (order == -3 ? ((1 + sigma) * a + (2 - sigma) * b) * Real(1.0 / 3.0)
                                    : Real(0.5) * (a + b));
  if (a * b <= 0) return donor;
  if (order == 3) {
    const Real s3 = ((1 + sigma) * a + (2 - sigma) * b) * Real(1.0 / 3.0);
    const Real bound = 2 * mmin(mabs(a), mabs(b));
    const Real slope = a > 0 ? mmin(s3, bound) : mmax(s3, -bound);
    return donor + Real(0.5) * (1 - sigma) * slope;
  }
  const Real slope = 2 * a * b / (a + b);  // van Leer's harmonic mean of the one-sided slopes
  return donor + Real(0.5) * (1 - sigma) * slope;
}

// Mass and internal-energy flux through a face with volume flux f (signed along the axis) out of
// a donor cell of volume `pre`, from the limited face values of density (Courant number |f|/pre)
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

}  // namespace mp::remap
