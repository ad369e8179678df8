// The per-rank lighting-time construction (lighting_device.hpp says what it computes).
#include "burn/lighting_device.hpp"

#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "mesh/halo.hpp"

namespace mp::burn {

namespace {

using Labels = Kokkos::View<LightingLabel***, MemSpace>;
using Flags = Kokkos::View<std::uint8_t***, MemSpace>;
using Words = Kokkos::View<std::uint32_t*, MemSpace>;

// A detonator as plain data for kernels.
struct Det {
  Detonator::Kind kind;
  double a[3], b[3], t0;
};
using Dets = Kokkos::View<Det*, MemSpace>;

// Where a corner pivot sits: the corner moved this fraction of the way to the centre of the
// explosive cell it belongs to (lighting.hpp's kNudge).
constexpr double kNudge = 1e-9;

// Marks the owned cells whose fraction is at least the threshold (every owned cell without one).
struct MarkBits {
  Words w;
  Field3 frac;
  bool all;
  Real threshold;
  Geometry geo;
  long nx, ny;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    if (!all && !(frac(i, j, k) >= threshold)) return;
    const long c = geo.global_cell(i, j, k, nx, ny);
    Kokkos::atomic_fetch_or(&w(c >> 5), std::uint32_t(1) << (c & 31));
  }
};

ExplosiveBits reduce_bits(const Mesh& mesh, const LightingGrid& g, Words w) {
  auto h = Kokkos::create_mirror_view(w);
  Kokkos::deep_copy(h, w);
  MPI_CHECK(
      MPI_Allreduce(MPI_IN_PLACE, h.data(), int(h.extent(0)), MPI_UINT32_T, MPI_BOR, mesh.comm()));
  Kokkos::deep_copy(w, h);
  return {w, g.box()};
}

Words new_words(const LightingGrid& g) {
  return Words("burn::lighting_mask", std::size_t((g.cells() + 31) / 32));
}

// The block's place in the grid: global index of mesh index i along d, cell centres.
struct Frame {
  LightingBox g;
  int off[3];
  KOKKOS_INLINE_FUNCTION int global(int d, int i) const { return off[d] + i - Mesh::ng; }
  KOKKOS_INLINE_FUNCTION void centre(int gi, int gj, int gk, double* x) const {
    x[0] = g.origin[0] + (gi + 0.5) * g.h[0];
    x[1] = g.origin[1] + (gj + 0.5) * g.h[1];
    x[2] = g.origin[2] + (gk + 0.5) * g.h[2];
  }
};

// Each detonator in turn lights the explosive cells within half a cell diagonal of it.
struct Seed {
  Labels cur;
  Flags chg;
  ExplosiveBits bits;
  Frame f;
  Det det;
  int q;
  double d_cj, reach;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, long& lit) const {
    const int gi = f.global(0, i), gj = f.global(1, j), gk = f.global(2, k);
    if (!bits.explosive(gi, gj, gk)) return;
    double x[3], s[3];
    f.centre(gi, gj, gk, x);
    detail::foot3(det.kind, det.a, det.b, x, s);
    const double r = detail::dist3(s, x);
    if (r > reach) return;
    ++lit;
    const double tc = det.t0 + r / d_cj;
    LightingLabel& l = cur(i, j, k);
    if (tc < l.t) {
      l.t = tc;
      l.code = -(q + 1);
      chg(i, j, k) = 1;
    }
  }
};

// One Jacobi sweep: proposals of the cells whose neighbours changed into nxt (flagged in out).
struct Sweep {
  Labels cur, nxt;
  Flags chg, out;
  ExplosiveBits bits;
  Dets dets;
  Frame f;
  double d_cj;

