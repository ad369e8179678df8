// Verification of the PLIC point functions (issue: multi-material, Youngs interface
// reconstruction). The analytic plane-cube volume is checked against an independent geometric
// computation: the box clipped by the half-space, its volume by the divergence theorem.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "precision.hpp"
#include "remap/plic.hpp"

using namespace mp;

namespace {

using Vec = std::array<double, 3>;

double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Tolerances are stated for double; a float build scales them by the ratio of round-offs.
const double scale = mp::test::roundoff(1.0);

// Volume of the box [lo, hi] on the side n.x <= alpha (n != 0). Each of the six faces is
// clipped by the half-space (Sutherland-Hodgman against one plane); the volume is
// (1/3) sum over faces of x_f . S_f (divergence theorem, S_f the outward vector area). The cap
// on the plane closes the polyhedron, so its vector area is minus the sum of the others and any
// point of the plane serves as x_cap.
double clipped_box_volume(const Vec& lo, const Vec& hi, const Vec& n, double alpha) {
  double vol3 = 0;
  Vec s_sum = {0, 0, 0};
  for (int d = 0; d < 3; ++d) {
    const int e = (d + 1) % 3, f = (d + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      std::vector<Vec> poly(4);
      const double uv[4][2] = {{lo[e], lo[f]}, {hi[e], lo[f]}, {hi[e], hi[f]}, {lo[e], hi[f]}};
      for (int c = 0; c < 4; ++c) {
        poly[c][d] = side ? hi[d] : lo[d];
        poly[c][e] = uv[c][0];
        poly[c][f] = uv[c][1];
      }
      std::vector<Vec> out;
      for (size_t c = 0; c < poly.size(); ++c) {
        const Vec& p = poly[c];
        const Vec& q = poly[(c + 1) % poly.size()];
        const double dp = dot(n, p) - alpha, dq = dot(n, q) - alpha;
        if (dp <= 0) out.push_back(p);
        if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
          const double t = dp / (dp - dq);
          out.push_back(
              {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])});
        }
      }
      if (out.size() < 3) continue;
      Vec s = {0, 0, 0};
      for (size_t c = 0; c < out.size(); ++c) {
        const Vec x = cross(out[c], out[(c + 1) % out.size()]);
        for (int i = 0; i < 3; ++i) s[i] += 0.5 * x[i];
      }
      const double outward = side ? 1.0 : -1.0;
      if (s[d] * outward < 0)
        for (double& si : s) si = -si;
      vol3 += dot(out[0], s);
      for (int i = 0; i < 3; ++i) s_sum[i] += s[i];
    }
  }
  const double nn = dot(n, n);
  const Vec x_cap = {alpha * n[0] / nn, alpha * n[1] / nn, alpha * n[2] / nn};
  vol3 -= dot(x_cap, s_sum);
  return vol3 / 3;
}

double cube_reference(const Vec& n, double alpha) {
  return clipped_box_volume({0, 0, 0}, {1, 1, 1}, n, alpha);
}

// Random normals of every kind the remap meets: generic, axis-aligned, one zero component
// (2-D-like), one or two tiny components, equal components (branch boundaries), all with
// random signs and magnitudes.
Vec random_normal(std::mt19937_64& rng, int kind) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> axis(0, 2);
  const double mag = std::pow(10.0, 2 * u(rng));
  Vec n = {u(rng), u(rng), u(rng)};
  switch (kind % 7) {
    case 1: {  // axis-aligned
      const int a = axis(rng);
      n = {0, 0, 0};
      n[a] = u(rng) < 0 ? -1 : 1;
      break;
    }
    case 2:  // one zero component
      n[axis(rng)] = 0;
      break;
    case 3:  // one tiny component
      n[axis(rng)] *= std::pow(10.0, -4 - 8 * std::abs(u(rng)));
      break;
    case 4: {  // two equal magnitudes
      const int a = axis(rng), b = (a + 1) % 3;
      n[b] = (u(rng) < 0 ? -1 : 1) * n[a];
      break;
    }
    case 5:  // all magnitudes equal
      n = {u(rng) < 0 ? -1.0 : 1.0, u(rng) < 0 ? -1.0 : 1.0, u(rng) < 0 ? -1.0 : 1.0};
      break;
    case 6: {  // two tiny components
      const int a = axis(rng);
      n[(a + 1) % 3] *= 1e-7;
      n[(a + 2) % 3] *= 1e-9;
      break;
    }
    default:
      break;
  }
  if (n[0] == 0 && n[1] == 0 && n[2] == 0) n[0] = 1;
  for (double& c : n) c *= mag;
  return n;
}

