#include "mesh/halo.hpp"

#include <cstdlib>
#include <type_traits>
#include <utility>

#if __has_include(<mpi-ext.h>)
#include <mpi-ext.h>  // Open MPI: MPIX_CUDA_AWARE_SUPPORT, MPIX_Query_cuda_support
#endif

#include "core/axis.hpp"
#include "core/columns.hpp"
#include "core/error.hpp"
#include "core/profiling.hpp"

namespace mp {

namespace {

// The slab [lo, hi) along axis d, whole extent along the other axes.
struct Slab {
  int lo[3], hi[3];
  int size() const { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

Slab slab(const Mesh& mesh, const HaloField& f, int d, int first, int last) {
  Slab s{};
  for (int a = 0; a < 3; ++a) {
    const auto r = mesh.range(f.along(a), Region::All, a);
    s.lo[a] = r[0];
    s.hi[a] = r[1];
  }
  s.lo[d] = first;
  s.hi[d] = last;
  return s;
}

// Index ranges along d for what side s sends and what it receives.
// Cells: send the ng owned layers next to the face, receive into the ng ghost layers.
// Nodes: the face node is shared and never sent; send the ng layers inside it.
int send_first(const Mesh& m, Centering c, int d, int s) {
  const int ng = Mesh::ng, nl = m.owned_cells(d);
  if (c == Centering::Cell) return s == 0 ? ng : nl;
  return s == 0 ? ng + 1 : nl;
}
int recv_first(const Mesh& m, Centering c, int d, int s) {
  const int ng = Mesh::ng, nl = m.owned_cells(d);
  if (c == Centering::Cell) return s == 0 ? 0 : ng + nl;
  return s == 0 ? 0 : ng + nl + 1;
}

// Every field of an exchange (up to kMaxFields, one layout) handled by one kernel per axis.
constexpr int kMaxFields = 8;

// What one axis of an exchange does on each side, as a kernel sees it. The kernel's index along
// the axis is a layer number t, not a mesh index: t in [0, ng) are the ghost layers of side 0,
// [ng, 2 ng) those of side 1, and (node fields next to a reflective wall) 2 ng and 2 ng + 1 the
// wall nodes of sides 0 and 1. The other two axes run over their whole extent, ghosts included.
struct AxisPlan {
  // Neighbour: another rank sends the layers. Self: a periodic axis with one rank along it, the
  // layers copied from the opposite side of this block, with no message. Reflective, Outflow:
  // a physical boundary.
  enum Kind { Neighbour = 0, Self = 1, Reflective = 2, Outflow = 3 };
  Kokkos::Array<Field3, kMaxFields> f;
  Kokkos::Array<Real, kMaxFields> sign;  // parity under reflection along d
  int n = 0;                             // fields
  int d = 0;
  bool node = false;  // node-centred along d
  int kind[2] = {0, 0};
  int ghost[2] = {0, 0};  // first ghost index (receive range) per side
  int send[2] = {0, 0};   // first index of the send range per side
  int wall[2] = {0, 0};   // the wall: owned layer next to the face (cells) or the face node
  // A reflective wall node of a field odd under reflection in d (the normal velocity) is zero
  // (zero_wall[s] set: side s is such a wall and node-centred along d). The zero is written by
  // the fill kernel and read as zero by the pack kernel and by the mirror, so that a block only
  // ng cells thick sends the zero and not what the wall node held, whatever the thread order.
  bool zero_wall[2] = {false, false};
  int per_field = 0;
  int lo[3] = {0, 0, 0};  // the slab of every side: whole extent along the other axes
  int n1 = 0, n2 = 0;     // slab extents along axes 1 and 2 (buffer indexing)

  // Field q at (i, j, k) as the sequential order (walls zeroed first) would read it.
  // (D >= 0: the kernel's axis at compile time, equal to d)
  template <int D = -1>
  KOKKOS_INLINE_FUNCTION Real read(int q, int i, int j, int k) const {
    const int a = D >= 0 ? D : d;
    return zeroed_at(q, a == 0 ? i : a == 1 ? j : k) ? Real(0) : f[q](i, j, k);
  }
  // Position of (i, j, k) in a side's slab, the slab's first index along d being x0; axis 2
  // (a field's contiguous axis) runs fastest, so that a run along it is a run in the buffer.
  template <int D = -1>
  KOKKOS_INLINE_FUNCTION int at(int i, int j, int k, int x0) const {
    const int a = D >= 0 ? D : d;
    int idx[3] = {i - lo[0], j - lo[1], k - lo[2]};
    idx[a] = (a == 0 ? i : a == 1 ? j : k) - x0;
    return idx[2] + n2 * (idx[1] + n1 * idx[0]);
  }
  // Whether field q reads as a zeroed wall node at index x along d.
  KOKKOS_INLINE_FUNCTION bool zeroed_at(int q, int x) const {
    if (!(sign[q] < 0)) return false;
    for (int s = 0; s < 2; ++s)
      if (zero_wall[s] && x == wall[s]) return true;
    return false;
  }
};

AxisPlan plan_axis(const Mesh& mesh, const std::vector<HaloField>& fields, std::size_t first,
                   int d) {
  AxisPlan p;
  const HaloField& f0 = fields[0];
  const Centering c = f0.along(d);
  p.d = d;
  p.node = c == Centering::Node;
  const int ng = Mesh::ng, nl = mesh.owned_cells(d);
  for (std::size_t q = first; q < fields.size() && p.n < kMaxFields; ++q) {
    p.f[p.n] = fields[q].view;
    p.sign[p.n] = Real(fields[q].parity[d]);
    ++p.n;
  }
  bool odd = false;
  for (int q = 0; q < p.n; ++q) odd = odd || p.sign[q] < 0;
  for (int s = 0; s < 2; ++s) {
    p.ghost[s] = recv_first(mesh, c, d, s);
    p.send[s] = send_first(mesh, c, d, s);
    p.wall[s] = s == 0 ? ng : (p.node ? ng + nl : ng + nl - 1);
    if (!mesh.physical_boundary(d, s)) {
      p.kind[s] = mesh.neighbor(d, s) == mesh.rank() ? AxisPlan::Self : AxisPlan::Neighbour;
    } else {
      const BoundaryKind k = mesh.boundary(d, s);
      if (k == BoundaryKind::Periodic) throw RunError("halo: periodic side without a neighbour");
      p.kind[s] = k == BoundaryKind::Reflective ? AxisPlan::Reflective : AxisPlan::Outflow;
    }
    p.zero_wall[s] = p.node && odd && p.kind[s] == AxisPlan::Reflective;
  }
  const Slab sl = slab(mesh, f0, d, p.send[0], p.send[0] + ng);
  p.per_field = sl.size();
  for (int a = 0; a < 3; ++a) p.lo[a] = sl.lo[a];
  p.n1 = sl.hi[1] - sl.lo[1];
  p.n2 = sl.hi[2] - sl.lo[2];
  return p;
}

// The launch of one axis D's pack or fill over layer numbers t in [0, layers) along D and the
// whole extent of the other two axes, as k-columns (core/columns.hpp): body(i, j, k0, k1) takes
// a whole run of the contiguous axis 2 on host backends (a plane's row when D is 0 or 1, whose
// k loop is a contiguous copy GCC vectorizes; the layers of a column when D is 2), one point on
// GPU backends. (A Kokkos MDRange body per point, the earlier form, left every fill a scalar loop
// over index arithmetic: about 4 ns a value at two ranks of bm_short.)
template <int D, class Body>
void for_layer_runs(const char* name, const Mesh& mesh, const HaloField& f0, int layers,
                    const Body& body) {
  const Slab s = slab(mesh, f0, D, 0, layers);
  for_columns(name, s.lo, s.hi, body);
}

// Packs both sides' send slabs of every field in one launch (sides with a neighbour only).
template <int D>
void pack_axis(const Mesh& mesh, const HaloField& f0, const AxisPlan& p, const Buffer& b0,
               const Buffer& b1, int first_field) {
  const int ng = Mesh::ng;
  for_layer_runs<D>(
      "halo::pack", mesh, f0, 2 * ng, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
        // (captured here: nvcc allows an extended lambda no first capture in an if constexpr)
        (void)ng, (void)p, (void)b0, (void)b1, (void)first_field;
        if constexpr (D == 2) {
          for (int t = k0; t < k1; ++t) {
            const int s = t < ng ? 0 : 1;
            if (p.kind[s] != AxisPlan::Neighbour) continue;
            const int k = p.send[s] + t - s * ng;
            const int at = p.template at<D>(i, j, k, p.send[s]);
            const Buffer& b = s == 0 ? b0 : b1;
            for (int q = 0; q < p.n; ++q)
              b((first_field + q) * p.per_field + at) = p.template read<D>(q, i, j, k);
          }
        } else {
          int idx[3] = {i, j, k0};
          const int t = idx[D];
          const int s = t < ng ? 0 : 1;
          if (p.kind[s] != AxisPlan::Neighbour) return;
          idx[D] = p.send[s] + t - s * ng;
          const int at = p.template at<D>(idx[0], idx[1], k0, p.send[s]);
          Real* const b = (s == 0 ? b0 : b1).data() + at;
          for (int q = 0; q < p.n; ++q) {
            const auto F = local(p.f[q]);
            Real* const bq = b + (first_field + q) * p.per_field - k0;
            if (p.zeroed_at(q, idx[D])) {
              for (int k = k0; k < k1; ++k) bq[k] = Real(0);
            } else {
#pragma GCC ivdep
              for (int k = k0; k < k1; ++k) bq[k] = F(idx[0], idx[1], k);
            }
          }
        }
      });
}

// Packs both sides' send slabs (the axis at compile time: constant index steps).
void pack(const Mesh& mesh, const HaloField& f0, const AxisPlan& p, const Buffer& b0,
          const Buffer& b1, int first_field) {
  with_axis(p.d, [&](auto a) { pack_axis<decltype(a)::value>(mesh, f0, p, b0, b1, first_field); });
}

// Fills every ghost layer of both sides of axis d of every field in one launch: unpacks what a
// neighbour sent, or applies the physical boundary, and zeroes the reflective wall nodes of
// odd fields.
// Reflective: the ghost layer is the mirror image of the interior, times the field's parity
// (a velocity normal to the wall changes sign; it vanishes on the wall node itself).
// Outflow: zero gradient, every ghost layer copies the boundary cell or node.
// Nothing a thread writes is read by another: the mirror reads owned layers along d (never a
// ghost), and reads a zeroed wall node as the zero it becomes.
template <int D>
void fill_axis(const Mesh& mesh, const HaloField& f0, const AxisPlan& p, const Buffer& b0,
               const Buffer& b1, int first_field) {
  const int ng = Mesh::ng;
  const bool walls = p.zero_wall[0] || p.zero_wall[1];
  // Layer t along D at (i, j) and the run [k0, k1) of axis 2 (D < 2), or at (i, j) alone
  // (D == 2: the layer is the point along axis 2, k0 and k1 unused).
  // Every value is what the per-point form wrote: a zeroed wall reads as 0 (read), a mirror
  // is the parity times the value read, an outflow ghost the value read.
  auto layer = [=] KOKKOS_FUNCTION(int t, int i, int j, int k0, int k1) {
    int idx[3] = {i, j, k0};
    if (t >= 2 * ng) {  // a wall node
      const int s = t - 2 * ng;
      if (!p.zero_wall[s]) return;
      idx[D] = p.wall[s];
      const int a = D == 2 ? idx[2] : k0, e = D == 2 ? idx[2] + 1 : k1;
      for (int q = 0; q < p.n; ++q)
        if (p.sign[q] < 0) {
          const auto F = local(p.f[q]);
          for (int k = a; k < e; ++k) F(idx[0], idx[1], k) = 0;
        }
      return;
    }
    const int s = t < ng ? 0 : 1;
    const int x = p.ghost[s] + t - s * ng;
    idx[D] = x;
    // the run along axis 2 this call writes: [a, e) (one point when D == 2)
    const int a = D == 2 ? x : k0, e = D == 2 ? x + 1 : k1;
    if (p.kind[s] == AxisPlan::Neighbour) {
      const Buffer& b = s == 0 ? b0 : b1;
      const int at = p.template at<D>(idx[0], idx[1], a, p.ghost[s]);
      for (int q = 0; q < p.n; ++q) {
        const auto F = local(p.f[q]);
        const Real* const bq = b.data() + (first_field + q) * p.per_field + at - a;
#pragma GCC ivdep
        for (int k = a; k < e; ++k) F(idx[0], idx[1], k) = bq[k];
      }
      return;
    }
    int src[3] = {idx[0], idx[1], idx[2]};
    bool reflective = false;
    if (p.kind[s] == AxisPlan::Self) {  // what this block would have sent itself
      src[D] = p.send[1 - s] + t - s * ng;
    } else {
      const int dir = s == 0 ? -1 : 1;  // from the wall outwards
      const int first_ghost = p.node ? p.wall[s] + dir : (s == 0 ? ng - 1 : p.wall[s] + 1);
      const int l = (x - first_ghost) * dir;  // 0 next to the wall, 1 beyond
      // cells: mirror across the face; nodes: mirror across the wall node; outflow: the
      // wall value
      reflective = p.kind[s] == AxisPlan::Reflective;
      src[D] = reflective ? (p.node ? p.wall[s] - dir * (l + 1) : p.wall[s] - dir * l) : p.wall[s];
    }
    const int shift = D == 2 ? src[2] - x : 0;  // source k of destination k
    for (int q = 0; q < p.n; ++q) {
      const auto F = local(p.f[q]);
      const bool z = p.zeroed_at(q, src[D]);
      const Real sg = reflective ? p.sign[q] : Real(1);
      if (z) {
        for (int k = a; k < e; ++k) F(idx[0], idx[1], k) = reflective ? sg * Real(0) : Real(0);
      } else {
#pragma GCC ivdep
        for (int k = a; k < e; ++k) {
          const Real v = F(src[0], src[1], k + shift);
          F(idx[0], idx[1], k) = reflective ? sg * v : v;
        }
      }
    }
  };
  for_layer_runs<D>(
      "halo::fill", mesh, f0, 2 * ng + (walls ? 2 : 0),
      KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
        (void)layer;  // (captured here, as pack's)
        if constexpr (D == 2) {
          for (int t = k0; t < k1; ++t) layer(t, i, j, t, t + 1);
        } else {
          layer(D == 0 ? i : j, i, j, k0, k1);
        }
      });
}

// Fills every ghost layer of both sides of axis p.d (at compile time, as pack).
void fill(const Mesh& mesh, const HaloField& f0, const AxisPlan& p, const Buffer& b0,
          const Buffer& b1, int first_field) {
  with_axis(p.d, [&](auto a) { fill_axis<decltype(a)::value>(mesh, f0, p, b0, b1, first_field); });
}

// The whole exchange in one launch, for a block with no neighbour rank on any side (every side
// a physical boundary or a periodic axis it holds alone). The three sweeps x, y, z compose into
// one index map per point: along each axis a ghost index maps to its source (mirror, wall copy
// or the opposite side) and a factor (the parity for a mirror, else 1); a reflective wall node
// of a field odd in that axis reads as zero, and the factors of the axes before it are lost
// (the sweep along that axis wrote +0 there before mirroring). So the value is
//   (product of the later factors) x (+0)  or  (product of all factors) x f(source),
// bit for bit what the three sweeps leave (a factor of +-1 is exact, signed zeros included).
// Sources are owned along every axis and never a zeroed wall, so no thread reads what another
// writes. Iterates the (i, j) plane with a loop over k: every k in columns that are ghosts or
// walls along x or y, only the ghost layers and walls along z elsewhere.
struct Local {
  Kokkos::Array<AxisPlan, 3> a;
  int ext[3] = {0, 0, 0};
  // The z points of a column that is owned along x and y and on no wall (most columns): the
  // ghost layers and wall nodes of z, each with its source and, per field, what point() would
  // write there (mode 0 nothing, 1 mult x f(source), 2 mult x 0), found once on the host.
  struct ZPoint {
    int dst = 0, src = 0;
    Kokkos::Array<Real, kMaxFields> mult;
    Kokkos::Array<unsigned char, kMaxFields> mode;
  };
  Kokkos::Array<ZPoint, 2 * 2 + 2> zp;  // 2 ng ghost layers and up to 2 wall nodes
  int nzp = 0;
  void plan_columns() {
    static_assert(Mesh::ng == 2, "halo: the z table holds 2 ng + 2 points");
    const AxisPlan& p = a[2];
    nzp = 0;
    auto add = [&](int k) {
      ZPoint z;
      bool g2, m2;
      z.dst = k;
      z.src = source(2, k, g2, m2);
      for (int q = 0; q < a[0].n; ++q) {
        z.mult[q] = m2 ? p.sign[q] : Real(1);
        z.mode[q] = zeroed(2, z.src, q) ? 2 : (g2 ? 1 : 0);
      }
      zp[nzp++] = z;
    };
    for (int s = 0; s < 2; ++s)
      for (int k = p.ghost[s]; k < p.ghost[s] + Mesh::ng; ++k) add(k);
    for (int s = 0; s < 2; ++s)
      if (p.zero_wall[s]) add(p.wall[s]);
  }
  KOKKOS_INLINE_FUNCTION bool ghost(int d, int x, int& s) const {
    s = x < a[d].ghost[0] + Mesh::ng && x >= a[d].ghost[0] ? 0 : 1;
    return (x >= a[d].ghost[0] && x < a[d].ghost[0] + Mesh::ng) ||
           (x >= a[d].ghost[1] && x < a[d].ghost[1] + Mesh::ng);
  }
  KOKKOS_INLINE_FUNCTION bool wall(int d, int x) const {
    return (a[d].zero_wall[0] && x == a[d].wall[0]) || (a[d].zero_wall[1] && x == a[d].wall[1]);
  }
  // The source index of x along d and whether it is a mirror (the field's parity applies).
  KOKKOS_INLINE_FUNCTION int source(int d, int x, bool& ghosted, bool& mirror) const {
    const AxisPlan& p = a[d];
    int s = 0;
    mirror = false;
    ghosted = ghost(d, x, s);
    if (!ghosted) return x;
    if (p.kind[s] == AxisPlan::Self) return p.send[1 - s] + x - p.ghost[s];
    const int dir = s == 0 ? -1 : 1;
    const int first_ghost = p.node ? p.wall[s] + dir : (s == 0 ? Mesh::ng - 1 : p.wall[s] + 1);
    const int layer = (x - first_ghost) * dir;
    if (p.kind[s] == AxisPlan::Outflow) return p.wall[s];
    mirror = true;
    return p.node ? p.wall[s] - dir * (layer + 1) : p.wall[s] - dir * layer;
  }
  // Field q read at source index src along d is a zeroed wall node.
  KOKKOS_INLINE_FUNCTION bool zeroed(int d, int src, int q) const { return a[d].zeroed_at(q, src); }
  // One column (i, j): the maps of axes x and y once, then the points along z.
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j) const {
    bool g0, g1, m0, m1;
    const int s0 = source(0, i, g0, m0), s1 = source(1, j, g1, m1);
    const bool w01 = wall(0, i) || wall(1, j);
    const int n = a[0].n;
    Real fac[kMaxFields];
    bool zero[kMaxFields];
    for (int q = 0; q < n; ++q) {
      Real sgn = 1;
      bool z = false;
      if (zeroed(0, s0, q)) z = true, sgn = 1;
      if (m0) sgn *= a[0].sign[q];
      if (zeroed(1, s1, q)) z = true, sgn = 1;
      if (m1) sgn *= a[1].sign[q];
      fac[q] = sgn;
      zero[q] = z;
    }
    auto point = [&](int k) {
      bool g2, m2;
      const int s2 = source(2, k, g2, m2);
      const bool any = g0 || g1 || g2;
      if (!any && !w01 && !wall(2, k)) return;
      for (int q = 0; q < n; ++q) {
        Real sgn = fac[q];
        bool z = zero[q];
        if (zeroed(2, s2, q)) z = true, sgn = 1;
        if (m2) sgn *= a[2].sign[q];
        const Field3& f = a[0].f[q];
        if (z)
          f(i, j, k) = sgn * Real(0);
        else if (any)
          f(i, j, k) = sgn * f(s0, s1, s2);
      }
    };
    if (g0 || g1 || w01) {
      // the ghosts and walls along z point by point, the owned run between them in one loop
      // per field (there, no z map: the value is fac x f(s0, s1, k), or fac x 0)
      const AxisPlan& p = a[2];
      for (int s = 0; s < 2; ++s)
        for (int k = p.ghost[s]; k < p.ghost[s] + Mesh::ng; ++k) point(k);
      int b = Mesh::ng, e = p.ghost[1];
      if (p.zero_wall[0]) point(b++);  // wall[0] == ng
      if (p.zero_wall[1]) point(--e);  // wall[1] == ng + nl, the last owned node
      if (!(g0 || g1)) {
        for (int k = b; k < e; ++k) point(k);
        return;
      }
      for (int q = 0; q < n; ++q) {
        const Field3& f = a[0].f[q];
        const Real c = fac[q];
        if (zero[q])
          for (int k = b; k < e; ++k) f(i, j, k) = c * Real(0);
        else
          for (int k = b; k < e; ++k) f(i, j, k) = c * f(s0, s1, k);
      }
      return;
    }
    // owned along x and y, on no wall: the z table (what point() does there, bit for bit)
    for (int q = 0; q < n; ++q) {
      const Field3& f = a[0].f[q];
      for (int t = 0; t < nzp; ++t) {
        const ZPoint& z = zp[t];
        if (z.mode[q] == 2)
          f(i, j, z.dst) = z.mult[q] * Real(0);
        else if (z.mode[q] == 1)
          f(i, j, z.dst) = z.mult[q] * f(i, j, z.src);
      }
    }
  }
};

// The same exchange for a block thin across axis L (x or y): a quasi-1-D run's mesh, at most
// kThin points along the two other axes (column_axis()). There Local's z columns are a few
// points long and 6 (N + 4) of them for an N x 2 x 2 block, most of its time spent per column;
// here one iteration per layer c along L fills the ghosts and walls of that layer's plane of
// the two other axes (A < B; contiguous in memory), from tables of the plane's maps found once
// on the host. It writes what Local writes, bit for bit: per point and field the same factors
// (+-1) composed in axis order, those of the plane's axes before L (fac, zero), then L's, then
// those after L (post, post_zero).
constexpr int kThin = 2 * Mesh::ng + 5;  // up to 4 owned cells, node-centred fields included
template <int L>
struct LocalThin {
  static_assert(L == 0 || L == 1, "halo: a thin block's long axis is x or y");
  static constexpr int A = L == 0 ? 1 : 0;  // the plane's axes
  static constexpr int B = 2;
  static constexpr int kPlane = kThin * kThin;
  Local m;  // the three axes' plans and maps
  // Every point (u, v) of the plane: its source and, per field, the factors of the plane's axes
  // before and after L (for the ghost and wall layers along L).
  struct PlanePoint {
    int u = 0, v = 0, su = 0, sv = 0;
    bool ghost = false;
    Kokkos::Array<Real, kMaxFields> fac, post;
    Kokkos::Array<unsigned char, kMaxFields> zero, post_zero;
  };
  Kokkos::Array<PlanePoint, kPlane> pp;
  int npp = 0;
  // What a layer owned along L and on no wall takes, per field q: the points [first_copy[q],
  // first_copy[q + 1]) of `copy` mult x f(c, src), those of `zero` the value given (mult x 0);
  // offsets in the layer (every field of an exchange has the same strides).
  struct Copy {
    int dst = 0, src = 0;
    Real mult = 1;
  };
  Kokkos::Array<Copy, kMaxFields * kPlane> copy, zero;
  Kokkos::Array<int, kMaxFields + 1> first_copy, first_zero;
  long stride_l = 0;  // the layers' stride
  void plan_plane() {
    const int n = m.a[0].n;
    const Field3& f0 = m.a[0].f[0];
    stride_l = long(f0.stride(L));
    auto offset = [&](int u, int v) { return int(u * f0.stride(A) + v * f0.stride(B)); };
    npp = 0;
    for (int u = 0; u < m.ext[A]; ++u)
      for (int v = 0; v < m.ext[B]; ++v) {
        PlanePoint& p = pp[npp++];
        bool gu, gv, mu, mv;
        p.u = u;
        p.v = v;
        p.su = m.source(A, u, gu, mu);
        p.sv = m.source(B, v, gv, mv);
        p.ghost = gu || gv;
        for (int q = 0; q < n; ++q) {
          p.fac[q] = p.post[q] = 1;
          p.zero[q] = p.post_zero[q] = false;
          Real& sa = A < L ? p.fac[q] : p.post[q];
          unsigned char& za = A < L ? p.zero[q] : p.post_zero[q];
          if (m.zeroed(A, p.su, q)) za = true, sa = 1;
          if (mu) sa *= m.a[A].sign[q];
          if (m.zeroed(B, p.sv, q)) p.post_zero[q] = true, p.post[q] = 1;
          if (mv) p.post[q] *= m.a[B].sign[q];
        }
      }
    int nc = 0, nz = 0;
    for (int q = 0; q < n; ++q) {
      first_copy[q] = nc;
      first_zero[q] = nz;
      for (int t = 0; t < npp; ++t) {
        // in a layer c owned along L and no wall: no factor of L, so the value is
        // (fac x post) x f(c, su, sv), or post x 0 where an axis after L is zeroed, or
        // fac x 0 where one before it is; nothing where (u, v) is owned and no wall
        const PlanePoint& p = pp[t];
        const Real mult = p.post_zero[q] ? p.post[q] : p.fac[q] * p.post[q];
        if (p.zero[q] || p.post_zero[q])
          zero[nz++] = Copy{offset(p.u, p.v), 0, mult * Real(0)};
        else if (p.ghost)
          copy[nc++] = Copy{offset(p.u, p.v), offset(p.su, p.sv), mult};
      }
    }
    first_copy[n] = nc;
    first_zero[n] = nz;
  }
  // Whether every field has field 0's strides (the offsets' premise).
  bool same_strides() const {
    const Field3& f0 = m.a[0].f[0];
    for (int q = 1; q < m.a[0].n; ++q)
      for (int d = 0; d < 3; ++d)
        if (m.a[0].f[q].stride(d) != f0.stride(d)) return false;
    return true;
  }
  KOKKOS_FORCEINLINE_FUNCTION static Real& at(const Field3& f, int c, int u, int v) {
    if constexpr (L == 0)
      return f(c, u, v);
    else
      return f(u, c, v);
  }
  KOKKOS_INLINE_FUNCTION void operator()(int c) const {
    bool gc, mc;
    const int sc = m.source(L, c, gc, mc);
    const int n = m.a[0].n;
    if (!gc && !m.wall(L, c)) {
      // owned along L, no wall: the plane's ghosts and walls from the tables
      for (int q = 0; q < n; ++q) {
        Real* const b = m.a[0].f[q].data() + c * stride_l;
        for (int t = first_zero[q]; t < first_zero[q + 1]; ++t) b[zero[t].dst] = zero[t].mult;
        for (int t = first_copy[q]; t < first_copy[q + 1]; ++t)
          b[copy[t].dst] = copy[t].mult * b[copy[t].src];
      }
      return;
    }
    // a ghost or wall layer along L: every point of its plane, the factors composed
    for (int q = 0; q < n; ++q) {
      const Field3& f = m.a[0].f[q];
      const bool zc = m.zeroed(L, sc, q);
      for (int t = 0; t < npp; ++t) {
        const PlanePoint& p = pp[t];
        const bool any = gc || p.ghost;
        Real sgn = p.fac[q];
        bool z = p.zero[q];
        if (zc) z = true, sgn = 1;
        if (mc) sgn *= m.a[L].sign[q];
        if (p.post_zero[q])
          z = true, sgn = p.post[q];
        else
          sgn *= p.post[q];
        if (z)
          at(f, c, p.u, p.v) = sgn * Real(0);
        else if (any)
          at(f, c, p.u, p.v) = sgn * at(f, sc, p.su, p.sv);
      }
    }
  }
};

// The long axis of a block thin across the two others (x or y, longer than z, the others at
// most kThin points); else 2: Local's z columns.
[[maybe_unused]] int column_axis(const int ext[3]) {
  if (ext[2] > kThin) return 2;
  if (ext[1] <= kThin && ext[0] > ext[2]) return 0;
  if (ext[0] <= kThin && ext[1] > ext[2]) return 1;
  return 2;
}

// Fills a thin block's ghosts (LocalThin) with long axis L, the plans made in l; false (and
// nothing done) where its fields' strides differ.
template <int L>
bool thin_fill(const Local& l) {
  LocalThin<L> t;
  t.m = l;
  if (!t.same_strides()) return false;
  t.plan_plane();
  Kokkos::parallel_for("halo::fill", Policy1(0, l.ext[L]), t);
  return true;
}

// The bytes a periodic axis held by one rank copies in place: what its two messages to itself
// would carry (bytes_sent counts them, so a count does not depend on how the copy is done).
double self_bytes(const AxisPlan& p, int nfields) {
  double b = 0;
  for (int s = 0; s < 2; ++s)
    if (p.kind[s] == AxisPlan::Self) b += double(nfields) * p.per_field * sizeof(Real);
  return b;
}

// True when every side of every axis is filled without a message.
bool all_local(const Mesh& m) {
  for (int d = 0; d < 3; ++d)
    for (int s = 0; s < 2; ++s)
      if (!m.physical_boundary(d, s) && m.neighbor(d, s) != m.rank()) return false;
  return true;
}

MPI_Datatype mpi_real() {
  return sizeof(Real) == sizeof(double) ? MPI_DOUBLE : MPI_FLOAT;
}

// The one-launch exchange (no neighbour rank) of fields first .. first + kMaxFields - 1 of one
// layout; returns the bytes a periodic axis held alone counts (self_bytes).
double fill_local(const Mesh& mesh, const std::vector<HaloField>& fields, std::size_t first) {
  Local l;
  double bytes = 0;
  for (int d = 0; d < 3; ++d) {
    l.a[d] = plan_axis(mesh, fields, first, d);
    l.ext[d] = mesh.extent(fields[0].along(d), d);
    bytes += self_bytes(l.a[d], l.a[d].n);
  }
#if !(defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL))
  // (host backends: a thin block along its long axis)
  const int c = column_axis(l.ext);
  if (c != 2 && (c == 0 ? thin_fill<0>(l) : thin_fill<1>(l))) return bytes;
#endif
  l.plan_columns();
  Kokkos::parallel_for(
      "halo::fill", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>({0, 0}, {l.ext[0], l.ext[1]}),
      l);
  return bytes;
}

}  // namespace