  // The time at x by the straight path from label l's parent, and that path's start s.
  KOKKOS_INLINE_FUNCTION double via(const LightingLabel& l, const double* x, double* s) const {
    if (l.code < 0) {
      const Det& d = dets(-l.code - 1);
      detail::foot3(d.kind, d.a, d.b, x, s);
      return d.t0 + detail::dist3(s, x) / d_cj;
    }
    for (int q = 0; q < 3; ++q) s[q] = l.px[q];
    return l.pt + detail::dist3(s, x) / d_cj;
  }
  KOKKOS_INLINE_FUNCTION bool sees(const double* a, const double* p, int bi, int bj, int bk,
                                   int* blocker = nullptr) const {
    return detail::sees(f.g, bits, a, p, bi, bj, bk, blocker);
  }
  KOKKOS_INLINE_FUNCTION static bool same_parent(const LightingLabel& a, const LightingLabel& b) {
    if (a.code != b.code) return false;
    return a.code < 0 ||
           (a.pt == b.pt && a.px[0] == b.px[0] && a.px[1] == b.px[1] && a.px[2] == b.px[2]);
  }
  KOKKOS_INLINE_FUNCTION static void take(LightingLabel& best, double t, const LightingLabel& l) {
    best = l;
    best.t = t;
  }
  KOKKOS_INLINE_FUNCTION static void take_pivot(LightingLabel& best, double t, const double* p,
                                                double tp) {
    best.t = t;
    best.pt = tp;
    for (int q = 0; q < 3; ++q) best.px[q] = p[q];
    best.code = 1;
  }
  // True when corner (i + oi, j + oj, k + ok) of global cell (i, j, k) touches an inert cell.
  KOKKOS_INLINE_FUNCTION bool corner_touches_inert(int i, int j, int k, int oi, int oj,
                                                   int ok) const {
    for (int dk = -1; dk <= 0; ++dk)
      for (int dj = -1; dj <= 0; ++dj)
        for (int di = -1; di <= 0; ++di)
          if (bits(i + oi + di, j + oj + dj, k + ok + dk)) return true;
    return false;
  }
  // The corners of inert cell blk as pivots reached straight from l's parent, for the cell at
  // x (global g).
  KOKKOS_INLINE_FUNCTION void blocker_corners(const LightingLabel& l, const int* blk,
                                              const double* x, const int* g,
                                              LightingLabel& best) const {
    for (int ok = 0; ok <= 1; ++ok)
      for (int oj = 0; oj <= 1; ++oj)
        for (int oi = 0; oi <= 1; ++oi) {
          // the explosive cell at this corner: the first found
          int e[3] = {-1, -1, -1};
          for (int dk = -1; dk <= 0 && e[0] < 0; ++dk)
            for (int dj = -1; dj <= 0 && e[0] < 0; ++dj)
              for (int di = -1; di <= 0 && e[0] < 0; ++di) {
                const int a = blk[0] + oi + di, b = blk[1] + oj + dj, c = blk[2] + ok + dk;
                if (bits.in_grid(a, b, c) && bits.explosive(a, b, c)) {
                  e[0] = a;
                  e[1] = b;
                  e[2] = c;
                }
              }
          if (e[0] < 0) continue;
          double xe[3], kx[3], s[3];
          f.centre(e[0], e[1], e[2], xe);
          kx[0] = f.g.origin[0] + (blk[0] + oi) * f.g.h[0];
          kx[1] = f.g.origin[1] + (blk[1] + oj) * f.g.h[1];
          kx[2] = f.g.origin[2] + (blk[2] + ok) * f.g.h[2];
          for (int ax = 0; ax < 3; ++ax) kx[ax] += kNudge * (xe[ax] - kx[ax]);
          const double tk = via(l, kx, s);
          const double cand = tk + detail::dist3(kx, x) / d_cj;
          if (!(cand < best.t)) continue;
          if (!sees(s, kx, e[0], e[1], e[2])) continue;
          if (!sees(kx, x, g[0], g[1], g[2])) continue;
          take_pivot(best, cand, kx, tk);
        }
  }
  // fn(di, dj, dk, label) for each neighbour of mesh cell (i, j, k) (global g) in the grid that
  // is lit and changed in the last sweep (the others offer nothing the cell has not weighed).
  template <class Fn>
  KOKKOS_INLINE_FUNCTION void lit_changed(int i, int j, int k, const int* g, const Fn& fn) const {
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if ((di == 0 && dj == 0 && dk == 0) || !bits.in_grid(g[0] + di, g[1] + dj, g[2] + dk) ||
              !chg(i + di, j + dj, k + dk))
            continue;
          const LightingLabel& l = cur(i + di, j + dj, k + dk);
          if (l.code != 0) fn(di, dj, dk, l);
        }
  }
  // The hidden cell's candidates (lighting.hpp's, in its order).
  KOKKOS_INLINE_FUNCTION void hidden(int i, int j, int k, const int* g, const double* x,
                                     const LightingLabel& assumed, const int* blk, bool blocked,
                                     LightingLabel& best) const {
    lit_changed(i, j, k, g, [&](int di, int dj, int dk, const LightingLabel& l) {
      const int a = g[0] + di, b = g[1] + dj, c = g[2] + dk;
      double xn[3], s[3];
      f.centre(a, b, c, xn);
      const double cand = l.t + detail::dist3(xn, x) / d_cj;
      if (cand < best.t) take_pivot(best, cand, xn, l.t);
      const double cand2 = via(l, x, s);
      if (cand2 < best.t && sees(s, x, g[0], g[1], g[2])) take(best, cand2, l);
      for (int ok = 0; ok <= 1; ++ok)
        for (int oj = 0; oj <= 1; ++oj)
          for (int oi = 0; oi <= 1; ++oi) {
            if (!corner_touches_inert(a, b, c, oi, oj, ok)) continue;
            double kx[3] = {f.g.origin[0] + (a + oi) * f.g.h[0],
                            f.g.origin[1] + (b + oj) * f.g.h[1],
                            f.g.origin[2] + (c + ok) * f.g.h[2]};
            for (int ax = 0; ax < 3; ++ax) kx[ax] += kNudge * (xn[ax] - kx[ax]);
            double s3[3];
            const double tk = via(l, kx, s3);
            const double cand3 = tk + detail::dist3(kx, x) / d_cj;
            if (!(cand3 < best.t)) continue;
            if (!sees(s3, kx, a, b, c)) continue;
            if (!sees(kx, x, g[0], g[1], g[2])) continue;
            take_pivot(best, cand3, kx, tk);
          }
    });
    if (blocked) blocker_corners(assumed, blk, x, g, best);
    lit_changed(i, j, k, g, [&](int, int, int, const LightingLabel& l) {
      if (same_parent(l, assumed)) return;
      double s[3];
      via(l, x, s);
      int b2[3] = {-1, -1, -1};
      if (!sees(s, x, g[0], g[1], g[2], b2) && b2[0] >= 0) blocker_corners(l, b2, x, g, best);
    });
  }

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, long& changed) const {
    out(i, j, k) = 0;
    const int g[3] = {f.global(0, i), f.global(1, j), f.global(2, k)};
    if (!bits.explosive(g[0], g[1], g[2])) return;
    // anything changed around (ghosts outside the grid hold no change: exchange_axis)
    int active = 0;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) active |= chg(i + di, j + dj, k + dk);
    if (!active) return;
    double x[3];
    f.centre(g[0], g[1], g[2], x);
    const LightingLabel own = cur(i, j, k);
    // the neighbours' parents: the earliest (Lazy Theta*'s assumed parent)
    double tmin = detail::kInfinity, smin[3] = {0, 0, 0};
    int nmin[3] = {0, 0, 0};
    const LightingLabel* last = nullptr;  // the parent just weighed (neighbours share parents)
    lit_changed(i, j, k, g, [&](int di, int dj, int dk, const LightingLabel& l) {
      if (last && same_parent(l, *last)) return;
      last = &l;
      double s[3];
      const double cand = via(l, x, s);
      if (cand < tmin) {
        tmin = cand;
        for (int q = 0; q < 3; ++q) smin[q] = s[q];
        nmin[0] = di;
        nmin[1] = dj;
        nmin[2] = dk;
      }
    });
    if (!(tmin < own.t)) return;
    const LightingLabel assumed = cur(i + nmin[0], j + nmin[1], k + nmin[2]);
    LightingLabel best = own;
    int blk[3] = {-1, -1, -1};
    if (sees(smin, x, g[0], g[1], g[2], blk))
      take(best, tmin, assumed);
    else
      hidden(i, j, k, g, x, assumed, blk, blk[0] >= 0, best);
    if (!(best.t < own.t)) return;
    nxt(i, j, k) = best;
    out(i, j, k) = 1;
    ++changed;
  }
};

