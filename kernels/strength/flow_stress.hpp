// Flow-stress models (von Mises yield stress Y and shear modulus G of a material point), as
// point functions, and one trivially copyable record that dispatches on the model so a device
// kernel can hold a View<FlowStress*> of the materials (as eos::Eos does).
//
// Units: cm / g / us (kernels/materials/library.hpp): Y, G, p in Mbar; strain rates in 1/us;
// temperatures in K; specific heat in (cm/us)^2 / K (1 J/(kg K) = 1e-8 (cm/us)^2/K).
// Melt (T >= T_melt) gives Y = G = 0: the material has no strength and radial_return zeroes
// its deviator.
//
// Models:
//  - constant (elastic-perfectly plastic): Y = Y0, G = G0.
//  - Johnson-Cook (G. R. Johnson, W. H. Cook, Proc. 7th Int. Symp. Ballistics, The Hague,
//    1983, 541-547):  Y = (A + B eps_p^n) (1 + C ln eps_dot*) (1 - T*^m),
//    eps_dot* = eps_dot / eps_dot0, T* = (T - T_room) / (T_melt - T_room). Clamps (the model
//    is fitted only there): eps_dot* >= 1 (no rate softening below the reference rate),
//    T* >= 0 (no hardening below room temperature). G = G0, constant (JC give no modulus).
//  - Steinberg-Guinan (D. J. Steinberg, S. G. Cochran, M. W. Guinan, J. Appl. Phys. 51 (1980)
//    1498), with eta = rho/rho0 and T_ref = 300 K:
//      G = G0 [1 + A p eta^(-1/3) - B (T - 300)],
//      Y = Y0 [1 + beta (eps_p + eps_i)]^n [1 + A p eta^(-1/3) - B (T - 300)],
//          with Y0 [1 + beta (eps_p + eps_i)]^n <= Y_max,
//      T_melt(eta) = T_m0 exp(2 a (1 - 1/eta)) eta^(2 (Gamma0 - a - 1/3)),
//    A = G'_p / G0 (1/Mbar), B = -G'_T / G0 (1/K). The bracket is clamped at 0 (a state so
//    hot or so far in tension that the linear form would give a negative modulus has none).
//  - Zerilli-Armstrong, the FCC form (F. J. Zerilli, R. W. Armstrong, J. Appl. Phys. 61 (1987)
//    1816): Y = C0 + C2 eps_p^(1/2) exp(-C3 T + C4 T ln eps_dot*), eps_dot* = eps_dot / (1/s),
//    C0 = Delta sigma_G' + k l^(-1/2) the athermal part. Clamp (ours, as for Johnson-Cook):
//    eps_dot* >= 1. G = G0, constant (the 1987 FCC form has no modulus); Y = G = 0 at or above
//    T_melt (the form has no melt term: the library gives the material's melting point).
//  - Temperature: T = T_ref + e / c_v, with e the specific internal energy measured from the
//    ambient state (e = 0 at T_ref, as the EOS tables take it) and c_v a cited constant. The
//    cold-compression part of e is not subtracted, so T is overestimated in strong compression
//    (docs/materials.md, "Strength").
#pragma once
#include "core/math.hpp"
#include "strength/tensor.hpp"

namespace mp::strength {

KOKKOS_INLINE_FUNCTION Real mlog(Real x) {
  return MP_KOKKOS_MATH::log(x);
}
KOKKOS_INLINE_FUNCTION Real mexp(Real x) {
  return MP_KOKKOS_MATH::exp(x);
}
KOKKOS_INLINE_FUNCTION Real mpow(Real x, Real y) {
  return MP_KOKKOS_MATH::pow(x, y);
}

// Equivalent (von Mises) strain rate sqrt(2/3 D':D') of a velocity gradient, 1/us.
KOKKOS_INLINE_FUNCTION Real equivalent_strain_rate(const Mat3& L) {
  const Sym d = deviator(strain_rate(L));
  return msqrt(Real(2) / 3 * ddot(d, d));
}

// Temperature from the specific internal energy (see the header).
KOKKOS_INLINE_FUNCTION Real temperature(Real e, Real cv, Real t_ref) {
  return t_ref + e / cv;
}

struct ConstantYield {
  Real G0;  // Mbar
  Real Y0;  // Mbar
  KOKKOS_INLINE_FUNCTION Real shear_modulus() const { return G0; }
  KOKKOS_INLINE_FUNCTION Real yield_stress() const { return Y0; }
};

struct JohnsonCook {
  Real A, B;      // Mbar
  Real n, C, m;   // dimensionless
  Real eps_dot0;  // reference strain rate, 1/us (1/s = 1e-6/us)
  Real T_room;    // K
  Real T_melt;    // K
  Real G0;        // Mbar (constant shear modulus, not part of the JC fit)