namespace {

// The bytes of a message as MPI sees them: the buffer itself where MPI may read and write it
// (message_in_place), else a host staging array kept between exchanges (grown, never shrunk, so
// that a cycle allocates nothing), copied from or to the buffer around the message.
template <class T>
struct Staging {
  std::vector<T> send[2], recv[2];
};
template <class T>
Staging<T>& staging() {
  static Staging<T> s;
  return s;
}

template <class T>
using HostSlice = Kokkos::View<T*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;

template <class T>
T* staged(std::vector<T>& v, long n) {
  if (long(v.size()) < n) v.resize(std::size_t(n));
  return v.data();
}

// The first n values of b copied to the host array at h, and back.
template <class T>
void to_host(T* h, const Kokkos::View<T*, MemSpace>& b, long n) {
  Kokkos::deep_copy(HostSlice<T>(h, std::size_t(n)), Kokkos::subview(b, std::make_pair(0L, n)));
}
template <class T>
void from_host(const Kokkos::View<T*, MemSpace>& b, const T* h, long n) {
  Kokkos::deep_copy(Kokkos::subview(b, std::make_pair(0L, n)),
                    HostSlice<T>(const_cast<T*>(h), std::size_t(n)));
}

template <class T>
MPI_Datatype mpi_type() {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, float>);
  return std::is_same_v<T, double> ? MPI_DOUBLE : MPI_FLOAT;
}

}  // namespace

