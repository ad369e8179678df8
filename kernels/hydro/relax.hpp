// Pressure relaxation of a mixed cell (DESIGN.md §4 item 2, the option beside equal strain).
//
// Equal strain gives every material of a cell the cell's relative volume change, so two
// materials of very different stiffness (water and air, copper and detonation products) leave
// the Lagrangian step at different pressures. Relaxation moves volume between the materials of
// the cell, at fixed cell volume, until their pressures agree:
//
//  - linearise each material's pressure along its isentrope about its current state,
//    p_m(V_m + dV_m) ~ p_m - K_m dV_m / V_m with K_m = rho_m c_m^2 (the adiabatic bulk modulus);
//  - the common pressure that makes sum dV_m = 0 is
//        P* = sum(V_m p_m / K_m) / sum(V_m / K_m),   dV_m = V_m (p_m - P*) / K_m
//    (the stiffness-weighted mean: a soft material takes almost all of the volume change);
//  - every material does work at the common pressure, e_m += -P* dV_m / M_m, so the cell's
//    internal energy sum M_m e_m is unchanged (sum dV_m = 0): relaxation conserves mass, volume
//    and energy of the cell exactly, and the compressed material gains the work the expanding
//    one gives up;
//  - the step is damped so that no material loses more than half or gains more than all of its
//    volume in one iteration (one common factor on every dV_m keeps sum dV_m = 0), which keeps
//    volumes and densities positive when a sliver of soft gas sits in a stiff liquid;
//  - iterate with the EOS re-evaluated until the pressures agree to `tol` relative to the
//    largest |p_m| or `max_iter` iterations are spent. The linearisation follows the isentrope
//    but the work is charged at P*, so this is a damped fixed-point iteration (linear, not
//    quadratic, convergence) and the end state depends on the path: the compressed material
//    gains more than isentropic work, as across a weak shock (a dissipative closure). With few
//    iterations the cell moves part of the way toward equilibrium each cycle.
//
// Works with any EOS kind of eos.hpp (the only EOS input is p and c^2 at (rho, e)). A material
// whose c^2 is not positive (outside its validity range, e.g. a stiffened gas below -p_inf) is
// thermodynamically unstable there: compressing it at its own pressure lowers that pressure
// further, and relaxing toward it runs away (its volume to zero). Such a material is left
// alone (volume and energy kept) and the others relax among themselves; with fewer than two
// materials in range nothing moves.
#pragma once
#include "core/math.hpp"
#include "eos/eos.hpp"