  KOKKOS_INLINE_FUNCTION Real homologous_temperature(Real T) const {
    return mmax((T - T_room) / (T_melt - T_room), Real(0));
  }
  KOKKOS_INLINE_FUNCTION Real shear_modulus(Real T) const { return T >= T_melt ? Real(0) : G0; }
  KOKKOS_INLINE_FUNCTION Real yield_stress(Real eps_p, Real eps_dot, Real T) const {
    if (T >= T_melt) return 0;
    const Real hardening = A + (eps_p > 0 ? B * mpow(eps_p, n) : Real(0));
    const Real rate = 1 + C * mlog(mmax(eps_dot / eps_dot0, Real(1)));
    const Real ts = homologous_temperature(T);
    const Real thermal = 1 - (ts > 0 ? mpow(ts, m) : Real(0));
    return hardening * rate * thermal;
  }
};

struct SteinbergGuinan {
  Real G0;                                  // Mbar
  Real Y0;                                  // Mbar
  Real Y_max;                               // Mbar
  Real beta;                                // dimensionless
  Real n;                                   // dimensionless
  Real eps_i;                               // initial equivalent plastic strain
  Real A;                                   // G'_p / G0, 1/Mbar
  Real B;                                   // -G'_T / G0, 1/K
  Real T_m0;                                // K
  Real gamma0;                              // dimensionless
  Real a;                                   // dimensionless
  static constexpr Real T_ref = Real(300);  // K, the reference temperature of the fit

  KOKKOS_INLINE_FUNCTION Real melt_temperature(Real eta) const {
    return T_m0 * mexp(2 * a * (1 - 1 / eta)) * mpow(eta, 2 * (gamma0 - a - Real(1) / 3));
  }
  // The bracket 1 + A p eta^-1/3 - B (T - 300), clamped at 0; 0 at or above melt.
  KOKKOS_INLINE_FUNCTION Real modulus_factor(Real p, Real eta, Real T) const {
    if (T >= melt_temperature(eta)) return 0;
    return mmax(1 + A * p / mpow(eta, Real(1) / 3) - B * (T - T_ref), Real(0));
  }
  KOKKOS_INLINE_FUNCTION Real shear_modulus(Real p, Real eta, Real T) const {
    return G0 * modulus_factor(p, eta, T);
  }
  KOKKOS_INLINE_FUNCTION Real work_hardening(Real eps_p) const {
    return mmin(Y0 * mpow(1 + beta * (eps_p + eps_i), n), Y_max);
  }
  KOKKOS_INLINE_FUNCTION Real yield_stress(Real eps_p, Real p, Real eta, Real T) const {
    return work_hardening(eps_p) * modulus_factor(p, eta, T);
  }
};

struct ZerilliArmstrong {
  Real C0, C2;    // Mbar
  Real C3, C4;    // 1/K
  Real eps_dot0;  // the unit of the rate in the logarithm, 1/s in 1/us
  Real T_melt;    // K
  Real G0;        // Mbar (constant shear modulus, not part of the fit)

  KOKKOS_INLINE_FUNCTION Real shear_modulus(Real T) const { return T >= T_melt ? Real(0) : G0; }
  KOKKOS_INLINE_FUNCTION Real yield_stress(Real eps_p, Real eps_dot, Real T) const {
    if (T >= T_melt) return 0;
    if (!(eps_p > 0)) return C0;
    const Real rate = mlog(mmax(eps_dot / eps_dot0, Real(1)));
    return C0 + C2 * msqrt(eps_p) * mexp(-C3 * T + C4 * T * rate);
  }
};

enum FlowStressKind : int {
  kNoStrength = 0,
  kConstantYield = 1,
  kJohnsonCook = 2,
  kSteinbergGuinan = 3,
  kZerilliArmstrong = 4,
};

// The inputs every model may need; each uses the ones it depends on.
struct PointState {
  Real eps_p = 0;    // equivalent plastic strain
  Real eps_dot = 0;  // equivalent strain rate, 1/us
  Real p = 0;        // pressure, Mbar
  Real eta = 1;      // rho / rho0
  Real T = 300;      // temperature, K
};

struct FlowStress {
  int kind = kNoStrength;
  ConstantYield constant{0, 0};
  JohnsonCook jc{0, 0, 0, 0, 0, 1, 0, 1, 0};
  SteinbergGuinan sg{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  ZerilliArmstrong za{0, 0, 0, 0, 1, 0, 0};
  Real cv = 0;     // specific heat for the temperature, (cm/us)^2/K
  Real T_ref = 0;  // temperature at e = 0, K

  KOKKOS_INLINE_FUNCTION Real temperature_of(Real e) const {
    return cv > 0 ? temperature(e, cv, T_ref) : T_ref;
  }
  KOKKOS_INLINE_FUNCTION Real shear_modulus(const PointState& x) const {
    switch (kind) {
      case kConstantYield:
        return constant.shear_modulus();
      case kJohnsonCook:
        return jc.shear_modulus(x.T);
      case kSteinbergGuinan:
        return sg.shear_modulus(x.p, x.eta, x.T);
      case kZerilliArmstrong:
        return za.shear_modulus(x.T);
      default:
        return 0;
    }
  }
  KOKKOS_INLINE_FUNCTION Real yield_stress(const PointState& x) const {
    switch (kind) {
      case kConstantYield:
        return constant.yield_stress();
      case kJohnsonCook:
        return jc.yield_stress(x.eps_p, x.eps_dot, x.T);
      case kSteinbergGuinan:
        return sg.yield_stress(x.eps_p, x.p, x.eta, x.T);
      case kZerilliArmstrong:
        return za.yield_stress(x.eps_p, x.eps_dot, x.T);
      default:
        return 0;
    }
  }
};

}  // namespace mp::strength