bool message_in_place() {
  static const bool in_place = [] {
    const char* env = std::getenv("MINIPAGOSA_MPI_DEVICE_BUFFERS");
    if (env && *env) return std::string(env) != "0";
    if constexpr (Kokkos::SpaceAccessibility<Kokkos::HostSpace, MemSpace>::accessible) {
      return true;
    } else {
#if defined(MPIX_CUDA_AWARE_SUPPORT) && MPIX_CUDA_AWARE_SUPPORT
      return MPIX_Query_cuda_support() == 1;
#else
      return false;
#endif
    }
  }();
  return in_place;
}

std::string message_path() {
  constexpr bool host = Kokkos::SpaceAccessibility<Kokkos::HostSpace, MemSpace>::accessible;
  if (!message_in_place()) return "staged through host arrays";
  return host ? "from the host buffers" : "from the device buffers (CUDA-aware MPI)";
}

template <class T>
double exchange_buffers(const Mesh& mesh, int d, const Kokkos::View<T*, MemSpace> send[2],
                        const Kokkos::View<T*, MemSpace> recv[2], long count, int tag_base) {
  Kokkos::fence();  // the pack kernel's values, before MPI or a copy reads them
  const bool in_place = message_in_place();
  Staging<T>& st = staging<T>();
  T* hsend[2] = {nullptr, nullptr};
  T* hrecv[2] = {nullptr, nullptr};
  MPI_Request req[4];
  int nreq = 0;
  double bytes = 0;
  for (int s = 0; s < 2; ++s) {
    if (mesh.physical_boundary(d, s)) continue;
    hsend[s] = in_place ? send[s].data() : staged(st.send[s], count);
    hrecv[s] = in_place ? recv[s].data() : staged(st.recv[s], count);
    if (!in_place) to_host(hsend[s], send[s], count);
  }
  for (int s = 0; s < 2; ++s) {
    if (mesh.physical_boundary(d, s)) continue;
    // What arrives from side s was sent by that neighbour towards side 1-s: tag by the
    // sending side so a rank that is its own periodic neighbour pairs messages correctly.
    MPI_CHECK(MPI_Irecv(hrecv[s], int(count), mpi_type<T>(), mesh.neighbor(d, s),
                        tag_base + 10 * d + 1 - s, mesh.comm(), &req[nreq++]));
  }
  for (int s = 0; s < 2; ++s) {
    if (mesh.physical_boundary(d, s)) continue;
    MPI_CHECK(MPI_Isend(hsend[s], int(count), mpi_type<T>(), mesh.neighbor(d, s),
                        tag_base + 10 * d + s, mesh.comm(), &req[nreq++]));
    bytes += double(count) * sizeof(T);
  }
  MPI_CHECK(MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE));
  if (!in_place)
    for (int s = 0; s < 2; ++s)
      if (!mesh.physical_boundary(d, s)) from_host(recv[s], hrecv[s], count);
  return bytes;
}
template double exchange_buffers<float>(const Mesh&, int, const Kokkos::View<float*, MemSpace>[2],
                                        const Kokkos::View<float*, MemSpace>[2], long, int);
