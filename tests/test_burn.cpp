// High-explosive burn: programmed-burn lighting times against the Kenamond problems (with and
// without an inert obstacle, 2-D and 3-D, two resolutions each), the burn-fraction point
// functions (ramp, CJ volume burn, their combination), the CJ volume of every JWL explosive in
// the library, the partly-burnt pressure and its sound speed, and the Mader exact solution
// checked on its own (tests/exact/mader.hpp). Units: cm, g, us -> Mbar.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "burn/burn.hpp"
#include "burn/lighting.hpp"
#include "exact/kenamond.hpp"
#include "exact/mader.hpp"
#include "materials/library.hpp"
#include "precision.hpp"

namespace {

using mp::Real;
using mp::burn::Detonator;
using mp::burn::LightingGrid;
using mp::test::by_precision;
using mp::test::roundoff;

// ---------------------------------------------------------------------------------------------
// Lighting times.

// A cube [-half, half]^dim of n cells a side; 2-D grids are one cell thick in z, centred on
// z = 0.
LightingGrid box_grid(int dim, int n, double half) {
  LightingGrid g;
  const double h = 2 * half / n;
  g.n = {n, n, dim == 3 ? n : 1};
  g.h = {h, h, h};
  g.origin = {-half, -half, dim == 3 ? -half : -0.5 * h};
  return g;
}

// Explosive everywhere except the cells whose centre lies inside the ball of radius r at the
// origin (r = 0: no obstacle).
std::vector<std::uint8_t> mask_outside_ball(const LightingGrid& g, double r) {
  std::vector<std::uint8_t> m(g.cells(), 1);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const auto x = g.centre(i, j, k);
        if (mp::exact::kenamond_norm(x) < r) m[g.index(i, j, k)] = 0;
      }
  return m;
}

struct KenamondErrors {
  double max_err = 0;   // max |t - t_exact| over explosive cells, us
  double mean_err = 0;  // mean of the same
  double max_err_shadow = 0;
  long shadow_cells = 0;
  double min_shadow_excess = 1e300;  // min over shadow cells of t - t_line_of_sight
  double max_shadow_delay = 0;       // max over shadow cells of t_exact - t_line_of_sight
  long cells = 0;
};

// Kenamond problem 3 (problem 1 when r = 0) on a grid: lighting times against the exact ones.
KenamondErrors kenamond(int dim, int n, double half, double r, const mp::exact::Point3& xd,
                        double d) {
  const LightingGrid g = box_grid(dim, n, half);
  const auto mask = mask_outside_ball(g, r);
  Detonator det;
  det.a = xd;
  const auto t = mp::burn::lighting_times(g, mask, {det}, d);
  KenamondErrors e;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const long c = g.index(i, j, k);
        if (!mask[c]) {
          EXPECT_EQ(t[c], double(mp::burn::kNeverLit));
          continue;
        }
        const auto x = g.centre(i, j, k);
        const double los = mp::exact::kenamond1_time(x, xd, d);
        const double exact = r > 0 ? mp::exact::kenamond3_time(x, xd, r, d) : los;
        const double err = std::fabs(t[c] - exact);
        e.max_err = std::max(e.max_err, err);
        e.mean_err += err;
        ++e.cells;
        if (r > 0 && mp::exact::segment_hits_ball(xd, x, r)) {
          ++e.shadow_cells;
          e.max_err_shadow = std::max(e.max_err_shadow, err);
          e.min_shadow_excess = std::min(e.min_shadow_excess, t[c] - los);
          e.max_shadow_delay = std::max(e.max_shadow_delay, exact - los);
        }
      }
  e.mean_err /= double(std::max(e.cells, 1L));
  return e;
}

// The exact Kenamond 3 times against values of ExactPack's formula (kenamond3.py:
// theta = pi - alpha - beta - psi), evaluated for the problem's defaults R = 3, D = 2,
// x_d = (0, 5) [(0, 0, 5) in 3-D], t_d = 0, in double with a pure-Python transcription of that
// formula (ExactPack itself needs numpy, absent here). Our kenamond3_time decides the shadow by
// a segment-ball test and measures the arc from the angle between x and x_d; agreement to
// round-off checks both routes.
TEST(Kenamond, ExactTimesMatchExactPackFormula) {
  struct Case {
    mp::exact::Point3 x;
    double t;
  };
  const mp::exact::Point3 xd2{0, 5, 0}, xd3{0, 0, 5};
  const Case cases2[] = {{{0, -5, 0}, 5.930503326379853},       // straight behind: shadow
                         {{4, -4, 0}, 5.023554978787592},       // shadow
                         {{-3.5, -2, 0}, 3.993090964460959},    // shadow, near its edge
                         {{6, 0, 0}, 3.905124837953327},        // line of sight
                         {{5, 1, 0}, 3.201562118716424},        // line of sight
                         {{0.5, -3.2, 0}, 5.119637188199851}};  // shadow, hugging the obstacle
  const Case cases3[] = {{{0, 0, -5}, 5.930503326379853},
                         {{2, -3, -4}, 4.987256780447719},
                         {{4, 4, -1}, 4.123105625617661},
                         {{1, 1, 6}, 0.866025403784439}};
  for (const auto& c : cases2) {
    const double t = mp::exact::kenamond3_time(c.x, xd2, 3.0, 2.0);
    std::printf("  2-D (%5.2f, %5.2f): t = %.15f (ExactPack formula %.15f)\n", c.x[0], c.x[1], t,
                c.t);
    // 1e-14: round-off of a dozen operations on O(10) numbers (these are doubles in every
    // build).
    EXPECT_NEAR(t, c.t, 1e-14 * 10);
  }
  for (const auto& c : cases3) {
    const double t = mp::exact::kenamond3_time(c.x, xd3, 3.0, 2.0);
    std::printf("  3-D (%5.2f, %5.2f, %5.2f): t = %.15f (ExactPack formula %.15f)\n", c.x[0],
                c.x[1], c.x[2], t, c.t);
    EXPECT_NEAR(t, c.t, 1e-14 * 10);
  }
}