namespace mp::hydro {

struct RelaxResult {
  int iterations;  // iterations spent (Newton updates applied)
  Real spread;     // max |p_m - P*| / max |p_m| after the last update's EOS evaluation
};

// n materials with EOS eos[id[s]], volumes vol[s] (> 0), masses mass[s] (> 0) and specific
// energies e[s]. Updates vol and e in place; sum vol and sum mass e are kept (to round-off).
// p[s] gets the final material pressures. No volume is squeezed below v_min (the fraction
// floor times the cell volume: below it the other fractions round to 1 in float, see
// hydro::kMinFractionFloor); a material at the floor that still wants to shrink stops the
// relaxation of its cell, and the next remap removes it.
//
// relax_pressures_with takes the materials' closure as a callable, pc(s, rho, e, p, c2) setting
// material s's pressure and c^2 at (rho, e) (an explosive's p = F P_products with its frozen-F
// c^2, burn.hpp); relax_pressures is it with each material's own EOS.
template <class PC>
KOKKOS_INLINE_FUNCTION RelaxResult relax_pressures_with(int n, const PC& pc, Real* vol,
                                                        const Real* mass, Real* e, Real* p,
                                                        int max_iter, Real tol, Real v_min = 0) {
  constexpr int kMax = 16;
  Real wgt[kMax], dv[kMax];
  Real total = 0;
  for (int s = 0; s < n; ++s) total += vol[s];
  RelaxResult r{0, 0};
  for (int it = 0;; ++it) {
    Real num = 0, den = 0, scale = 0;
    int active = 0;
    for (int s = 0; s < n; ++s) {
      const Real rho = mass[s] / vol[s];
      Real c2 = 0;
      pc(s, rho, e[s], p[s], c2);
      // volume change per unit pressure change; 0: out of range, left alone
      wgt[s] = c2 > 0 ? vol[s] / (rho * c2) : Real(0);
      if (!(wgt[s] > 0)) continue;
      ++active;
      num += wgt[s] * p[s];
      den += wgt[s];
      scale = mmax(scale, mabs(p[s]));
    }
    if (active < 2) {  // nothing to relax; report the spread over all materials
      Real lo = p[0], hi = p[0], big = 0;
      for (int s = 0; s < n; ++s) {
        lo = mmin(lo, p[s]);
        hi = mmax(hi, p[s]);
        big = mmax(big, mabs(p[s]));
      }
      r.spread = big > 0 ? (hi - lo) / big : Real(0);
      break;
    }
    const Real pstar = num / den;
    // p_s - P* as sum_o w_o (p_s - p_o) / sum_o w_o: no cancellation when one weight dwarfs
    // the others (a soft gas beside a stiff solid, whose P* is the gas's p to round-off), so
    // sum dV = 0 holds to round-off.
    Real spread = 0;
    for (int s = 0; s < n; ++s) {
      dv[s] = 0;
      if (!(wgt[s] > 0)) continue;
      Real diff = 0;
      for (int o = 0; o < n; ++o) diff += wgt[o] * (p[s] - p[o]);
      diff /= den;
      spread = mmax(spread, mabs(diff));
      dv[s] = wgt[s] * diff;
    }
    r.spread = scale > 0 ? spread / scale : spread;
    if (!(r.spread > tol) || it == max_iter) break;
    // one factor on every dV: no material below half or above twice its volume per update
    Real theta = 1;
    for (int s = 0; s < n; ++s) {
      if (dv[s] < 0) {
        theta = mmin(theta, Real(0.5) * vol[s] / -dv[s]);
        theta = mmin(theta, mmax(Real(0), (vol[s] - v_min) / -dv[s]));
      }
      if (dv[s] > 0) theta = mmin(theta, vol[s] / dv[s]);
    }
    if (!(theta > 0)) break;
    Real sum = 0;
    for (int s = 0; s < n; ++s) {
      const Real d = theta * dv[s];
      e[s] -= pstar * d / mass[s];
      vol[s] += d;
      sum += vol[s];
    }
    // sum dV = 0 to round-off (above); rescale so the cell volume is kept to the last bit
    for (int s = 0; s < n; ++s) vol[s] *= total / sum;
    r.iterations = it + 1;
  }
  return r;
}

KOKKOS_INLINE_FUNCTION RelaxResult relax_pressures(int n, const eos::Eos* eos, const int* id,
                                                   Real* vol, const Real* mass, Real* e, Real* p,
                                                   int max_iter, Real tol, Real v_min = 0) {
  const auto own = [=](int s, Real rho, Real en, Real& ps, Real& c2) {
    ps = eos[id[s]].pressure(rho, en);
    c2 = eos[id[s]].sound_speed2(rho, en);
  };
  return relax_pressures_with(n, own, vol, mass, e, p, max_iter, tol, v_min);
}

// Solid floor of a mixed cell (docs/numerics.md, "Stretched solids in mixed cells"). Equal
// strain stretches every material of an expanding cell alike, so a sliver of metal beside a
// gas follows the gas toward vacuum densities, where the Mie-Grueneisen expansion branch
// (valid for rho/rho0 >~ 0.8) keeps a finite pressure and an unbounded c^2 (the perforator's
// step fell to 0.001 us at copper stretched below 1 % of rho0). A real solid fails in tension
// and opens void instead. Here a Mie-Grueneisen material whose volume exceeds
// mass / (rho_floor rho0) is put back at rho_floor x rho0; the volume it gives up goes to the
// cell's other materials in proportion to V / (rho c^2) (the soft ones take it, as in the
// relaxation) with no work done (free expansion into the opened void), so every mass, the cell
// volume and every material's energy are kept exactly. A Mie-Grueneisen taker stops at its own
// floor (its share goes to the other takers); what no taker can hold returns to the givers in
// proportion to what each gave. (The final rescale to the cell volume may leave a capped taker
// an ulp past its floor; the next call then has it give back that ulp.) Nothing moves when no other
// material can take the volume unless two or more materials are below the floor: then those share
// the volume they held at equal rho/rho0. Returns true when volumes changed.
KOKKOS_INLINE_FUNCTION bool solid_floor(int n, const eos::Eos* eos, const int* id, Real* vol,
                                        const Real* mass, const Real* e, Real rho_floor) {
  constexpr int kMax = 16;
  Real wgt[kMax], keep[kMax], room[kMax];
  Real give = 0, den = 0, total = 0;
  for (int s = 0; s < n; ++s) {
    total += vol[s];
    keep[s] = vol[s];
    room[s] = -1;  // what it may take (< 0: no limit)
    const eos::Eos& q = eos[id[s]];
    if (q.kind == eos::kMieGruneisen) {
      const Real vmax = mass[s] / (rho_floor * q.params[0]);  // params[0]: rho0
      if (vol[s] > vmax) {
        give += vol[s] - vmax;
        vol[s] = vmax;
        wgt[s] = 0;  // put back; takes nothing
        continue;
      }
      room[s] = vmax - vol[s];  // a solid taking volume stops at the floor itself
    }
    const Real rho = mass[s] / vol[s];
    const Real c2 = q.sound_speed2(rho, e[s]);
    wgt[s] = c2 > 0 ? vol[s] / (rho * c2) : Real(0);
    den += wgt[s];
  }
  if (!(give > 0)) return false;
  if (!(den > 0)) {
    // Every material is at the floor or cannot take volume (the zone-0.05 perforator's stop:
    // water, Mie-Grueneisen too, at 0.797 g/cm3 beside a steel sliver at 3e-7 rho0). With two
    // or more below the floor they share the volume they held so that each ends at the same
    // rho/rho0 (equal stretch: the sliver comes back, the water stretches a little); with one
    // nothing moves.
    int floored = 0;
    Real held = 0, need = 0;  // the floored materials' volume, and their sum of mass / rho0
    for (int s = 0; s < n; ++s) {
      if (!(vol[s] < keep[s])) continue;  // not floored
      ++floored;
      held += keep[s];
      need += mass[s] / eos[id[s]].params[0];
    }
    if (floored < 2) {
      for (int s = 0; s < n; ++s) vol[s] = keep[s];
      return false;
    }
    for (int s = 0; s < n; ++s)
      if (vol[s] < keep[s]) vol[s] = mass[s] / eos[id[s]].params[0] * (held / need);
    give = 0;
    den = 1;  // every weight is 0 here: nothing more to share
  }
  // The takers share `give` by weight; a Mie-Grueneisen taker stops at its own floor and its
  // share goes to the others. Without that limit a sliver of steel beside water put back at the
  // floor took the water's whole excess, 2 % of the cell, and came out at 1.2e-7 g/cm3 (the
  // default perforator's blow-up at 42.6 us). What no taker can hold stays with the materials
  // that gave it, in proportion to what each gave.
  Real left = give;
  bool full[kMax], placed = false;
  for (int s = 0; s < n; ++s) full[s] = false;
  for (int pass = 0; pass < n && left > 0; ++pass) {
    Real d = 0;
    for (int s = 0; s < n; ++s)
      if (wgt[s] > 0 && !full[s]) d += wgt[s];
    if (!(d > 0)) break;
    bool capped = false;
    for (int s = 0; s < n; ++s)
      if (wgt[s] > 0 && !full[s] && room[s] >= 0 && left * (wgt[s] / d) >= room[s]) {
        vol[s] += room[s];
        left -= room[s];
        full[s] = capped = true;
        placed = placed || room[s] > 0;
      }
    if (capped) continue;  // share what is left again among the others
    for (int s = 0; s < n; ++s)
      if (wgt[s] > 0 && !full[s]) vol[s] += left * (wgt[s] / d);
    left = 0;
    placed = true;
  }
  if (left > 0) {
    if (!placed) {  // nothing could be placed: nothing moves
      for (int s = 0; s < n; ++s) vol[s] = keep[s];
      return false;
    }
    for (int s = 0; s < n; ++s)
      if (wgt[s] == 0 && vol[s] < keep[s]) vol[s] += left * ((keep[s] - vol[s]) / give);
  }
  Real sum = 0;
  for (int s = 0; s < n; ++s) sum += vol[s];
  for (int s = 0; s < n; ++s) vol[s] *= total / sum;  // the cell volume to the last bit
  return true;
}

}  // namespace mp::hydro
