// One trivially copyable EOS record per material, dispatching on its kind, so a device kernel can
// hold a View<Eos*> of the materials in a problem and call pressure / sound_speed on any of them.
//
// Units: cm / g / us throughout (kernels/materials/library.hpp): rho g/cm^3, e cm^2/us^2,
// p Mbar, c cm/us. Validity ranges: see the header of each EOS.
#pragma once
#include <type_traits>

#include "core/math.hpp"
#include "eos/ideal_gas.hpp"
#include "eos/jwl.hpp"
#include "eos/mie_gruneisen.hpp"
#include "eos/polynomial.hpp"
#include "eos/stiffened_gas.hpp"

namespace mp::eos {

enum EosKind : int {
  kIdealGas = 0,      // params: gamma
  kStiffenedGas = 1,  // params: gamma, p_inf
  kMieGruneisen = 2,  // params: rho0, c0, s, gamma0
  kPolynomial = 3,    // params: rho0, A1, A2, A3, B0, B1
  kJwl = 4,           // params: rho0, A, B, R1, R2, omega
};
inline constexpr int kEosKindCount = 5;
// The decks' and the material library's name of an EOS kind.
inline const char* eos_name(EosKind k) {
  switch (k) {
    case kIdealGas:
      return "ideal_gas";
    case kStiffenedGas:
      return "stiffened_gas";
    case kMieGruneisen:
      return "mie_gruneisen";
    case kPolynomial:
      return "polynomial";
    case kJwl:
      return "jwl";
  }
  return "?";
}

// Smallest c^2 handed out, (cm/us)^2, wherever the analytic c^2 is not positive.
inline constexpr Real kSoundSpeed2Floor = Real(1e-24);

// `p_min` of a material with no tension cutoff: below any pressure a Real can reach.
inline constexpr Real kNoTensionCutoff = Real(-1e30);

struct Eos {
  static constexpr int max_params = 8;
  int kind = kIdealGas;
  Real params[max_params] = {};
  // Tension cutoff (Mbar): the pressure the hydro uses never falls below p_min. A liquid that
  // cavitates or a solid that spalls cannot carry the tension its EOS would give; the cutoff
  // holds such a material at p_min instead (docs/numerics.md, "Tension cutoff"). The EOS
  // itself (pressure, sound_speed2) is unchanged; only pressure_cut applies it.
  Real p_min = kNoTensionCutoff;
  // Void density (g/cm^3, numerics.void_density; 0: off): below it a material exerts no pressure
  // and carries no sound in the hydro (pressure_cut, sound_speed_cut), as a vacuum would. Gas
  // drawn down to near vacuum behind a fast body is heated by the remap (it spreads the mass it
  // moves over the receiving cell without the work of expansion; docs/numerics.md, "LeBlanc
  // and near vacuum"), and its sound speed then sets the step (docs/perforator.md, air in the
  // well). Its mass and energy stay where they are: nothing is removed or changed.
  Real rho_void = 0;
  // True below the void density (never when it is off; a negative rho is not void).
  KOKKOS_INLINE_FUNCTION bool is_void(Real rho) const { return rho < rho_void && rho_void > 0; }

  // The pressure and c^2 of kind K with this record's parameters. A kernel over many cells
  // that dispatches on the kind once (outside its loop) calls these, so its loop has no switch
  // and can be vectorized; pressure and sound_speed2 are the same functions behind a switch.
  template <int K>
  KOKKOS_INLINE_FUNCTION Real pressure_of(Real rho, Real e) const {
    if constexpr (K == kStiffenedGas)
      return StiffenedGas{params[0], params[1]}.pressure(rho, e);
    else if constexpr (K == kMieGruneisen)
      return mie_gruneisen().pressure(rho, e);
    else if constexpr (K == kPolynomial)
      return polynomial().pressure(rho, e);
    else if constexpr (K == kJwl)
      return jwl().pressure(rho, e);
    else
      return IdealGas{params[0]}.pressure(rho, e);
  }
  template <int K>
  KOKKOS_INLINE_FUNCTION Real sound_speed2_of(Real rho, Real e) const {
    if constexpr (K == kStiffenedGas)
      return StiffenedGas{params[0], params[1]}.sound_speed2(rho, e);
    else if constexpr (K == kMieGruneisen)
      return mie_gruneisen().sound_speed2(rho, e);
    else if constexpr (K == kPolynomial)
      return polynomial().sound_speed2(rho, e);
    else if constexpr (K == kJwl)
      return jwl().sound_speed2(rho, e);
    else
      return params[0] * (params[0] - 1) * e;  // gamma p / rho
  }

