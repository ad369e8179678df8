// Programmed-burn lighting times on a Cartesian grid: the time the detonation front, running at
// the CJ speed D from the detonators, reaches each explosive cell centre, going around inert
// material (Huygens' construction: the front is the envelope of wavelets; the lighting time is
// the length of the shortest path through explosive over D).
//
// This file: the reference construction (host code over the global grid, `materials[].burn.
// lighting: host`) and the geometry it shares, device-ready, with the per-rank construction the
// runs use by default (lighting_device.hpp: the same candidates as a label-correcting iteration
// of Kokkos kernels; tests/test_lighting_device.cpp compares the two).
//
// Construction (host code, run once at set-up): an any-angle Dijkstra on the cell graph, Lazy
// Theta* (A. Nash, S. Koenig, C. Tovey, "Lazy Theta*: Any-Angle Path Planning and Path Length
// Analysis in 3D", AAAI 2010; Theta*: Nash, Daniel, Koenig, Felner, AAAI 2007). Each cell keeps
// a parent, either a detonator or a pivot (a point where the front bent around inert material,
// with its own time and parent), and its time is the parent's time plus the straight distance
// over D. A cell takes its neighbour's parent when the straight segment from that parent
// crosses only explosive cells (line of sight: a 3-D DDA walk, Amanatides & Woo, Eurographics
// 1987; a segment through an edge or corner is blocked if any cell touching it there is
// inert). When it is hidden, the best of these becomes its parent: a closed neighbour's centre;
// a closed neighbour's parent it sees; a corner of the inert cell that hid it (or of one that
// hides a neighbour's parent), or a staircase corner of a closed neighbour, reached straight
// from that parent. Corner pivots sit at the corner moved 1e-9 of the way into an explosive
// cell touching it. Then the string is pulled: a pivot's own parent, when seen, replaces it.
// So:
// - in line of sight of a detonator the time is exact (|x - x_det| / D to round-off), with no
//   grid-direction error of a fast-marching or 26-neighbour Dijkstra;
// - in the shadow of an inert obstacle the path wraps the obstacle's staircase (the mask is all
//   the geometry this sees), at its corners: tests/test_burn.cpp finds the times within 0.1
//   cell transits h/D of the exact shortest path around that staircase (2-D), and within one
//   h/D (up to 1.3 at some resolutions) of the Kenamond times for the true ball, whose
//   staircase stands up to half a cell diagonal outside it: first order in h.
// A pure line-of-sight construction (t = min over detonators of |x - x_det| / D, skipping
// hidden cells or not) is wrong throughout the shadow; this one is not.
//
// Cost: one priority-queue pass, O(N log N), plus one line-of-sight walk (O(grid width)) per
// cell, and a few dozen more per cell where the front bends (64^3 cells around a ball: about
// 1 s on one core). On many ranks Burn::light gathers the global mask, every rank computes the
// times of the whole grid and keeps its own block.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <vector>

#include "burn/burn.hpp"
#include "core/math.hpp"

namespace mp::burn {

// The grid as plain data for kernels (LightingGrid::box()).
struct LightingBox {
  int n[3];
  double origin[3];
  double h[3];
};

// Cell (i, j, k) spans origin + [i, i+1) h; its centre is origin + (i + 1/2) h. Cells are
// numbered i + n[0] (j + n[1] k), x fastest. A 2-D grid is n[2] = 1.
struct LightingGrid {
  std::array<int, 3> n{1, 1, 1};
  std::array<double, 3> origin{0, 0, 0};
  std::array<double, 3> h{1, 1, 1};