// Problem 1 (no obstacle): every cell is in line of sight of the detonator, so the
// construction gives |x - x_d| / D to round-off, at any resolution (the detonator sits off the
// cell centres and off the grid's symmetry lines).
TEST(Kenamond, Problem1LineOfSightIsExact) {
  const mp::exact::Point3 xd2{0.3, -0.7, 0}, xd3{0.3, -0.7, 0.45};
  for (int dim : {2, 3}) {
    const auto e = kenamond(dim, dim == 2 ? 80 : 32, 8.0, 0.0, dim == 2 ? xd2 : xd3, 1.0);
    std::printf("  Kenamond 1, %d-D: %ld cells, max |t - exact| = %.3e us\n", dim, e.cells,
                e.max_err);
    // Round-off of a distance of O(10) in double: 1e-13 us (the construction runs in double
    // in every build).
    EXPECT_LT(e.max_err, 1e-13);
  }
}

// Problem 3 (inert obstacle), 2-D and 3-D at two resolutions. The mask (cells whose centre is
// inside the ball are inert) is all the geometry the construction sees: its staircase stands
// up to half a cell diagonal outside the ball, and a path wrapping it through an angle theta
// is longer by about theta x that offset (d(path)/dR = theta for the Kenamond path); theta
// reaches pi - acos(3/5) = 2.21 rad at the back of the obstacle. So the error is first order
// and its maximum depends on how the lattice meets the ball: observed max 0.88 / 0.90 h/D
// (2-D, n = 64 / 128) and 0.72 / 0.97 h/D (3-D, n = 32 / 64); over other resolutions 0.52 to
// 1.23 h/D (3-D n = 24..80) and 0.88 to 1.28 h/D (2-D n = 64..512). The next test shows the
// construction itself is within 0.2 h/D of the shortest path around that staircase.
// Asserted: max <= 1.5 h/D (the issue asks for one cell transit: met at these resolutions,
// 0.97 at worst, but not at every resolution, see above), mean <= 0.15 h/D (observed 0.04 to
// 0.12), the mean error falling by at least 1.5x per halving of h (first order: 2x), and
// the shadow: every shadow cell lit no earlier than line of sight would light it, and later
// somewhere by far more than the error.
TEST(Kenamond, Problem3ShadowFirstOrder) {
  const double r = 3, d = 2, half = 8;
  for (int dim : {2, 3}) {
    const mp::exact::Point3 xd = dim == 2 ? mp::exact::Point3{0, 5, 0} : mp::exact::Point3{0, 0, 5};
    const int n_coarse = dim == 2 ? 64 : 32;
    double prev_mean = 0;
    for (int n : {n_coarse, 2 * n_coarse}) {
      const double h = 2 * half / n;
      const auto e = kenamond(dim, n, half, r, xd, d);
      std::printf(
          "  Kenamond 3, %d-D, h = %.4f: max |t - exact| = %.4f us = %.3f h/D, mean %.5f us = "
          "%.3f h/D; %ld shadow cells: min(t - t_los) = %.4f us, max exact delay %.4f us\n",
          dim, h, e.max_err, e.max_err / (h / d), e.mean_err, e.mean_err / (h / d), e.shadow_cells,
          e.min_shadow_excess, e.max_shadow_delay);
      EXPECT_LE(e.max_err, 1.5 * h / d);
      EXPECT_LE(e.mean_err, 0.15 * h / d);
      EXPECT_GT(e.shadow_cells, 0);
      // Never earlier than line of sight (the path is never shorter than the straight line;
      // 1e-13: round-off of O(10) distances).
      EXPECT_GE(e.min_shadow_excess, -1e-13);
      EXPECT_GT(e.max_shadow_delay, 3 * e.max_err);
      if (prev_mean > 0) {
        std::printf("  mean error coarse / fine: %.2f\n", prev_mean / e.mean_err);
        EXPECT_GT(prev_mean / e.mean_err, 1.5);
      }
      prev_mean = e.mean_err;
    }
  }
}

