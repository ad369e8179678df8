// Forest Fire reactive burn as point functions: a burn rate that is a function of the local
// pressure alone, constructed from the explosive's Pop plot and its unreacted shock Hugoniot
// (C. L. Mader and C. A. Forest, "Two-dimensional homogeneous and heterogeneous detonation wave
// propagation", LA-6259, 1976; C. L. Mader, Numerical Modeling of Explosives and Propellants,
// the Forest Fire chapter). Neither text was read here; the construction below is derived from
// its two stated assumptions, and docs/numerics.md, "Burn", sets it out.
//
// Units: cm / g / us; p in Mbar; rates in 1/us.
//
// 1. Single-curve buildup: a shock of pressure P has run x*(P_0) - x*(P) since it entered the
//    explosive at P_0, x* the Pop plot's run distance to detonation; so along the shock
//      dP_s/dx_s = -1 / (dx*/dP) = P / (-b x*(P)),   log10 x* = a + b log10 P  (b < 0).
// 2. The reaction behind the shock front drives its growth: the forward characteristic's
//    relation dp + rho c du = (dp/dlambda)_{rho,e} R dt, evaluated along the shock path with the
//    unreacted Hugoniot's dp/du = rho0 Us (1 + (up/Us) dUs/dup), gives the rate at the front
//      R(P) = Us (dP_s/dx_s) [1 + rho c / (rho0 Us (1 + s up / Us))] / (dp/dlambda)_{rho,e},
//    all at the unreacted Hugoniot state of pressure P (Us = c0 + s up). The same shock-change
//    construction is R. Menikoff and M. S. Shaw's (Review of the Forest Fire model, LA-UR-07-2272,
//    2007), whose form LANL EOSlib's FFrate evaluates; read there, not copied.
// Forest Fire then applies R(P) everywhere, to the local pressure: -(1/W) dW/dt = R(p), W = 1 - F
// the unreacted mass fraction (Mader's form; Mader fits log R by a polynomial in P, here it is
// evaluated directly). dp/dlambda and c are those of the code's own mixture closure at F = 0
// (eos/reactive.hpp): c is the unreacted solid's, and dp/dF = P_products(rho, e) - P_u(rho, e - e0)
// with both phases at the cell's state (he_pressure_mixed), or (dP_u/dv)_e (v - v_p*) with the
// phases at one pressure (he_dpdf_equilibrium).
#pragma once
#include "core/math.hpp"
#include "eos/eos.hpp"
#include "eos/reactive.hpp"