// min and max of n.x over [0,1]^3.
void cube_range(const Vec& n, double& lo, double& hi) {
  lo = hi = 0;
  for (double c : n) (c < 0 ? lo : hi) += c;
}

Real vol(const Vec& n, double alpha) {
  return plic::plane_cube_volume(Real(n[0]), Real(n[1]), Real(n[2]), Real(alpha));
}
Real alpha_of(const Vec& n, double f) {
  return plic::plane_cube_alpha(Real(n[0]), Real(n[1]), Real(n[2]), Real(f));
}

TEST(Plic, VolumeMatchesClippedPolyhedron) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> u(0, 1);
  double max_err = 0;
  int count = 0;
  for (int t = 0; t < 7000; ++t) {
    const Vec n = random_normal(rng, t);
    double lo, hi;
    cube_range(n, lo, hi);
    const double w = hi - lo;
    // Random alphas over and beyond the cube's range, plus every vertex value (branch points).
    std::vector<double> alphas = {
        lo - 0.1 * w + 1.2 * w * u(rng), lo + w * u(rng), lo, hi, lo - w, hi + w};
    const int vx = t % 8;
    alphas.push_back((vx & 1 ? n[0] : 0) + (vx & 2 ? n[1] : 0) + (vx & 4 ? n[2] : 0));
    for (double a : alphas) {
      const double ref = cube_reference(n, a);
      const double got = vol(n, a);
      max_err = std::max(max_err, std::abs(got - ref));
      ASSERT_NEAR(got, ref, 1e-12 * scale)
          << "n = " << n[0] << " " << n[1] << " " << n[2] << " alpha = " << a;
      ++count;
    }
  }
  // Outside the range and for a zero normal.
  EXPECT_EQ(vol({1, -2, 3}, -2.5), 0);
  EXPECT_EQ(vol({1, -2, 3}, 4.5), 1);
  EXPECT_EQ(vol({0, 0, 0}, 0.0), 1);
  // just below zero: the most negative Real short of -0 (-1e-300 would round to -0 in float)
  EXPECT_EQ(vol({0, 0, 0}, -std::numeric_limits<Real>::denorm_min()), 0);
  // Exact values: axis-aligned plane at x = 0.3; diagonal plane through the centre.
  EXPECT_NEAR(vol({1, 0, 0}, 0.3), 0.3, 1e-16 * scale);
  EXPECT_NEAR(vol({0, 0, -2}, -0.6), 0.7, 1e-15 * scale);
  // one ulp of 0.5 in double; float rounds this one to 1.5 ulps (8.9e-8), so 2 ulps there
  EXPECT_NEAR(vol({1, 1, 1}, 1.5), 0.5, mp::test::by_precision(1e-16, 1.2e-7));
  EXPECT_NEAR(vol({1, 1, 1}, 0.5), 1.0 / 48, 1e-16 * scale);
  std::printf("plane_cube_volume: %d cases, max |error| vs clipped polyhedron = %.2e\n", count,
              max_err);
}

