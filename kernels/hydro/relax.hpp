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
//  - the step is damped so that no material loses more than half its volume in one iteration
//    (one common factor on every dV_m keeps sum dV_m = 0), which keeps volumes and densities
//    positive when a sliver of soft gas sits in a stiff liquid;
//  - iterate with the EOS re-evaluated (Newton on the linearised system) until the pressures
//    agree to `tol` relative to the largest |p_m| or `max_iter` iterations are spent. With few
//    iterations the cell moves part of the way toward equilibrium each cycle.
//
// Works with any EOS kind of eos.hpp (the only EOS input is p and c^2 at (rho, e)); a material
// whose c^2 is not positive (outside its validity range) gets the floor kSoundSpeed2Floor and
// so takes (almost) all of the volume change, which is the stable choice.
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
// p[s] gets the final material pressures.
KOKKOS_INLINE_FUNCTION RelaxResult relax_pressures(int n, const eos::Eos* eos, const int* id,
                                                   Real* vol, const Real* mass, Real* e, Real* p,
                                                   int max_iter, Real tol) {
  constexpr int kMax = 16;
  Real k[kMax], dv[kMax];
  Real total = 0;
  for (int s = 0; s < n; ++s) total += vol[s];
  RelaxResult r{0, 0};
  for (int it = 0;; ++it) {
    Real num = 0, den = 0, scale = 0;
    for (int s = 0; s < n; ++s) {
      const Real rho = mass[s] / vol[s];
      p[s] = eos[id[s]].pressure(rho, e[s]);
      k[s] = rho * mmax(eos[id[s]].sound_speed2(rho, e[s]), eos::kSoundSpeed2Floor);
      num += vol[s] * p[s] / k[s];
      den += vol[s] / k[s];
      scale = mmax(scale, mabs(p[s]));
    }
    const Real pstar = num / den;
    Real spread = 0;
    for (int s = 0; s < n; ++s) spread = mmax(spread, mabs(p[s] - pstar));
    r.spread = scale > 0 ? spread / scale : spread;
    if (!(r.spread > tol) || it == max_iter) break;
    Real theta = 1;
    for (int s = 0; s < n; ++s) {
      dv[s] = vol[s] * (p[s] - pstar) / k[s];
      if (dv[s] < 0) theta = mmin(theta, Real(0.5) * vol[s] / -dv[s]);
    }
    Real sum = 0;
    for (int s = 0; s < n; ++s) {
      const Real d = theta * dv[s];
      e[s] -= pstar * d / mass[s];
      vol[s] += d;
      sum += vol[s];
    }
    // sum dV = 0 in exact arithmetic; rescale so the cell volume is kept to the last bit
    for (int s = 0; s < n; ++s) vol[s] *= total / sum;
    r.iterations = it + 1;
  }
  return r;
}

}  // namespace mp::hydro
