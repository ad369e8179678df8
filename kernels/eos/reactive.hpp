// A partly burnt explosive as an EOS closure of its burn fraction F, the products' EOS and,
// optionally, the unreacted solid's: p = F P_products(rho, e), or p = (1 - F) P_u(rho, e - e0) +
// F P_products(rho, e) (both phases at the cell's state), or the two phases at one pressure
// (he_equilibrium), with the sound speeds of the same definitions (docs/numerics.md, "Burn").
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
// (Its pressure: he_pressure_mixed, below, beside the pressure-equilibrium closure's.)
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

// The pressure-equilibrium closure (burn.closure: pressure_equilibrium): the two phases keep
// their own densities, at one pressure, and each carries the cell's specific energy,
//   (1 - f) v_u + f v_p = v,   e_u = e_p = e,   P_u(1/v_u, e - e0) = P_p(1/v_p, e),
// the cell's volume and energy shared exactly ((1 - f) e + f e = e). The thermal assumption is
// that of burning at constant volume and energy: a mass element that reacts turns into products
// of its own specific energy, and no energy passes between the phases as they come to one
// pressure (no p dV work exchanged, no common temperature: neither EOS here has one). The
// unknown is the volume fraction y of the phase of smaller mass fraction m (the products while
// f <= 1/2): that phase at rho m / y, the other at rho (1 - m) / (1 - y); their pressure difference
// is monotone in y wherever both (dP/drho)_e > 0, and Newton's method from y = m (equal
// densities: the shared-state closure's state), kept inside the bracket by bisection, finds its
// root to a few ulps. f <= 0 and f >= 1 are the pure phases.
struct PhaseSplit {
  Real p;             // the common pressure
  Real rho_u, rho_p;  // the phases' densities (rho_p = rho at f = 0, rho_u = rho at f = 1)
  int iterations;
};
// (dP/drho)_e of an EOS record from its c^2 = P_rho + P P_e / rho^2.
KOKKOS_INLINE_FUNCTION Real eos_dp_drho(const Eos& m, Real rho, Real e, Real p) {
  return m.sound_speed2(rho, e) - p * eos_dp_de(m, rho) / (rho * rho);
}
KOKKOS_INLINE_FUNCTION PhaseSplit he_equilibrium(const Eos& unreacted, const Eos& products, Real e0,
                                                 Real f, Real rho, Real e) {
  if (!(f > 0)) return {unreacted.pressure(rho, e - e0), rho, rho, 0};
  if (!(f < 1)) return {products.pressure(rho, e), rho, rho, 0};
  // the unknown is the volume fraction y of the phase with the smaller mass fraction m (a: it,
  // b: the other), so that y keeps its relative precision however small m is
  const bool prod_a = f <= Real(0.5);
  const Real m = prod_a ? f : 1 - f;
  const Eos& ea = prod_a ? products : unreacted;
  const Eos& eb = prod_a ? unreacted : products;
  const Real ea0 = prod_a ? e : e - e0, eb0 = prod_a ? e - e0 : e;
  // g(y) = P_b(rho (1 - m) / (1 - y)) - P_a(rho m / y) rises with y
  Real lo = 0, hi = 1, y = m;
  Real ra = rho, rb = rho, pb = 0;
  int it = 0;
  for (; it < 100; ++it) {
    ra = rho * m / y;
    rb = rho * (1 - m) / (1 - y);
    const Real pa = ea.pressure(ra, ea0);
    pb = eb.pressure(rb, eb0);
    const Real g = pb - pa;
    // (a few ulps of the larger pressure: Newton's last steps only dither about the root)
    if (!(mabs(g) > 8 * kRealEpsilon * mmax(mabs(pa), mabs(pb)))) break;
    if (g < 0)
      lo = y;
    else
      hi = y;
    const Real dg =
        eos_dp_drho(eb, rb, eb0, pb) * rb / (1 - y) + eos_dp_drho(ea, ra, ea0, pa) * ra / y;
    Real next = y - g / dg;
    // outside the bracket: its geometric mean (its arithmetic one while lo = 0)
    if (!(next > lo && next < hi)) next = lo > 0 ? msqrt(lo * hi) : Real(0.5) * hi;
    const bool done = mabs(next - y) <= 4 * kRealEpsilon * next;
    y = next;
    if (done) break;
  }
  ra = rho * m / y;
  rb = rho * (1 - m) / (1 - y);
  // the pressure of the majority phase (the better conditioned of the two)
  pb = eb.pressure(rb, eb0);
  return prod_a ? PhaseSplit{pb, rb, ra, it} : PhaseSplit{pb, ra, rb, it};
}
// Its frozen-f c^2 = (dp/drho)_e + p/rho^2 (dp/de)_rho, by implicit differentiation of the three
// conditions: with a_i = (dP_i/dv_i)_e = -rho_i^2 P_i,rho and b_i = (dP_i/de_i)_v,
//   K = f a_u + (1 - f) a_p,   (dp/dv)_e = a_u a_p / K,
//   (dp/de)_v = (f a_u b_p + (1 - f) a_p b_u) / K
// (f -> 0: a_u, b_u; f -> 1: a_p, b_p). Wood's frozen mixture sound speed would instead take
// each phase along its own isentrope; this is the closure's own derivative, as the
// shared-state closure's c^2 is its own.
KOKKOS_INLINE_FUNCTION Real he_sound_speed2_equilibrium(const Eos& unreacted, const Eos& products,
                                                        Real e0, Real f, Real rho, Real e) {
  if (!(f > 0)) return unreacted.sound_speed2(rho, e - e0);
  if (!(f < 1)) return products.sound_speed2(rho, e);
  const PhaseSplit s = he_equilibrium(unreacted, products, e0, f, rho, e);
  const Real pp = products.pressure(s.rho_p, e);
  const Real au = -s.rho_u * s.rho_u * eos_dp_drho(unreacted, s.rho_u, e - e0, s.p);
  const Real ap = -s.rho_p * s.rho_p * eos_dp_drho(products, s.rho_p, e, pp);
  const Real bu = eos_dp_de(unreacted, s.rho_u), bp = eos_dp_de(products, s.rho_p);
  const Real k = f * au + (1 - f) * ap;
  const Real dpdv = au * ap / k, dpde = (f * au * bp + (1 - f) * ap * bu) / k;
  const Real v = 1 / rho;
  return v * v * (s.p * dpde - dpdv);
}
// (dp/df)_{rho,e} at f = 0, what the Forest Fire rate divides by (burn/forest_fire.hpp): the
// unreacted phase squeezed by the first products, which take the volume v_p* where they stand at
// the solid's pressure P_u(rho, e - e0) with the cell's energy: dp/df = a_u (v - v_p*). Newton on
// the products alone from v_p = v (0 where the products are not stiffer than the solid there).
KOKKOS_INLINE_FUNCTION Real he_dpdf_equilibrium(const Eos& unreacted, const Eos& products, Real e0,
                                                Real rho, Real e) {
  const Real pu = unreacted.pressure(rho, e - e0);
  if (!(products.pressure(rho, e) > pu)) return 0;
  Real rp = rho;
  for (int it = 0; it < 100; ++it) {
    const Real pp = products.pressure(rp, e);
    Real next = rp - (pp - pu) / eos_dp_drho(products, rp, e, pp);
    if (!(next > 0)) next = Real(0.5) * rp;
    const bool done = mabs(next - rp) <= 4 * kRealEpsilon * next;
    rp = next;
    if (done) break;
  }
  const Real au = -rho * rho * eos_dp_drho(unreacted, rho, e - e0, pu);
  return au * (1 / rho - 1 / rp);
}

