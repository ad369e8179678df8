// Density of the Sedov-Taylor point blast (standard case: uniform ambient density rho0, zero
// ambient pressure, gamma-law gas; j = 1, 2, 3 for planar, cylindrical, spherical), in the
// parametric form of L. I. Sedov, "Similarity and Dimensional Methods in Mechanics" (1959),
// ch. IV, as J. R. Kamm writes it ("Evaluation of the Sedov-von Neumann-Taylor blast wave
// solution", LA-UR-00-6055, 2000, eqs. 33-47, with w = 0): behind the shock (radius R) the
// similarity variable V runs from V0 = 2 / (gamma (j + 2)) at the centre to
// V2 = 4 / ((j + 2)(gamma + 1)) at the shock, and
//   r / R     = (a V)^-alpha0 (b (c V - 1))^-alpha2 (d (1 - e V))^-alpha1,
//   rho / rho2 = (b (c V - 1))^alpha3 (d (1 - e V))^alpha4 (b (1 - c V / gamma))^alpha5,
// rho2 = rho0 (gamma + 1) / (gamma - 1) the density just behind the shock. r / R falls
// monotonically from 1 to 0 as V goes from V2 to V0, so each radius is a bisection in V.
// The shock radius comes from the caller (R = (E t^2 / (alpha rho0))^(1 / (j + 2)); alpha from
// the energy integral, 0.851072 for gamma = 1.4, j = 3: configs/sedov.yaml).
#pragma once
#include <cmath>

namespace mp::exact {

class Sedov {
 public:
  Sedov(int j, double gamma, double rho0 = 1.0) : g_(gamma), rho0_(rho0) {
    const double j2 = j + 2.0;  // j + 2 - w, w = 0
    a_ = j2 * (g_ + 1) / 4;
    b_ = (g_ + 1) / (g_ - 1);
    c_ = j2 * g_ / 2;
    d_ = j2 * (g_ + 1) / (j2 * (g_ + 1) - 2 * (2 + j * (g_ - 1)));
    e_ = (2 + j * (g_ - 1)) / 2;
    al0_ = 2 / j2;
    al2_ = -(g_ - 1) / (2 * (g_ - 1) + j);
    al1_ = g_ * j2 / (2 + j * (g_ - 1)) * (2 * j * (2 - g_) / (g_ * j2 * j2) - al2_);
    al3_ = j / (2 * (g_ - 1) + j);
    al4_ = al1_ * j * j2 / (j * (2 - g_));
    al5_ = -2.0 * j / (j * (2 - g_));
    v0_ = 2 / (g_ * j2);
    v2_ = 4 / (j2 * (g_ + 1));
  }
  // r / R at the similarity variable V (V0 < V <= V2)
  double lambda(double v) const {
    return std::pow(a_ * v, -al0_) * std::pow(b_ * (c_ * v - 1), -al2_) *
           std::pow(d_ * (1 - e_ * v), -al1_);
  }
  // density / rho2 at V
  double density_ratio(double v) const {
    return std::pow(b_ * (c_ * v - 1), al3_) * std::pow(d_ * (1 - e_ * v), al4_) *
           std::pow(b_ * (1 - c_ * v / g_), al5_);
  }
  // density at distance r from the centre with the shock at radius R
  double density(double r, double R) const {
    if (r >= R) return rho0_;
    const double x = r / R;
    double lo = v0_, hi = v2_;  // lambda(lo) < x <= lambda(hi) = 1
    for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (lambda(mid) < x ? lo : hi) = mid;
    }
    return rho0_ * (g_ + 1) / (g_ - 1) * density_ratio(0.5 * (lo + hi));
  }

 private:
  double g_, rho0_, a_, b_, c_, d_, e_, al0_, al1_, al2_, al3_, al4_, al5_, v0_, v2_;
};

}  // namespace mp::exact
