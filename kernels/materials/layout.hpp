// Per-material state behind two layouts, picked at run time (DESIGN.md §3.1):
//
//  dense   (the paper's layout): alpha, rho, e, p, p_half are (nmat, i, j, k) arrays, one
//          contiguous block per material; every kernel visits every material of every cell.
//          Memory and work grow as cells x nmat.
//  compact (this project's default): a pure cell keeps its material's state in the cell arrays
//          (rho, e, p, p_half) and its material id in `mat`; a mixed cell (mat < 0) owns a run
//          of slots [first, first + nm) in a pool, sorted by material id, and sits in the mixed
//          list. Kernels run an MDRange over the pure cells and a range over the mixed list.
//          Memory and work grow as cells + sum over mixed cells of their material count.
//
// The pool covers every cell of the block, ghosts included. It is rebuilt, never edited in
// place, whenever cells change their material content (after each remap sweep, after each
// halo exchange): a count pass, an exclusive parallel_scan over the cells for the slot offsets
// and mixed-list rows, and a fill pass, into a second buffer set that is then swapped in.
//
// Kernels never see which layout they run on: they get a cell accessor (count(), get(s),
// aliases()) and call the same point functions through it. Summation over a cell's materials
// runs in material-id order in both layouts, and absent materials (dense) add exact zeros, so
// both layouts produce the same bits.
#pragma once
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/columns.hpp"
#include "core/types.hpp"
#include "eos/eos.hpp"
#include "mesh/mesh.hpp"