  long cells() const { return long(n[0]) * n[1] * n[2]; }
  long index(int i, int j, int k) const { return i + long(n[0]) * (j + long(n[1]) * k); }
  std::array<double, 3> centre(int i, int j, int k) const {
    return {origin[0] + (i + 0.5) * h[0], origin[1] + (j + 0.5) * h[1],
            origin[2] + (k + 0.5) * h[2]};
  }
  double largest_edge() const { return std::max({h[0], h[1], h[2]}); }
  LightingBox box() const {
    return {{n[0], n[1], n[2]}, {origin[0], origin[1], origin[2]}, {h[0], h[1], h[2]}};
  }
};

// Host bytes per global cell that the construction and its caller (Burn::light) hold at once,
// on every rank: the mask gathered over the ranks (2 x 1 B), the times, parents and centre
// pivots (3 x 8 B), the closed and seeded flags (2 x 1 B), the pivots (40 B each) and the open
// queue (16 B an entry). Counted in the run's memory estimate (src/driver/memory.cpp); 50
// covers the 28 B of fixed arrays and the pivots and queue of the shipped decks.
constexpr double kLightingHostBytesPerCell = 50;

// A detonator fires at t0:
// - Point: at a;
// - Line: along the segment a -> b;
// - Plane: the whole plane through a with normal b (a plane-wave lens), lighting every
//   explosive cell it passes through at t0.
struct Detonator {
  enum class Kind { Point, Line, Plane };
  Kind kind = Kind::Point;
  std::array<double, 3> a{0, 0, 0};
  std::array<double, 3> b{0, 0, 0};
  double t0 = 0;
};

inline const char* to_string(Detonator::Kind k) {
  switch (k) {
    case Detonator::Kind::Point:
      return "point";
    case Detonator::Kind::Line:
      return "line";
    case Detonator::Kind::Plane:
      return "plane";
  }
  return "?";
}

namespace detail {

using Vec = std::array<double, 3>;

// std::numeric_limits' infinity as a constant kernels may read (its function is host code to nvcc).
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Device-ready forms of the geometry below (the host reference and the per-rank construction,
// lighting_device.hpp, run the same operations, so the two agree bit for bit in line of sight).
KOKKOS_INLINE_FUNCTION double dot3(const double* u, const double* v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}
KOKKOS_INLINE_FUNCTION double dist3(const double* u, const double* v) {
  const double w[3] = {u[0] - v[0], u[1] - v[1], u[2] - v[2]};
  return MP_KOKKOS_MATH::sqrt(dot3(w, w));
}
// The point f of detonator (kind, a, b) nearest to x (see foot below).
KOKKOS_INLINE_FUNCTION void foot3(Detonator::Kind kind, const double* a, const double* b,
                                  const double* x, double* f) {
  if (kind == Detonator::Kind::Line) {
    const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double xa[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
    const double len2 = dot3(ab, ab);
    double s = len2 > 0 ? dot3(xa, ab) / len2 : 0;
    s = s < 0.0 ? 0.0 : s;
    s = s > 1.0 ? 1.0 : s;
    for (int d = 0; d < 3; ++d) f[d] = a[d] + s * ab[d];
  } else if (kind == Detonator::Kind::Plane) {
    const double xa[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
    const double s = dot3(xa, b) / dot3(b, b);
    for (int d = 0; d < 3; ++d) f[d] = x[d] - s * b[d];
  } else {
    for (int d = 0; d < 3; ++d) f[d] = a[d];
  }
}

inline double dot(const Vec& u, const Vec& v) {
  return dot3(u.data(), v.data());
}
inline Vec sub(const Vec& u, const Vec& v) {
  return {u[0] - v[0], u[1] - v[1], u[2] - v[2]};
}
inline double dist(const Vec& u, const Vec& v) {
  return dist3(u.data(), v.data());
}

// The point of the detonator nearest to x (where the front that reaches x straight starts).
inline Vec foot(const Detonator& d, const Vec& x) {
  Vec f;
  foot3(d.kind, d.a.data(), d.b.data(), x.data(), f.data());
  return f;
}

// True when the segment from point a to point p, which lies inside cell (bi, bj, bk), crosses
// no inert cell (inert(i, j, k): a cell of the grid that is not explosive; false outside it).
// The cell containing a (a detonator on the surface of the explosive, or a pivot) is not
// checked, nor is the end cell. Where the segment passes exactly through a cell edge or corner,
// every cell touching it there must be explosive (a front does not squeeze through a point
// contact of inert cells). Parts of the segment outside the grid block nothing.
// blocker (when not null) receives the first inert cell met (i, j, k), walking from p toward a.
template <class Inert>
KOKKOS_INLINE_FUNCTION bool sees(const LightingBox& g, const Inert& inert, const double* a,
                                 const double* p, int bi, int bj, int bk, int* blocker) {
  const double d[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]};
  int c[3] = {bi, bj, bk};
  int step[3];
  double tmax[3], tdelta[3];
  const double inf = kInfinity;
  for (int ax = 0; ax < 3; ++ax) {
    const int cc = c[ax];
    if (d[ax] > 0) {
      step[ax] = 1;
      tdelta[ax] = g.h[ax] / d[ax];
      tmax[ax] = (g.origin[ax] + (cc + 1) * g.h[ax] - p[ax]) / d[ax];  // to the first face
    } else if (d[ax] < 0) {
      step[ax] = -1;
      tdelta[ax] = -g.h[ax] / d[ax];
      tmax[ax] = (g.origin[ax] + cc * g.h[ax] - p[ax]) / d[ax];
    } else {
      step[ax] = 0;
      tdelta[ax] = inf;
      tmax[ax] = inf;
    }
  }
  // Relative tolerance for "the segment leaves through an edge or a corner" and "a lies on the
  // face": a few ulps of the segment parameter.
  constexpr double tie = 1e-12;
  bool first = true;
  while (true) {
    double tmin = tmax[0] < tmax[1] ? tmax[0] : tmax[1];
    tmin = tmax[2] < tmin ? tmax[2] : tmin;
    if (tmin >= 1 - tie) return true;  // a lies in the current cell
    if (!first && inert(c[0], c[1], c[2])) {
      if (blocker)
        for (int q = 0; q < 3; ++q) blocker[q] = c[q];
      return false;
    }
    first = false;
    int ties[3], nt = 0;
    for (int ax = 0; ax < 3; ++ax)
      if (tmax[ax] <= tmin * (1 + tie) + tie) ties[nt++] = ax;
    // Cells touching the edge / corner the segment leaves through: every proper subset of the
    // axes that tie.
    for (int mask = 1; mask < (1 << nt) - 1; ++mask) {
      int s[3] = {c[0], c[1], c[2]};
      for (int q = 0; q < nt; ++q)
        if (mask & (1 << q)) s[ties[q]] += step[ties[q]];
      if (inert(s[0], s[1], s[2])) {
        if (blocker)
          for (int q = 0; q < 3; ++q) blocker[q] = s[q];
        return false;
      }
    }
    for (int q = 0; q < nt; ++q) {
      c[ties[q]] += step[ties[q]];
      tmax[ties[q]] += tdelta[ties[q]];
    }
    if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= g.n[0] || c[1] >= g.n[1] || c[2] >= g.n[2])
      return true;
  }
}

// inert(i, j, k) of a global host mask (one byte a cell, LightingGrid order).
struct HostInert {
  const std::uint8_t* explosive;
  int n[3];
  KOKKOS_INLINE_FUNCTION bool operator()(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= n[0] || j >= n[1] || k >= n[2]) return false;
    return explosive[i + long(n[0]) * (j + long(n[1]) * k)] == 0;
  }
};

// sees() on a host mask; *blocker (when given) receives the blocking cell's index.
inline bool visible(const LightingGrid& g, const std::vector<std::uint8_t>& explosive, const Vec& a,
                    const Vec& p, int bi, int bj, int bk, long* blocker = nullptr) {
  const HostInert inert{explosive.data(), {g.n[0], g.n[1], g.n[2]}};
  int b[3];
  const bool v = sees(g.box(), inert, a.data(), p.data(), bi, bj, bk, blocker ? b : nullptr);
  if (!v && blocker) *blocker = g.index(b[0], b[1], b[2]);
  return v;
}

// The errors of a detonator that lights nothing and of a plane detonator without a normal.
inline std::string misplaced(std::size_t q, const Detonator& det) {
  return std::string("lighting_times: ") + to_string(det.kind) + " detonator " + std::to_string(q) +
         " at (" + std::to_string(det.a[0]) + ", " + std::to_string(det.a[1]) + ", " +
         std::to_string(det.a[2]) + ") is more than half a cell diagonal from every explosive cell";
}
inline std::string zero_normal(std::size_t q) {
  return "lighting_times: plane detonator " + std::to_string(q) + " has a zero normal";
}

}  // namespace detail

// Lighting time of every cell (cell order of LightingGrid), us. explosive[c] != 0 marks the
// cells the front runs through; every other cell, and explosive no detonator reaches, gets
// kNeverLit. d_cj > 0 is the detonation speed, cm/us.
//
// Each detonator lights the explosive cells whose centre lies within half a cell diagonal of it
// (so every cell it passes through, and a detonator on the surface of the explosive still
// lights its neighbours) at t0 + distance / D. A detonator that lights no explosive cell is an
// error (std::invalid_argument naming it): a scene whose detonator misses its charge must not
// run silently unburnt.
inline std::vector<double> lighting_times(const LightingGrid& g,
                                          const std::vector<std::uint8_t>& explosive,
                                          const std::vector<Detonator>& detonators, double d_cj) {
  using detail::Vec;
  const long n = g.cells();
  if (long(explosive.size()) != n)
    throw std::invalid_argument("lighting_times: explosive mask has " +
                                std::to_string(explosive.size()) + " cells, grid has " +
                                std::to_string(n));
  if (!(d_cj > 0)) throw std::invalid_argument("lighting_times: detonation speed must be > 0");
  const double never = double(kNeverLit);
  // String pulls per expanded cell (see below); more changes nothing measurable on the
  // Kenamond problems.
  constexpr int kMaxPulls = 4;
  // Where a corner pivot sits: the corner moved this fraction of the way to the centre of the
  // explosive cell it belongs to, so that it lies strictly inside that cell (the line-of-sight
  // walk then never starts on a grid line). Moves the path by 1e-9 cells.
  constexpr double kNudge = 1e-9;
  std::vector<double> t(n, never);
  // A parent code >= 0 is a pivot (a point the front bent around, with its own time and parent);
  // < 0 is detonator -(code + 1).
  struct Pivot {
    Vec x;
    double t;
    long parent;
  };
  std::vector<Pivot> pivots;
  std::vector<long> parent(n, -1), centre_pivot(n, -1);
  std::vector<std::uint8_t> closed(n, 0), seeded(n, 0);
  using Entry = std::pair<double, long>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;

  auto ijk = [&](long c, int& i, int& j, int& k) {
    i = int(c % g.n[0]);
    j = int((c / g.n[0]) % g.n[1]);
    k = int(c / (long(g.n[0]) * g.n[1]));
  };
  auto centre = [&](long c) {
    int i, j, k;
    ijk(c, i, j, k);
    return g.centre(i, j, k);
  };
  auto in_grid = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < g.n[0] && j < g.n[1] && k < g.n[2];
  };
  // Time at point x by the straight path from parent code `par`, and that path's start.
  auto time_via = [&](long par, const Vec& x, Vec& start) {
    if (par >= 0) {
      start = pivots[par].x;
      return pivots[par].t + detail::dist(start, x) / d_cj;
    }
    const Detonator& det = detonators[-(par + 1)];
    start = detail::foot(det, x);
    return det.t0 + detail::dist(start, x) / d_cj;
  };
  // A closed cell's centre as a pivot (one record per cell).
  auto pivot_at_centre = [&](long c) {
    if (centre_pivot[c] < 0) {
      centre_pivot[c] = long(pivots.size());
      pivots.push_back({centre(c), t[c], parent[c]});
    }
    return centre_pivot[c];
  };
  // True when corner (ci + oi, cj + oj, ck + ok) of a cell, o in {0, 1}, touches an inert cell
  // (a vertex of the inert staircase). In 2-D (one cell in z) only the plane counts.
  auto corner_touches_inert = [&](int i, int j, int k, int oi, int oj, int ok) {
    const int kz0 = g.n[2] == 1 ? 0 : -1, kz1 = 0;
    for (int dk = kz0; dk <= kz1; ++dk)
      for (int dj = -1; dj <= 0; ++dj)
        for (int di = -1; di <= 0; ++di) {
          const int a = i + oi + di, b = j + oj + dj, c = k + (g.n[2] == 1 ? 0 : ok + dk);
          if (in_grid(a, b, c) && !explosive[g.index(a, b, c)]) return true;
        }
    return false;
  };