template double exchange_buffers<double>(const Mesh&, int, const Kokkos::View<double*, MemSpace>[2],
                                         const Kokkos::View<double*, MemSpace>[2], long, int);

double exchange_sized(const Mesh& mesh, int d, const Buffer send[2], const long send_count[2],
                      Buffer recv[2], int tag_base, const std::string& recv_label) {
  Kokkos::fence();
  const bool in_place = message_in_place();
  Staging<Real>& st = staging<Real>();
  MPI_Request req[2];
  int nreq = 0;
  double bytes = 0;
  for (int s = 0; s < 2; ++s) {
    if (mesh.physical_boundary(d, s)) continue;
    Real* h = in_place ? send[s].data() : staged(st.send[s], send_count[s]);
    if (!in_place) to_host(h, send[s], send_count[s]);
    // tags as exchange_buffers': by the sending side
    MPI_CHECK(MPI_Isend(h, int(send_count[s]), mpi_real(), mesh.neighbor(d, s),
                        tag_base + 10 * d + s, mesh.comm(), &req[nreq++]));
    bytes += double(send_count[s]) * sizeof(Real);
  }
  for (int s = 0; s < 2; ++s) {
    if (mesh.physical_boundary(d, s)) continue;
    const int src = mesh.neighbor(d, s), tag = tag_base + 10 * d + 1 - s;
    MPI_Status status;
    MPI_CHECK(MPI_Probe(src, tag, mesh.comm(), &status));
    int n = 0;
    MPI_CHECK(MPI_Get_count(&status, mpi_real(), &n));
    if (long(recv[s].extent(0)) < n)
      recv[s] = Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, recv_label),
                       std::max(n + n / 4, 1));
    Real* h = in_place ? recv[s].data() : staged(st.recv[s], n);
    MPI_CHECK(MPI_Recv(h, n, mpi_real(), src, tag, mesh.comm(), MPI_STATUS_IGNORE));
    if (!in_place) from_host(recv[s], h, n);
  }
  MPI_CHECK(MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE));
  return bytes;
}

