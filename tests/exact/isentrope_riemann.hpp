// Exact solution of a Riemann problem whose left state, of ANY equation of state p(rho, e),
// expands in a rarefaction into an ideal gas on the right (shock or rarefaction there): the
// detonation-products-into-air tube. The left wave curve is the isentrope through the left
// state, integrated numerically:
//   along an isentrope  de = p / rho^2 drho,  and across a left-facing rarefaction
//   du = -c / rho drho  (the Riemann invariant u + int c/rho drho is constant),
// written in s = ln(rho) as de/ds = p / rho, du/ds = -c, and integrated by classical RK4 from
// rho_L down to 1e-4 rho_L (or to where p or c^2 stops being positive) on a fine table; the
// step error is far below the tests' tolerances, and test_multimat checks the solver against
// the closed-form one of riemann.hpp and against itself at half the number of steps. The right
// (ideal-gas) wave, its curve and its sampling, is riemann.hpp's (Toro, "Riemann Solvers and
// Numerical Methods for Fluid Dynamics", 3rd ed., ch. 4). The star pressure solves
// u_L(p) = u_R(p) by bisection on the table.
#pragma once
#include <cmath>
#include <stdexcept>
#include <vector>

#include "eos/eos.hpp"
#include "riemann.hpp"

namespace mp::exact {

struct EosState {
  double rho, u, p, e;
};

class IsentropeRiemann {
 public:
  // Left: EOS `left_eos` at (rho_l, u_l, e_l). Right: ideal gas `gamma_r` at (rho_r, u_r, p_r).
  IsentropeRiemann(const eos::Eos& left_eos, double rho_l, double u_l, double e_l, double rho_r,
                   double u_r, double p_r, double gamma_r, int steps = 200000)
      : eos_(left_eos), ul_(u_l), rr_(rho_r), ur_(u_r), pr_(p_r), gr_(gamma_r) {
    integrate(rho_l, e_l, steps);
    solve();
  }

  double p_star() const { return ps_; }
  double u_star() const { return us_; }
  double rho_star_left() const { return at(is_).rho; }
  double e_star_left() const { return at(is_).e; }
  double rho_star_right() const { return Riemann::side_density(right(), gr_, 0, ps_); }
  double left_head_speed() const { return ul_ - c(0); }
  double left_tail_speed() const { return us_ - at(is_).c; }
  double right_head_speed() const {
    return ps_ > pr_ ? Riemann::shock_speed(right(), gr_, 0, cr(), +1, ps_) : ur_ + cr();
  }

  // The solution at similarity coordinate s = (x - x0) / t.
  EosState sample(double xi) const {
    if (xi >= us_) {
      const Primitive q = Riemann::sample_side(xi, right(), gr_, 0, cr(), +1, ps_, us_);
      return {q.rho, q.u, q.p, q.p / ((gr_ - 1) * q.rho)};
    }
    if (xi <= left_head_speed()) return state(0);
    if (xi >= left_tail_speed()) return plain(at(is_));
    // in the fan: u - c increases as the products expand; bisect the table, interpolate
    std::size_t lo = 0, hi = is_.i + 1;
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      (u_[mid] - c(mid) < xi ? lo : hi) = mid;
    }
    const double w = (xi - (u_[lo] - c(lo))) / ((u_[hi] - c(hi)) - (u_[lo] - c(lo)));
    return plain(at({lo, w}));
  }

 private:
  struct Where {
    std::size_t i;
    double w;  // fraction of the way from node i to node i+1
  };
  struct Point {
    double rho, u, p, e, c;
  };