struct Commit {
  Labels cur, nxt;
  Flags out;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    if (out(i, j, k)) cur(i, j, k) = nxt(i, j, k);
  }
};

constexpr int kPacked = 7;  // doubles a cell: t, pt, px[3], code, changed

constexpr int kTag = 7100;  // message tags kTag + 10 d + side

// One ghost layer of labels and flags along axis d exchanged with the neighbour ranks (the whole
// extent of the other axes, so edges and corners arrive by the z sweep).
void exchange_axis(const Mesh& mesh_, const Labels& lab, const Flags& chg, int d) {
  {
    // global index of mesh index 0 (gi + i), the grid's cells
    const Kokkos::Array<int, 3> gi = {mesh_.offset(0) - Mesh::ng, mesh_.offset(1) - Mesh::ng,
                                      mesh_.offset(2) - Mesh::ng},
                                gn = {mesh_.global_cells(0), mesh_.global_cells(1),
                                      mesh_.global_cells(2)};
    const double never = double(kNeverLit);
    const int ng = Mesh::ng, nl = mesh_.owned_cells(d);
    const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
    const int n1 = mesh_.extent(Centering::Cell, e1), n2 = mesh_.extent(Centering::Cell, e2);
    const long count = long(n1) * n2 * kPacked;
    using Buf = Kokkos::View<double*, MemSpace>;
    using Plane = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>;
    Buf send[2], recv[2];
    for (int s = 0; s < 2; ++s) {
      if (mesh_.physical_boundary(d, s)) continue;
      send[s] = Buf("burn::lighting_send", count);
      recv[s] = Buf("burn::lighting_recv", count);
      const Buf b = send[s];
      const int plane = s == 0 ? ng : ng + nl - 1;
      Kokkos::parallel_for(
          "burn::lighting_pack", Plane({0, 0}, {n1, n2}), KOKKOS_LAMBDA(int a, int c) {
            int ix[3];
            ix[d] = plane;
            ix[e1] = a;
            ix[e2] = c;
            const LightingLabel& l = lab(ix[0], ix[1], ix[2]);
            double* v = &b((long(c) * n1 + a) * kPacked);
            v[0] = l.t;
            v[1] = l.pt;
            v[2] = l.px[0];
            v[3] = l.px[1];
            v[4] = l.px[2];
            v[5] = double(l.code);
            v[6] = double(chg(ix[0], ix[1], ix[2]));
          });
    }
    // the halo's messages (device buffers or staged, mesh/halo.hpp), in doubles whatever Real is
    exchange_buffers<double>(mesh_, d, send, recv, count, kTag);
    for (int s = 0; s < 2; ++s) {
      if (mesh_.physical_boundary(d, s)) continue;
      const Buf b = recv[s];
      const int plane = s == 0 ? ng - 1 : ng + nl;
      Kokkos::parallel_for(
          "burn::lighting_unpack", Plane({0, 0}, {n1, n2}), KOKKOS_LAMBDA(int a, int c) {
            int ix[3];
            ix[d] = plane;
            ix[e1] = a;
            ix[e2] = c;
            LightingLabel& l = lab(ix[0], ix[1], ix[2]);
            const double* v = &b((long(c) * n1 + a) * kPacked);
            // a periodic neighbour's cells beyond the grid's edge: no cells of this grid
            const bool beyond = gi[0] + ix[0] < 0 || gi[1] + ix[1] < 0 || gi[2] + ix[2] < 0 ||
                                gi[0] + ix[0] >= gn[0] || gi[1] + ix[1] >= gn[1] ||
                                gi[2] + ix[2] >= gn[2];
            if (beyond) {
              l.t = never;
              l.code = 0;
              chg(ix[0], ix[1], ix[2]) = 0;
              return;
            }
            l.t = v[0];
            l.pt = v[1];
            l.px[0] = v[2];
            l.px[1] = v[3];
            l.px[2] = v[4];
            l.code = int(v[5]);
            chg(ix[0], ix[1], ix[2]) = std::uint8_t(v[6]);
          });
    }
    Kokkos::fence();
  }
}