TEST(Plic, AlphaInvertsVolume) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(0, 1);
  const double special[] = {0, 1e-300, 1e-12, 1e-9, 1e-6, 0.5, 1 - 1e-6, 1 - 1e-9, 1 - 1e-12, 1};
  double max_abs = 0, max_rel_tiny = 0;
  int count = 0;
  for (int t = 0; t < 7000; ++t) {
    const Vec n = random_normal(rng, t);
    double lo, hi;
    cube_range(n, lo, hi);
    std::vector<double> fs(std::begin(special), std::end(special));
    fs.push_back(u(rng));
    fs.push_back(std::pow(10.0, -12 * u(rng)));
    for (double f : fs) {
      const Real a = alpha_of(n, f);
      ASSERT_GE(a, Real(lo) - 1e-15 * scale * (hi - lo));
      ASSERT_LE(a, Real(hi) + 1e-15 * scale * (hi - lo));
      const double v = vol(n, a);
      const double err = std::abs(v - f);
      max_abs = std::max(max_abs, err);
      ASSERT_NEAR(v, f, 1e-12 * scale) << "n = " << n[0] << " " << n[1] << " " << n[2];
      // alpha is stored as an absolute plane constant, so a tiny fraction is resolved only to
      // the rounding of n.x over the cube: assert alpha lies within 4 ulps of that range of the
      // exact root (f is bracketed), and relative accuracy where nothing cancels (n >= 0).
      const double ulp4 = 4 * std::numeric_limits<Real>::epsilon() * (std::abs(lo) + hi - lo);
      // (against f as the code holds it: 1 - 1e-9 is 1 in float)
      const double fr = double(Real(f));
      if (f > 0 && f < 1) {
        ASSERT_LE(vol(n, a - ulp4), fr);
        ASSERT_GE(vol(n, a + ulp4), fr);
      }
      if (f >= 1e-12 && f <= 1e-6 && lo == 0) {
        max_rel_tiny = std::max(max_rel_tiny, err / f);
        ASSERT_LE(err / f, 1e-12 * scale)
            << "f = " << f << " n = " << n[0] << " " << n[1] << " " << n[2];
      }
      ++count;
    }
    EXPECT_EQ(vol(n, alpha_of(n, 0)), 0);
    EXPECT_EQ(vol(n, alpha_of(n, 1)), 1);
  }
  // Inner solver alone (positive sorted normal, alpha from 0): relative accuracy of tiny fractions.
  double max_rel_unit = 0;
  for (int t = 0; t < 2000; ++t) {
    double m[3] = {0.05 + u(rng), 0.05 + u(rng), 0.05 + u(rng)};
    std::sort(m, m + 3);
    const double s = m[0] + m[1] + m[2];
    for (double& c : m) c /= s;
    for (double f : {1e-12, 1e-9, 1e-6, 1e-3}) {
      const Real a = plic::detail::unit_alpha(Real(m[0]), Real(m[1]), Real(m[2]), Real(f));
      const double v = plic::detail::unit_volume(Real(m[0]), Real(m[1]), Real(m[2]), a);
      max_rel_unit = std::max(max_rel_unit, std::abs(v - f) / f);
      ASSERT_NEAR(v, f, 1e-13 * scale * f);
    }
  }
  std::printf(
      "plane_cube_alpha: %d round trips, max |V(alpha(f)) - f| = %.2e; relative for 1e-12 <= f <= "
      "1e-6, n >= 0: "
      "%.2e (unit-cube solver alone %.2e)\n",
      count, max_abs, max_rel_tiny, max_rel_unit);
}

TEST(Plic, CellWrappersScaleTheNormal) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (int t = 0; t < 1000; ++t) {
    const Vec nv = random_normal(rng, t);
    const Real n[3] = {Real(nv[0]), Real(nv[1]), Real(nv[2])};
    const double dx = 0.1 + u(rng), dy = 0.1 + 3 * u(rng), dz = 0.1 + 0.5 * u(rng);
    const Vec hi = {dx, dy, dz};
    double lo_a = 0, hi_a = 0;
    for (int i = 0; i < 3; ++i) (nv[i] < 0 ? lo_a : hi_a) += nv[i] * hi[i];
    const double alpha = lo_a + (hi_a - lo_a) * u(rng);
    const double ref = clipped_box_volume({0, 0, 0}, hi, nv, alpha);
    const double cell = dx * dy * dz;
    ASSERT_NEAR(plic::cell_plane_volume(n, Real(alpha), Real(dx), Real(dy), Real(dz)), ref,
                1e-12 * scale * cell);
    const double f = u(rng);
    const Real a = plic::cell_plane_alpha(n, Real(f), Real(dx), Real(dy), Real(dz));
    ASSERT_NEAR(plic::cell_plane_fraction(n, a, Real(dx), Real(dy), Real(dz)), f, 1e-12 * scale);
  }
}