// The construction on its own geometry: in 2-D the shortest path from the detonator around the
// mask's inert staircase, for a cell outside the staircase's convex hull, is the straight line
// when that misses the hull, else a tangent to a hull vertex, along the hull, and a tangent to
// the cell (computed here independently: monotone-chain hull, Dijkstra along its vertices).
// The lighting times match it within 0.25 h/D (observed 0.09 / 0.06 h/D at n = 64 / 128; 0.17
// at n = 256): the Kenamond error above is the staircase, not the path construction.
TEST(Kenamond, Problem3MatchesShortestPathAroundTheMask) {
  using P2 = std::array<double, 2>;
  const double r = 3, d = 2, half = 8;
  const P2 det{0, 5};
  for (int n : {64, 128}) {
    const LightingGrid g = box_grid(2, n, half);
    const double h = g.h[0];
    const auto mask = mask_outside_ball(g, r);
    Detonator dt;
    dt.a = {det[0], det[1], 0};
    const auto t = mp::burn::lighting_times(g, mask, {dt}, d);
    // Convex hull (counter-clockwise) of the corners of the inert cells.
    std::vector<P2> pts;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (!mask[g.index(i, j, 0)])
          for (int a = 0; a <= 1; ++a)
            for (int b = 0; b <= 1; ++b)
              pts.push_back({g.origin[0] + (i + a) * h, g.origin[1] + (j + b) * h});
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    auto cross = [](const P2& o, const P2& a, const P2& b) {
      return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    };
    std::vector<P2> hull;
    for (int pass = 0; pass < 2; ++pass) {
      const std::size_t base = hull.size();
      for (std::size_t q = 0; q < pts.size(); ++q) {
        const P2& p = pass == 0 ? pts[q] : pts[pts.size() - 1 - q];
        while (hull.size() >= base + 2 && cross(hull[hull.size() - 2], hull.back(), p) <= 0)
          hull.pop_back();
        hull.push_back(p);
      }
      hull.pop_back();
    }
    const int m = int(hull.size());
    auto dist2 = [](const P2& a, const P2& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); };
    // Vertex k seen from q: q outside one of its two edges.
    auto sees = [&](const P2& q, int k) {
      return cross(hull[(k + m - 1) % m], hull[k], q) <= 0 ||
             cross(hull[k], hull[(k + 1) % m], q) <= 0;
    };
    auto outside_hull = [&](const P2& q) {
      for (int k = 0; k < m; ++k)
        if (cross(hull[k], hull[(k + 1) % m], q) < 0) return true;
      return false;
    };
    // The segment a-b misses the hull's interior: a separating line (an edge with both ends
    // outside it, or the segment's own line with the hull on one side).
    auto clear = [&](const P2& a, const P2& b) {
      for (int k = 0; k < m; ++k)
        if (cross(hull[k], hull[(k + 1) % m], a) <= 0 && cross(hull[k], hull[(k + 1) % m], b) <= 0)
          return true;
      bool pos = true, neg = true;
      for (const auto& v : hull) {
        const double c = cross(a, b, v);
        pos = pos && c >= -1e-12;
        neg = neg && c <= 1e-12;
      }
      return pos || neg;
    };
    // Path length from the detonator to every hull vertex (Dijkstra along the hull).
    std::vector<double> gd(m, 1e300);
    for (int k = 0; k < m; ++k)
      if (sees(det, k)) gd[k] = dist2(det, hull[k]);
    for (int sweep = 0; sweep < m; ++sweep)  // m relaxation sweeps: Bellman-Ford on a cycle
      for (int k = 0; k < m; ++k)
        for (int kk : {(k + 1) % m, (k + m - 1) % m})
          gd[kk] = std::min(gd[kk], gd[k] + dist2(hull[k], hull[kk]));
    double worst = 0;
    long cells = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const long c = g.index(i, j, 0);
        const auto x3 = g.centre(i, j, 0);
        const P2 x{x3[0], x3[1]};
        if (!mask[c] || !outside_hull(x)) continue;
        double len = 1e300;
        if (clear(det, x)) {
          len = dist2(det, x);
        } else {
          for (int k = 0; k < m; ++k)
            if (sees(x, k)) len = std::min(len, gd[k] + dist2(hull[k], x));
        }
        worst = std::max(worst, std::fabs(t[c] - len / d));
        ++cells;
      }
    std::printf(
        "  n = %d: %d hull vertices, %ld cells outside the hull, max |t - path/D| = %.3e "
        "us = %.3f h/D\n",
        n, m, cells, worst, worst / (h / d));
    EXPECT_LE(worst, 0.25 * h / d);
  }
}

// A plane-wave lens lights along a plane and a line detonator along a segment: both give the
// exact distance over D in line of sight.
TEST(Lighting, LineAndPlaneDetonators) {
  const LightingGrid g = box_grid(3, 24, 1.5);
  const std::vector<std::uint8_t> mask(g.cells(), 1);
  const double d = 0.8;
  Detonator plane;
  plane.kind = Detonator::Kind::Plane;
  plane.a = {0, 0, -1.5};  // the bottom face
  plane.b = {0, 0, 2};     // any length
  plane.t0 = 0.25;
  Detonator line;
  line.kind = Detonator::Kind::Line;
  line.a = {-0.4, 0.1, 0.2};
  line.b = {0.9, 0.3, 0.2};
  line.t0 = 0.5;
  const auto tp = mp::burn::lighting_times(g, mask, {plane}, d);
  const auto tl = mp::burn::lighting_times(g, mask, {line}, d);
  const auto tb = mp::burn::lighting_times(g, mask, {plane, line}, d);
  double ep = 0, el = 0, eb = 0;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const long c = g.index(i, j, k);
        const auto x = g.centre(i, j, k);
        const double exact_p = plane.t0 + (x[2] + 1.5) / d;
        const auto f = mp::burn::detail::foot(line, x);
        const double exact_l = line.t0 + mp::burn::detail::dist(f, x) / d;
        ep = std::max(ep, std::fabs(tp[c] - exact_p));
        el = std::max(el, std::fabs(tl[c] - exact_l));
        eb = std::max(eb, std::fabs(tb[c] - std::min(exact_p, exact_l)));
      }
  std::printf("  plane: max err %.3e us; line: %.3e us; both: %.3e us\n", ep, el, eb);
  // Round-off of distances of O(1) in double.
  EXPECT_LT(ep, 1e-14);
  EXPECT_LT(el, 1e-14);
  EXPECT_LT(eb, 1e-14);
}

// Explosive cut off from the detonator stays unlit; a detonator away from every explosive cell
// is refused.
TEST(Lighting, UnreachableAndMisplaced) {
  LightingGrid g = box_grid(2, 20, 1.0);
  std::vector<std::uint8_t> mask(g.cells(), 1);
  for (int j = 0; j < g.n[1]; ++j) mask[g.index(10, j, 0)] = 0;  // an inert wall at i = 10
  Detonator det;
  det.a = {-0.55, 0.05, 0};
  const auto t = mp::burn::lighting_times(g, mask, {det}, 1.0);
  long lit_left = 0, unlit_right = 0;
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i) {
      const double ti = t[g.index(i, j, 0)];
      if (i < 10 && ti < double(mp::burn::kNeverLit)) ++lit_left;
      if (i > 10 && ti == double(mp::burn::kNeverLit)) ++unlit_right;
    }
  std::printf("  wall: %ld cells lit on the detonator's side (of 200), %ld unlit beyond (of 180)\n",
              lit_left, unlit_right);
  EXPECT_EQ(lit_left, 200);
  EXPECT_EQ(unlit_right, 180);
  Detonator lost;
  lost.a = {0.05, 0.05, 0};  // in the wall
  try {
    (void)mp::burn::lighting_times(g, mask, {lost}, 1.0);
    ADD_FAILURE() << "a detonator inside inert material was accepted";
  } catch (const std::invalid_argument& e) {
    std::printf("  refused: %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("point detonator 0"), std::string::npos);
  }
}