// The closure's pressure: shared state (the default), or pressure equilibrium (equilibrium).
KOKKOS_INLINE_FUNCTION Real he_pressure_mixed(const eos::Eos& unreacted, const eos::Eos& products,
                                              Real e0, Real f, Real rho, Real e,
                                              bool equilibrium = false) {
  if (equilibrium) return he_equilibrium(unreacted, products, e0, f, rho, e).p;
  return (1 - f) * unreacted.pressure(rho, e - e0) + f * products.pressure(rho, e);
}

// What the cycle uses (module.hpp mixed()): he_pressure_mixed with each phase's tension cutoff
// (eos.hpp pressure_cut; equal to he_pressure_mixed where neither phase has one), and the
// frozen-F sound speed floored as the EOS module floors its own. Below the void density
// (numerics.void_density, carried by the products' EOS, the explosive material's own) the
// explosive has no pressure and the floor's sound speed whatever its burn fraction, as every
// other material (eos.hpp pressure_cut, sound_speed_cut).
KOKKOS_INLINE_FUNCTION Real he_pressure_mixed_cut(const eos::Eos& unreacted,
                                                  const eos::Eos& products, Real e0, Real f,
                                                  Real rho, Real e, bool equilibrium = false) {
  if (products.is_void(rho)) return 0;
  if (equilibrium) {
    // (the common pressure cut off at the higher of the two phases' tension cutoffs)
    const Real p = he_equilibrium(unreacted, products, e0, f, rho, e).p;
    const Real cut = mmax(unreacted.p_min, products.p_min);
    return p < cut ? cut : p;
  }
  return (1 - f) * unreacted.pressure_cut(rho, e - e0) + f * products.pressure_cut(rho, e);
}
KOKKOS_INLINE_FUNCTION Real he_sound_speed_mixed(const eos::Eos& unreacted,
                                                 const eos::Eos& products, Real e0, Real f,
                                                 Real rho, Real e, bool equilibrium = false) {
  if (products.is_void(rho)) return msqrt(eos::kSoundSpeed2Floor);
  const Real c2 = equilibrium ? he_sound_speed2_equilibrium(unreacted, products, e0, f, rho, e)
                              : he_sound_speed2_mixed(unreacted, products, e0, f, rho, e);
  return msqrt(mmax(c2, eos::kSoundSpeed2Floor));
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
  bool equilibrium = false;  // mixed: the pressure-equilibrium closure (he_equilibrium) instead
};

}  // namespace mp::eos