// Fractions of the 27 cells around a plane through the centre cell [0,1]^3 (cell (i,j,k) of
// the block is [i-1, i] x ... scaled by the cell sizes).
void plane_stencil(const Vec& n, double alpha, const Vec& h, Real a[3][3][3]) {
  const Real nr[3] = {Real(n[0]), Real(n[1]), Real(n[2])};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const double shift = n[0] * (i - 1) * h[0] + n[1] * (j - 1) * h[1] + n[2] * (k - 1) * h[2];
        a[i][j][k] =
            plic::cell_plane_fraction(nr, Real(alpha - shift), Real(h[0]), Real(h[1]), Real(h[2]));
      }
}

double angle_deg(const Vec& n, const Real m[3]) {
  const double c = dot(n, {m[0], m[1], m[2]}) / std::sqrt(dot(n, n));
  return std::acos(std::min(1.0, std::max(-1.0, c))) * 180 / M_PI;
}

TEST(Plic, YoungsNormalOfAPlanarInterface) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  Real a[3][3][3];
  Real m[3];
  // Axis-aligned planes: exactly the axis.
  for (int d = 0; d < 3; ++d)
    for (double sign : {-1.0, 1.0}) {
      Vec n = {0, 0, 0};
      n[d] = sign;
      plane_stencil(n, sign * (0.1 + 0.8 * u(rng)), {1, 1, 1}, a);
      plic::youngs_normal(a, m);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(m[i], i == d ? Real(sign) : Real(0));
    }
  // Uniform stencils: no normal.
  for (Real value : {Real(0), Real(0.37), Real(1)}) {
    for (auto& p : a)
      for (auto& q : p)
        for (Real& r : q) r = value;
    plic::youngs_normal(a, m);
    EXPECT_EQ(m[0], 0);
    EXPECT_EQ(m[1], 0);
    EXPECT_EQ(m[2], 0);
  }
  // Symmetric diagonals are exact by symmetry.
  for (const Vec& n : {Vec{1, 1, 0}, Vec{1, -1, 1}, Vec{-1, 0, -1}}) {
    plane_stencil(n, dot(n, {0.5, 0.5, 0.5}), {1, 1, 1}, a);
    plic::youngs_normal(a, m);
    EXPECT_LT(angle_deg(n, m), 1e-6);
  }
  // Random planes through the centre cell: the code computes Youngs' formula, n = -g / |g| with
  // g_d the (1,2,1) x (1,2,1)-weighted difference of the fractions across the stencil along d,
  // divided by the cell size (Youngs 1982; DESIGN.md step 7). Evaluated here independently, in
  // double and in another order, it must give the same direction to round-off.
  std::mt19937_64 rng2(13);
  double max_formula = 0;
  for (int t = 0; t < 500; ++t) {
    const Vec n = {s(rng2), s(rng2), s(rng2)};
    const Vec h = t % 2 ? Vec{1, 2, 0.5} : Vec{1, 1, 1};
    const Vec p = {u(rng2), u(rng2), u(rng2)};
    plane_stencil(n, dot(n, {p[0] * h[0], p[1] * h[1], p[2] * h[2]}), h, a);
    plic::youngs_normal(a, Real(h[0]), Real(h[1]), Real(h[2]), m);
    Vec g = {0, 0, 0};
    const double w[3] = {1, 2, 1};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) {
          const double c = double(a[i][j][k]);
          g[0] += (i - 1) * w[j] * w[k] * c;
          g[1] += (j - 1) * w[i] * w[k] * c;
          g[2] += (k - 1) * w[i] * w[j] * c;
        }
    const Vec want = {-g[0] / h[0], -g[1] / h[1], -g[2] / h[2]};
    // the angle from its sine, |want x m| / (|want| |m|): acos near 1 resolves only 1e-6 deg
    const Vec mm = {double(m[0]), double(m[1]), double(m[2])};
    const Vec x = {want[1] * mm[2] - want[2] * mm[1], want[2] * mm[0] - want[0] * mm[2],
                   want[0] * mm[1] - want[1] * mm[0]};
    const double sine = std::sqrt(dot(x, x) / (dot(want, want) * dot(mm, mm)));
    max_formula = std::max(max_formula, std::asin(std::min(1.0, sine)) * 180 / M_PI);
  }
  std::printf("youngs_normal against the formula evaluated in double: max angle %.2e deg\n",
              max_formula);
  // Round-off: the code sums 9 weighted differences per axis (8 roundings of eps/2 of the
  // largest partial sum, which can exceed the component when the terms cancel) and normalises
  // in Real: 16 eps rad bounds the direction (2e-13 deg in double, 1.1e-4 deg in float); the
  // observed 2.7e-14 deg is 2 eps, the roundings mostly cancelling.
  EXPECT_LT(max_formula, 16 * mp::test::kEps * 180 / M_PI);
}