// ---------------------------------------------------------------------------------------------
// Burn fraction point functions.

// The programmed ramp: 0 up to the lighting time, linear over ramp_length / D, 1 after; the
// unlit sentinel never burns.
TEST(BurnFraction, ProgrammedRampLimits) {
  const Real d = Real(0.8), ramp = Real(2 * 0.05), tl = Real(3.0);
  const Real t_full = tl + ramp / d;  // 3.125 us, exact in binary
  const Real f_before = mp::burn::programmed_burn_fraction(Real(2.5), tl, d, ramp);
  const Real f_at = mp::burn::programmed_burn_fraction(tl, tl, d, ramp);
  const Real f_half = mp::burn::programmed_burn_fraction(tl + Real(0.0625), tl, d, ramp);
  const Real f_full = mp::burn::programmed_burn_fraction(t_full, tl, d, ramp);
  const Real f_after = mp::burn::programmed_burn_fraction(Real(50), tl, d, ramp);
  const Real f_never = mp::burn::programmed_burn_fraction(Real(1e20), mp::burn::kNeverLit, d, ramp);
  std::printf(
      "  F before %.3g, at t_light %.3g, half way %.9g, at t_light + ramp/D %.9g, "
      "after %.3g, never lit %.3g\n",
      double(f_before), double(f_at), double(f_half), double(f_full), double(f_after),
      double(f_never));
  EXPECT_EQ(f_before, Real(0));
  EXPECT_EQ(f_at, Real(0));
  // (t - t_l) D / ramp = 0.0625 * 0.8 / 0.1: a few roundings from 0.5.
  EXPECT_NEAR(double(f_half), 0.5, roundoff(1e-15));
  EXPECT_NEAR(double(f_full), 1.0, roundoff(1e-15));
  EXPECT_EQ(f_after, Real(1));
  EXPECT_EQ(f_never, Real(0));
}

// CJ volume burn: 0 at v0 (and in expansion), 1 at v_cj (and beyond), linear between; the
// combined update takes the larger fraction and never goes back.
TEST(BurnFraction, VolumeBurnAndCombination) {
  const auto* m = mp::materials::find_material("pbx9404_products");
  ASSERT_NE(m, nullptr);
  const Real rho0 = Real(m->rho0);
  const auto b = mp::burn::make_burn_params(rho0, Real(m->param("D")), Real(m->param("p_cj")),
                                            Real(0.05), true, true);
  const Real v_mid = Real(0.5) * (b.v0 + b.v_cj);
  const Real f_v0 = mp::burn::volume_burn_fraction(b.v0, b.v0, b.v_cj);
  const Real f_exp = mp::burn::volume_burn_fraction(Real(1.2) * b.v0, b.v0, b.v_cj);
  const Real f_mid = mp::burn::volume_burn_fraction(v_mid, b.v0, b.v_cj);
  const Real f_cj = mp::burn::volume_burn_fraction(b.v_cj, b.v0, b.v_cj);
  const Real f_over = mp::burn::volume_burn_fraction(Real(0.9) * b.v_cj, b.v0, b.v_cj);
  std::printf(
      "  v0 %.6f, v_cj %.6f cm^3/g: F(v0) %.3g, F(1.2 v0) %.3g, F(mid) %.9g, F(v_cj) "
      "%.9g, F(0.9 v_cj) %.3g\n",
      double(b.v0), double(b.v_cj), double(f_v0), double(f_exp), double(f_mid), double(f_cj),
      double(f_over));
  EXPECT_EQ(f_v0, Real(0));
  EXPECT_EQ(f_exp, Real(0));
  // v0 - v_mid loses a factor v0 / (v0 - v_cj) ~ 4 to cancellation.
  EXPECT_NEAR(double(f_mid), 0.5, roundoff(1e-14));
  EXPECT_NEAR(double(f_cj), 1.0, roundoff(1e-15));
  EXPECT_EQ(f_over, Real(1));

  // Combination: at t_light + ramp / (4 D) the ramp gives 1/4; compressed to 3/4 of the way to
  // v_cj the volume burn gives 3/4 and wins; then re-expanded to v0 at an earlier ramp value
  // it keeps 3/4 (irreversible).
  const Real tl = Real(1);
  const Real t_q = tl + b.ramp_length / (4 * b.d_cj);
  const Real v_34 = b.v0 - Real(0.75) * (b.v0 - b.v_cj);
  const Real f1 = mp::burn::update_burn_fraction(b, Real(0), t_q, tl, rho0);
  const Real f2 = mp::burn::update_burn_fraction(b, f1, t_q, tl, 1 / v_34);
  const Real f3 = mp::burn::update_burn_fraction(b, f2, t_q, tl, rho0);
  auto prog_only = b;
  prog_only.volume_burn = false;
  const Real f4 = mp::burn::update_burn_fraction(prog_only, Real(0), t_q, tl, 1 / v_34);
  auto vol_only = b;
  vol_only.programmed = false;
  const Real f5 = mp::burn::update_burn_fraction(vol_only, Real(0), Real(100), tl, rho0);
  std::printf(
      "  ramp only %.6f; with compression %.6f; re-expanded %.6f; programmed only "
      "%.6f; volume only, uncompressed, late %.3g\n",
      double(f1), double(f2), double(f3), double(f4), double(f5));
  // Round-off of a few operations on O(1) numbers.
  EXPECT_NEAR(double(f1), 0.25, roundoff(1e-15));
  EXPECT_NEAR(double(f2), 0.75, roundoff(1e-14));
  EXPECT_EQ(f3, f2);
  EXPECT_NEAR(double(f4), 0.25, roundoff(1e-15));
  EXPECT_EQ(f5, Real(0));
}

