// Exact solution of the 1-D elastic-plastic piston: a piston moving at u_p (in +x) drives a
// half-space of elastic-perfectly plastic solid (uniaxial strain, constant yield Y, shear
// modulus G, Mie-Grueneisen EOS on a linear Us-up Hugoniot) from rest. Two shocks run ahead of
// the piston: an elastic precursor that takes the material to the yield point (the Hugoniot
// elastic limit), and a slower plastic shock that takes it to the piston speed with the
// deviator held on the yield surface.
//
// Formulas: the problem and its solution procedure are those of LANL ExactPack's EPpiston
// (github.com/lanl/ExactPack, exactpack/solvers/ep_piston, after Udaykumar et al. 2003 and
// Lieberman et al. 2019); this is an independent implementation of the same jump conditions.
// Sign convention: compression positive for p; the deviator s = s_xx (tension positive), the
// axial stress sigma = s - p.
//  1. Yield point. In uniaxial strain s = s_xx diag(1, -1/2, -1/2), so sqrt(3/2 s:s) = 3/2 |s_xx|
//     and yield is s_xx = -2/3 Y. The density there depends on the elastic law:
//       hypoelastic (this code's rate form, ds_xx/dt = 4/3 G D_xx, D_xx = -d ln rho / dt):
//         rho_y = rho0 exp(Y / (2 G));
//       infinitesimal hyperelastic (s_xx = -4/3 G (1 - rho0/rho)):
//         rho_y = rho0 / (1 - Y / (2 G)).
//  2. Elastic shock 0 -> y (mass, momentum, energy with the axial stress):
//       e_y = -sigma_y / 2 (1/rho0 - 1/rho_y),  solved with p linear in e;
//       U_e^2 = rho_y (-sigma_y) / (rho0 (rho_y - rho0)),  u_y = U_e (1 - rho0/rho_y).
//     The Hugoniot elastic limit is sigma_HEL = -sigma_y = p_y + 2/3 Y. For a linear solid
//     (p = K (rho/rho0 - 1)) this is (K + 4/3 G) Y / (2 G) = Y (1 - nu) / (1 - 2 nu) to first
//     order in Y/G, and U_e -> sqrt((K + 4/3 G) / rho0) as Y -> 0.
//  3. Plastic shock y -> 2 (u_2 = u_p, s_2 = s_y), with m = rho_y (U_p - u_y):
//       rho_2 = rho_y (U_p - u_y) / (U_p - u_p),  p_2 = p_y + m (u_p - u_y),
//       e_2 = e_y + (p_y + p_2 - 2 s_y) / 2 (1/rho_y - 1/rho_2),
//     and p_2 = p_EOS(rho_2, e_2) closes it; solved here for rho_2: the first sign change of the
//     residual above rho_y, bisected to round-off.
// Everything is in double, whatever the build's Real.
//
// EOS forms (both Mie-Grueneisen on p_H(eta) = rho0 c0^2 eta / (1 - s eta)^2,
// e_H = p_H eta / (2 rho0), eta = 1 - rho0/rho):
//   kGammaConstant  p = p_H + Gamma0 rho  (e - e_H)  (ExactPack's form),
//   kRhoGammaConst  p = p_H + Gamma0 rho0 (e - e_H)  (this code's eos/mie_gruneisen.hpp).
#pragma once
#include <cmath>
#include <stdexcept>

namespace mp::exact {

struct EpPistonMaterial {
  enum GammaForm { kGammaConstant, kRhoGammaConstant };
  enum ElasticLaw { kHypoelastic, kHyperelasticInfinitesimal };
  double rho0, c0, s, gamma0;  // EOS, cm g us
  double G, Y;                 // shear modulus, yield stress, Mbar
  GammaForm gamma_form = kRhoGammaConstant;
  ElasticLaw law = kHypoelastic;