// Regression pin, not verification: the angle between Youngs' normal and the exact normal of
// 2000 random planes (fixed seed) through a 3x3x3 stencil. Youngs' gradient is first order in
// the normal, exact only for symmetric planes (verified above); no reference gives these
// statistics, so they are this code's own, observed max 3.72 and mean 1.11 degrees on cubes,
// max 7.44 degrees on 1:2:0.5 cells, pinned 7-13 % above to catch a change of the stencil or
// its weights (which would move them by far more).
TEST(PlicRegressionPin, YoungsNormalAngleStatistics) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  Real a[3][3][3];
  Real m[3];
  double max_angle = 0, mean_angle = 0, max_angle_aniso = 0;
  const int trials = 2000;
  for (int t = 0; t < trials; ++t) {
    Vec n = {s(rng), s(rng), s(rng)};
    if (t % 4 == 1) n[t % 3] = 0;  // 2-D-like
    const Vec p = {u(rng), u(rng), u(rng)};
    plane_stencil(n, dot(n, p), {1, 1, 1}, a);
    plic::youngs_normal(a, m);
    EXPECT_NEAR(m[0] * m[0] + m[1] * m[1] + m[2] * m[2], 1, 1e-14 * scale);
    const double ang = angle_deg(n, m);
    max_angle = std::max(max_angle, ang);
    mean_angle += ang / trials;
    // Non-cubic cells 1 : 2 : 0.5.
    const Vec h = {1, 2, 0.5};
    plane_stencil(n, dot(n, {p[0] * h[0], p[1] * h[1], p[2] * h[2]}), h, a);
    plic::youngs_normal(a, Real(h[0]), Real(h[1]), Real(h[2]), m);
    max_angle_aniso = std::max(max_angle_aniso, angle_deg(n, m));
  }
  std::printf(
      "youngs_normal (pin): %d planes, angle to exact normal max %.2f mean %.2f deg; "
      "1:2:0.5 cells max %.2f deg\n",
      trials, max_angle, mean_angle, max_angle_aniso);
  EXPECT_LT(max_angle, 4.0);
  EXPECT_LT(mean_angle, 1.25);
  EXPECT_LT(max_angle_aniso, 8.0);
}