// The CJ volume of every JWL explosive in the library from its own (rho0, D, p_cj):
// v_cj / v0 = 1 - u_cj / D with u_cj = p_cj / (rho0 D), the same state as the EOS module's
// jwl_cj_from_tabulated; and the JWL pressure at (v_cj, e_cj = e0 + p_cj (v0 - v_cj) / 2),
// e0 = E0 / rho0 (the library's E0 is the detonation energy per unit INITIAL volume,
// library.hpp / jwl.hpp), is p_cj to the accuracy the library states for its rows: each row
// reproduces its tabulated CJ state to 0.03 % through the products Hugoniot; at the tabulated
// (D, p_cj) the jump conditions land on the EOS within the same (observed: +0.001 % PBX 9404,
// -0.004 % Composition B, +0.030 % PETN; bound 0.05 %).
TEST(BurnFraction, CjVolumeOfLibraryExplosives) {
  int checked = 0;
  for (const auto& name : mp::materials::material_names()) {
    const auto* m = mp::materials::find_material(name);
    if (m->eos != mp::eos::kJwl) continue;
    const double rho0 = m->rho0, d = m->param("D"), pcj = m->param("p_cj");
    const double e0 = m->param("E0") / rho0;
    const double rel = double(mp::burn::cj_relative_volume(Real(rho0), Real(d), Real(pcj)));
    const double u_cj = pcj / (rho0 * d);
    const double v0 = 1 / rho0, v_cj = rel * v0;
    const auto eos = mp::materials::make_eos(*m);
    const auto tab = mp::eos::jwl_cj_from_tabulated(eos.jwl(), Real(e0), Real(d), Real(pcj));
    const double e_cj = e0 + 0.5 * pcj * (v0 - v_cj);
    const double p = double(eos.pressure(Real(1 / v_cj), Real(e_cj)));
    std::printf(
        "  %-18s v_cj/v0 = %.6f, u_cj = %.5f cm/us, rho_cj = %.5f g/cc, e_cj = %.6f "
        "cm^2/us^2, P_jwl(v_cj, e_cj) = %.5f Mbar (p_cj %.3f, %+.3f %%)\n",
        name.c_str(), rel, u_cj, 1 / v_cj, e_cj, p, pcj, 100 * (p / pcj - 1));
    // Same jump conditions two ways: round-off.
    EXPECT_NEAR(rel, 1 - u_cj / d, roundoff(1e-15));
    EXPECT_NEAR(double(tab.rho) * v_cj, 1.0, roundoff(1e-14));
    EXPECT_NEAR(double(tab.e) / e_cj, 1.0, roundoff(1e-14));
    // The library's stated 0.03 % with margin; float rounding (1e-7) is far inside.
    EXPECT_NEAR(p / pcj, 1.0, 5e-4) << name;
    // A detonation compresses: 0.7 < v_cj / v0 < 0.8 for condensed explosives (gamma_cj ~ 3:
    // v_cj / v0 = gamma / (gamma + 1)).
    EXPECT_GT(rel, 0.7);
    EXPECT_LT(rel, 0.8);
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

// The partly burnt explosive: p = F P_products, the products' own p and c at F = 1, no
// pressure at F = 0, and c^2 at frozen F against an isentropic finite difference of p.
TEST(BurnFraction, MixedPressureAndSoundSpeed) {
  const auto* m = mp::materials::find_material("pbx9404_products");
  const auto eos = mp::materials::make_eos(*m);
  const double rho0 = m->rho0, d = m->param("D"), pcj = m->param("p_cj");
  const double e0 = m->param("E0") / rho0;
  const double v_cj = double(mp::burn::cj_specific_volume(Real(rho0), Real(d), Real(pcj)));
  const Real rho = Real(1 / v_cj);
  const Real e = Real(e0 + 0.5 * pcj * (1 / rho0 - v_cj));
  EXPECT_EQ(mp::burn::he_pressure(eos, Real(1), rho, e), eos.pressure(rho, e));
  EXPECT_EQ(mp::burn::he_pressure(eos, Real(0), rho, e), Real(0));
  const double c1 = double(mp::burn::he_sound_speed(eos, Real(1), rho, e));
  const double cp = double(eos.sound_speed(rho, e));
  // F = 1: the formula's f (1 - f) term vanishes; what is left is f c^2 = c^2 (round-off).
  EXPECT_NEAR(c1 / cp, 1.0, roundoff(1e-15));
  EXPECT_EQ(mp::burn::he_sound_speed2(eos, Real(0), rho, e), Real(0));
  for (double f : {0.25, 0.5, 0.9}) {
    // c^2 = dp/drho along the isentrope de = p / rho^2 drho at fixed F, central difference in
    // double on the Real EOS (step 1e-3 rho in double; 3e-3 rho in float, where rounding of
    // p, not the O(step^2) truncation, dominates; cf. test_eos).
    const double step = by_precision(1e-3, 3e-3) * double(rho);
    auto p_of = [&](double r) {
      // Isentrope through (rho, e) to second order: e(r) = e + p/rho^2 dr + ... The second-order
      // term of e cancels in the central difference of p.
      const double p0 = double(mp::burn::he_pressure(eos, Real(f), rho, e));
      const double dr = r - double(rho);
      return double(mp::burn::he_pressure(eos, Real(f), Real(r),
                                          Real(double(e) + p0 / (double(rho) * double(rho)) * dr)));
    };
    const double fd = (p_of(double(rho) + step) - p_of(double(rho) - step)) / (2 * step);
    const double c2 = double(mp::burn::he_sound_speed2(eos, Real(f), rho, e));
    std::printf(
        "  F = %.2f: c^2 = %.6f (cm/us)^2, isentropic FD %.6f (rel. %.1e), products' %.6f\n", f, c2,
        fd, fd / c2 - 1, cp * cp);
    // Double: the O(step^2) truncation, step^2 = 1e-6 relative times a curvature factor of
    // O(1) (the isentrope's second-order term cancels in the central difference); observed
    // -4.4e-7 to -4.8e-7, bound 2e-6 (4.2x; was 1e-5, whose comment said "observed below
    // 1e-7"). Float: p rounding / step, 1e-7 * 0.4 / 0.008 ~ 1e-5 relative of c^2; observed
    // -7.8e-6 to -1.3e-5, bound 5e-5 (3.8x; was 1e-3).
    EXPECT_NEAR(fd / c2, 1.0, by_precision(2e-6, 5e-5)) << "F = " << f;
    // Frozen c below the products' own (f <= 1, P >= 0): the time step may use c_products.
    EXPECT_LT(c2, cp * cp);
  }
}

// The mixture closure p = (1 - F) P_u(rho, e - e0) + F P_products(rho, e): the unreacted solid's
// pressure at F = 0, the products' at F = 1, and c^2 at frozen F against an isentropic finite
// difference. The unreacted solid is a FIXTURE, not a material: a Mie-Grueneisen solid with
// magnitudes typical of an HMX-based explosive (rho0 1.84, c0 0.25 cm/us, s 2, Gamma0 1), written
// before the library had one (pbx9404_unreacted; in the cycle: tests/test_burn_unreacted.cpp).
TEST(BurnFraction, MixtureClosure) {
  const auto* m = mp::materials::find_material("pbx9404_products");
  const auto prod = mp::materials::make_eos(*m);
  const auto solid =
      mp::eos::make_eos(mp::eos::MieGruneisen{Real(1.84), Real(0.25), Real(2), Real(1)});
  const Real e0 = Real(m->param("E0") / m->rho0);
  const Real rho = Real(1.84 * 1.2), e = e0 + Real(0.004);  // shocked, not yet burnt
  EXPECT_EQ(mp::burn::he_pressure_mixed(solid, prod, e0, Real(0), rho, e),
            solid.pressure(rho, e - e0));
  EXPECT_EQ(mp::burn::he_pressure_mixed(solid, prod, e0, Real(1), rho, e), prod.pressure(rho, e));
  // Unburnt at rest: no pressure (the solid is referenced at rho0, e = 0).
  EXPECT_NEAR(double(mp::burn::he_pressure_mixed(solid, prod, e0, Real(0), Real(1.84), e0)), 0.0,
              roundoff(1e-15));
  for (double f : {0.0, 0.5, 1.0}) {
    // Step 1e-4 rho in double: the solid's p is stiffer in rho than the products' (p''' larger).
    const double step = by_precision(1e-4, 3e-3) * double(rho);
    const double p0 = double(mp::burn::he_pressure_mixed(solid, prod, e0, Real(f), rho, e));
    auto p_of = [&](double r) {
      const double dr = r - double(rho);
      return double(
          mp::burn::he_pressure_mixed(solid, prod, e0, Real(f), Real(r),
                                      Real(double(e) + p0 / (double(rho) * double(rho)) * dr)));
    };
    const double fd = (p_of(double(rho) + step) - p_of(double(rho) - step)) / (2 * step);
    const double c2 = double(mp::burn::he_sound_speed2_mixed(solid, prod, e0, Real(f), rho, e));
    std::printf("  mixture F = %.1f: p = %.5f Mbar, c^2 = %.6f, isentropic FD %.6f (rel. %.1e)\n",
                f, p0, c2, fd, fd / c2 - 1);
    // Double: the O(step^2) truncation, step^2 = 1e-8 relative times the curvature factor,
    // larger for the stiff solid (observed 6.4e-8, 1.9e-8, -3.7e-9 at F = 0, 0.5, 1); bound
    // 3e-7 (4.7x; was 1e-5, 156x). Float: p rounding / step (the step of
    // MixedPressureAndSoundSpeed, the solid's p larger): observed 5.7e-5, 1.7e-5, -2.4e-6;
    // bound 2.5e-4 (4.4x; was 1e-3).
    EXPECT_NEAR(fd / c2, 1.0, by_precision(3e-7, 2.5e-4)) << "F = " << f;
  }
  // At F = 0 and 1 the closure's c^2 is the phase's own.
  EXPECT_NEAR(double(mp::burn::he_sound_speed2_mixed(solid, prod, e0, Real(0), rho, e)) /
                  double(solid.sound_speed2(rho, e - e0)),
              1.0, roundoff(1e-14));
  EXPECT_NEAR(double(mp::burn::he_sound_speed2_mixed(solid, prod, e0, Real(1), rho, e)) /
                  double(prod.sound_speed2(rho, e)),
              1.0, roundoff(1e-14));
}

// numerics.void_density reaches the mixture closure too: below it the explosive has no pressure
// and the floor's sound speed at every burn fraction; at and above it, and with it off, the
// closure's values bit for bit (the products' EOS carries the void density, as the driver sets
// it on every material's EOS).
TEST(BurnFraction, MixtureClosureVoidDensity) {
  const auto* m = mp::materials::find_material("pbx9404_products");
  auto prod = mp::materials::make_eos(*m);
  const auto solid = mp::materials::make_eos(*mp::materials::find_material("pbx9404_unreacted"));
  const Real e0 = Real(m->param("E0") / m->rho0);
  const Real thin = Real(1e-7), e = e0 + Real(0.5);  // expanded, hot: p > 0, c well above 0
  std::vector<Real> p_off, c_off;
  for (double f : {0.0, 0.5, 1.0}) {
    p_off.push_back(mp::burn::he_pressure_mixed_cut(solid, prod, e0, Real(f), thin, e));
    c_off.push_back(mp::burn::he_sound_speed_mixed(solid, prod, e0, Real(f), thin, e));
    EXPECT_EQ(p_off.back(), mp::burn::he_pressure_mixed(solid, prod, e0, Real(f), thin, e));
    EXPECT_GT(c_off.back(), Real(1e-6)) << f;  // the closure's own, not the floor
  }
  EXPECT_GT(p_off[2], Real(0));
  prod.rho_void = Real(1e-6);
  for (int n = 0; n < 3; ++n) {
    const Real f = Real(0.5 * n);
    EXPECT_EQ(mp::burn::he_pressure_mixed_cut(solid, prod, e0, f, thin, e), Real(0)) << f;
    EXPECT_EQ(mp::burn::he_sound_speed_mixed(solid, prod, e0, f, thin, e),
              std::sqrt(mp::eos::kSoundSpeed2Floor))
        << f;
    for (Real rho : {Real(1e-6), Real(1.0)}) {  // at the void density and above: unchanged
      auto off = prod;
      off.rho_void = 0;
      EXPECT_EQ(mp::burn::he_pressure_mixed_cut(solid, prod, e0, f, rho, e),
                mp::burn::he_pressure_mixed_cut(solid, off, e0, f, rho, e))
          << f << " " << rho;
      EXPECT_EQ(mp::burn::he_sound_speed_mixed(solid, prod, e0, f, rho, e),
                mp::burn::he_sound_speed_mixed(solid, off, e0, f, rho, e))
          << f << " " << rho;
    }
  }
}

// The test_burn::update kernel of DeviceKernelMatchesHost (a functor: nvcc allows no extended
// lambda in a TEST body, a private member function): F and p at point i.
struct BurnPointKernel {
  Real rho0;
  mp::burn::BurnParams b;
  mp::eos::Eos eos;
  Real e;
  Kokkos::View<Real*> f, p;

  KOKKOS_INLINE_FUNCTION void operator()(int i) const {
    const Real rho = rho0 * (1 + Real(0.005) * i);
    const Real fi = mp::burn::update_burn_fraction(b, Real(0), Real(0.001) * i, Real(0.01), rho);
    f(i) = fi;
    p(i) = mp::burn::he_pressure(eos, fi, rho, e);
  }
};

// The point functions run in a named device kernel and give the host's numbers bit for bit.
// (In an OpenMP build the kernel runs on the host CPU: this checks that the functions compile
// and dispatch inside a kernel; only a GPU build compares a device's arithmetic.)
TEST(BurnFraction, DeviceKernelMatchesHost) {
  const auto* m = mp::materials::find_material("comp_b_products");
  const auto eos = mp::materials::make_eos(*m);
  const auto b = mp::burn::make_burn_params(Real(m->rho0), Real(m->param("D")),
                                            Real(m->param("p_cj")), Real(0.02), true, true);
  const int n = 64;
  Kokkos::View<Real*> f("f", n), p("p", n);
  const Real e = Real(m->param("E0") / m->rho0);
  const Real rho0 = Real(m->rho0);
  Kokkos::parallel_for("test_burn::update", Kokkos::RangePolicy<>(0, n),
                       BurnPointKernel{rho0, b, eos, e, f, p});
  auto fh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f);
  auto ph = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p);
  int burning = 0;
  for (int i = 0; i < n; ++i) {
    const Real rho = rho0 * (1 + Real(0.005) * i);
    const Real fi = mp::burn::update_burn_fraction(b, Real(0), Real(0.001) * i, Real(0.01), rho);
    EXPECT_EQ(fh(i), fi) << i;
    EXPECT_EQ(ph(i), mp::burn::he_pressure(eos, fi, rho, e)) << i;
    if (fi > 0 && fi < 1) ++burning;
  }
  std::printf("  %d of %d points part-burnt, F(63) = %.6f, p(63) = %.6f Mbar\n", burning, n,
              double(fh(n - 1)), double(ph(n - 1)));
  EXPECT_GT(burning, 10);
}

