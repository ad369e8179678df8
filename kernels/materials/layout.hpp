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
// and mixed-list rows, and a fill pass, into a second buffer set that is then swapped in
// (MaterialState::assign, rebuild.hpp).
//
// Kernels never see which layout they run on: they get a cell accessor (count(), get(s),
// aliases()) and call the same point functions through it. Summation over a cell's materials
// runs in material-id order in both layouts, and absent materials (dense) add exact zeros, so
// both layouts produce the same bits.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "eos/eos.hpp"
#include "materials/layout_kind.hpp"
#include "mesh/mesh.hpp"

namespace mp::mat {

// Largest number of materials one scene may hold (local per-cell arrays are sized by it).
constexpr int kMaxMaterials = 16;
// Most per-slot quantities a module may keep in the compact pool beside the layout's own (the
// strength module keeps 7: its 6 deviator components and the plastic strain).
constexpr int kMaxExtras = 8;

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

}  // namespace mp::mat

// MaterialState::assign and the content sources' traits
#include "materials/rebuild.hpp"