namespace mp::mat {

// Largest number of materials one scene may hold (local per-cell arrays are sized by it).
constexpr int kMaxMaterials = 16;
// Most per-slot quantities a module may keep in the compact pool beside the layout's own (the
// strength module keeps 7: its 6 deviator components and the plastic strain).
constexpr int kMaxExtras = 8;

enum class LayoutKind { Dense, Compact };

// The EOS of each material, copied into every kernel that needs it.
struct MaterialSet {
  int n = 0;
  eos::Eos eos[kMaxMaterials];
};

// One material of one cell as a kernel sees it: the volume fraction by value, the state by
// pointer into wherever the layout keeps it.
struct MatRef {
  int m;
  Real alpha;
  Real *rho, *e, *p, *ph;
};

using Field4 = Kokkos::View<Real****, Kokkos::LayoutRight, MemSpace>;
using IntBuffer = Kokkos::View<int*, MemSpace>;

// ------------------------------------------------------------------------------------------
// Device-side handles.

struct DenseDev {
  int nmat = 0;
  Field4 alpha, rho, e, p, ph;
  Field4 fv, fm, fe;  // signed volume, mass, energy flux of each material through each face
};

struct CompactDev {
  int nmat = 0;
  IntField3 mat;    // material of a pure cell; -(row + 1) for a mixed cell (row in `mixed`)
  IntField3 first;  // first slot of a mixed cell
  IntField3 nm;     // number of materials in the cell
  IntBuffer smat;   // slot -> material id
  Buffer salpha, srho, se, sp, sph;
  Buffer sfv[2], sfm[2], sfe[2];  // slot fluxes through the cell's low (0) / high (1) face
  IntBuffer mixed;                // row -> linear cell index (i * ey + j) * ez + k
  int nmixed = 0;
  // A module's per-slot quantities (MaterialState::set_extras): nx buffers, of which the first
  // nxc are carried across a rebuild for the cells it leaves unchanged (the others are
  // scratch of one cycle phase). Their pure-cell values live in the module's cell arrays.
  int nx = 0, nxc = 0;
  Buffer sx[kMaxExtras];
};

// Accessors handed to per-cell operations.
struct DenseCell {
  const DenseDev* d;
  int i, j, k;
  KOKKOS_INLINE_FUNCTION int count() const { return d->nmat; }
  KOKKOS_INLINE_FUNCTION bool aliases() const { return false; }
  KOKKOS_INLINE_FUNCTION MatRef get(int s) const {
    return {s,
            d->alpha(s, i, j, k),
            &d->rho(s, i, j, k),
            &d->e(s, i, j, k),
            &d->p(s, i, j, k),
            &d->ph(s, i, j, k)};
  }
  // Sets the volume fraction of slot s (pressure relaxation moves volume between materials).
  KOKKOS_INLINE_FUNCTION void set_alpha(int s, Real a) const { d->alpha(s, i, j, k) = a; }
};

// A pure compact cell: its one material's state IS the cell state (aliases() == true).
struct PureCell {
  int m;
  Real *rho, *e, *p, *ph;
  KOKKOS_INLINE_FUNCTION int count() const { return 1; }
  KOKKOS_INLINE_FUNCTION bool aliases() const { return true; }
  KOKKOS_INLINE_FUNCTION MatRef get(int) const { return {m, Real(1), rho, e, p, ph}; }
  KOKKOS_INLINE_FUNCTION void set_alpha(int, Real) const {}  // a pure cell's fraction is 1
};

struct MixedCell {
  const CompactDev* d;
  int first, n;
  KOKKOS_INLINE_FUNCTION int count() const { return n; }
  KOKKOS_INLINE_FUNCTION bool aliases() const { return false; }
  KOKKOS_INLINE_FUNCTION MatRef get(int s) const {
    const int q = first + s;
    return {d->smat(q), d->salpha(q), &d->srho(q), &d->se(q), &d->sp(q), &d->sph(q)};
  }
  KOKKOS_INLINE_FUNCTION void set_alpha(int s, Real a) const { d->salpha(first + s) = a; }
};

// Reads a cell's content into per-material arrays (zero where absent); returns the number of
// materials present.
KOKKOS_INLINE_FUNCTION int read_cell(const DenseDev& d, int i, int j, int k, Real* alpha, Real* rho,
                                     Real* e) {
  int n = 0;
  for (int m = 0; m < d.nmat; ++m) {
    alpha[m] = d.alpha(m, i, j, k);
    rho[m] = d.rho(m, i, j, k);
    e[m] = d.e(m, i, j, k);
    n += alpha[m] > 0 ? 1 : 0;
  }
  return n;
}

KOKKOS_INLINE_FUNCTION int read_cell(const CompactDev& d, const Field3& crho, const Field3& ce,
                                     int i, int j, int k, Real* alpha, Real* rho, Real* e) {
  for (int m = 0; m < d.nmat; ++m) alpha[m] = rho[m] = e[m] = 0;
  const int id = d.mat(i, j, k);
  if (id >= 0) {
    alpha[id] = 1;
    rho[id] = crho(i, j, k);
    e[id] = ce(i, j, k);
    return 1;
  }
  const int f = d.first(i, j, k), n = d.nm(i, j, k);
  for (int q = f; q < f + n; ++q) {
    alpha[d.smat(q)] = d.salpha(q);
    rho[d.smat(q)] = d.srho(q);
    e[d.smat(q)] = d.se(q);
  }
  return n;
}

// Sum of the volume fractions of the materials with id <= level (the onion-skin cumulative
// fraction that Youngs' reconstruction of layer `level` works on).
KOKKOS_INLINE_FUNCTION Real cumulative_fraction(const DenseDev& d, int i, int j, int k, int level) {
  Real s = 0;
  for (int m = 0; m <= level; ++m) s += d.alpha(m, i, j, k);
  return s;
}

KOKKOS_INLINE_FUNCTION Real cumulative_fraction(const CompactDev& d, int i, int j, int k,
                                                int level) {
  const int id = d.mat(i, j, k);
  if (id >= 0) return id <= level ? Real(1) : Real(0);
  Real s = 0;
  const int f = d.first(i, j, k), n = d.nm(i, j, k);
  for (int q = f; q < f + n && d.smat(q) <= level; ++q) s += d.salpha(q);
  return s;
}

// Does a cell (through its accessor) hold more than one material?
template <class Cell>
KOKKOS_INLINE_FUNCTION bool holds_several(const Cell& cell) {
  int n = 0;
  for (int s = 0; s < cell.count(); ++s) n += cell.get(s).alpha > 0 ? 1 : 0;
  return n > 1;
}

// Does cell (i,j,k) hold material m and nothing else?
KOKKOS_INLINE_FUNCTION bool pure_of(const DenseDev& d, int i, int j, int k, int m) {
  return d.alpha(m, i, j, k) == Real(1);
}
KOKKOS_INLINE_FUNCTION bool pure_of(const CompactDev& d, int i, int j, int k, int m) {
  return d.mat(i, j, k) == m;
}

// Cell averages of a content: rho = sum alpha_m rho_m, e mass-weighted; a single material gives
// its own values exactly.
KOKKOS_INLINE_FUNCTION void cell_average(int nmat, const Real* alpha, const Real* rho,
                                         const Real* e, Real& rho_c, Real& e_c) {
  Real r = 0, en = 0;
  int n = 0, last = 0;
  for (int m = 0; m < nmat; ++m) {
    if (!(alpha[m] > 0)) continue;
    r += alpha[m] * rho[m];
    en += alpha[m] * rho[m] * e[m];
    ++n;
    last = m;
  }
  if (n == 1) {
    rho_c = rho[last];
    e_c = e[last];
  } else {
    rho_c = r;
    e_c = en / r;
  }
}

// ------------------------------------------------------------------------------------------
// Host-side owner of the material state.

class MaterialState {
 public:
  // `rho, e, p, ph` are the hydro's cell arrays (cell averages; a pure compact cell's state).
  MaterialState(const Mesh& mesh, LayoutKind kind, int nmat, Field3 rho, Field3 e, Field3 p,
                Field3 ph);