// ---------------------------------------------------------------------------------------------
// Mader problem (exact solution, checked on its own).

// ExactPack's defaults: p_cj = 0.3 Mbar, D = 0.8 cm/us, gamma = 3, piston at rest; at
// t = 6.25 us the front is at 5 cm.
TEST(Mader, CjStateAtTheFront) {
  const mp::exact::Mader m(0.3, 0.8, 3.0);
  const double t = 6.25, xf = m.d() * t;
  const auto s = m.sample(xf * (1 - 1e-15), t);  // just behind the front
  const auto a = m.sample(xf * (1 + 1e-12), t);  // just ahead
  std::printf(
      "  rho0 %.6f, rho_cj %.6f g/cc, u_cj %.6f, c_cj %.6f cm/us; behind the front: rho "
      "%.6f u %.6f p %.6f c %.6f\n",
      m.rho0(), m.rho_cj(), m.u_cj(), m.c_cj(), s.rho, s.u, s.p, s.c);
  // Hand values of the gamma = 3 problem: rho0 = 4 p / D^2 = 1.875 (the "1.875 g/cc" of
  // ExactPack's comment), rho_cj = 2.5, u_cj = 0.2, c_cj = 0.6. 1e-13: round-off of the
  // sampling (doubles in every build).
  EXPECT_NEAR(m.rho0(), 1.875, 1e-14);
  EXPECT_NEAR(s.rho, 2.5, 1e-13);
  EXPECT_NEAR(s.u, 0.2, 1e-13);
  EXPECT_NEAR(s.p, 0.3, 1e-13);
  EXPECT_NEAR(s.c, 0.6, 1e-13);
  // Jump conditions from the unburnt state (rho0, 0, p = 0, e0 = q) and the CJ (sonic)
  // condition; the gamma-law e = p / ((gamma - 1) rho) includes q.
  const double g = m.gamma();
  const double e_cj = s.p / ((g - 1) * s.rho), e0 = m.heat_of_reaction();
  const double r_mass = m.rho0() * m.d() - s.rho * (m.d() - s.u);
  const double r_mom = s.p - m.rho0() * m.d() * s.u;
  const double r_energy = (e_cj - e0) - 0.5 * s.p * (1 / m.rho0() - 1 / s.rho);
  const double r_sonic = s.u + s.c - m.d(), r_c = std::sqrt(g * s.p / s.rho) - s.c;
  std::printf(
      "  residuals: mass %.1e, momentum %.1e, energy %.1e, sonic %.1e, c of the gas %.1e "
      "(bound 1e-13)\n",
      r_mass, r_mom, r_energy, r_sonic, r_c);
  EXPECT_LT(std::abs(r_mass), 1e-13);
  EXPECT_LT(std::abs(r_mom), 1e-13);
  EXPECT_LT(std::abs(r_energy), 1e-13);
  EXPECT_LT(std::abs(r_sonic), 1e-13);
  EXPECT_LT(std::abs(r_c), 1e-13);
  EXPECT_EQ(a.rho, m.rho0());
  EXPECT_EQ(a.u, 0.0);
  EXPECT_EQ(a.p, 0.0);
}

