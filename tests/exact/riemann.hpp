// Exact solution of the Riemann problem for two ideal gases (pressure/velocity equilibrium
// across the contact), by Newton iteration on the star pressure; the wave curves follow
// Toro, "Riemann Solvers and Numerical Methods for Fluid Dynamics", 3rd ed., ch. 4.
// Each side may have its own gamma, so the same solver serves the two-material shock tube.
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
  Riemann(Primitive left, Primitive right, double gamma_left, double gamma_right)
      : l_(left), r_(right), gl_(gamma_left), gr_(gamma_right) {
    cl_ = std::sqrt(gl_ * l_.p / l_.rho);
    cr_ = std::sqrt(gr_ * r_.p / r_.rho);
    solve();
  }

  double p_star() const { return ps_; }
  double u_star() const { return us_; }
  double rho_star_left() const { return side_density(l_, gl_, ps_); }
  double rho_star_right() const { return side_density(r_, gr_, ps_); }
  // Speeds of the head of the left wave (shock or rarefaction head) etc.
  double left_head_speed() const { return ps_ > l_.p ? shock_speed(l_, gl_, cl_, -1) : l_.u - cl_; }
  double right_head_speed() const {
    return ps_ > r_.p ? shock_speed(r_, gr_, cr_, +1) : r_.u + cr_;
  }
  double left_tail_speed() const {
    return ps_ > l_.p ? left_head_speed() : us_ - std::sqrt(gl_ * ps_ / rho_star_left());
  }
  double right_tail_speed() const {
    return ps_ > r_.p ? right_head_speed() : us_ + std::sqrt(gr_ * ps_ / rho_star_right());
  }

  // The solution at similarity coordinate s = (x - x0) / t.
  Primitive sample(double s) const {
    if (s < us_) return sample_side(s, l_, gl_, cl_, -1);
    return sample_side(s, r_, gr_, cr_, +1);
  }

 private:
  // f_K(p) and its derivative (Toro eqs. 4.6, 4.7).
  static void wave(double p, const Primitive& k, double g, double c, double& f, double& df) {
    if (p > k.p) {
      const double a = 2 / ((g + 1) * k.rho), b = (g - 1) / (g + 1) * k.p;
      const double q = std::sqrt(a / (p + b));
      f = (p - k.p) * q;
      df = q * (1 - 0.5 * (p - k.p) / (p + b));
    } else {
      const double e = (g - 1) / (2 * g);
      f = 2 * c / (g - 1) * (std::pow(p / k.p, e) - 1);
      df = 1 / (k.rho * c) * std::pow(p / k.p, -(g + 1) / (2 * g));
    }
  }

  void solve() {
    const double du = r_.u - l_.u;
    // Start from the two-rarefaction guess, which is exact for two rarefactions.
    const double el = (gl_ - 1) / (2 * gl_), er = (gr_ - 1) / (2 * gr_);
    double p = 0.5 * (l_.p + r_.p);
    if (std::abs(gl_ - gr_) < 1e-14) {
      const double g = gl_;
      const double num = cl_ + cr_ - 0.5 * (g - 1) * du;
      const double den = cl_ / std::pow(l_.p, el) + cr_ / std::pow(r_.p, er);
      if (num > 0) p = std::pow(num / den, 1 / el);
    }
    p = std::max(p, 1e-14 * std::max(l_.p, r_.p));
    for (int it = 0; it < 200; ++it) {
      double fl, dfl, fr, dfr;
      wave(p, l_, gl_, cl_, fl, dfl);
      wave(p, r_, gr_, cr_, fr, dfr);
      const double g = fl + fr + du;
      double pn = p - g / (dfl + dfr);
      if (pn <= 0) pn = 0.1 * p;
      const double change = 2 * std::abs(pn - p) / (pn + p);
      p = pn;
      if (change < 1e-14) break;
    }
    double fl, dfl, fr, dfr;
    wave(p, l_, gl_, cl_, fl, dfl);
    wave(p, r_, gr_, cr_, fr, dfr);
    ps_ = p;
    us_ = 0.5 * (l_.u + r_.u) + 0.5 * (fr - fl);
  }

  static double side_density(const Primitive& k, double g, double p) {
    if (p > k.p) {
      const double r = p / k.p, m = (g - 1) / (g + 1);
      return k.rho * (r + m) / (m * r + 1);
    }
    return k.rho * std::pow(p / k.p, 1 / g);
  }

  double shock_speed(const Primitive& k, double g, double c, int dir) const {
    return k.u + dir * c * std::sqrt((g + 1) / (2 * g) * ps_ / k.p + (g - 1) / (2 * g));
  }

  // dir = -1 for the left side, +1 for the right.
  Primitive sample_side(double s, const Primitive& k, double g, double c, int dir) const {
    const double rho_star = side_density(k, g, ps_);
    if (ps_ > k.p) {  // shock
      const double sk = shock_speed(k, g, c, dir);
      if ((dir < 0 && s < sk) || (dir > 0 && s > sk)) return k;
      return {rho_star, us_, ps_};
    }
    const double head = k.u + dir * c;
    const double c_star = c * std::pow(ps_ / k.p, (g - 1) / (2 * g));
    const double tail = us_ + dir * c_star;
    if ((dir < 0 && s < head) || (dir > 0 && s > head)) return k;
    if ((dir < 0 && s > tail) || (dir > 0 && s < tail)) return {rho_star, us_, ps_};
    // inside the fan (Toro eq. 4.56 / 4.63)
    const double a = 2 / (g + 1), b = (g - 1) / ((g + 1) * c);
    const double rho = k.rho * std::pow(a - dir * b * (k.u - s), 2 / (g - 1));
    const double u = a * (-dir * c + 0.5 * (g - 1) * k.u + s);
    const double p = k.p * std::pow(a - dir * b * (k.u - s), 2 * g / (g - 1));
    return {rho, u, p};
  }

  Primitive l_, r_;
  double gl_, gr_, cl_, cr_;
  double ps_ = 0, us_ = 0;
};

}  // namespace mp::exact