// The ELVIRA-type normal (plic::elvira_normal): exact, to round-off, for a plane whose column
// sums along its dominant axis are its heights (slopes below 0.2 through the centre cell's
// middle: every column of three cells is full below the plane and empty above it), where
// Youngs' weighted gradient is off by up to a few degrees; a uniform block has no normal; and
// over random planes through the centre cell (the pin's set above) it is on average closer to
// the exact normal than Youngs' (the least-misfit choice includes Youngs' normal itself).
TEST(Plic, ElviraNormalReproducesPlanes) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  Real a[3][3][3];
  Real m[3], y[3];
  double max_elvira = 0, max_youngs = 0;
  for (int t = 0; t < 500; ++t) {
    const int c = t % 3;
    Vec n = {0.2 * s(rng), 0.2 * s(rng), 0.2 * s(rng)};
    n[c] = t % 2 ? 1 : -1;
    const Vec h = t % 4 < 2 ? Vec{1, 1, 1} : Vec{1, 1.5, 0.8};
    Vec p = {0.5, 0.5, 0.5};
    p[c] = 0.3 + 0.4 * u(rng);
    plane_stencil(n, dot(n, {p[0] * h[0], p[1] * h[1], p[2] * h[2]}), h, a);
    // (the slope bound in cell units on the non-cubic cells: at most 0.2 x 1.5 / 0.8 = 0.375,
    // still inside the columns)
    plic::elvira_normal(a, Real(h[0]), Real(h[1]), Real(h[2]), m);
    plic::youngs_normal(a, Real(h[0]), Real(h[1]), Real(h[2]), y);
    max_elvira = std::max(max_elvira, angle_deg(n, m));
    max_youngs = std::max(max_youngs, angle_deg(n, y));
  }
  std::printf("elvira_normal, 500 planes of slope < 0.2: max angle %.2e deg (Youngs %.2f deg)\n",
              max_elvira, max_youngs);
  // Round-off: the heights are sums of three fractions, each exact to a few ulps; the
  // angle's acos resolves about 1e-6 deg in double (angle_deg), so the bound is that in double
  // and 1e-6 x 2^29 ulps' worth in float: observed 1.7e-6 deg in double (the acos's
  // resolution), bound 1e-5. Youngs' is off by a visible angle on the same planes: observed max
  // 0.63 deg; the bound 0.5 says the test's planes are ones Youngs' gradient gets wrong.
  EXPECT_LT(max_elvira, mp::test::kFloat ? 0.05 : 1e-5);
  EXPECT_GT(max_youngs, 0.5);
  for (Real value : {Real(0), Real(0.37), Real(1)}) {
    for (auto& pl : a)
      for (auto& q : pl)
        for (Real& r : q) r = value;
    plic::elvira_normal(a, Real(1), Real(1), Real(1), m);
    EXPECT_EQ(m[0], 0);
    EXPECT_EQ(m[1], 0);
    EXPECT_EQ(m[2], 0);
  }
  // the pin's random planes (any slope, 2-D-like ones included): mean angle to the exact normal
  std::mt19937_64 rng2(9);
  double mean_e = 0, mean_y = 0;
  const int trials = 2000;
  for (int t = 0; t < trials; ++t) {
    Vec n = {s(rng2), s(rng2), s(rng2)};
    if (t % 4 == 1) n[t % 3] = 0;
    const Vec p = {u(rng2), u(rng2), u(rng2)};
    plane_stencil(n, dot(n, p), {1, 1, 1}, a);
    plic::elvira_normal(a, m);
    plic::youngs_normal(a, y);
    EXPECT_NEAR(m[0] * m[0] + m[1] * m[1] + m[2] * m[2], 1, 1e-14 * scale);
    mean_e += angle_deg(n, m) / trials;
    mean_y += angle_deg(n, y) / trials;
  }
  std::printf("elvira_normal, %d random planes: mean angle %.3f deg (Youngs %.3f deg)\n", trials,
              mean_e, mean_y);
  // observed 0.004 against Youngs' 1.110 deg (the misses: planes steep enough that a column of
  // three holds no full or no empty cell); the bound is a tenth of Youngs'
  EXPECT_LT(mean_e, 0.1 * mean_y);
}

