// Exact solution of the Riemann problem for two stiffened gases, p = (gamma - 1) rho e -
// gamma p_inf (ideal gases: p_inf = 0), with pressure/velocity equilibrium across the contact,
// by Newton iteration on the star pressure; the wave curves follow Toro, "Riemann Solvers and
// Numerical Methods for Fluid Dynamics", 3rd ed., ch. 4. Each side may have its own gamma and
// p_inf, so the same solver serves the two-material shock tubes (gas-gas, water-air).
//
// Stiffened gas: with pbar = p + p_inf the isentropes, Hugoniots and sound speed
// c^2 = gamma pbar / rho are the ideal-gas ones in pbar (Ivings, Causon & Toro, Int. J. Numer.
// Meth. Fluids 28 (1998) 395-418), so each side's wave curve is Toro's with p -> p + p_inf
// wherever an absolute pressure appears (differences p - p_K are unchanged).
#pragma once
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mp::exact {

struct Primitive {
  double rho, u, p;
};

class Riemann {
 public:
  Riemann(Primitive left, Primitive right, double gamma_left, double gamma_right,
          double p_inf_left = 0, double p_inf_right = 0)
      : l_(left), r_(right), gl_(gamma_left), gr_(gamma_right), pl_(p_inf_left), pr_(p_inf_right) {
    if (!(l_.p + pl_ > 0 && r_.p + pr_ > 0 && l_.rho > 0 && r_.rho > 0))
      throw std::invalid_argument("Riemann: states need rho > 0 and p + p_inf > 0");
    cl_ = std::sqrt(gl_ * (l_.p + pl_) / l_.rho);
    cr_ = std::sqrt(gr_ * (r_.p + pr_) / r_.rho);
    solve();
  }

  double p_star() const { return ps_; }
  double u_star() const { return us_; }
  double rho_star_left() const { return side_density(l_, gl_, pl_, ps_); }
  double rho_star_right() const { return side_density(r_, gr_, pr_, ps_); }
  // Speeds of the head of the left wave (shock or rarefaction head) etc.
  double left_head_speed() const {
    return ps_ > l_.p ? shock_speed(l_, gl_, pl_, cl_, -1, ps_) : l_.u - cl_;
  }
  double right_head_speed() const {
    return ps_ > r_.p ? shock_speed(r_, gr_, pr_, cr_, +1, ps_) : r_.u + cr_;
  }
  double left_tail_speed() const {
    return ps_ > l_.p ? left_head_speed() : us_ - std::sqrt(gl_ * (ps_ + pl_) / rho_star_left());
  }
  double right_tail_speed() const {
    return ps_ > r_.p ? right_head_speed() : us_ + std::sqrt(gr_ * (ps_ + pr_) / rho_star_right());
  }

  // The solution at similarity coordinate s = (x - x0) / t.
  Primitive sample(double s) const {
    if (s < us_) return sample_side(s, l_, gl_, pl_, cl_, -1, ps_, us_);
    return sample_side(s, r_, gr_, pr_, cr_, +1, ps_, us_);
  }

  // One side's wave, given the star pressure ps and velocity us (also used by
  // isentrope_riemann.hpp for its ideal-gas side). k: the side's state, g its gamma, pinf its
  // p_inf, c its sound speed, dir = -1 for the left side, +1 for the right.
  // f_K(p) and its derivative (Toro eqs. 4.6, 4.7, with p -> p + p_inf).
  static void wave(double p, const Primitive& k, double g, double pinf, double c, double& f,
                   double& df) {
    const double pb = p + pinf, kb = k.p + pinf;
    if (p > k.p) {
      const double a = 2 / ((g + 1) * k.rho), b = (g - 1) / (g + 1) * kb;
      const double q = std::sqrt(a / (pb + b));
      f = (p - k.p) * q;
      df = q * (1 - 0.5 * (p - k.p) / (pb + b));
    } else {
      const double e = (g - 1) / (2 * g);
      f = 2 * c / (g - 1) * (std::pow(pb / kb, e) - 1);
      df = 1 / (k.rho * c) * std::pow(pb / kb, -(g + 1) / (2 * g));
    }
  }

 private:
  void solve() {
    const double du = r_.u - l_.u;
    // Start from the two-rarefaction guess, which is exact for two ideal-gas rarefactions of
    // the same gamma; otherwise from the mean pressure.
    double p = 0.5 * (l_.p + r_.p);
    if (std::abs(gl_ - gr_) < 1e-14 && pl_ == 0 && pr_ == 0) {
      const double g = gl_, el = (g - 1) / (2 * g);
      const double num = cl_ + cr_ - 0.5 * (g - 1) * du;
      const double den = cl_ / std::pow(l_.p, el) + cr_ / std::pow(r_.p, el);
      if (num > 0) p = std::pow(num / den, 1 / el);
    }
    // the star pressure lies above -min(p_inf) (vacuum otherwise; not handled)
    const double floor = -std::min(pl_, pr_) + 1e-14 * std::max(l_.p + pl_, r_.p + pr_);
    p = std::max(p, floor);
    for (int it = 0; it < 200; ++it) {
      double fl, dfl, fr, dfr;
      wave(p, l_, gl_, pl_, cl_, fl, dfl);
      wave(p, r_, gr_, pr_, cr_, fr, dfr);
      const double g = fl + fr + du;
      double pn = p - g / (dfl + dfr);
      if (pn <= floor) pn = floor + 0.1 * (p - floor);
      const double change = 2 * std::abs(pn - p) / (std::abs(pn) + std::abs(p));
      p = pn;
      if (change < 1e-14) break;
    }
    double fl, dfl, fr, dfr;
    wave(p, l_, gl_, pl_, cl_, fl, dfl);
    wave(p, r_, gr_, pr_, cr_, fr, dfr);
    if (!(std::abs(fl + fr + du) <= 1e-10 * (std::abs(fl) + std::abs(fr) + std::abs(du) + 1e-300)))
      throw std::runtime_error("Riemann: Newton iteration on the star pressure did not converge");
    ps_ = p;
    us_ = 0.5 * (l_.u + r_.u) + 0.5 * (fr - fl);
  }

 public:
  static double side_density(const Primitive& k, double g, double pinf, double p) {
    const double ratio = (p + pinf) / (k.p + pinf);
    if (p > k.p) {
      const double m = (g - 1) / (g + 1);
      return k.rho * (ratio + m) / (m * ratio + 1);
    }
    return k.rho * std::pow(ratio, 1 / g);
  }

  static double shock_speed(const Primitive& k, double g, double pinf, double c, int dir,
                            double ps) {
    const double ratio = (ps + pinf) / (k.p + pinf);
    return k.u + dir * c * std::sqrt((g + 1) / (2 * g) * ratio + (g - 1) / (2 * g));
  }

  static Primitive sample_side(double s, const Primitive& k, double g, double pinf, double c,
                               int dir, double ps, double us) {
    const double rho_star = side_density(k, g, pinf, ps);
    if (ps > k.p) {  // shock
      const double sk = shock_speed(k, g, pinf, c, dir, ps);
      if ((dir < 0 && s < sk) || (dir > 0 && s > sk)) return k;
      return {rho_star, us, ps};
    }
    const double head = k.u + dir * c;
    const double c_star = c * std::pow((ps + pinf) / (k.p + pinf), (g - 1) / (2 * g));
    const double tail = us + dir * c_star;
    if ((dir < 0 && s < head) || (dir > 0 && s > head)) return k;
    if ((dir < 0 && s > tail) || (dir > 0 && s < tail)) return {rho_star, us, ps};
    // inside the fan (Toro eq. 4.56 / 4.63, in pbar)
    const double a = 2 / (g + 1), b = (g - 1) / ((g + 1) * c);
    const double rho = k.rho * std::pow(a - dir * b * (k.u - s), 2 / (g - 1));
    const double u = a * (-dir * c + 0.5 * (g - 1) * k.u + s);
    const double p = (k.p + pinf) * std::pow(a - dir * b * (k.u - s), 2 * g / (g - 1)) - pinf;
    return {rho, u, p};
  }

 private:
  Primitive l_, r_;
  double gl_, gr_, pl_, pr_, cl_, cr_;
  double ps_ = 0, us_ = 0;
};

}  // namespace mp::exact