// Behind the front: the C- invariant u - 2c/(gamma - 1) is constant, the C+ characteristics are
// the rays x/t = u + c, the flow is isentropic, the rear region is at rest (piston at rest), the
// fan ends at x = D t / 2 for gamma = 3, and the solution satisfies the Euler equations
// (central-difference residual of mass and momentum falls as step^2).
TEST(Mader, TaylorWaveCharacteristicsAndRearState) {
  const mp::exact::Mader m(0.3, 0.8, 3.0);
  const double g = m.gamma(), t = 6.25, xf = m.d() * t;
  const double k = m.p_cj() / std::pow(m.rho_cj(), g);
  double max_j = 0, max_c = 0, max_s = 0;
  for (int i = 1; i < 100; ++i) {
    const double x = xf * i / 100.0;
    const auto s = m.sample(x, t);
    max_j = std::max(max_j, std::fabs(s.u - 2 * s.c / (g - 1) - m.riemann_invariant()));
    if (x / t > m.tail_speed()) max_c = std::max(max_c, std::fabs(s.u + s.c - x / t));
    max_s = std::max(max_s, std::fabs(s.p / std::pow(s.rho, g) / k - 1));
  }
  std::printf(
      "  max |J- - J_cj| %.2e, max |u + c - x/t| in the fan %.2e, max |p/rho^g / K - 1| "
      "%.2e; fan tail at x/t = %.6f (D/2 = %.6f)\n",
      max_j, max_c, max_s, m.tail_speed(), 0.5 * m.d());
  // Round-off (doubles).
  EXPECT_LT(max_j, 1e-14);
  EXPECT_LT(max_c, 1e-14);
  EXPECT_LT(max_s, 1e-13);
  EXPECT_NEAR(m.tail_speed(), 0.5 * m.d(), 1e-15);
  // Rear region: at rest, at the state the fan ends on, continuous across the tail.
  const auto rear = m.sample(0.3 * xf, t);
  const auto tail_in = m.sample(m.tail_speed() * t * (1 + 1e-12), t);
  std::printf("  rear: u %.3g, p %.6f Mbar, rho %.6f g/cc (fan side of the tail: u %.2e, p %.6f)\n",
              rear.u, rear.p, rear.rho, tail_in.u, tail_in.p);
  EXPECT_EQ(rear.u, 0.0);
  EXPECT_NEAR(tail_in.u, 0.0, 1e-12);
  EXPECT_NEAR(tail_in.p / rear.p, 1.0, 1e-11);
  // Hand value at the middle of the fan (x = 3.75 cm): x/t = 0.6, J = -0.4, so u = 0.1,
  // c = 0.5, p = 0.3 (5/6)^3, rho = 2.5 (5/6).
  const auto mid = m.sample(3.75, t);
  EXPECT_NEAR(mid.u, 0.1, 1e-14);
  EXPECT_NEAR(mid.c, 0.5, 1e-14);
  EXPECT_NEAR(mid.p, 0.3 * std::pow(5.0 / 6.0, 3), 1e-14);
  EXPECT_NEAR(mid.rho, 2.5 * 5.0 / 6.0, 1e-14);

  // Euler residuals at interior fan points, central differences in x and t with step s and s/2.
  auto residual = [&](double step) {
    double worst = 0;
    for (double x : {3.3, 3.75, 4.2, 4.8}) {
      auto q = [&](double xx, double tt) { return m.sample(xx, tt); };
      const auto xp = q(x + step, t), xm = q(x - step, t);
      const auto tp = q(x, t + step), tm = q(x, t - step);
      const auto c = q(x, t);
      const double mass =
          (tp.rho - tm.rho) / (2 * step) + (xp.rho * xp.u - xm.rho * xm.u) / (2 * step);
      const double mom = (tp.u - tm.u) / (2 * step) + c.u * (xp.u - xm.u) / (2 * step) +
                         (xp.p - xm.p) / (2 * step) / c.rho;
      // Scale: rho D / (D t) and D / t.
      worst = std::max({worst, std::fabs(mass) / (c.rho / t), std::fabs(mom) / (m.d() / t)});
    }
    return worst;
  };
  const double r1 = residual(1e-2), r2 = residual(5e-3);
  std::printf("  Euler residual (relative): step 1e-2 %.3e, 5e-3 %.3e, ratio %.2f\n", r1, r2,
              r1 / r2);
  // Second-order central differences of a smooth solution: the residual is O(step^2), so small
  // and falling about 4x per halving (3..5 allows the next-order term).
  EXPECT_LT(r1, 1e-4);
  EXPECT_GT(r1 / r2, 3.0);
  EXPECT_LT(r1 / r2, 5.0);
}

// A moving piston (u_p = 0.1 cm/us): the rear state moves with it and the fan ends where
// u = u_p; a piston faster than u_cj is refused (an overdriven detonation, not this problem).
TEST(Mader, MovingPiston) {
  const mp::exact::Mader m(0.3, 0.8, 3.0, 0.1);
  const auto rear = m.sample(1.0, 6.25);
  std::printf("  u_p = 0.1: fan tail at x/t = %.6f, rear u %.6f, p %.6f\n", m.tail_speed(), rear.u,
              rear.p);
  // gamma = 3: c = u - J = 0.1 + 0.4 = 0.5, tail speed u + c = 0.6.
  EXPECT_NEAR(m.tail_speed(), 0.6, 1e-15);
  EXPECT_EQ(rear.u, 0.1);
  EXPECT_NEAR(rear.p, 0.3 * std::pow(0.5 / 0.6, 3), 1e-14);
  EXPECT_THROW(mp::exact::Mader(0.3, 0.8, 3.0, 0.25), std::invalid_argument);
}

}  // namespace