TEST(Plic, FluxVolume) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(0, 1);
  // Axis-aligned interface x = xi in a cell [0,dx]x[0,dy]x[0,dz], material on x <= xi.
  for (int t = 0; t < 200; ++t) {
    const double dx = 0.5 + u(rng), dy = 0.5 + u(rng), dz = 0.5 + u(rng);
    const double xi = dx * u(rng), area = dy * dz, h = dx * u(rng), dv = h * area;
    const Real n[3] = {1, 0, 0};
    const Real hi_flux =
        plic::flux_volume(n, Real(xi), Real(dx), Real(dy), Real(dz), 0, true, Real(dv));
    const Real lo_flux =
        plic::flux_volume(n, Real(xi), Real(dx), Real(dy), Real(dz), 0, false, Real(-dv));
    EXPECT_NEAR(hi_flux, std::max(0.0, xi - (dx - h)) * area, 1e-14 * scale);
    EXPECT_NEAR(lo_flux, std::min(xi, h) * area, 1e-14 * scale);
    // Across a face parallel to the interface plane: the fraction of the slab.
    const double dvy = dx * dz * dy * u(rng);
    EXPECT_NEAR(plic::flux_volume(n, Real(xi), Real(dx), Real(dy), Real(dz), 1, true, Real(dvy)),
                xi / dx * dvy, 1e-14 * scale);
  }
  // Random planes, slabs and faces against the clipped slab; complementary materials sum to the
  // slab volume.
  double max_err = 0, max_sum_err = 0;
  for (int t = 0; t < 5000; ++t) {
    const Vec nv = random_normal(rng, t);
    const Real n[3] = {Real(nv[0]), Real(nv[1]), Real(nv[2])};
    const Real nneg[3] = {-n[0], -n[1], -n[2]};
    const Vec len = {0.2 + u(rng), 0.2 + u(rng), 0.2 + u(rng)};
    const double cell = len[0] * len[1] * len[2];
    const int axis = t % 3;
    const bool high = (t / 3) % 2;
    const double area = cell / len[axis];
    const double h = len[axis] * (t % 17 == 0 ? 1.0 : u(rng));
    const double dv = h * area;
    const double f = t % 23 == 0 ? 1e-9 : u(rng);
    const Real alpha = plic::cell_plane_alpha(n, Real(f), Real(len[0]), Real(len[1]), Real(len[2]));
    Vec lo = {0, 0, 0}, hi = len;
    if (high)
      lo[axis] = len[axis] - h;
    else
      hi[axis] = h;
    const double ref = clipped_box_volume(lo, hi, nv, alpha);
    const Real got =
        plic::flux_volume(n, alpha, Real(len[0]), Real(len[1]), Real(len[2]), axis, high, Real(dv));
    max_err = std::max(max_err, std::abs(got - ref) / cell);
    ASSERT_NEAR(got, ref, 1e-12 * scale * cell) << "t = " << t;
    // The other material: fraction 1 - f, normal -n.
    const Real other = plic::material_flux(nneg, Real(1 - f), Real(len[0]), Real(len[1]),
                                           Real(len[2]), axis, high, Real(dv));
    const Real mine = plic::material_flux(n, Real(f), Real(len[0]), Real(len[1]), Real(len[2]),
                                          axis, high, Real(dv));
    max_sum_err = std::max(max_sum_err, std::abs(mine + other - dv) / dv);
    ASSERT_NEAR(mine + other, dv, 1e-12 * scale * dv) << "t = " << t;
    ASSERT_GE(got, 0);
    ASSERT_LE(got, dv * (1 + 1e-14 * scale));
  }
  // A whole-cell slab carries the whole material volume.
  const Real n[3] = {0.3, -0.5, 0.8};
  const Real a = plic::cell_plane_alpha(n, Real(0.4), 1, 2, 3);
  EXPECT_NEAR(plic::flux_volume(n, a, 1, 2, 3, 1, false, 6), 0.4 * 6, 1e-13 * scale);
  // Zero normal and pure cells.
  const Real zero[3] = {0, 0, 0};
  EXPECT_NEAR(plic::material_flux(zero, Real(0.25), 1, 1, 1, 0, true, Real(0.2)), 0.05,
              1e-16 * scale);
  EXPECT_EQ(plic::material_flux(n, Real(0), 1, 1, 1, 0, true, Real(0.2)), 0);
  EXPECT_EQ(plic::material_flux(n, Real(1), 1, 1, 1, 0, true, Real(0.2)), Real(0.2));
  std::printf(
      "flux_volume: max |error| / cell volume vs clipped slab = %.2e; "
      "complementary materials sum to the slab within %.2e relative\n",
      max_err, max_sum_err);
}

}  // namespace