  LayoutKind kind() const { return kind_; }
  int nmat() const { return nmat_; }
  const DenseDev& dense() const { return dense_; }
  const CompactDev& compact() const { return compact_; }
  Field3 cell_rho() const { return rho_; }
  Field3 cell_e() const { return e_; }

  // Runs op(i, j, k, cell) on every cell of the box [lo, hi): one MDRange (dense), or an
  // MDRange over the pure cells and a range over the mixed list (compact).
  template <class Op>
  void for_cells(const std::string& name, const std::array<int, 3>& lo,
                 const std::array<int, 3>& hi, Op op) const;
  // for_cells' range over the mixed list alone (compact layout; name + "[mixed]", no launch
  // when there are no mixed cells), for a kernel that runs its pure cells itself (as k-columns
  // over the cell arrays, kernels/hydro/mixed_lagrange.cpp and mixed_ke_fix.cpp).
  template <class Op>
  void for_mixed(const std::string& name, const std::array<int, 3>& lo,
                 const std::array<int, 3>& hi, Op op) const;

  // Sets the content of every cell with src.changed(i,j,k): src.content(i,j,k, alpha, rho, e)
  // fills per-material arrays and returns the count of materials present. Other cells keep
  // their content. Cell averages of changed cells are written to the cell arrays.
  template <class Source>
  void assign(const std::string& name, const Source& src);

  // Fills the ghost cells' material content from the neighbours and the boundary conditions
  // (axis by axis, like the field halo; messages carry nmat x (alpha, rho, e) per cell).
  void exchange();
  // exchange() for one layout (public: it launches kernels, see Floors)
  template <class Dev>
  void exchange_layout(const Dev& dev);

  // sum alpha_m rho_m over the materials m whose bit is set in `mask`, on every cell (ghosts
  // included): the density of a module's carrier materials (kernels/hydro/hydro.hpp).
  void carrier_density(unsigned mask, const Field3& out) const;
  // The same for n carriers at once (n <= kMaxMaterials + 1), one pass over the cells: out[c]
  // gets mask[c]'s density, bit for bit what carrier_density gives.
  void carrier_densities(const unsigned* mask, const Field3* out, int n) const;
  // Gives every slot of the compact pool `total` more values (kMaxExtras at most) for a module
  // that stores per-material quantities only where the material is (the strength module's
  // stress sets, issue #12); a rebuild copies the first `carried` of them for the cells it
  // leaves unchanged. The dense layout has none (the module keeps cell arrays per material).
  void set_extras(int total, int carried);
  // The compact pool as it stood before the last assign: the previous buffer set when that
  // assign rebuilt the pool, else the current one (the layout, slot materials and extras are
  // then unchanged). Read by a module that remaps its per-slot quantities after the update.
  const CompactDev& previous() const { return rebuilt_ ? next_ : compact_; }
  // Mass of each material over the owned cells (global sums).
  std::vector<double> material_masses() const;
  // Volume fraction of material m on the block (ghosts included), for output.
  Field3 fraction(int m) const;
  // Density (which == 1) or specific internal energy (which == 2) of material m on the block,
  // as stored (0 where a compact cell lacks m); which == 0 is fraction(m). For checkpoints.
  Field3 material_field(int m, int which) const;
  // Number of mixed cells and slots owned by this rank's block (ghosts included) and the bytes
  // the per-material state takes (for the perf harness).
  long mixed_cells() const;
  long slots() const;
  double bytes() const;
  // First owned cell (global linear index, or LONG_MAX) holding a material with non-positive
  // or non-finite density, negative or non-finite energy (global over the ranks); sets
  // `material` to the lowest such material of that cell and `what` to its first bad quantity:
  // 0 density not positive, 1 density non-finite, 2 energy negative, 3 energy non-finite.
  long first_bad(int& material, int& what) const;
  // The lowest specific energy each material may hold in a mixed cell before first_bad calls it
  // negative (default 0). A Mie-Grueneisen solid measures e from its ambient reference state:
  // below it is colder than ambient, not unphysical (docs/numerics.md, "Health check").
  void set_energy_floors(const std::vector<Real>& floors);
  // The same, with (material, what, 0) in `vals` (the form tests/test_multimat.cpp calls).
  long first_bad(double vals[3]) const;

