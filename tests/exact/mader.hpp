// Exact solution of the Mader problem: a planar CJ detonation in a gamma-law explosive,
// initiated at t = 0 at a wall (a piston at rest, or moving at u_p <= u_cj) at x = 0 and running
// into x > 0, followed by the self-similar rarefaction (Taylor wave) that brings the products
// from the CJ state at the front back to the piston's speed.
// (W. Fickett & W. C. Davis, "Detonation: Theory and Experiment", Univ. of California Press
// 1979, p. 24, as ExactPack cites it; derived here from the characteristics. The problem as set
// in LANL's ExactPack, exactpack/solvers/mader, defaults
// p_cj = 0.3 Mbar, D = 0.8 cm/us, gamma = 3; written here from the theory, not that code.)
//
// Strong (p0 = 0) gamma-law detonation: p_cj = rho0 D^2 / (gamma + 1),
//   u_cj = D / (gamma + 1),  c_cj = gamma D / (gamma + 1),  rho_cj = rho0 (gamma + 1) / gamma,
// heat of reaction q = D^2 / (2 (gamma^2 - 1)) (so the products' e = p / ((gamma - 1) rho)
// counts q in, as the hydro's e does).
// Behind the front the C- Riemann invariant u - 2c/(gamma - 1) = J is that of the CJ state, and
// the C+ characteristics are the rays x/t = u + c from the origin, so:
//   u = (2 x/t + (gamma - 1) J) / (gamma + 1),  c = x/t - u           (fan, x_p t < x < D t),
//   u = u_p, c = c_cj + (gamma - 1)/2 (u_p - u_cj)                   (x < x_p t),
// with x_p = u_p + c at the fan's tail; p = p_cj (c/c_cj)^(2 gamma/(gamma - 1)),
// rho = rho_cj (c/c_cj)^(2/(gamma - 1)) (the flow behind the front is isentropic).
// Ahead of the front the explosive is at rest at rho0, p = 0.
#pragma once
#include <cmath>
#include <stdexcept>

namespace mp::exact {

struct MaderState {
  double rho, u, p, c;
};

class Mader {
 public:
  Mader(double p_cj, double d, double gamma, double u_piston = 0)
      : pcj_(p_cj), d_(d), g_(gamma), up_(u_piston) {
    if (!(p_cj > 0 && d > 0 && gamma > 1)) throw std::invalid_argument("Mader: bad parameters");
    rho0_ = (g_ + 1) * pcj_ / (d_ * d_);
    rhocj_ = rho0_ * (g_ + 1) / g_;
    ucj_ = d_ / (g_ + 1);
    ccj_ = g_ * d_ / (g_ + 1);
    j_ = ucj_ - 2 * ccj_ / (g_ - 1);
    if (up_ > ucj_ || c_of_u(up_) <= 0)
      throw std::invalid_argument("Mader: piston speed outside (u where c > 0, u_cj]");
    xp_ = up_ + c_of_u(up_);
  }

  double rho0() const { return rho0_; }
  double rho_cj() const { return rhocj_; }
  double u_cj() const { return ucj_; }
  double c_cj() const { return ccj_; }
  double p_cj() const { return pcj_; }
  double d() const { return d_; }
  double gamma() const { return g_; }
  double heat_of_reaction() const { return d_ * d_ / (2 * (g_ * g_ - 1)); }
  // Similarity speed of the fan's tail: the state is constant for x/t below it.
  double tail_speed() const { return xp_; }
  // The C- invariant u - 2c/(gamma - 1) behind the front.
  double riemann_invariant() const { return j_; }

  MaderState sample(double x, double t) const {
    if (!(t > 0)) throw std::invalid_argument("Mader::sample needs t > 0");
    const double s = x / t;
    if (s > d_) return {rho0_, 0, 0, 0};
    double u, c;
    if (s <= xp_) {
      u = up_;
      c = c_of_u(up_);
    } else {
      u = (2 * s + (g_ - 1) * j_) / (g_ + 1);
      c = s - u;
    }
    const double r = c / ccj_;
    return {rhocj_ * std::pow(r, 2 / (g_ - 1)), u, pcj_ * std::pow(r, 2 * g_ / (g_ - 1)), c};
  }

 private:
  double c_of_u(double u) const { return (g_ - 1) / 2 * (u - j_); }
  double pcj_, d_, g_, up_;
  double rho0_, rhocj_, ucj_, ccj_, j_, xp_;
};

}  // namespace mp::exact