// The onion skin's two faces of a divergent donor (plic::onion_volumes, plic::limit_pair):
// three materials, a sliver (1e-4 to 1e-8 of the cell) between two layers whose planes have
// different normals, thin flux slabs through both faces along x. Unlimited, some pairs of
// faces take more of the sliver than the donor holds (the perforator's steel slivers between
// air and products: 1.26-1.56 times); limited, no pair does, each face's share is scaled by
// the same factor as the other's, and a pair within the content is left bit for bit.
TEST(Plic, OnionFacesOfADivergentDonorTakeNoMoreThanItHolds) {
  std::vector<std::array<Real, 3>> normals;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k) {
        if (i == 0 && j == 0 && k == 0) continue;
        const double l = std::sqrt(double(i * i + j * j + k * k));
        normals.push_back({Real(i / l), Real(j / l), Real(k / l)});
      }
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0, 1);
  for (int t = 0; t < 24; ++t) {
    const double x = g(rng), y = g(rng), z = g(rng), l = std::sqrt(x * x + y * y + z * z);
    normals.push_back({Real(x / l), Real(y / l), Real(z / l)});
  }
  const Real dx = 1, dy = Real(0.8), dz = Real(1.2), pd = dx * dy * dz;
  long cases = 0, over = 0, unchanged = 0;
  double worst_unlimited = 0, worst_limited = 0;
  for (const double a0 : {0.2, 0.5, 0.8})
    for (const double eps : {1e-4, 1e-6, 1e-8})
      for (const double slab : {0.002, 0.02, 0.2})
        for (const auto& n0 : normals)
          for (const auto& n1 : normals) {
            const Real a[3] = {Real(a0), Real(eps), Real(1 - a0 - eps)};
            const Real nrm[3][3] = {{n0[0], n0[1], n0[2]}, {n1[0], n1[1], n1[2]}, {0, 0, 0}};
            const auto normal = [&](int m, Real* n) {
              for (int c = 0; c < 3; ++c) n[c] = nrm[m][c];
            };
            const Real fl =
                Real(slab) * pd;  // out through the high face, and as much through the low
            Real hi[3], lo[3];
            plic::onion_volumes(3, 3, a, normal, pd, dx, dy, dz, 0, fl, hi);
            plic::onion_volumes(3, 3, a, normal, pd, dx, dy, dz, 0, -fl, lo);
            Real hi_l[3] = {hi[0], hi[1], hi[2]}, lo_l[3] = {lo[0], lo[1], lo[2]};
            plic::limit_pair(3, a, pd, hi_l, lo);
            plic::limit_pair(3, a, pd, lo_l, hi);
            for (int m = 0; m < 3; ++m) {
              ++cases;
              const double cap = double(a[m]) * double(pd);
              const double ratio = (double(hi[m]) + double(lo[m])) / cap;
              worst_unlimited = std::max(worst_unlimited, ratio);
              if (ratio > 1) {
                ++over;
                // both faces scaled by the same factor (a face with no share keeps none; in
                // float most of these pairs exceed the content only by rounding, often with
                // one face's share 0)
                if (hi[m] > 0 && lo[m] > 0) {
                  EXPECT_NEAR(double(hi_l[m]) / double(hi[m]), double(lo_l[m]) / double(lo[m]),
                              4 * test::kEps);
                }
                if (!(hi[m] > 0)) {
                  EXPECT_EQ(hi_l[m], Real(0));
                }
                if (!(lo[m] > 0)) {
                  EXPECT_EQ(lo_l[m], Real(0));
                }
              } else if (hi_l[m] == hi[m] && lo_l[m] == lo[m]) {
                ++unchanged;
              }
              const double limited = (double(hi_l[m]) + double(lo_l[m])) / cap;
              worst_limited = std::max(worst_limited, limited);
              EXPECT_LE(limited, 1 + 4 * test::kEps) << "material " << m;
            }
          }
  std::printf(
      "onion faces: %ld material-pairs, %ld over the content unlimited (worst %.3f), "
      "%ld within it left unchanged; limited worst %.17g\n",
      cases, over, worst_unlimited, unchanged, worst_limited);
  // the unlimited split does over-draw (the limit is needed), and only where it does is
  // anything changed
  EXPECT_GT(over, 0);
  EXPECT_EQ(over + unchanged, cases);
}