  // p = pa(rho) + pb(rho) e
  void pressure_coefficients(double rho, double& pa, double& pb) const {
    const double eta = 1 - rho0 / rho;
    const double ph = rho0 * c0 * c0 * eta / ((1 - s * eta) * (1 - s * eta));
    const double eh = ph * eta / (2 * rho0);
    pb = gamma0 * (gamma_form == kGammaConstant ? rho : rho0);
    pa = ph - pb * eh;
  }
  double pressure(double rho, double e) const {
    double pa, pb;
    pressure_coefficients(rho, pa, pb);
    return pa + pb * e;
  }
};

struct EpState {
  double rho, u, p, e, s;  // s: axial deviator s_xx
  double sigma() const { return s - p; }
};

class EpPiston {
 public:
  EpPiston(const EpPistonMaterial& m, double u_piston) : m_(m), up_(u_piston) {
    if (!(m.G > 0 && m.Y > 0 && m.rho0 > 0 && m.c0 > 0 && u_piston >= 0))
      throw std::invalid_argument("EpPiston: needs G, Y, rho0, c0 > 0 and u_piston >= 0");
    // 1. yield point
    const double rho_y = m.law == EpPistonMaterial::kHypoelastic
                             ? m.rho0 * std::exp(m.Y / (2 * m.G))
                             : m.rho0 / (1 - m.Y / (2 * m.G));
    const double s_y = -2.0 / 3.0 * m.Y;
    // 2. elastic shock from rest
    const double dv = 1 / m.rho0 - 1 / rho_y;
    double pa, pb;
    m.pressure_coefficients(rho_y, pa, pb);
    const double e_y = 0.5 * (pa - s_y) * dv / (1 - 0.5 * pb * dv);
    const double p_y = pa + pb * e_y;
    const double sig_y = s_y - p_y;
    ue_ = std::sqrt(rho_y * (-sig_y) / (m.rho0 * (rho_y - m.rho0)));
    yield_ = {rho_y, ue_ * (1 - m.rho0 / rho_y), p_y, e_y, s_y};
    if (!(up_ > yield_.u))
      throw std::invalid_argument(
          "EpPiston: piston speed below the HEL particle speed: no "
          "plastic wave (elastic-only case not implemented)");
    // 3. plastic shock. Far up the Hugoniot (near the singular compression) the Gamma rho form
    // can turn the residual positive again, so the first sign change is found by scanning
    // rho_2 - rho_y geometrically up from 1e-12 (rho_top - rho_y), then bisected.
    const double top = m.rho0 / (1 - 0.999 / m.s);
    const int n_scan = 2400;
    double lo = rho_y + (top - rho_y) * 1e-12, hi = lo;
    if (!(residual(lo) > 0)) throw std::runtime_error("EpPiston: residual not positive at rho_y");
    bool found = false;
    for (int k = 1; k <= n_scan && !found; ++k) {
      hi = rho_y + (top - rho_y) * std::pow(10.0, -12.0 + 12.0 * k / n_scan);
      if (residual(hi) < 0) {
        found = true;
      } else {
        lo = hi;
      }
    }
    if (!found) throw std::runtime_error("EpPiston: plastic shock residual is not bracketed");
    for (int it = 0; it < 200 && hi - lo > 4e-16 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (residual(mid) > 0) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    const double rho2 = 0.5 * (lo + hi);
    plastic_ = plastic_state(rho2, up_);
  }

  double elastic_speed() const { return ue_; }   // cm/us, lab frame
  double plastic_speed() const { return up2_; }  // cm/us, lab frame
  const EpState& yield_state() const { return yield_; }
  const EpState& plastic_state() const { return plastic_; }
  double hel() const { return -yield_.sigma(); }  // Mbar, compression positive

  // The state at (x, t), x measured from the piston's starting position.
  EpState at(double x, double t) const {
    if (x > ue_ * t) return {m_.rho0, 0, 0, 0, 0};
    if (x > up2_ * t) return yield_;
    return plastic_;
  }

 private:
  // Plastic shock for a trial rho_2: the state behind it; sets up2_.
  EpState plastic_state(double rho2, double u2) {
    const EpState& y = yield_;
    up2_ = (rho2 * u2 - y.rho * y.u) / (rho2 - y.rho);  // mass: rho_y (U - u_y) = rho2 (U - u2)
    const double mflux = y.rho * (up2_ - y.u);
    const double p2 = y.p + mflux * (u2 - y.u);
    const double e2 = y.e + 0.5 * (y.p + p2 - 2 * y.s) * (1 / y.rho - 1 / rho2);
    return {rho2, u2, p2, e2, y.s};
  }
  double residual(double rho2) {
    const EpState st = plastic_state(rho2, up_);
    return st.p - m_.pressure(st.rho, st.e);
  }

  EpPistonMaterial m_;
  double up_;
  double ue_ = 0, up2_ = 0;
  EpState yield_{}, plastic_{};
};

}  // namespace mp::exact