namespace mp::burn {

// A Pop plot, log10(x* / cm) = a + b log10(P / Mbar), b < 0.
struct PopPlot {
  Real a = 0, b = -1;
};

// The cited Pop plots, as their source writes them: log10(P / GPa) = A - B log10(x* / mm).
struct PopPlotData {
  const char* name;
  double A, B;
  double rho0;  // the density the data are for, g/cm^3
  const char* citation;
};

// PBX 9404 at 1.84 g/cm^3: A = 1.11, B = 0.65 (T. R. Gibbs and A. Popolato (eds.),
// LASL Explosive Property Data, University of California Press, 1980, p. 93; read in the
// transcription of LANL EOSlib, github.com/lanl/EOSlib DATA/HOM.data, `HErate:FFrate=PBX9404`,
// which names that page; the book was not read).
inline constexpr PopPlotData kPopPlots[] = {
    {"pbx9404", 1.11, 0.65, 1.84,
     "Gibbs & Popolato, LASL Explosive Property Data (1980) p. 93, via LANL EOSlib HOM.data"},
};

inline const PopPlotData* find_pop_plot(const char* name) {
  for (const PopPlotData& d : kPopPlots) {
    const char *x = d.name, *y = name;
    while (*x && *x == *y) ++x, ++y;
    if (*x == 0 && *y == 0) return &d;
  }
  return nullptr;
}

// log10(P/GPa) = A - B log10(x/mm)  ->  log10(x/cm) = a + b log10(P/Mbar):
// x/mm = 10 x/cm, P/GPa = 100 P/Mbar, so a = (A - 2) / B - 1, b = -1 / B.
inline PopPlot pop_plot_from_gpa_mm(double A, double B) {
  PopPlot p;
  p.a = Real((A - 2) / B - 1);
  p.b = Real(-1 / B);
  return p;
}

// Run distance to detonation x*(P), cm.
KOKKOS_INLINE_FUNCTION Real pop_run_distance(const PopPlot& pp, Real p) {
  return MP_KOKKOS_MATH::pow(Real(10), pp.a + pp.b * MP_KOKKOS_MATH::log10(p));
}
// The inverse: the input pressure whose run distance is x, Mbar.
KOKKOS_INLINE_FUNCTION Real pop_pressure(const PopPlot& pp, Real x) {
  return MP_KOKKOS_MATH::pow(Real(10), (MP_KOKKOS_MATH::log10(x) - pp.a) / pp.b);
}

// What the Forest Fire rate needs: the Pop plot, the unreacted Hugoniot (Us = c0 + s up from
// rho0 at e = e0, p = 0), the two EOS of the mixture closure, and where the rate stops growing.
struct ForestFire {
  PopPlot pop;
  Real rho0 = 0, c0 = 0, s = 0;  // unreacted Hugoniot, g/cm^3, cm/us, -
  Real e0 = 0;                   // unreacted energy origin, cm^2/us^2
  Real p_max = 0;                // the rate is R(min(p, p_max)); p_max = p_cj
  eos::Eos unreacted, products;
  bool equilibrium = false;  // the mixture closure: pressure equilibrium (eos/reactive.hpp)
};

// The unreacted Hugoniot state of pressure p > 0: particle and shock speeds, density, energy.
struct HugoniotPoint {
  Real up, us, rho, e;
};
KOKKOS_INLINE_FUNCTION HugoniotPoint unreacted_hugoniot(const ForestFire& ff, Real p) {
  // p = rho0 (c0 + s up) up: the positive root of s up^2 + c0 up - p / rho0 = 0
  HugoniotPoint h;
  const Real q = 4 * ff.s * p / ff.rho0;
  // (written as 2 (p/rho0) / (c0 + sqrt(c0^2 + 4 s p/rho0)): no cancellation at small p)
  h.up = 2 * p / ff.rho0 / (ff.c0 + msqrt(ff.c0 * ff.c0 + q));
  h.us = ff.c0 + ff.s * h.up;
  h.rho = ff.rho0 * h.us / (h.us - h.up);
  h.e = ff.e0 + Real(0.5) * h.up * h.up;
  return h;
}

// The Forest Fire rate R(p) = -(1/W) dW/dt, 1/us (the construction at the top); 0 for p <= 0.
KOKKOS_INLINE_FUNCTION Real forest_fire_rate(const ForestFire& ff, Real p) {
  if (!(p > 0)) return 0;
  p = mmin(p, ff.p_max);
  const HugoniotPoint h = unreacted_hugoniot(ff, p);
  const Real dpdx = p / (-ff.pop.b * pop_run_distance(ff.pop, p));
  const Real dpdf =
      ff.equilibrium ? eos::he_dpdf_equilibrium(ff.unreacted, ff.products, ff.e0, h.rho, h.e)
                     : ff.products.pressure(h.rho, h.e) - ff.unreacted.pressure(h.rho, h.e - ff.e0);
  const Real c = ff.unreacted.sound_speed(h.rho, h.e - ff.e0);
  const Real slope = h.us * (1 + ff.s * h.up / h.us);  // dp/du / rho0 on the Hugoniot
  const Real factor = 1 + h.rho * c / (ff.rho0 * slope);
  // dp/dF > 0 wherever the products are stiffer than the solid at the same (rho, e); where it
  // is not the construction has no meaning: no reaction
  if (!(dpdf > 0)) return 0;
  return h.us * dpdx * factor / dpdf;
}

// One step of dt at frozen pressure p: W' = -R(p) W integrated exactly,
//   F_new = 1 - (1 - F_old) exp(-R(p) dt),
// unconditionally stable however stiff R dt is (the rate near p_cj makes the reaction zone a
// few hundredths of a microsecond long).
KOKKOS_INLINE_FUNCTION Real forest_fire_step(const ForestFire& ff, Real f_old, Real p, Real dt) {
  const Real r = forest_fire_rate(ff, p);
  if (!(r > 0)) return f_old;
  return 1 - (1 - f_old) * MP_KOKKOS_MATH::exp(-r * dt);
}

}  // namespace mp::burn
