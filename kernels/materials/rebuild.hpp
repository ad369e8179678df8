// MaterialState::assign (declared in layout.hpp): the update of the cells a content source
// changes, in place where it can be, else the compact pool's count / scan / fill rebuild; with the
// traits a source declares to take the shortcuts, and the ghost-shell walk they use.
#pragma once
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/columns.hpp"
#include "materials/layout.hpp"

namespace mp::mat {

// A content source whose content(i, j, k) reads no cell state but cell (i, j, k)'s own (the
// remap update: the cell plus the stored face fluxes) declares
//   static constexpr bool own_cell_only = true;
// The compact rebuild then writes a cell that comes out pure during the count pass and skips it
// in the fill pass, so its content is computed once instead of twice. Sources that read other
// cells (the halo's mirrors) must not: the count pass would overwrite what they read.
template <class S, class = void>
struct OwnCellOnly : std::false_type {};
template <class S>
struct OwnCellOnly<S, std::void_t<decltype(S::own_cell_only)>>
    : std::integral_constant<bool, S::own_cell_only> {};

// A source whose content(i, j, k) of a changed cell reads no stored state of another changed
// cell (the remap: its own cell and the face fluxes; the halo: owned cells and the messages)
// declares
//   static constexpr bool in_place = true;
// The compact layout then writes every changed cell whose slot count stays the same straight
// into the current pool (issue #15: no rebuild when no cell's material count changed).
template <class S, class = void>
struct InPlace : std::false_type {};
template <class S>
struct InPlace<S, std::void_t<decltype(S::in_place)>> : std::integral_constant<bool, S::in_place> {
};

// A source whose sparse_content(i, j, k, ids, a, r, en) gives content()'s values for the
// materials ids[0..nc) (ascending, every material the cell may hold after it among them; nc
// returned), the others absent: assign's in-place path then loops over those alone.
template <class S, class = void>
struct Sparse : std::false_type {};
template <class S>
struct Sparse<S, std::void_t<decltype(S::sparse)>> : std::integral_constant<bool, S::sparse> {};

// A source may also offer a shortcut for the commonest case, a cell that stays one material:
//   static constexpr bool has_pure = true;
//   bool pure(i, j, k, int& id, Real& rho, Real& e) const;
// true only when content(i, j, k) would give exactly one material `id` with these values, bit
// for bit (the same arithmetic on the same operands); false says "ask content()". It spares
// the per-material arrays (3 x nmat values zeroed, filled and scanned per cell).
template <class S, class = void>
struct HasPure : std::false_type {};
template <class S>
struct HasPure<S, std::void_t<decltype(S::has_pure)>> : std::integral_constant<bool, S::has_pure> {
};

// A source whose changed cells are the box [lo, hi) (int lo[3], hi[3] members) may also do the
// shortcut a column at a time, where a loop over k vectorizes (core/columns.hpp):
//   static constexpr bool pure_columns = true;
//   bool pure_column(i, j, k0, k1, crho, ce, stamp) const;  // true: every cell stamped 1
//   bool reads_pool(const CompactDev& pool) const;  // (it reads `pool`, the one assign starts
//   from)
// For each k0 <= k < k1: where the cell stays its stored pure material (the shortcut has_pure
// describes), writes its values to crho, ce and stamps 1; elsewhere stamps 0 and leaves crho,
// ce as they were (the general path then takes the cell).
template <class S, class = void>
struct PureColumns : std::false_type {};
template <class S>
struct PureColumns<S, std::void_t<decltype(S::pure_columns)>>
    : std::integral_constant<bool, S::pure_columns> {};

// A source whose changed cells are all ghosts (the halo) declares
//   static constexpr bool ghosts_only = true;
// The in-place pass then runs over the ghost shell of the block (the ng layers on each side of
// every axis) instead of the whole block.
template <class S, class = void>
struct GhostsOnly : std::false_type {};
template <class S>
struct GhostsOnly<S, std::void_t<decltype(S::ghosts_only)>>
    : std::integral_constant<bool, S::ghosts_only> {};

// A ghosts-only source of the three halo sweeps may also give the source of a ghost's content
// column by column (the message-free case: walls and periodic axes held by one rank):
//   static constexpr bool ghost_columns = true;
//   bool source_column(i, j, int& si, int& sj) const;  // false: x or y took a message
//   int source_k(k) const;                             // -1: z took a message
// where content(i, j, k) is then exactly the stored content of (si, sj, source_k(k)). The host
// in-place pass then takes the ghosts that stay the stored pure material of their source as a
// loop over k (vectorized for the owned layers of a ghost slab's column), without walking the
// sweeps per cell; the shortcut has_pure describes, the same values.
template <class S, class = void>
struct GhostColumns : std::false_type {};
template <class S>
struct GhostColumns<S, std::void_t<decltype(S::ghost_columns)>>
    : std::integral_constant<bool, S::ghost_columns> {};

// Cell r of the ghost shell of an ex x ey x ez block with ng ghost layers: first the two x slabs
// (whole y, z extent), then the two y slabs of the interior x, then the two z slabs of the
// interior x and y; k fastest in each.
KOKKOS_INLINE_FUNCTION void shell_cell(long r, int ex, int ey, int ez, int ng, int& i, int& j,
                                       int& k) {
  const int ix = ex - 2 * ng, iy = ey - 2 * ng;
  const long nx = long(2 * ng) * ey * ez, ny = long(ix) * 2 * ng * ez;
  if (r < nx) {
    const int a = int(r / (long(ey) * ez));
    i = a < ng ? a : ex - 2 * ng + a;
    j = int((r / ez) % ey);
    k = int(r % ez);
    return;
  }
  r -= nx;
  if (r < ny) {
    const int b = int((r / ez) % (2 * ng));
    i = ng + int(r / (long(2 * ng) * ez));
    j = b < ng ? b : ey - 2 * ng + b;
    k = int(r % ez);
    return;
  }
  r -= ny;
  const int c = int(r % (2 * ng));
  i = ng + int(r / (long(iy) * 2 * ng));
  j = ng + int((r / (2 * ng)) % iy);
  k = c < ng ? c : ez - 2 * ng + c;
}
KOKKOS_INLINE_FUNCTION long shell_cells(int ex, int ey, int ez, int ng) {
  return long(ex) * ey * ez - long(ex - 2 * ng) * (ey - 2 * ng) * (ez - 2 * ng);
}

// A changed cell's new content from the source; returns the count of materials present and
// sets `id` to the last of them (0 for none).
template <class Source>
KOKKOS_INLINE_FUNCTION int new_content(const Source& src, int i, int j, int k, int nmat, Real* a,
                                       Real* r, Real* en, int& id) {
  for (int m = 0; m < nmat; ++m) a[m] = r[m] = en[m] = 0;
  src.content(i, j, k, a, r, en);
  int n = 0;
  id = 0;
  for (int m = 0; m < nmat; ++m)
    if (a[m] > 0) {
      ++n;
      id = m;
    }
  return n;
}

template <class Source>
void MaterialState::assign(const std::string& name, const Source& src) {
  const int nmat = nmat_;
  auto crho = rho_, ce = e_;
  if (kind_ == LayoutKind::Dense) {
    const DenseDev d = dense_;
    Kokkos::parallel_for(
        name, Policy3({0, 0, 0}, {ex_, ey_, ez_}), KOKKOS_LAMBDA(int i, int j, int k) {
          if (!src.changed(i, j, k)) return;
          Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
          for (int m = 0; m < nmat; ++m) a[m] = r[m] = en[m] = 0;
          src.content(i, j, k, a, r, en);
          for (int m = 0; m < nmat; ++m) {
            d.alpha(m, i, j, k) = a[m];
            d.rho(m, i, j, k) = a[m] > 0 ? r[m] : Real(0);
            d.e(m, i, j, k) = a[m] > 0 ? en[m] : Real(0);
          }
          cell_average(nmat, a, r, en, crho(i, j, k), ce(i, j, k));
        });
    return;
  }
  // Compact: count, scan, fill into the second buffer set, swap. A changed cell's content is
  // computed in the count pass and, for a mixed cell (or any cell of a source that reads other
  // cells), again in the fill pass instead of staged: staging would need a per-cell x nmat
  // buffer, the dense layout's memory. Pure results of an own-cell-only source are written in
  // the count pass (most cells of a scene are pure).
  rebuilt_ = false;
  const CompactDev old = compact_;
  CompactDev nw = next_;
  const int ey = ey_, ez = ez_;
  constexpr bool early = OwnCellOnly<Source>::value;
  // In place first (sources that allow it): a changed cell that keeps its materials (the same
  // pure material, or the same materials in its slots) is written where it is, and stamped; the
  // layout (mat, first, nm, slot materials, the mixed list) is unchanged by it. Only when some
  // cell's materials change does the rebuild below run, for the cells not stamped (a stamped
  // cell is copied as it is).
  // Every value written is the one the rebuild would write, so the fields do not depend on
  // the path (dense == compact bit for bit holds either way).
  auto stamp = stamp_;
  if constexpr (InPlace<Source>::value) {
    long moved = 0;
    // a changed cell that the shortcut below did not write
    auto general = KOKKOS_LAMBDA(int i, int j, int k, long& acc) {
      (void)src;  // (captured here: nvcc allows no first capture in an if constexpr)
      // the new content as entries c < nc of material ids[c], ascending: every material, or a
      // Sparse source's list (the materials it may hold; the others absent)
      Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
      int ids[kMaxMaterials];
      int nc = nmat, n = 0, id = 0;
      if constexpr (Sparse<Source>::value) {
        nc = src.sparse_content(i, j, k, ids, a, r, en);
        for (int c = 0; c < nc; ++c)
          if (a[c] > 0) {
            ++n;
            id = ids[c];
          }
      } else {
        n = new_content(src, i, j, k, nmat, a, r, en, id);
        for (int m = 0; m < nmat; ++m) ids[m] = m;
      }
      // The same materials in the same slots: a neighbour's content may read this cell's
      // layout (the remap reads the donor's material ids to split its face fluxes), so only
      // values change here, never which material a pure cell or a slot holds.
      const int om = old.mat(i, j, k), onm = old.nm(i, j, k);
      bool same = onm == n && (om >= 0) == (n <= 1);
      if (same && om >= 0) {
        same = om == id;  // (id 0 for an empty cell, as the rebuild stores it)
      } else if (same) {
        int q = old.first(i, j, k);
        for (int c = 0; c < nc && same; ++c)
          if (a[c] > 0) same = old.smat(q++) == ids[c];
      }
      if (same && om < 0) {
        int q = old.first(i, j, k);
        for (int c = 0; c < nc; ++c) {
          if (!(a[c] > 0)) continue;
          old.salpha(q) = a[c];
          old.srho(q) = r[c];
          old.se(q) = en[c];
          old.sp(q) = 0;
          ++q;
        }
      } else if (!same) {
        stamp(i, j, k) = 0;
        ++acc;  // the layout changes here: left to the rebuild
        return;
      }
      cell_average(nc, a, r, en, crho(i, j, k), ce(i, j, k));
      stamp(i, j, k) = 1;
    };
    auto in_place = KOKKOS_LAMBDA(int i, int j, int k, long& acc) {
      // (captured here: nvcc allows an extended lambda no first capture in an if constexpr)
      (void)old, (void)crho, (void)ce, (void)stamp;
      if (!src.changed(i, j, k)) return;
      if constexpr (HasPure<Source>::value) {
        int pid = -1;
        Real pr = 0, pe = 0;
        if (old.mat(i, j, k) >= 0 && src.pure(i, j, k, pid, pr, pe) && pid == old.mat(i, j, k)) {
          crho(i, j, k) = pr;  // (cell_average of one material: its own values)
          ce(i, j, k) = pe;
          stamp(i, j, k) = 1;
          return;
        }
      }
      general(i, j, k, acc);
    };
    if constexpr (PureColumns<Source>::value) {
      static_assert(!GhostsOnly<Source>::value, "a pure_columns source changes a box of cells");
      if (!src.reads_pool(old))
        throw std::logic_error("MaterialState::assign: a pure_columns source reads another pool");
      // k-columns of the changed box (core/columns.hpp): the source's vector pass writes the
      // cells that stay the same pure material and stamps the column (1 written, 0 not), then
      // the general path takes the others, one by one
      reduce_columns(
          name + "::in_place", src.lo, src.hi,
          KOKKOS_LAMBDA(int i, int j, int k0, int k1, long& acc) {
            if (src.pure_column(i, j, k0, k1, crho, ce, stamp)) return;  // every cell written
            for (int k = k0; k < k1; ++k)
              if (!stamp(i, j, k)) general(i, j, k, acc);
          },
          moved);
    } else if constexpr (GhostsOnly<Source>::value) {
      const int ex = ex_, ng = Mesh::ng;
#if !defined(KOKKOS_ENABLE_CUDA) && !defined(KOKKOS_ENABLE_HIP) && !defined(KOKKOS_ENABLE_SYCL)
      // host backends: the shell as k-columns (a column in a ghost slab of x or y whole, any
      // other its ng cells at each end of k), without shell_cell's divisions per cell
      // (its own Rank<2> launch, not reduce_columns: the body walks the whole column itself)
      Kokkos::parallel_reduce(
          name + "::in_place", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>({0, 0}, {ex, ey}),
          KOKKOS_LAMBDA(int i, int j, long& acc) {
            const bool slab = i < ng || i >= ex - ng || j < ng || j >= ey - ng;
            int si = 0, sj = 0;
            if constexpr (GhostColumns<Source>::value) {
              if (src.source_column(i, j, si, sj)) {
                // a ghost that stays its source's pure material takes the source's values
                const auto mt = local(old.mat);
                const auto st = local(stamp);
                const auto r = local(crho), en = local(ce);
                auto pure_from = [&](int k, int sk) {
                  const int m = mt(si, sj, sk);
                  const bool ok = (m >= 0) & (mt(i, j, k) == m);
                  const Real r0 = r(i, j, k), e0 = en(i, j, k);
                  r(i, j, k) = select_bits(ok, r(si, sj, sk), r0);
                  en(i, j, k) = select_bits(ok, en(si, sj, sk), e0);
                  st(i, j, k) = ok ? 1 : 0;
                };
                for (int k = 0; k < ez; k = (slab || k != ng - 1) ? k + 1 : ez - ng) {
                  if (k == ng && slab) {  // the owned layers: a column of other cells' values
                    const int ka = ng, kb = ez - ng;  // (locals: the loop's bounds are known)
#pragma GCC ivdep
                    for (int kk = ka; kk < kb; ++kk) pure_from(kk, kk);
                    for (int kk = ka; kk < kb; ++kk)
                      if (!st(i, j, kk)) general(i, j, kk, acc);
                    k = ez - ng - 1;
                    continue;
                  }
                  const int sk = src.source_k(k);
                  if (sk < 0) {
                    in_place(i, j, k, acc);
                    continue;
                  }
                  pure_from(k, sk);
                  if (!st(i, j, k)) general(i, j, k, acc);
                }
                return;
              }
            }
            for (int k = 0; k < ez; k = (slab || k != ng - 1) ? k + 1 : ez - ng)
              in_place(i, j, k, acc);
          },
          moved);
#else
      Kokkos::parallel_reduce(
          name + "::in_place",
          Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long>>(0, shell_cells(ex, ey, ez, ng)),
          KOKKOS_LAMBDA(long r, long& acc) {
            int i, j, k;
            shell_cell(r, ex, ey, ez, ng, i, j, k);
            in_place(i, j, k, acc);
          },
          moved);
#endif
    } else {
      Kokkos::parallel_reduce(name + "::in_place", Policy3({0, 0, 0}, {ex_, ey_, ez_}), in_place,
                              moved);
    }
    if (moved == 0) return;
  }
  // Changed and not yet written in place (every changed cell's stamp was written above).
  constexpr bool stamped = InPlace<Source>::value;
  auto pending = [=] KOKKOS_FUNCTION(int i, int j, int k) {
    return src.changed(i, j, k) && !(stamped && stamp(i, j, k));
  };
  Kokkos::parallel_for(
      name + "::count", Policy3({0, 0, 0}, {ex_, ey_, ez_}), KOKKOS_LAMBDA(int i, int j, int k) {
        if (!pending(i, j, k)) {
          nw.nm(i, j, k) = old.nm(i, j, k);
          return;
        }
        Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
        int id = 0;
        int n = new_content(src, i, j, k, nmat, a, r, en, id);
        if (early && n <= 1) {
          nw.mat(i, j, k) = id;
          cell_average(nmat, a, r, en, crho(i, j, k), ce(i, j, k));
          n = -1 - n;  // done: the fill pass skips it (and restores n)
        }
        nw.nm(i, j, k) = n;
      });
  // Slots before each cell (low 32 bits) and mixed rows before it (high bits), in one scan.
  const long ncell = long(ex_) * ey_ * ez_;
  long long total = 0;
  // The cells in linear order (i * ey + j) * ez + k. Where the cell arrays are LayoutRight
  // (every host backend) that is their memory order, and the scan reads and writes them by
  // that offset: recovering (i, j, k) from it took three integer divisions per cell and pass,
  // most of the scan's time (it calls the body twice per cell).
  constexpr bool linear = std::is_same<IntField3::array_layout, Kokkos::LayoutRight>::value;
  if (linear && (long(nw.nm.span()) != ncell || long(nw.first.span()) != ncell ||
                 long(nw.mat.span()) != ncell))
    throw std::logic_error("MaterialState: cell arrays are not contiguous");
  Kokkos::parallel_scan(
      name + "::scan", Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long>>(0, ncell),
      KOKKOS_LAMBDA(long lin, long long& acc, bool final) {
        // (captured here: nvcc allows an extended lambda no first capture in an if constexpr)
        // (and `linear` spelled out: nvcc takes a constexpr local in it for a capture)
        (void)nw, (void)ey, (void)ez;
        int *pn, *pf, *pm;
        if constexpr (std::is_same<IntField3::array_layout, Kokkos::LayoutRight>::value) {
          pn = nw.nm.data() + lin;
          pf = nw.first.data() + lin;
          pm = nw.mat.data() + lin;
        } else {
          const int k = int(lin % ez), j = int((lin / ez) % ey), i = int(lin / (long(ez) * ey));
          pn = &nw.nm(i, j, k);
          pf = &nw.first(i, j, k);
          pm = &nw.mat(i, j, k);
        }
        const int n = *pn;
        if (final) {
          *pf = int(acc & 0xffffffffLL);
          if (n >= 0) *pm = n > 1 ? -int(acc >> 32) - 1 : 0;
        }
        if (n > 1) acc += (1LL << 32) + n;
      },
      total);
  const int slots = int(total & 0xffffffffLL);
  const int rows = int(total >> 32);
  resize_pool(nw, slots);
  if (int(nw.mixed.extent(0)) < rows)
    nw.mixed = IntBuffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "mixed_list"),
                         std::max(rows, 1) + rows / 4);
  nw.nmixed = rows;
  Kokkos::parallel_for(
      name + "::fill", Policy3({0, 0, 0}, {ex_, ey_, ez_}), KOKKOS_LAMBDA(int i, int j, int k) {
        const int n = nw.nm(i, j, k);
        if (n < 0) {  // written by the count pass
          nw.nm(i, j, k) = -1 - n;
          return;
        }
        const int q0 = nw.first(i, j, k);
        if (n > 1) nw.mixed(-nw.mat(i, j, k) - 1) = (i * ey + j) * ez + k;
        if (!pending(i, j, k)) {
          const int id = old.mat(i, j, k);
          if (id >= 0) {
            nw.mat(i, j, k) = id;
            return;
          }
          const int f = old.first(i, j, k);
          for (int x = 0; x < old.nxc; ++x)
            for (int s = 0; s < n; ++s) nw.sx[x](q0 + s) = old.sx[x](f + s);
          for (int s = 0; s < n; ++s) {
            nw.smat(q0 + s) = old.smat(f + s);
            nw.salpha(q0 + s) = old.salpha(f + s);
            nw.srho(q0 + s) = old.srho(f + s);
            nw.se(q0 + s) = old.se(f + s);
            nw.sp(q0 + s) = old.sp(f + s);
            nw.sph(q0 + s) = old.sph(f + s);  // unread across a rebuild today; kept, not a trap
          }
          return;
        }
        Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
        for (int m = 0; m < nmat; ++m) a[m] = r[m] = en[m] = 0;
        src.content(i, j, k, a, r, en);
        if (n == 1) {
          for (int m = 0; m < nmat; ++m)
            if (a[m] > 0) nw.mat(i, j, k) = m;
        } else {
          // a module's carried values start at 0 (its remap or halo writes them next)
          for (int x = 0; x < nw.nxc; ++x)
            for (int s = 0; s < n; ++s) nw.sx[x](q0 + s) = 0;
          int q = q0;
          for (int m = 0; m < nmat; ++m) {
            if (!(a[m] > 0)) continue;
            nw.smat(q) = m;
            nw.salpha(q) = a[m];
            nw.srho(q) = r[m];
            nw.se(q) = en[m];
            nw.sp(q) = 0;
            ++q;
          }
        }
        cell_average(nmat, a, r, en, crho(i, j, k), ce(i, j, k));
      });
  next_ = compact_;  // the old buffers become the next rebuild's target
  compact_ = nw;
  rebuilt_ = true;
}

}  // namespace mp::mat