  // Seeds.
  const double half_diag = 0.5 * std::sqrt(g.h[0] * g.h[0] + g.h[1] * g.h[1] + g.h[2] * g.h[2]);
  for (std::size_t q = 0; q < detonators.size(); ++q) {
    const Detonator& det = detonators[q];
    if (det.kind == Detonator::Kind::Plane && detail::dot(det.b, det.b) == 0)
      throw std::invalid_argument(detail::zero_normal(q));
    bool lit = false;
    for (long c = 0; c < n; ++c) {
      if (!explosive[c]) continue;
      const Vec x = centre(c);
      const double r = detail::dist(detail::foot(det, x), x);
      if (r > half_diag * (1 + 1e-12)) continue;
      lit = true;
      const double tc = det.t0 + r / d_cj;
      if (tc < t[c]) {
        t[c] = tc;
        parent[c] = -long(q + 1);
        seeded[c] = 1;
        open.push({tc, c});
      }
    }
    if (!lit) throw std::invalid_argument(detail::misplaced(q, det));
  }

  while (!open.empty()) {
    const auto [tc, c] = open.top();
    open.pop();
    if (closed[c] || tc > t[c]) continue;  // stale entry
    int ci, cj, ck;
    ijk(c, ci, cj, ck);
    const Vec x = centre(c);
    // Lazy Theta* SetVertex: the parent was assumed visible when c was queued; check it now.
    if (!seeded[c]) {
      Vec start;
      time_via(parent[c], x, start);
      long blocker = -1;
      if (!detail::visible(g, explosive, start, x, ci, cj, ck, &blocker)) {
        // Hidden: the front reaches c around inert material. Candidates, best time wins:
        // a closed neighbour's centre; a closed neighbour's own parent, if c sees it; a corner
        // of a closed neighbour that touches inert cells (a vertex of the inert staircase)
        // reached straight from that neighbour's parent, if c sees it. The corners make the
        // path wrap the staircase itself instead of the cell centres outside it.
        double best = std::numeric_limits<double>::infinity();
        long best_code = 0;  // parent code of the winner...
        int best_kind = -1;  // ...0: neighbour centre (cell best_code), 1: parent code,
        Vec best_x{};        // 2: new corner pivot at best_x, time best_tp, parent best_code
        double best_tp = 0;
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const int i = ci + di, j = cj + dj, k = ck + dk;
              if (!in_grid(i, j, k)) continue;
              const long nb = g.index(i, j, k);
              if (nb == c || !closed[nb]) continue;
              const Vec xn = centre(nb);
              const double cand = t[nb] + detail::dist(xn, x) / d_cj;
              if (cand < best) {
                best = cand;
                best_code = nb;
                best_kind = 0;
              }
              Vec s2;
              const double cand2 = time_via(parent[nb], x, s2);
              if (cand2 < best && detail::visible(g, explosive, s2, x, ci, cj, ck)) {
                best = cand2;
                best_code = parent[nb];
                best_kind = 1;
              }
              for (int ok = 0; ok <= (g.n[2] == 1 ? 0 : 1); ++ok)
                for (int oj = 0; oj <= 1; ++oj)
                  for (int oi = 0; oi <= 1; ++oi) {
                    if (!corner_touches_inert(i, j, k, oi, oj, ok)) continue;
                    Vec kx{g.origin[0] + (i + oi) * g.h[0], g.origin[1] + (j + oj) * g.h[1],
                           g.n[2] == 1 ? xn[2] : g.origin[2] + (k + ok) * g.h[2]};
                    for (int ax = 0; ax < 3; ++ax) kx[ax] += kNudge * (xn[ax] - kx[ax]);
                    Vec s3;
                    const double tk = time_via(parent[nb], kx, s3);
                    const double cand3 = tk + detail::dist(kx, x) / d_cj;
                    if (!(cand3 < best)) continue;
                    if (!detail::visible(g, explosive, s3, kx, i, j, k)) continue;
                    if (!detail::visible(g, explosive, kx, x, ci, cj, ck)) continue;
                    best = cand3;
                    best_code = parent[nb];
                    best_kind = 2;
                    best_x = kx;
                    best_tp = tk;
                  }
            }
        // The bend of a hidden straight path belongs at the inert cell that hides it: try the
        // corners of that blocking cell as pivots, reached straight from the parent, for c's
        // own assumed parent and for its closed neighbours' parents.
        auto try_blocker_corners = [&](long par, long blk) {
          int bi, bj, bk;
          ijk(blk, bi, bj, bk);
          for (int ok = 0; ok <= (g.n[2] == 1 ? 0 : 1); ++ok)
            for (int oj = 0; oj <= 1; ++oj)
              for (int oi = 0; oi <= 1; ++oi) {
                // The explosive cell at this corner nearest c's side: the first found.
                int ei = -1, ej = -1, ek = -1;
                for (int dk = (g.n[2] == 1 ? 0 : -1); dk <= 0 && ei < 0; ++dk)
                  for (int dj = -1; dj <= 0 && ei < 0; ++dj)
                    for (int di = -1; di <= 0 && ei < 0; ++di) {
                      const int a = bi + oi + di, b = bj + oj + dj,
                                cz = bk + (g.n[2] == 1 ? 0 : ok + dk);
                      if (in_grid(a, b, cz) && explosive[g.index(a, b, cz)]) {
                        ei = a;
                        ej = b;
                        ek = cz;
                      }
                    }
                if (ei < 0) continue;
                const Vec xe = g.centre(ei, ej, ek);
                Vec kx{g.origin[0] + (bi + oi) * g.h[0], g.origin[1] + (bj + oj) * g.h[1],
                       g.n[2] == 1 ? xe[2] : g.origin[2] + (bk + ok) * g.h[2]};
                for (int ax = 0; ax < 3; ++ax) kx[ax] += kNudge * (xe[ax] - kx[ax]);
                Vec s3;
                const double tk = time_via(par, kx, s3);
                const double cand = tk + detail::dist(kx, x) / d_cj;
                if (!(cand < best)) continue;
                if (!detail::visible(g, explosive, s3, kx, ei, ej, ek)) continue;
                if (!detail::visible(g, explosive, kx, x, ci, cj, ck)) continue;
                best = cand;
                best_code = par;
                best_kind = 2;
                best_x = kx;
                best_tp = tk;
              }
        };
        if (blocker >= 0) try_blocker_corners(parent[c], blocker);
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const int i = ci + di, j = cj + dj, k = ck + dk;
              if (!in_grid(i, j, k)) continue;
              const long nb = g.index(i, j, k);
              if (nb == c || !closed[nb] || parent[nb] == parent[c]) continue;
              Vec s2;
              time_via(parent[nb], x, s2);
              long blk = -1;
              if (!detail::visible(g, explosive, s2, x, ci, cj, ck, &blk) && blk >= 0)
                try_blocker_corners(parent[nb], blk);
            }
        // c was queued from a closed neighbour, so best_kind >= 0.
        t[c] = best;
        if (best_kind == 0) {
          parent[c] = pivot_at_centre(best_code);
        } else if (best_kind == 1) {
          parent[c] = best_code;
        } else {
          parent[c] = long(pivots.size());
          pivots.push_back({best_x, best_tp, best_code});
        }
      }
      // Pull the string: when c sees its pivot's own parent, the straight path to it is
      // shorter (triangle inequality). A few pulls at most; each is one line-of-sight walk.
      for (int pull = 0; pull < kMaxPulls && parent[c] >= 0; ++pull) {
        const long pp = pivots[parent[c]].parent;
        Vec s2;
        const double cand = time_via(pp, x, s2);
        if (!(cand < t[c]) || !detail::visible(g, explosive, s2, x, ci, cj, ck)) break;
        t[c] = cand;
        parent[c] = pp;
      }
    }
    closed[c] = 1;
    // Lazy Theta* ComputeCost: offer each open neighbour c's parent (visibility assumed until
    // the neighbour is expanded).
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int i = ci + di, j = cj + dj, k = ck + dk;
          if (!in_grid(i, j, k)) continue;
          const long nb = g.index(i, j, k);
          if (nb == c || closed[nb] || !explosive[nb]) continue;
          Vec start;
          const double cand = time_via(parent[c], centre(nb), start);
          if (cand < t[nb]) {
            t[nb] = cand;
            parent[nb] = parent[c];
            seeded[nb] = 0;
            open.push({cand, nb});
          }
        }
  }
  return t;
}

}  // namespace mp::burn