void exchange(const Mesh& mesh, const Labels& lab, const Flags& chg) {
  for (int d = 0; d < 3; ++d) exchange_axis(mesh, lab, chg, d);
}

// The index along d of an explosive cell, or -1.
struct Along {
  ExplosiveBits bits;
  Frame f;
  int d;
  KOKKOS_INLINE_FUNCTION int operator()(int i, int j, int k) const {
    if (!bits.explosive(f.global(0, i), f.global(1, j), f.global(2, k))) return -1;
    return d == 0 ? i : (d == 1 ? j : k);
  }
};

// The smallest box of mesh indices that holds the rank's explosive cells (empty without any).
Policy3 explosive_box(const Mesh& mesh, const ExplosiveBits& bits, const Frame& f) {
  int lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    int first = 0, last = 0;
    const Along along{bits, f, d};
    Kokkos::parallel_reduce(
        "burn::lighting_box", mesh.cells(Region::Owned),
        KOKKOS_LAMBDA(int i, int j, int k, int& a) {
          const int v = along(i, j, k);
          if (v >= 0 && v < a) a = v;
        },
        Kokkos::Min<int>(first));
    Kokkos::parallel_reduce(
        "burn::lighting_box", mesh.cells(Region::Owned),
        KOKKOS_LAMBDA(int i, int j, int k, int& b) {
          const int v = along(i, j, k);
          if (v > b) b = v;
        },
        Kokkos::Max<int>(last));
    lo[d] = first;
    hi[d] = last + 1;
  }
  if (lo[0] >= hi[0])
    return Policy3({Mesh::ng, Mesh::ng, Mesh::ng}, {Mesh::ng, Mesh::ng, Mesh::ng});
  return Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]});
}

}  // namespace

