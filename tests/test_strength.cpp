// Strength point functions (kernels/strength/): the Jaumann-rotated Hooke update, the von Mises
// radial return, objectivity under rigid rotation, the Johnson-Cook and Steinberg-Guinan flow
// stresses of the library against hand-computed values, and the exact elastic-plastic piston
// (tests/exact/ep_piston.hpp) against LANL ExactPack's numbers and its own jump conditions.
// Units: cm, g, us -> Mbar; K.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "exact/ep_piston.hpp"
#include "materials/library.hpp"
#include "precision.hpp"
#include "strength/flow_stress.hpp"
#include "strength/library.hpp"
#include "strength/stress_update.hpp"

namespace {

using mp::Real;
using mp::test::by_precision;
using mp::test::kEps;
using mp::test::roundoff;
namespace st = mp::strength;

// Equal to 4 ulps of this build's Real (gtest's DOUBLE_EQ / FLOAT_EQ).
#ifdef MINIPAGOSA_REAL_FLOAT
#define EXPECT_REAL_EQ(a, b) EXPECT_FLOAT_EQ(float(a), float(b))
#else
#define EXPECT_REAL_EQ(a, b) EXPECT_DOUBLE_EQ(a, b)
#endif

// A material point's state for the flow-stress models.
st::PointState point_state(Real eps_p, Real eps_dot, Real p, Real eta, Real T) {
  st::PointState x;
  x.eps_p = eps_p;
  x.eps_dot = eps_dot;
  x.p = p;
  x.eta = eta;
  x.T = T;
  return x;
}

st::Mat3 gradient(std::initializer_list<double> g) {
  Real a[9];
  int i = 0;
  for (double v : g) a[i++] = Real(v);
  return st::velocity_gradient(a);
}

double max_abs_diff(const st::Sym& a, const double b[6]) {
  const double c[6] = {a.xx, a.yy, a.zz, a.xy, a.yz, a.zx};
  double m = 0;
  for (int i = 0; i < 6; ++i) m = std::max(m, std::abs(c[i] - b[i]));
  return m;
}

// ---- elastic update ------------------------------------------------------------------------

// Pure shear (D_xy = D_yx = g, no spin) from s = 0: s_xy = 2 G g t after any number of steps,
// every other component exactly 0; both integrators.
TEST(Elastic, PureShearFollowsHooke) {
  const Real G = 0.477, g = 1e-3, dt = 0.01;  // Mbar, 1/us, us
  const st::Mat3 L = gradient({0, 1e-3, 0, 1e-3, 0, 0, 0, 0, 0});
  const int n = 20;
  st::Sym se, sr;
  for (int k = 0; k < n; ++k) {
    se = st::elastic_trial_euler(se, L, G, dt);
    sr = st::elastic_trial_rotated(sr, L, G, dt);
  }
  const double expect = 2.0 * G * g * dt * n;
  std::printf("pure shear, %d steps: s_xy euler %.17g rotated %.17g, 2 G g t = %.17g\n", n, se.xy,
              sr.xy, expect);
  // n additions of one rounded increment: n/2 ulps at most
  EXPECT_NEAR(se.xy, expect, n * kEps * expect);
  EXPECT_NEAR(sr.xy, expect, n * kEps * expect);
  for (const st::Sym& s : {se, sr}) {
    EXPECT_EQ(s.xx, 0);
    EXPECT_EQ(s.yy, 0);
    EXPECT_EQ(s.zz, 0);
    EXPECT_EQ(s.yz, 0);
    EXPECT_EQ(s.zx, 0);
  }
}

// One step of simple shear (v_x = gdot y: D_xy = gdot/2 and spin W_xy = gdot/2) from s = 0.
// Forward form: the spin has nothing to rotate, s_xy = 2 G (gdot/2) dt to round-off. Rotated
// form: the first half increment h = G dt gdot/2 turns with the Cayley rotation about z by
// phi = -2 atan(gdot dt/4), so s_xy = h (1 + cos 2 phi), s_xx = -s_yy = -h sin 2 phi.
TEST(Elastic, SimpleShearFirstStep) {
  const Real G = 0.477, gdot = 2e-3, dt = 0.05;
  const st::Mat3 L = gradient({0, 2e-3, 0, 0, 0, 0, 0, 0, 0});
  const st::Sym se = st::elastic_trial_euler(st::Sym{}, L, G, dt);
  const st::Sym sr = st::elastic_trial_rotated(st::Sym{}, L, G, dt);
  const Real expect = 2 * G * (gdot / 2) * dt;
  const double h = double(G) * dt * gdot / 2, phi = -2 * std::atan(double(gdot) * dt / 4);
  std::printf(
      "simple shear one step: s_xy euler %.17g (2 G D_xy dt %.17g), rotated xy %.17g "
      "(%.17g) xx %.6g (%.6g)\n",
      se.xy, expect, sr.xy, h * (1 + std::cos(2 * phi)), sr.xx, -h * std::sin(2 * phi));
  EXPECT_REAL_EQ(se.xy, expect);
  EXPECT_EQ(st::trace(se), 0);
  EXPECT_NEAR(sr.xy, h * (1 + std::cos(2 * phi)), 8 * kEps * h);
  EXPECT_NEAR(sr.xx, -h * std::sin(2 * phi), 8 * kEps * h);
  EXPECT_NEAR(sr.yy, h * std::sin(2 * phi), 8 * kEps * h);
  EXPECT_NEAR(st::trace(sr), 0, 8 * kEps * h);
}

// Simple shear to gamma = gdot t = 1 with no yield: the Jaumann-rate hypoelastic solution is
// s_xx = -s_yy = G (1 - cos gamma), s_xy = G sin gamma (ds_xx/dgamma = s_xy,
// ds_xy/dgamma = G - s_xx). The rotated update converges at second order, the forward form at
// first.
TEST(Elastic, SimpleShearConvergesToTheJaumannSolution) {
  const Real G = 0.5, gdot = 0.1;  // Mbar, 1/us
  const double t_end = 1.0 / gdot;
  const st::Mat3 L = gradient({0, 0.1, 0, 0, 0, 0, 0, 0, 0});
  const double exact[6] = {
      G * (1 - std::cos(1.0)), -G * (1 - std::cos(1.0)), 0, G * std::sin(1.0), 0, 0};
  const std::vector<int> steps = {8, 16, 32, 64};
  std::vector<double> err_rot, err_eul;
  for (int n : steps) {
    st::Sym sr, se;
    for (int k = 0; k < n; ++k) {
      sr = st::elastic_trial_rotated(sr, L, G, Real(t_end / n));
      se = st::elastic_trial_euler(se, L, G, Real(t_end / n));
    }
    err_rot.push_back(max_abs_diff(sr, exact) / G);
    err_eul.push_back(max_abs_diff(se, exact) / G);
    std::printf("simple shear to gamma 1, %3d steps: rotated err %.3e, euler err %.3e (of G)\n", n,
                err_rot.back(), err_eul.back());
  }
  for (size_t i = 1; i < steps.size(); ++i) {
    const double q_rot = std::log2(err_rot[i - 1] / err_rot[i]);
    const double q_eul = std::log2(err_eul[i - 1] / err_eul[i]);
    std::printf("order %d->%d: rotated %.3f euler %.3f\n", steps[i - 1], steps[i], q_rot, q_eul);
    EXPECT_NEAR(q_rot, 2.0, 0.15);  // second-order splitting (stress_update.hpp)
    EXPECT_NEAR(q_eul, 1.0, 0.25);  // forward Euler
  }
}

// Uniaxial strain rate D_xx = d: the deviator is 2 G d dt (2/3, -1/3, -1/3), traceless.
TEST(Elastic, UniaxialStrainDeviator) {
  const Real G = 0.3, d = -1e-2, dt = 0.1;
  const st::Mat3 L = gradient({-1e-2, 0, 0, 0, 0, 0, 0, 0, 0});
  const st::Sym s = st::elastic_trial_rotated(st::Sym{}, L, G, dt);
  std::printf("uniaxial: s = (%.17g %.17g %.17g), expect s_xx %.17g\n", s.xx, s.yy, s.zz,
              4.0 / 3.0 * G * d * dt);
  EXPECT_NEAR(s.xx, 4.0 / 3.0 * G * d * dt, 4 * kEps * std::abs(s.xx));
  EXPECT_NEAR(s.yy, -2.0 / 3.0 * G * d * dt, 4 * kEps * std::abs(s.yy));
  EXPECT_NEAR(s.zz, s.yy, 4 * kEps * std::abs(s.yy));
  EXPECT_NEAR(st::trace(s), 0, 4 * kEps * std::abs(s.xx));
}

// ---- radial return -------------------------------------------------------------------------

TEST(RadialReturn, LandsOnTheYieldSurfaceWithPositiveWork) {
  const Real G = 0.477, Y = 0.0012;
  const st::Sym trial = st::deviator({3e-3, -1e-3, 0.5e-3, 1.2e-3, -0.7e-3, 0.4e-3});
  const double j_trial = st::von_mises(trial);
  st::Sym s = trial;
  const st::ReturnResult r = st::radial_return(s, Y, G);
  const double j = st::von_mises(s);
  // plastic strain increment tensor (s* - s) / (2 G), and s : d_eps_p from it
  const st::Sym dep{(trial.xx - s.xx) / (2 * G), (trial.yy - s.yy) / (2 * G),
                    (trial.zz - s.zz) / (2 * G), (trial.xy - s.xy) / (2 * G),
                    (trial.yz - s.yz) / (2 * G), (trial.zx - s.zx) / (2 * G)};
  const double work_tensor = st::ddot(s, dep);
  std::printf(
      "return: J trial %.6g -> %.17g (Y %.17g), d_eps_p %.17g (expect %.17g), work "
      "%.17g, s:d_eps_p %.17g\n",
      j_trial, j, double(Y), r.d_eps_p, (j_trial - Y) / (3 * G), r.work, work_tensor);
  ASSERT_GT(j_trial, 2 * Y);
  EXPECT_TRUE(r.yielded);
  // one multiply by Y/J and a square root: a few ulps of Y
  EXPECT_NEAR(j, Y, 4 * kEps * Y);
  EXPECT_NEAR(r.d_eps_p, (j_trial - Y) / (3 * G), 8 * kEps * r.d_eps_p);
  EXPECT_GT(r.work, 0);
  // Y d_eps_p against s : (s* - s)/(2G): the same quantity by two roundings (the subtraction
  // s* - s loses log2(J/(J-Y)) < 1 bit here)
  EXPECT_NEAR(r.work, work_tensor, 16 * kEps * r.work);
  // radial: s parallel to s*
  EXPECT_NEAR(s.xy / trial.xy, Y / j_trial, 4 * kEps);
  EXPECT_NEAR(st::trace(s), 0, 4 * kEps * Y);
}

TEST(RadialReturn, ElasticStateAndMeltUntouchedOrZeroed) {
  const st::Sym trial = st::deviator({1e-4, -2e-4, 0, 3e-5, 0, 0});
  st::Sym s = trial;
  const st::ReturnResult r = st::radial_return(s, Real(1e-2), Real(0.5));
  EXPECT_FALSE(r.yielded);
  EXPECT_EQ(r.d_eps_p, 0);
  EXPECT_EQ(r.work, 0);
  EXPECT_EQ(s.xx, trial.xx);
  EXPECT_EQ(s.xy, trial.xy);
  st::Sym m = trial;
  st::radial_return(m, Real(0), Real(0));  // melted: no strength
  EXPECT_EQ(st::von_mises(m), 0);
}

// ---- objectivity ---------------------------------------------------------------------------

// R(n, phi) s R^T in double, Rodrigues' formula.
void rotated_exact(const double s0[6], const double n[3], double phi, double out[6]) {
  const double c = std::cos(phi), sn = std::sin(phi);
  double R[3][3], S[3][3] = {{s0[0], s0[3], s0[5]}, {s0[3], s0[1], s0[4]}, {s0[5], s0[4], s0[2]}};
  const double K[3][3] = {{0, -n[2], n[1]}, {n[2], 0, -n[0]}, {-n[1], n[0], 0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0) + sn * K[i][j] + (1 - c) * n[i] * n[j];
  double T[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) T[i][j] += R[i][k] * S[k][l] * R[j][l];
  out[0] = T[0][0];
  out[1] = T[1][1];
  out[2] = T[2][2];
  out[3] = T[0][1];
  out[4] = T[1][2];
  out[5] = T[2][0];
}

// A stressed point in rigid rotation (v = w x x: D = 0, W = [w]_x) about the axis (1,2,2)/3
// for a quarter turn. The rotated update keeps J2 to round-off and converges to R s0 R^T at
// second order; the forward (Euler) form converges at first order with J2 growing; dropping
// the spin term leaves s0 unrotated, far from R s0 R^T.
TEST(Objectivity, QuarterTurnRigidRotation) {
  const double s0d[6] = {1.0e-3, -0.4e-3, -0.6e-3, 0.3e-3, 0.2e-3, -0.1e-3};
  const double nax[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3};
  const double omega = 0.7, angle = M_PI / 2, t_end = angle / omega;  // 1/us, rad, us
  const st::Mat3 L = gradient({0, -omega * nax[2], omega * nax[1], omega * nax[2], 0,
                               -omega * nax[0], -omega * nax[1], omega * nax[0], 0});
  const st::Sym s0{Real(s0d[0]), Real(s0d[1]), Real(s0d[2]),
                   Real(s0d[3]), Real(s0d[4]), Real(s0d[5])};
  double exact[6];
  rotated_exact(s0d, nax, angle, exact);
  const double norm0 = std::sqrt(st::ddot(s0, s0)), j0 = st::von_mises(s0);
  const Real G = 0.5;  // irrelevant with D = 0, but a real modulus
  const std::vector<int> steps = {8, 16, 32, 64};
  std::vector<double> err_rot, err_eul;
  for (int n : steps) {
    const Real dt = Real(t_end / n);
    st::Sym sr = s0, se = s0;
    for (int k = 0; k < n; ++k) {
      sr = st::elastic_trial_rotated(sr, L, G, dt);
      se = st::elastic_trial_euler(se, L, G, dt);
    }
    err_rot.push_back(max_abs_diff(sr, exact) / norm0);
    err_eul.push_back(max_abs_diff(se, exact) / norm0);
    const double dj_rot = st::von_mises(sr) / j0 - 1, dj_eul = st::von_mises(se) / j0 - 1;
    std::printf("quarter turn, %3d steps: rotated err %.3e dJ %.2e | euler err %.3e dJ %.3e\n", n,
                err_rot.back(), dj_rot, err_eul.back(), dj_eul);
    // Q orthogonal to round-off: a few ulps per step
    EXPECT_LT(std::abs(dj_rot), 8 * kEps * n);
    // Euler: |s| grows by sqrt(1 + dt^2 |[W,s]|^2/|s|^2) per step, J2 strictly up
    EXPECT_GT(dj_eul, 0);
  }
  for (size_t i = 1; i < steps.size(); ++i) {
    const double q_rot = std::log2(err_rot[i - 1] / err_rot[i]);
    const double q_eul = std::log2(err_eul[i - 1] / err_eul[i]);
    std::printf("order %d->%d: rotated %.3f euler %.3f\n", steps[i - 1], steps[i], q_rot, q_eul);
    // Cayley angle 2 atan(w dt/2) = w dt - (w dt)^3/12: second order; forward Euler: first
    EXPECT_NEAR(q_rot, 2.0, 0.1);
    EXPECT_NEAR(q_eul, 1.0, 0.25);
  }
  // rotation-angle error of the Cayley update at 64 steps: (pi/2)^3 / (12 * 64^2) = 7.6e-5 rad
  EXPECT_LT(err_rot.back(), 4 * 7.6e-5);
  // Without the Jaumann (spin) term the update sees only D' = sym(L)' = 0 in a rigid rotation,
  // so the tensor does not rotate: s stays s0.
  const st::Mat3 no_spin = gradient({0, 0, 0, 0, 0, 0, 0, 0, 0});  // L with W removed
  st::Sym frozen = s0;
  for (int k = 0; k < 64; ++k)
    frozen = st::elastic_trial_euler(frozen, no_spin, G, Real(t_end / 64));
  const double err_frozen = max_abs_diff(frozen, exact) / norm0;
  std::printf("no spin term: error vs R s0 R^T %.3f of |s0| (rotated update %.2e)\n", err_frozen,
              err_rot.back());
  EXPECT_GT(err_frozen, 0.3);
  EXPECT_GT(err_frozen, 1000 * err_rot.back());
}

// ---- flow stress ---------------------------------------------------------------------------

// Johnson-Cook at one reference point per library set; the expected values are computed by hand
// (Python, double) from the cited parameters, in MPa. Float: the parameters themselves are
// rounded to 6e-8 and raised to powers n, m ~ 1: 2e-6.
TEST(FlowStress, JohnsonCookReferencePoints) {
  const double tol = by_precision(1e-13, 2e-6);
  struct Point {
    const char* name;
    double eps_p, rate_per_s, T, y_mpa;
  };
  const Point pts[] = {
      // (90 + 292 0.5^0.31)(1 + 0.025 ln 1e3)(1 - (302/1058)^1.09)
      {"copper", 0.5, 1e3, 600, 284.4146803019092},
      // (792 + 510 0.1^0.26)(1 + 0.014 ln 1e4)(1 - (202/1495)^1.03)
      {"steel_4340", 0.1, 1e4, 500, 1056.4984403713845},
      // (324 + 114 0.2^0.42)(1 + 0.002 ln 1e3)(1 - (102/635.47)^1.34)
      {"aluminium_6061", 0.2, 1e3, 400, 353.89302331630654},
      // (1506.96 + 176.64 0.3^0.12)(1 + 0.016 ln 1e5)(1 - 502/3397)
      {"tungsten", 0.3, 1e5, 800, 1675.1208716134618},
  };
  for (const Point& p : pts) {
    const st::StrengthData* d = st::find_strength(p.name);
    ASSERT_NE(d, nullptr) << p.name;
    ASSERT_TRUE(d->has_jc);
    const double y = d->jc.yield_stress(Real(p.eps_p), Real(p.rate_per_s * 1e-6), Real(p.T));
    std::printf("JC %-15s Y(%.2f, %.0e/s, %.0f K) = %.12g MPa, hand %.12g\n", p.name, p.eps_p,
                p.rate_per_s, p.T, y * 1e5, p.y_mpa);
    EXPECT_NEAR(y * 1e5 / p.y_mpa, 1.0, tol) << p.name;
    // reference state: Y = A exactly; melt: 0; below the reference rate: no rate softening
    EXPECT_EQ(d->jc.yield_stress(0, st::kPerSecond, d->jc.T_room), d->jc.A);
    EXPECT_EQ(d->jc.yield_stress(Real(p.eps_p), Real(1e-3), d->jc.T_melt), 0);
    EXPECT_EQ(d->jc.yield_stress(Real(0.1), Real(1e-12), Real(400)),
              d->jc.yield_stress(Real(0.1), st::kPerSecond, Real(400)));
  }
}

// Steinberg-Guinan G, Y and T_melt at one point per set (hand values, Python, double).
TEST(FlowStress, SteinbergGuinanReferencePoints) {
  const double tol = by_precision(1e-13, 2e-6);
  struct Point {
    const char* name;
    double eps_p, p, eta, T, g, y, tm;
  };
  const Point pts[] = {
      {"copper", 0.2, 0.1, 1.1, 500, 0.5718039377666924, 0.0037078848836027646, 2436.409306399886},
      {"aluminium_6061", 0.05, 0.05, 1.05, 400, 0.34752292037703436, 0.0044514978671960055,
       1426.2433788130088},
      {"tungsten", 0.1, 0.3, 1.1, 1000, 1.8816006828016354, 0.03264458518548715, 5765.34527430049},
  };
  for (const Point& q : pts) {
    const st::StrengthData* d = st::find_strength(q.name);
    ASSERT_NE(d, nullptr) << q.name;
    ASSERT_TRUE(d->has_sg);
    const st::SteinbergGuinan& sg = d->sg;
    const double g = sg.shear_modulus(Real(q.p), Real(q.eta), Real(q.T));
    const double y = sg.yield_stress(Real(q.eps_p), Real(q.p), Real(q.eta), Real(q.T));
    const double tm = sg.melt_temperature(Real(q.eta));
    std::printf("SG %-15s G %.12g (hand %.12g)  Y %.12g (%.12g)  Tm %.8g (%.8g)\n", q.name, g, q.g,
                y, q.y, tm, q.tm);
    EXPECT_NEAR(g / q.g, 1.0, tol) << q.name;
    EXPECT_NEAR(y / q.y, 1.0, tol) << q.name;
    EXPECT_NEAR(tm / q.tm, 1.0, tol) << q.name;
    // reference state (p 0, eta 1, 300 K): G = G0 and Y = Y0 exactly; work hardening capped
    EXPECT_EQ(sg.shear_modulus(0, 1, 300), sg.G0);
    EXPECT_EQ(sg.yield_stress(0, 0, 1, 300), sg.Y0);
    EXPECT_EQ(sg.yield_stress(1e4, 0, 1, 300), sg.Y_max);  // far past the cap
    EXPECT_EQ(sg.melt_temperature(1), sg.T_m0);
  }
}

// Steinberg-Guinan derivative signs (harder with pressure, softer with temperature), the
// analytic slopes G0 A eta^-1/3 and -G0 B (the model is linear in p and T: a centred difference
// is exact up to round-off of G / h), melt temperature rising with compression, and the melt
// cutoff.
TEST(FlowStress, SteinbergGuinanDerivativesAndMelt) {
  const st::SteinbergGuinan& sg = st::find_strength("copper")->sg;
  const Real p = 0.1, eta = 1.1, T = 500, hp = 0.01, hT = 10;
  const double dgdp =
      (double(sg.shear_modulus(p + hp, eta, T)) - sg.shear_modulus(p - hp, eta, T)) /
      (2 * double(hp));
  const double dgdt =
      (double(sg.shear_modulus(p, eta, T + hT)) - sg.shear_modulus(p, eta, T - hT)) /
      (2 * double(hT));
  const double dydp =
      (double(sg.yield_stress(0.2, p + hp, eta, T)) - sg.yield_stress(0.2, p - hp, eta, T)) /
      (2 * double(hp));
  const double dydt =
      (double(sg.yield_stress(0.2, p, eta, T + hT)) - sg.yield_stress(0.2, p, eta, T - hT)) /
      (2 * double(hT));
  const double dgdp_exact = sg.G0 * sg.A / std::cbrt(double(eta)), dgdt_exact = -sg.G0 * sg.B;
  std::printf(
      "SG copper: dG/dp %.10g (exact %.10g), dG/dT %.10g (exact %.10g), dY/dp %.4g, "
      "dY/dT %.4g\n",
      dgdp, dgdp_exact, dgdt, dgdt_exact, dydp, dydt);
  EXPECT_GT(dgdp, 0);
  EXPECT_LT(dgdt, 0);
  EXPECT_GT(dydp, 0);
  EXPECT_LT(dydt, 0);
  // round-off of G (~eps G) over the step: eps G / h relative to the slope, G/(h |slope|) ~ 4e3
  EXPECT_NEAR(dgdp / dgdp_exact, 1.0, 1e4 * kEps);
  EXPECT_NEAR(dgdt / dgdt_exact, 1.0, 1e4 * kEps);
  double tm_prev = 0;
  for (double e : {0.9, 1.0, 1.1, 1.2, 1.3}) {
    const double tm = sg.melt_temperature(Real(e));
    EXPECT_GT(tm, tm_prev) << "eta " << e;
    tm_prev = tm;
  }
  const Real tm = sg.melt_temperature(eta);
  std::printf("SG copper at eta 1.1: Tm %.6g K; G(Tm-1) %.4g, G(Tm+1) %g, Y(Tm+1) %g\n", tm,
              sg.shear_modulus(p, eta, tm - 1), sg.shear_modulus(p, eta, tm + 1),
              sg.yield_stress(0.2, p, eta, tm + 1));
  EXPECT_GT(sg.shear_modulus(p, eta, tm - 1), 0);
  EXPECT_EQ(sg.shear_modulus(p, eta, tm + 1), 0);
  EXPECT_EQ(sg.yield_stress(0.2, p, eta, tm + 1), 0);
  // melted point: the radial return leaves no deviator
  st::Sym s{1e-3, -5e-4, -5e-4, 2e-4, 0, 0};
  st::radial_return(s, sg.yield_stress(0.2, p, eta, tm + 1), sg.shear_modulus(p, eta, tm + 1));
  EXPECT_EQ(st::von_mises(s), 0);
}

// The device record dispatches to the same functions; temperature from energy and cv.
TEST(FlowStress, RecordDispatchAndTemperature) {
  const st::StrengthData* cu = st::find_strength("copper");
  const st::FlowStress sg = st::make_flow_stress(*cu, st::kSteinbergGuinan);
  const st::FlowStress jc = st::make_flow_stress(*cu, st::kJohnsonCook);
  const Real e = 100 * cu->cv;  // 100 K above the reference
  const Real T = sg.temperature_of(e);
  std::printf("copper: e %.6g cm^2/us^2 -> T %.9g K (cv %.4g)\n", e, T, cu->cv);
  EXPECT_NEAR(T, 400, 4 * kEps * 400);
  const st::PointState x = point_state(0.3, 1e-2, 0.05, 1.05, 450);
  EXPECT_EQ(sg.yield_stress(x), cu->sg.yield_stress(x.eps_p, x.p, x.eta, x.T));
  EXPECT_EQ(sg.shear_modulus(x), cu->sg.shear_modulus(x.p, x.eta, x.T));
  EXPECT_EQ(jc.yield_stress(x), cu->jc.yield_stress(x.eps_p, x.eps_dot, x.T));
  EXPECT_EQ(jc.shear_modulus(x), cu->G0);
  st::FlowStress none;
  EXPECT_EQ(none.yield_stress(x), 0);
  // equivalent strain rate of uniaxial strain D_xx = d: sqrt(2/3 D':D') = 2/3 |d|
  const st::Mat3 L = gradient({-3e-3, 0, 0, 0, 0, 0, 0, 0, 0});
  EXPECT_NEAR(st::equivalent_strain_rate(L), 2e-3, 4 * kEps * 2e-3);
}

// Zerilli-Armstrong (FCC) copper against its closed form written out here with the cited
// constants (C0 65 MPa, C2 890 MPa, C3 0.0028 /K, C4 0.000115 /K, the rate in 1/s): at eps_p
// 0.25, 1e4 /s, 400 K, Y = 65 + 445 exp(-1.12 + 0.046 ln 1e4) MPa = 286.8 MPa; the athermal
// part alone with no plastic strain; no rate softening below 1/s; none at or above melt; the
// device record dispatches to it with the library's G0.
TEST(FlowStress, ZerilliArmstrongCopper) {
  const st::StrengthData* cu = st::find_strength("copper");
  ASSERT_NE(cu, nullptr);
  ASSERT_TRUE(cu->has_za);
  const st::FlowStress za = st::make_flow_stress(*cu, st::kZerilliArmstrong);
  const double mpa = 1e-5;  // Mbar
  const auto closed = [&](double eps_p, double rate_per_s, double T) {
    return (65 +
            890 * std::sqrt(eps_p) * std::exp(-0.0028 * T + 0.000115 * T * std::log(rate_per_s))) *
           mpa;
  };
  const double y = za.yield_stress(point_state(0.25, 1e-2, 0.01, 1.01, 400));
  std::printf(
      "Zerilli-Armstrong copper: eps_p 0.25, 1e4/s, 400 K -> Y %.6g MPa (closed form %.6g)\n",
      y / mpa, closed(0.25, 1e4, 400) / mpa);
  EXPECT_NEAR(y, closed(0.25, 1e4, 400), 64 * kEps * y);
  EXPECT_NEAR(y / mpa, 286.8, 0.1);
  // a second hand value: 300 K, 1/s, eps_p 0.25: 65 + 445 exp(-0.84) = 257.1 MPa
  EXPECT_NEAR(za.yield_stress(point_state(0.25, 1e-6, 0, 1, 300)) / mpa, 257.1, 0.1);
  EXPECT_NEAR(za.yield_stress(point_state(0, 1e-2, 0, 1, 300)), 65 * mpa, 4 * kEps * 65 * mpa);
  // below the unit rate (1e-3 /s here) the logarithm is clamped at 0: the 1/s value
  EXPECT_EQ(za.yield_stress(point_state(0.1, 1e-9, 0, 1, 300)),
            za.yield_stress(point_state(0.1, 1e-6, 0, 1, 300)));
  EXPECT_NEAR(za.yield_stress(point_state(0.1, 1e-6, 0, 1, 300)), closed(0.1, 1, 300),
              64 * kEps * closed(0.1, 1, 300));
  // melted: no strength
  EXPECT_EQ(za.yield_stress(point_state(0.1, 1e-2, 0, 1, 1356)), 0);
  EXPECT_EQ(za.shear_modulus(point_state(0.1, 1e-2, 0, 1, 1356)), 0);
  EXPECT_EQ(za.shear_modulus(point_state(0.1, 1e-2, 0, 1, 1000)), cu->G0);
  // 4340 has no Zerilli-Armstrong set; a set without a shear modulus is refused
  EXPECT_THROW(st::make_flow_stress(*st::find_strength("steel_4340"), st::kZerilliArmstrong),
               mp::InputError);
  st::StrengthData no_g0 = *cu;
  no_g0.G0 = no_g0.za.G0 = 0;
  EXPECT_THROW(st::make_flow_stress(no_g0, st::kZerilliArmstrong), mp::InputError);
}

// Every strength entry belongs to an EOS library material; missing sets fail clearly.
TEST(FlowStress, LibraryNamesAndMissingSets) {
  for (const std::string& name : st::strength_names()) {
    EXPECT_NE(mp::materials::find_material(name), nullptr) << name;
  }
  EXPECT_EQ(st::find_strength("water"), nullptr);
  const st::StrengthData* steel = st::find_strength("steel_4340");
  ASSERT_NE(steel, nullptr);
  EXPECT_THROW(st::make_flow_stress(*steel, st::kSteinbergGuinan), mp::InputError);
  EXPECT_NO_THROW(st::make_flow_stress(*st::find_strength("tungsten"), st::kSteinbergGuinan));
}

// 4340's Johnson-Cook set carries the cited shear modulus (ASM/MatWeb, 80 GPa = 0.80 Mbar) and
// the flow stress built from it returns that modulus below T_melt and 0 above; an entry whose
// G0 were 0 is still refused.
TEST(FlowStress, Steel4340ShearModulus) {
  const st::StrengthData* steel = st::find_strength("steel_4340");
  ASSERT_NE(steel, nullptr);
  EXPECT_EQ(steel->G0, Real(0.80));
  EXPECT_EQ(steel->jc.G0, steel->G0);
  const st::FlowStress jc = st::make_flow_stress(*steel, st::kJohnsonCook);
  st::PointState x = point_state(0.1, 1e-2, 0.01, 1.01, 500);
  EXPECT_EQ(jc.shear_modulus(x), Real(0.80));
  x.T = 1800;  // above T_melt 1793 K
  EXPECT_EQ(jc.shear_modulus(x), Real(0));
  st::StrengthData no_g0 = *steel;
  no_g0.G0 = no_g0.jc.G0 = 0;
  EXPECT_THROW(st::make_flow_stress(no_g0, st::kJohnsonCook), mp::InputError);
}

// ---- exact elastic-plastic piston ----------------------------------------------------------

mp::exact::EpPistonMaterial exactpack_default() {
  // ExactPack EPpiston defaults (exactpack/solvers/ep_piston/ep_piston.py, after Lieberman et
  // al. 2019): Gamma 2, c0 0.533 cm/us, s0 1.34, G 0.286 Mbar, Y 0.0026 Mbar, rho0 2.79 g/cc,
  // piston 0.01 cm/us; Gamma-constant Mie-Grueneisen.
  mp::exact::EpPistonMaterial m{2.79, 0.533, 1.34, 2.0, 0.286, 0.0026};
  m.gamma_form = mp::exact::EpPistonMaterial::kGammaConstant;
  return m;
}

// ExactPack's own test numbers (exactpack/tests/test_ep_piston.py, infinitesimal hyperelastic
// model, default parameters): rho_y, e_y, p_y, vel_y and the plastic wave speed at which its
// residual vanishes; and the hypoelastic yield density.
TEST(EpPiston, MatchesExactPack) {
  auto m = exactpack_default();
  m.law = mp::exact::EpPistonMaterial::kHyperelasticInfinitesimal;
  const mp::exact::EpPiston ep(m, 0.01);
  const auto& y = ep.yield_state();
  std::printf("EP piston (ExactPack case): rho_y %.17g e_y %.17g p_y %.17g u_y %.17g\n", y.rho, y.e,
              y.p, y.u);
  std::printf("  U_elastic %.17g U_plastic %.17g (ExactPack 0.5505600903624002), HEL %.10g Mbar\n",
              ep.elastic_speed(), ep.plastic_speed(), ep.hel());
  // closed-form values: the same formulas in another order, a few ulps
  EXPECT_NEAR(y.rho / 2.802739726027397 - 1, 0, 4e-16);
  EXPECT_NEAR(y.e / 4.3893303503475645e-06 - 1, 0, 1e-14);
  EXPECT_NEAR(y.p / 0.003655008604753384 - 1, 0, 1e-14);
  EXPECT_NEAR(y.u / 0.0029628804735755254 - 1, 0, 1e-14);
  EXPECT_DOUBLE_EQ(y.s, -0.0017333333333333333);
  // ExactPack solves the plastic wave with scipy's fsolve (default xtol 1.49e-8 relative);
  // this solver bisects to 4e-16 in rho_2. Observed 3e-14.
  EXPECT_NEAR(ep.plastic_speed() / 0.5505600903624002 - 1, 0, 1.5e-8);
  m.law = mp::exact::EpPistonMaterial::kHypoelastic;
  const mp::exact::EpPiston hypo(m, 0.01);
  std::printf("  hypoelastic rho_y %.17g (ExactPack 2.8027106842157106)\n", hypo.yield_state().rho);
  EXPECT_NEAR(hypo.yield_state().rho / 2.8027106842157106 - 1, 0, 4e-16);
}

// Rankine-Hugoniot jump conditions across both waves (mass, momentum, energy with the axial
// stress), and the EOS closure of the plastic state, for this code's model (hypoelastic rate
// form, rho Gamma = rho0 Gamma0): ExactPack's aluminium and the library's copper with
// Steinberg's G0, Y0.
TEST(EpPiston, JumpConditionsHoldAcrossBothWaves) {
  const mp::materials::MaterialData* cu = mp::materials::find_material("copper");
  const st::StrengthData* cus = st::find_strength("copper");
  struct Case {
    const char* name;
    mp::exact::EpPistonMaterial m;
    double up;
  };
  auto al = exactpack_default();
  al.gamma_form = mp::exact::EpPistonMaterial::kRhoGammaConstant;
  const Case cases[] = {
      {"exactpack_al", al, 0.01},
      {"copper",
       {cu->rho0, cu->param("c0"), cu->param("s"), cu->param("gamma0"), double(cus->sg.G0),
        double(cus->sg.Y0)},
       0.005},
  };
  for (const Case& c : cases) {
    const mp::exact::EpPiston ep(c.m, c.up);
    const auto& y = ep.yield_state();
    const auto& p2 = ep.plastic_state();
    const double ue = ep.elastic_speed(), up = ep.plastic_speed(), rho0 = c.m.rho0;
    // elastic shock into rest: flux differences, each scaled by its largest term
    const double mass_e = (rho0 * ue - y.rho * (ue - y.u)) / (rho0 * ue);
    const double mom_e = (-y.sigma() - rho0 * ue * y.u) / (-y.sigma());
    const double en_e =
        (rho0 * ue * (y.e + 0.5 * y.u * y.u) - (-y.sigma()) * y.u) / ((-y.sigma()) * y.u);
    // plastic shock y -> 2
    const double m = y.rho * (up - y.u);
    const double mass_p = (m - p2.rho * (up - p2.u)) / m;
    const double mom_p = ((-p2.sigma()) - (-y.sigma()) - m * (p2.u - y.u)) / (-p2.sigma());
    const double en_p = (m * ((p2.e + 0.5 * p2.u * p2.u) - (y.e + 0.5 * y.u * y.u)) -
                         ((-p2.sigma()) * p2.u - (-y.sigma()) * y.u)) /
                        ((-p2.sigma()) * p2.u);
    const double eos = (p2.p - c.m.pressure(p2.rho, p2.e)) / p2.p;
    std::printf("EP %s: U_e %.10g U_p %.10g HEL %.6g Mbar, p2 %.6g rho2 %.8g\n", c.name, ue, up,
                ep.hel(), p2.p, p2.rho);
    // The exact solution is computed in double whatever Real is. rho_y - rho0 and
    // 1 - rho0/rho_y cancel down to eps_y = Y/(2G) (1.3e-3 for copper), so each term carries
    // a relative round-off of a few DBL_EPSILON / eps_y: 16 DBL_EPSILON / eps_y.
    const double bound = 16 * DBL_EPSILON / (c.m.Y / (2 * c.m.G));
    std::printf(
        "  residuals: elastic mass %.1e mom %.1e energy %.1e | plastic mass %.1e mom "
        "%.1e energy %.1e | EOS %.1e (bounds %.1e, 1e-13)\n",
        mass_e, mom_e, en_e, mass_p, mom_p, en_p, eos, bound);
    for (double r : {mass_e, mom_e, en_e, mass_p, mom_p, en_p}) EXPECT_LT(std::abs(r), bound);
    // bisection to 4e-16 in rho_2, times rho dp/drho / p = K / p2 (55 aluminium, 79 copper):
    // 2.2e-14 and 3.2e-14 (observed 7.2e-16 and 2.4e-14); bound 1e-13. Was 1e-12, whose
    // comment gave the same estimate.
    EXPECT_LT(std::abs(eos), 1e-13);
    EXPECT_GT(ue, up);
    EXPECT_GT(up, c.up);
    // sample: the three regions in order
    EXPECT_EQ(ep.at(1.01 * ue, 1.0).rho, rho0);
    EXPECT_EQ(ep.at(0.5 * (ue + up), 1.0).rho, y.rho);
    EXPECT_EQ(ep.at(0.99 * up, 1.0).rho, p2.rho);
  }
}

// The linear-elastic limits: as Y/G -> 0 the HEL tends to (K + 4/3 G) Y / (2 G) and the
// precursor speed to sqrt((K + 4/3 G)/rho0), K = rho0 c0^2; both at first order in Y/G (the
// EOS curvature 2 s eta and the Grueneisen energy term are O(eta), eta ~ Y/(2G)), so dividing
// Y by 10 divides both deviations by 10 (within 20 %).
TEST(EpPiston, LinearElasticLimit) {
  auto m = exactpack_default();
  m.gamma_form = mp::exact::EpPistonMaterial::kRhoGammaConstant;
  const double K = m.rho0 * m.c0 * m.c0, cl = std::sqrt((K + 4.0 / 3.0 * m.G) / m.rho0);
  double dev_hel[2], dev_c[2];
  for (int i = 0; i < 2; ++i) {
    auto mi = m;
    mi.Y = m.Y / (i == 0 ? 1 : 10);
    const mp::exact::EpPiston ep(mi, 0.01);
    const double hel_lin = (K + 4.0 / 3.0 * mi.G) * mi.Y / (2 * mi.G);
    dev_hel[i] = ep.hel() / hel_lin - 1;
    dev_c[i] = ep.elastic_speed() / cl - 1;
    std::printf(
        "Y %.5g Mbar: HEL %.8g vs linear %.8g (dev %.3e), U_e %.8g vs c_L %.8g (dev "
        "%.3e)\n",
        mi.Y, ep.hel(), hel_lin, dev_hel[i], ep.elastic_speed(), cl, dev_c[i]);
  }
  std::printf("deviation ratios Y / (Y/10): HEL %.4f, U_e %.4f (first order: 10)\n",
              dev_hel[0] / dev_hel[1], dev_c[0] / dev_c[1]);
  // With deviation a eta + b eta^2 (eta = Y/(2G) = 4.5e-3, b ~ s = 1.34) the ratio is
  // 10 (1 + 0.9 b eta) = 10.05: within 2 % (0.2) is 4x that second-order term. Observed
  // 10.05 and 10.03. Was 20 %.
  EXPECT_NEAR(dev_hel[0] / dev_hel[1], 10.0, 0.2);
  EXPECT_NEAR(dev_c[0] / dev_c[1], 10.0, 0.2);
  // and at the ExactPack amplitude (Y/(2G) = 0.45 %), within 3 s Y/(2G) = 1.8 %
  EXPECT_LT(std::abs(dev_hel[0]), 3 * m.s * m.Y / (2 * m.G));
  EXPECT_LT(std::abs(dev_c[0]), 3 * m.s * m.Y / (2 * m.G));
}

}  // namespace