Halo::Halo(const Mesh& mesh) : mesh_(mesh) {}

void Halo::exchange(const std::vector<HaloField>& fields) {
  if (fields.empty()) return;
  ProfileRegion region("halo::exchange");
  for (const auto& f : fields)
    if (f.centering != fields[0].centering || f.face_axis != fields[0].face_axis)
      throw RunError("halo: one exchange takes fields of one layout");
  if (all_local(mesh_)) {
    // one launch per kMaxFields fields
    for (std::size_t first = 0; first < fields.size(); first += kMaxFields)
      bytes_sent_ += fill_local(mesh_, fields, first);
    return;
  }
  for (int d = 0; d < 3; ++d) exchange_axis(fields, d);
}

// One axis: a pack launch (sides with a neighbour), the messages, then one fill launch for
// every ghost layer of both sides, walls and physical boundaries included, per kMaxFields
// fields (exchanges carry two to six).
void Halo::exchange_axis(const std::vector<HaloField>& fields, int d) {
  const HaloField& f0 = fields[0];
  const int nf = static_cast<int>(fields.size());
  std::vector<AxisPlan> plans;
  for (int q = 0; q < nf; q += kMaxFields) plans.push_back(plan_axis(mesh_, fields, q, d));
  const int count = nf * plans[0].per_field;

  bool any = false;  // a message to another rank
  for (int s = 0; s < 2; ++s) {
    if (mesh_.physical_boundary(d, s) || plans[0].kind[s] == AxisPlan::Self) continue;
    any = true;
    if (static_cast<int>(send_[s].extent(0)) < count) {
      send_[s] = Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "halo::send"), count);
      recv_[s] = Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "halo::recv"), count);
    }
  }
  bytes_sent_ += self_bytes(plans[0], nf);
  if (any) {
    for (std::size_t b = 0; b < plans.size(); ++b)
      pack(mesh_, f0, plans[b], send_[0], send_[1], int(b) * kMaxFields);
    bytes_sent_ += exchange_buffers(mesh_, d, send_, recv_, count, 0);
  }
  for (std::size_t b = 0; b < plans.size(); ++b)
    fill(mesh_, f0, plans[b], recv_[0], recv_[1], int(b) * kMaxFields);
}

}  // namespace mp