ExplosiveBits explosive_bits(const Mesh& mesh, const LightingGrid& g, const Field3* frac,
                             Real threshold) {
  Words w = new_words(g);
  const MarkBits mark{w,           frac ? *frac : Field3(), frac == nullptr,
                      threshold,   mesh.geometry(),         long(g.n[0]),
                      long(g.n[1])};
  Kokkos::parallel_for("burn::lighting_mask", mesh.cells(Region::Owned), mark);
  Kokkos::fence();
  return reduce_bits(mesh, g, w);
}

ExplosiveBits explosive_bits(const Mesh& mesh, const LightingGrid& g,
                             const std::vector<std::uint8_t>& explosive) {
  Words w = new_words(g);
  auto h = Kokkos::create_mirror_view(w);
  Kokkos::deep_copy(h, 0u);
  // the whole mask is known here: rank 0 contributes it, the reduction spreads it
  if (mesh.rank() == 0)
    for (long c = 0; c < g.cells(); ++c)
      if (explosive[c]) h(c >> 5) |= std::uint32_t(1) << (c & 31);
  Kokkos::deep_copy(w, h);
  return reduce_bits(mesh, g, w);
}

LightingRun lighting_times_device(const Mesh& mesh, const LightingGrid& g,
                                  const ExplosiveBits& bits,
                                  const std::vector<Detonator>& detonators, double d_cj) {
  for (int d = 0; d < 3; ++d)
    if (g.n[d] != mesh.global_cells(d))
      throw std::invalid_argument("lighting_times_device: the grid is not the mesh's");
  if (!(d_cj > 0)) throw std::invalid_argument("lighting_times: detonation speed must be > 0");
  Frame f{g.box(), {mesh.offset(0), mesh.offset(1), mesh.offset(2)}};
  const int ex[3] = {mesh.extent(Centering::Cell, 0), mesh.extent(Centering::Cell, 1),
                     mesh.extent(Centering::Cell, 2)};
  Labels cur(Kokkos::view_alloc(Kokkos::WithoutInitializing, "burn::lighting_labels"), ex[0], ex[1],
             ex[2]);
  Flags chg("burn::lighting_changed", ex[0], ex[1], ex[2]);
  const double never = double(kNeverLit);
  Kokkos::parallel_for(
      "burn::lighting_init", mesh.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
        LightingLabel& l = cur(i, j, k);
        l.t = never;
        l.pt = 0;
        l.px[0] = l.px[1] = l.px[2] = 0;
        l.code = 0;
      });
  // seeds, detonator by detonator (a cell lit by two keeps the earlier; a tie the first)
  const double half_diag = 0.5 * std::sqrt(g.h[0] * g.h[0] + g.h[1] * g.h[1] + g.h[2] * g.h[2]);
  Dets dets("burn::lighting_detonators", detonators.size());
  auto hd = Kokkos::create_mirror_view(dets);
  for (std::size_t q = 0; q < detonators.size(); ++q) {
    const Detonator& det = detonators[q];
    if (det.kind == Detonator::Kind::Plane && detail::dot(det.b, det.b) == 0)
      throw std::invalid_argument(detail::zero_normal(q));
    hd(q) = {det.kind, {det.a[0], det.a[1], det.a[2]}, {det.b[0], det.b[1], det.b[2]}, det.t0};
  }
  Kokkos::deep_copy(dets, hd);
  for (std::size_t q = 0; q < detonators.size(); ++q) {
    long lit = 0;
    Kokkos::parallel_reduce("burn::lighting_seed", mesh.cells(Region::Owned),
                            Seed{cur, chg, bits, f, hd(q), int(q), d_cj, half_diag * (1 + 1e-12)},
                            lit);
    MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, &lit, 1, MPI_LONG, MPI_SUM, mesh.comm()));
    if (lit == 0) throw std::invalid_argument(detail::misplaced(q, detonators[q]));
  }
  exchange(mesh, cur, chg);
  Labels nxt(Kokkos::view_alloc(Kokkos::WithoutInitializing, "burn::lighting_next"), ex[0], ex[1],
             ex[2]);
  Flags out("burn::lighting_out", ex[0], ex[1], ex[2]);
  // every sweep changes a label somewhere or ends the loop; a path in cells is shorter than
  // this, with room for the corrections
  const long most = 16L * (long(g.n[0]) + g.n[1] + g.n[2]) + 64;
  // the sweeps visit the box of the rank's explosive cells (a charge in a large scene: a few
  // thousand of its cells)
  const Policy3 sweep_box = explosive_box(mesh, bits, f);
  LightingRun run;
  for (;;) {
    long changed = 0;
    Kokkos::parallel_reduce("burn::lighting_sweep", sweep_box,
                            Sweep{cur, nxt, chg, out, bits, dets, f, d_cj}, changed);
    Kokkos::parallel_for("burn::lighting_commit", sweep_box, Commit{cur, nxt, out});
    std::swap(chg, out);
    exchange(mesh, cur, chg);
    MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_LONG, MPI_SUM, mesh.comm()));
    ++run.sweeps;
    if (changed == 0) break;
    if (run.sweeps > most)
      throw std::runtime_error("lighting_times_device: no convergence in " + std::to_string(most) +
                               " sweeps");
  }
  run.label = cur;
  return run;
}

}  // namespace mp::burn