  static EosState plain(const Point& q) { return {q.rho, q.u, q.p, q.e}; }
  double c(std::size_t i) const { return eos_.sound_speed(std::exp(s_[i]), e_[i]); }
  EosState state(std::size_t i) const {
    const double rho = std::exp(s_[i]);
    return {rho, u_[i], eos_.pressure(rho, e_[i]), e_[i]};
  }
  Point at(Where k) const {
    const std::size_t j = k.i + 1 < s_.size() ? k.i + 1 : k.i;
    const double s = s_[k.i] + k.w * (s_[j] - s_[k.i]);
    const double e = e_[k.i] + k.w * (e_[j] - e_[k.i]);
    const double rho = std::exp(s);
    return {rho, u_[k.i] + k.w * (u_[j] - u_[k.i]), eos_.pressure(rho, e), e,
            eos_.sound_speed(rho, e)};
  }

  void integrate(double rho_l, double e_l, int steps) {
    const double s0 = std::log(rho_l), s1 = std::log(rho_l * 1e-4), h = (s1 - s0) / steps;
    s_.resize(steps + 1);
    e_.resize(steps + 1);
    u_.resize(steps + 1);
    s_[0] = s0;
    e_[0] = e_l;
    u_[0] = ul_;
    auto f = [&](double s, double e, double& de, double& du) {
      const double rho = std::exp(s);
      de = eos_.pressure(rho, e) / rho;
      du = -eos_.sound_speed(rho, e);
    };
    for (int n = 0; n < steps; ++n) {
      const double s = s_[n], e = e_[n];
      double k1e, k1u, k2e, k2u, k3e, k3u, k4e, k4u;
      f(s, e, k1e, k1u);
      f(s + h / 2, e + h / 2 * k1e, k2e, k2u);
      f(s + h / 2, e + h / 2 * k2e, k3e, k3u);
      f(s + h, e + h * k3e, k4e, k4u);
      s_[n + 1] = s0 + (n + 1) * h;
      e_[n + 1] = e + h / 6 * (k1e + 2 * k2e + 2 * k3e + k4e);
      u_[n + 1] = u_[n] + h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
      // The table ends where the isentrope leaves p > 0 or the EOS range (c^2 > 0), e.g. a
      // stiffened gas nearing -p_inf; a star state beyond it is refused by solve().
      const double rho = std::exp(s_[n + 1]);
      if (!(eos_.pressure(rho, e_[n + 1]) > 0 && eos_.sound_speed2(rho, e_[n + 1]) > 0)) {
        s_.resize(n + 1);
        e_.resize(n + 1);
        u_.resize(n + 1);
        return;
      }
    }
  }

  // The right (ideal-gas) side's state and sound speed, and the velocity behind its wave for
  // star pressure p: riemann.hpp's wave curve with p_inf = 0.
  Primitive right() const { return {rr_, ur_, pr_}; }
  double cr() const { return std::sqrt(gr_ * pr_ / rr_); }
  double right_u(double p) const {
    double f, df;
    Riemann::wave(p, right(), gr_, 0, cr(), f, df);
    return ur_ + f;
  }

  void solve() {
    // g(i) = u_L - u_R at the pressure of node i: negative at the left state (a rarefaction
    // needs p* < p_L), growing as the products expand. Bisect on nodes, then on the fraction.
    auto g = [&](Where k) {
      const Point q = at(k);
      return q.u - right_u(q.p);
    };
    std::size_t lo = 0, hi = s_.size() - 1;
    if (!(g({lo, 0}) < 0)) throw std::invalid_argument("IsentropeRiemann: no left rarefaction");
    if (!(g({hi, 0}) > 0)) throw std::invalid_argument("IsentropeRiemann: table too short");
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      (g({mid, 0}) < 0 ? lo : hi) = mid;
    }
    double wl = 0, wh = 1;
    for (int it = 0; it < 60; ++it) {
      const double wm = 0.5 * (wl + wh);
      (g({lo, wm}) < 0 ? wl : wh) = wm;
    }
    is_ = {lo, 0.5 * (wl + wh)};
    const Point q = at(is_);
    ps_ = q.p;
    us_ = q.u;
  }

  eos::Eos eos_;
  double ul_, rr_, ur_, pr_, gr_;
  std::vector<double> s_, e_, u_;
  Where is_{0, 0};
  double ps_ = 0, us_ = 0;
};

}  // namespace mp::exact
