// Exact solution of Noh's implosion (W. F. Noh, J. Comput. Phys. 72 (1987) 78-120, section 4):
// a cold (p = 0) gamma-law gas of density rho0 streams at speed u0 towards a wall (planar,
// dims = 1), an axis (2) or a point (3). A shock runs out at D = (gamma - 1) u0 / 2; behind it
// the gas is at rest with rho = rho0 ((gamma + 1) / (gamma - 1))^dims and e = u0^2 / 2; ahead
// of it the converging flow compresses the gas to rho = rho0 (1 + u0 t / r)^(dims - 1).
#pragma once
#include <cmath>

namespace mp::exact {

class Noh {
 public:
  Noh(int dims, double gamma, double rho0 = 1.0, double u0 = 1.0)
      : dims_(dims), gamma_(gamma), rho0_(rho0), u0_(u0) {}
  double shock_speed() const { return 0.5 * (gamma_ - 1) * u0_; }
  // density at distance r from the wall / axis / centre at time t
  double density(double r, double t) const {
    if (r < shock_speed() * t) return rho0_ * std::pow((gamma_ + 1) / (gamma_ - 1), dims_);
    return rho0_ * std::pow(1 + u0_ * t / r, dims_ - 1);
  }

 private:
  int dims_;
  double gamma_, rho0_, u0_;
};

}  // namespace mp::exact