 private:
  void resize_pool(CompactDev& c, int slots) const;

  const Mesh& mesh_;
  LayoutKind kind_;
  int nmat_;
  Field3 rho_, e_, p_, ph_;
  DenseDev dense_;
  CompactDev compact_, next_;  // current and rebuild target (swapped after each rebuild)
  bool rebuilt_ = false;       // the last assign rebuilt the pool (previous() is next_)
  // compact: 1 where this assign wrote a changed cell in place (written for every changed
  // cell of an in-place source; read only for changed cells)
  Kokkos::View<unsigned char***, MemSpace> stamp_;
  Buffer send_[2];                            // material halo messages, per side
  Buffer recv_[3][2];                         // received, per sweep and side
  Kokkos::View<long*, MemSpace> pack_count_;  // record values packed, per sweep and side,
  long pack_total_[6] = {};                   // all exchanges so far (and its host copy)
  int ex_, ey_, ez_;

 public:
  // (public: a kernel captures it, and nvcc allows no private type in an extended lambda's
  // captures)
  struct Floors {
    Real e[kMaxMaterials] = {};
  };

 private:
  Floors floors_;
};

// ------------------------------------------------------------------------------------------
// Templates.

template <class Op>
void MaterialState::for_cells(const std::string& name, const std::array<int, 3>& lo,
                              const std::array<int, 3>& hi, Op op) const {
  const Policy3 box({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]});
  if (kind_ == LayoutKind::Dense) {
    const DenseDev d = dense_;
    Kokkos::parallel_for(
        name, box, KOKKOS_LAMBDA(int i, int j, int k) {
          const DenseCell c{&d, i, j, k};
          op(i, j, k, c);
        });
    return;
  }
  const CompactDev d = compact_;
  auto rho = rho_, e = e_, p = p_, ph = ph_;
  Kokkos::parallel_for(
      name + "[pure]", box, KOKKOS_LAMBDA(int i, int j, int k) {
        const int m = d.mat(i, j, k);
        if (m < 0) return;
        const PureCell c{m, &rho(i, j, k), &e(i, j, k), &p(i, j, k), &ph(i, j, k)};
        op(i, j, k, c);
      });
  for_mixed(name, lo, hi, op);
}

template <class Op>
void MaterialState::for_mixed(const std::string& name, const std::array<int, 3>& lo,
                              const std::array<int, 3>& hi, Op op) const {
  if (kind_ != LayoutKind::Compact)
    throw std::logic_error("MaterialState::for_mixed: dense layout");
  const CompactDev d = compact_;
  if (d.nmixed == 0) return;
  const int ey = ey_, ez = ez_;
  const int l0 = lo[0], l1 = lo[1], l2 = lo[2], h0 = hi[0], h1 = hi[1], h2 = hi[2];
  Kokkos::parallel_for(
      name + "[mixed]", Policy1(0, d.nmixed), KOKKOS_LAMBDA(int r) {
        const int lin = d.mixed(r);
        const int k = lin % ez, j = (lin / ez) % ey, i = lin / (ez * ey);
        if (i < l0 || i >= h0 || j < l1 || j >= h1 || k < l2 || k >= h2) return;
        const MixedCell c{&d, d.first(i, j, k), d.nm(i, j, k)};
        op(i, j, k, c);
      });
}

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