  KOKKOS_INLINE_FUNCTION Real pressure(Real rho, Real e) const {
    switch (kind) {
      case kStiffenedGas:
        return pressure_of<kStiffenedGas>(rho, e);
      case kMieGruneisen:
        return pressure_of<kMieGruneisen>(rho, e);
      case kPolynomial:
        return pressure_of<kPolynomial>(rho, e);
      case kJwl:
        return pressure_of<kJwl>(rho, e);
      default:
        return pressure_of<kIdealGas>(rho, e);
    }
  }
  // The pressure the hydro uses: the EOS pressure, cut off in tension at p_min. A NaN stays NaN
  // (the health check must still see a broken EOS state), so no mmax here. K: the kind, when
  // the caller has dispatched on it (-1: this record's kind, through the switch).
  template <int K = -1>
  // (Both values found, then one selected: a branch lets GCC sink the loads of e into it and
  // leave a kernel's loop scalar.)
  KOKKOS_INLINE_FUNCTION Real pressure_cut(Real rho, Real e) const {
    Real p;
    if constexpr (K < 0)
      p = pressure(rho, e);
    else
      p = pressure_of<K>(rho, e);
    const Real cut = p < p_min ? p_min : p;
    return is_void(rho) ? Real(0) : cut;  // (off: a negative rho keeps its p)
  }
  bool has_tension_cutoff() const { return p_min > kNoTensionCutoff; }
  // Analytic c^2 = (dp/drho)_e + p/rho^2 (dp/de)_rho, unclamped.
  KOKKOS_INLINE_FUNCTION Real sound_speed2(Real rho, Real e) const {
    switch (kind) {
      case kStiffenedGas:
        return sound_speed2_of<kStiffenedGas>(rho, e);
      case kMieGruneisen:
        return sound_speed2_of<kMieGruneisen>(rho, e);
      case kPolynomial:
        return sound_speed2_of<kPolynomial>(rho, e);
      case kJwl:
        return sound_speed2_of<kJwl>(rho, e);
      default:
        return sound_speed2_of<kIdealGas>(rho, e);
    }
  }
  // c, with c^2 clamped to kSoundSpeed2Floor: finite and positive for every finite (rho > 0, e).
  template <int K = -1>
  KOKKOS_INLINE_FUNCTION Real sound_speed(Real rho, Real e) const {
    Real c2;
    if constexpr (K < 0)
      c2 = sound_speed2(rho, e);
    else
      c2 = sound_speed2_of<K>(rho, e);
    return msqrt(mmax(c2, kSoundSpeed2Floor));
  }
  // The sound speed the hydro uses: that of the floor below the void density, else sound_speed.
  template <int K = -1>
  KOKKOS_INLINE_FUNCTION Real sound_speed_cut(Real rho, Real e) const {
    const Real c = sound_speed<K>(rho, e);
    return is_void(rho) ? msqrt(kSoundSpeed2Floor) : c;
  }

  // The lowest specific energy the health check accepts in a mixed cell. A Mie-Grueneisen
  // solid measures e from its ambient reference state, so it may fall below 0 (colder than
  // ambient; equal strain makes a cold solid expand with a gas at its half-step pressure):
  // -c0^2 / 100 (copper 1.6e-3 cm^2/us^2, about 400 K of cooling at its c_v of 383 J/(kg K):
  // colder than absolute zero). Every other EOS: 0. docs/numerics.md, "Health check".
  Real energy_floor() const {
    if (kind != kMieGruneisen) return 0;
    const Real c0 = params[1];
    return -c0 * c0 / 100;
  }

  KOKKOS_INLINE_FUNCTION MieGruneisen mie_gruneisen() const {
    return MieGruneisen{params[0], params[1], params[2], params[3]};
  }
  KOKKOS_INLINE_FUNCTION Polynomial polynomial() const {
    return Polynomial{params[0], params[1], params[2], params[3], params[4], params[5]};
  }
  KOKKOS_INLINE_FUNCTION Jwl jwl() const {
    return Jwl{params[0], params[1], params[2], params[3], params[4], params[5]};
  }
};

// body.template run<K>(args...) for the kind K = `kind` (device code: a column kernel that
// dispatches once per column; -1, the per-point switch, for any other value).
template <class Body, class... Args>
KOKKOS_INLINE_FUNCTION void run_kind(int kind, const Body& body, Args... args) {
  switch (kind) {
    case kIdealGas:
      return body.template run<kIdealGas>(args...);
    case kStiffenedGas:
      return body.template run<kStiffenedGas>(args...);
    case kMieGruneisen:
      return body.template run<kMieGruneisen>(args...);
    case kPolynomial:
      return body.template run<kPolynomial>(args...);
    case kJwl:
      return body.template run<kJwl>(args...);
    default:
      return body.template run<-1>(args...);
  }
}

// f(std::integral_constant<int, K>{}) for the kind K = `kind` (host code: a kernel launched per
// kind, so its loop calls Eos::pressure_of<K> with no switch).
template <class F>
void with_kind(int kind, F&& f) {
  switch (kind) {
    case kStiffenedGas:
      return f(std::integral_constant<int, kStiffenedGas>{});
    case kMieGruneisen:
      return f(std::integral_constant<int, kMieGruneisen>{});
    case kPolynomial:
      return f(std::integral_constant<int, kPolynomial>{});
    case kJwl:
      return f(std::integral_constant<int, kJwl>{});
    default:
      return f(std::integral_constant<int, kIdealGas>{});
  }
}

inline Eos make_eos(const IdealGas& g) {
  Eos e;
  e.kind = kIdealGas;
  e.params[0] = g.gamma;
  return e;
}
inline Eos make_eos(const StiffenedGas& g) {
  Eos e;
  e.kind = kStiffenedGas;
  e.params[0] = g.gamma;
  e.params[1] = g.p_inf;
  return e;
}
inline Eos make_eos(const MieGruneisen& m) {
  Eos e;
  e.kind = kMieGruneisen;
  e.params[0] = m.rho0;
  e.params[1] = m.c0;
  e.params[2] = m.s;
  e.params[3] = m.gamma0;
  return e;
}
inline Eos make_eos(const Polynomial& m) {
  Eos e;
  e.kind = kPolynomial;
  e.params[0] = m.rho0;
  e.params[1] = m.a1;
  e.params[2] = m.a2;
  e.params[3] = m.a3;
  e.params[4] = m.b0;
  e.params[5] = m.b1;
  return e;
}
inline Eos make_eos(const Jwl& m) {
  Eos e;
  e.kind = kJwl;
  e.params[0] = m.rho0;
  e.params[1] = m.a;
  e.params[2] = m.b;
  e.params[3] = m.r1;
  e.params[4] = m.r2;
  e.params[5] = m.omega;
  return e;
}

}  // namespace mp::eos
