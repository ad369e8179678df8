// MaterialState's host side: the two layouts' allocation (the pool's extras and growth) and the
// queries over the material state (masses, carrier densities, output fields, counts, health).
#include "materials/layout.hpp"

#include <climits>
#include <limits>

#include "core/columns.hpp"
#include "core/error.hpp"
#include "core/math.hpp"
#include "core/reduce.hpp"

namespace mp::mat {

MaterialState::MaterialState(const Mesh& mesh, LayoutKind kind, int nmat, Field3 rho, Field3 e,
                             Field3 p, Field3 ph)
    : mesh_(mesh), kind_(kind), nmat_(nmat), rho_(rho), e_(e), p_(p), ph_(ph) {
  if (nmat < 1 || nmat > kMaxMaterials)
    throw RunError("a scene holds 1 to " + std::to_string(kMaxMaterials) + " materials, not " +
                   std::to_string(nmat));
  ex_ = mesh.extent(Centering::Cell, 0);
  ey_ = mesh.extent(Centering::Cell, 1);
  ez_ = mesh.extent(Centering::Cell, 2);
  if (kind == LayoutKind::Dense) {
    dense_.nmat = nmat;
    auto make = [&](const char* n) { return Field4(std::string(n), nmat, ex_, ey_, ez_); };
    dense_.alpha = make("dense::alpha");
    dense_.rho = make("dense::rho");
    dense_.e = make("dense::e");
    dense_.p = make("dense::p");
    dense_.ph = make("dense::p_half");
    // face fluxes: node extent along every axis covers the faces of every sweep
    auto face = [&](const char* n) {
      return Field4(std::string(n), nmat, ex_ + 1, ey_ + 1, ez_ + 1);
    };
    dense_.fv = face("dense::volume_flux");
    dense_.fm = face("dense::mass_flux");
    dense_.fe = face("dense::energy_flux");
    return;
  }
  stamp_ = decltype(stamp_)("compact::stamp", ex_, ey_, ez_);
  for (CompactDev* c : {&compact_, &next_}) {
    c->nmat = nmat;
    c->mat = IntField3("compact::mat", ex_, ey_, ez_);
    c->first = IntField3("compact::first", ex_, ey_, ez_);
    c->nm = IntField3("compact::nm", ex_, ey_, ez_);
    c->mixed = IntBuffer("compact::mixed", 1);
    resize_pool(*c, 1);
    Kokkos::deep_copy(c->nm, 1);  // every cell pure material 0 until painted
  }
}

void MaterialState::set_extras(int total, int carried) {
  if (total < 0 || total > kMaxExtras || carried < 0 || carried > total)
    throw RunError("material pool: " + std::to_string(total) + " extra values per slot (" +
                   std::to_string(carried) + " carried); at most " + std::to_string(kMaxExtras));
  if (kind_ != LayoutKind::Compact) return;
  for (CompactDev* c : {&compact_, &next_}) {
    c->nx = total;
    c->nxc = carried;
    const std::size_t cap = c->smat.extent(0);
    for (int x = 0; x < total; ++x)
      if (c->sx[x].extent(0) < cap) c->sx[x] = Buffer("compact::slot_extra", cap);
  }
}

void MaterialState::resize_pool(CompactDev& c, int slots) const {
  if (c.smat.extent(0) >= std::size_t(slots) && c.smat.extent(0) > 0) return;
  const int cap = std::max(slots + slots / 4, 16);  // room to grow before the next allocation
  auto alloc = [&](const char* n) {
    return Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(n)), cap);
  };
  c.smat = IntBuffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "compact::slot_mat"), cap);
  c.salpha = alloc("compact::slot_alpha");
  c.srho = alloc("compact::slot_rho");
  c.se = alloc("compact::slot_e");
  c.sp = alloc("compact::slot_p");
  c.sph = alloc("compact::slot_p_half");
  for (int s = 0; s < 2; ++s) {
    c.sfv[s] = alloc("compact::slot_volume_flux");
    c.sfm[s] = alloc("compact::slot_mass_flux");
    c.sfe[s] = alloc("compact::slot_energy_flux");
  }
  for (int x = 0; x < c.nx; ++x) c.sx[x] = alloc("compact::slot_extra");
}

std::vector<double> MaterialState::material_masses() const {
  // (compensated sums, as the conservation totals' (core/reduce.hpp): a material's mass over
  // millions of cells to a rounding, so that its change is what left through the faces)
  const Geometry g = mesh_.geometry();
  const double vol = g.cell_volume();
  CompensatedSumN<kMaxMaterials> sum;
  const int ng = Mesh::ng;
  const std::array<int, 3> lo{ng, ng, ng}, hi = mesh_.owned_end();
  if (kind_ == LayoutKind::Dense) {
    const DenseDev d = dense_;
    const int nmat = nmat_;
    Kokkos::parallel_reduce(
        "matter::masses", Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}),
        KOKKOS_LAMBDA(int i, int j, int k, CompensatedSumN<kMaxMaterials>& acc) {
          for (int m = 0; m < nmat; ++m)
            acc.add(m, double(d.alpha(m, i, j, k)) * double(d.rho(m, i, j, k)) * vol);
        },
        Kokkos::Sum<CompensatedSumN<kMaxMaterials>>(sum));
  } else {
    const CompactDev d = compact_;
    auto rho = rho_;
    CompensatedSumN<kMaxMaterials> pure, mixed;
    Kokkos::parallel_reduce(
        "matter::masses[pure]", Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}),
        KOKKOS_LAMBDA(int i, int j, int k, CompensatedSumN<kMaxMaterials>& acc) {
          const int m = d.mat(i, j, k);
          if (m >= 0) acc.add(m, double(rho(i, j, k)) * vol);
        },
        Kokkos::Sum<CompensatedSumN<kMaxMaterials>>(pure));
    const int ey = ey_, ez = ez_;
    // (the box as a Kokkos::Array: std::array's operator[] is a host function to nvcc)
    const Kokkos::Array<int, 3> blo{lo[0], lo[1], lo[2]}, bhi{hi[0], hi[1], hi[2]};
    Kokkos::parallel_reduce(
        "matter::masses[mixed]", Policy1(0, d.nmixed),
        KOKKOS_LAMBDA(int r, CompensatedSumN<kMaxMaterials>& acc) {
          const int lin = d.mixed(r);
          const int k = lin % ez, j = (lin / ez) % ey, i = lin / (ez * ey);
          if (i < blo[0] || i >= bhi[0] || j < blo[1] || j >= bhi[1] || k < blo[2] || k >= bhi[2])
            return;
          const int f = d.first(i, j, k);
          for (int q = f; q < f + d.nm(i, j, k); ++q)
            acc.add(d.smat(q), double(d.salpha(q)) * double(d.srho(q)) * vol);
        },
        Kokkos::Sum<CompensatedSumN<kMaxMaterials>>(mixed));
    sum = pure;
    sum += mixed;
  }
  std::vector<double> mine(nmat_), out(nmat_);
  for (int m = 0; m < nmat_; ++m) mine[m] = sum.value(m);
  MPI_Allreduce(mine.data(), out.data(), nmat_, MPI_DOUBLE, MPI_SUM, mesh_.comm());
  return out;
}

void MaterialState::carrier_density(unsigned mask, const Field3& out) const {
  carrier_densities(&mask, &out, 1);
}

namespace {

// The carrier_densities kernel, a for_cells body (a functor at namespace scope, not a generic
// extended lambda, which nvcc rejects inside for_cells' own lambdas).
struct CarrierDensities {
  static constexpr int kMax = kMaxMaterials + 1;
  unsigned mask[kMax];
  Field3 out[kMax];
  int n;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    for (int q = 0; q < n; ++q) {
      Real r = 0;
      for (int s = 0; s < cell.count(); ++s) {
        const MatRef m = cell.get(s);
        if (m.alpha > 0 && (mask[q] >> m.m) & 1u) r += m.alpha * *m.rho;
      }
      out[q](i, j, k) = r;
    }
  }
};

}  // namespace

void MaterialState::carrier_densities(const unsigned* mask, const Field3* out, int n) const {
  constexpr int kMax = CarrierDensities::kMax;
  if (n < 1 || n > kMax) throw RunError("carrier_densities: 1 to kMaxMaterials + 1 carriers");
  CarrierDensities c;
  for (int q = 0; q < n; ++q) c.mask[q] = mask[q], c.out[q] = out[q];
  c.n = n;
  for_cells("matter::carrier_density", {0, 0, 0}, {ex_, ey_, ez_}, c);
}

Field3 MaterialState::fraction(int m) const {
  Field3 f(Kokkos::view_alloc(Kokkos::WithoutInitializing, "fraction"), ex_, ey_, ez_);
  if (kind_ == LayoutKind::Dense) {
    const DenseDev d = dense_;
    Kokkos::parallel_for(
        "matter::fraction", Policy3({0, 0, 0}, {ex_, ey_, ez_}),
        KOKKOS_LAMBDA(int i, int j, int k) { f(i, j, k) = d.alpha(m, i, j, k); });
    return f;
  }
  const CompactDev d = compact_;
  Kokkos::parallel_for(
      "matter::fraction", Policy3({0, 0, 0}, {ex_, ey_, ez_}), KOKKOS_LAMBDA(int i, int j, int k) {
        const int id = d.mat(i, j, k);
        Real a = id == m ? Real(1) : Real(0);
        if (id < 0)
          for (int q = d.first(i, j, k); q < d.first(i, j, k) + d.nm(i, j, k); ++q)
            if (d.smat(q) == m) a = d.salpha(q);
        f(i, j, k) = a;
      });
  return f;
}

Field3 MaterialState::material_field(int m, int which) const {
  if (which == 0) return fraction(m);
  Field3 f(Kokkos::view_alloc(Kokkos::WithoutInitializing, "material_field"), ex_, ey_, ez_);
  if (kind_ == LayoutKind::Dense) {
    const DenseDev d = dense_;
    Kokkos::parallel_for(
        "matter::material_field", Policy3({0, 0, 0}, {ex_, ey_, ez_}),
        KOKKOS_LAMBDA(int i, int j, int k) {
          f(i, j, k) = which == 1 ? d.rho(m, i, j, k) : d.e(m, i, j, k);
        });
    return f;
  }
  const CompactDev d = compact_;
  auto crho = rho_, ce = e_;
  Kokkos::parallel_for(
      "matter::material_field", Policy3({0, 0, 0}, {ex_, ey_, ez_}),
      KOKKOS_LAMBDA(int i, int j, int k) {
        const int id = d.mat(i, j, k);
        Real v = id == m ? (which == 1 ? crho(i, j, k) : ce(i, j, k)) : Real(0);
        if (id < 0)
          for (int q = d.first(i, j, k); q < d.first(i, j, k) + d.nm(i, j, k); ++q)
            if (d.smat(q) == m) v = which == 1 ? d.srho(q) : d.se(q);
        f(i, j, k) = v;
      });
  return f;
}

long MaterialState::mixed_cells() const {
  if (kind_ == LayoutKind::Compact) return compact_.nmixed;
  const DenseDev d = dense_;
  const int nmat = nmat_;
  long n = 0;
  Kokkos::parallel_reduce(
      "matter::count_mixed", Policy3({0, 0, 0}, {ex_, ey_, ez_}),
      KOKKOS_LAMBDA(int i, int j, int k, long& acc) {
        int c = 0;
        for (int m = 0; m < nmat; ++m) c += d.alpha(m, i, j, k) > 0 ? 1 : 0;
        if (c > 1) ++acc;
      },
      n);
  return n;
}

long MaterialState::slots() const {
  if (kind_ == LayoutKind::Dense) return long(nmat_) * ex_ * ey_ * ez_;
  const CompactDev d = compact_;
  long used = 0;
  Kokkos::parallel_reduce(
      "matter::count_slots", Policy3({0, 0, 0}, {ex_, ey_, ez_}),
      KOKKOS_LAMBDA(int i, int j, int k, long& acc) {
        if (d.mat(i, j, k) < 0) acc += d.nm(i, j, k);
      },
      used);
  return used;
}

double MaterialState::bytes() const {
  const double cells = double(ex_) * ey_ * ez_;
  if (kind_ == LayoutKind::Dense)
    // alpha, rho, e, p, p_half per material and cell, plus the three face-flux arrays
    return double(sizeof(Real)) * nmat_ * (5 * cells + 3 * double(ex_ + 1) * (ey_ + 1) * (ez_ + 1));
  // two buffer sets (the current one and the rebuild target, swapped after each rebuild),
  // each: three int cell arrays, per slot a material id, 5 state values and 6 face fluxes, and
  // the mixed list, and a module's extra values per slot; one byte per cell marks the cells an
  // assign wrote in place
  double b = cells;
  for (const CompactDev* c : {&compact_, &next_})
    b += 3 * sizeof(int) * cells +
         double(c->smat.extent(0)) * (sizeof(int) + (11 + c->nx) * sizeof(Real)) +
         sizeof(int) * double(c->mixed.extent(0));
  return b;
}

long MaterialState::first_bad(int& material, int& what) const {
  const Geometry g = mesh_.geometry();
  const long nx = mesh_.global_cells(0), ny = mesh_.global_cells(1);
  const int ng = Mesh::ng;
  const int hx = ng + mesh_.owned_cells(0), hy = ng + mesh_.owned_cells(1),
            hz = ng + mesh_.owned_cells(2);
  // key = (cell * kMaxMaterials + m) * 4 + what: the minimum is the lowest cell, then the
  // lowest material, then the first bad quantity (what: 0 density not positive, 1 density
  // non-finite, 2 energy negative, 3 energy non-finite)
  const Floors fl = floors_;
  auto code = [fl] KOKKOS_FUNCTION(int m, Real r, Real e) {
    if (!misfinite(r)) return 1;
    if (!(r > 0)) return 0;
    if (!misfinite(e)) return 3;
    if (!(e >= fl.e[m])) return 2;
    return -1;
  };
  constexpr long kM = kMaxMaterials;
  long first = LONG_MAX;
  if (kind_ == LayoutKind::Dense) {
    const DenseDev d = dense_;
    const int nmat = nmat_;
    Kokkos::parallel_reduce(
        "matter::check", Policy3({ng, ng, ng}, {hx, hy, hz}),
        KOKKOS_LAMBDA(int i, int j, int k, long& acc) {
          for (int m = 0; m < nmat; ++m) {
            if (!(d.alpha(m, i, j, k) > 0)) continue;
            const int c = code(m, d.rho(m, i, j, k), d.e(m, i, j, k));
            if (c < 0) continue;
            const long key = (g.global_cell(i, j, k, nx, ny) * kM + m) * 4 + c;
            if (key < acc) acc = key;
          }
        },
        Kokkos::Min<long>(first));
  } else {
    const CompactDev d = compact_;
    // one pass over the owned cells: a pure cell's material state is the cell's (checked
    // against the same floors as in a mixed cell), a mixed cell's are its slots
    auto crho = rho_, ce = e_;
    auto point = KOKKOS_LAMBDA(int i, int j, int k, long& acc) {
      const int id = d.mat(i, j, k);
      const long cell = g.global_cell(i, j, k, nx, ny);
      if (id >= 0) {
        const int c = code(id, crho(i, j, k), ce(i, j, k));
        if (c < 0) return;
        const long key = (cell * kM + id) * 4 + c;
        if (key < acc) acc = key;
        return;
      }
      const int f = d.first(i, j, k);
      for (int q = f; q < f + d.nm(i, j, k); ++q) {
        const int c = code(d.smat(q), d.srho(q), d.se(q));
        if (c < 0) continue;
        const long key = (cell * kM + d.smat(q)) * 4 + c;
        if (key < acc) acc = key;
      }
    };
    // (k-columns, core/columns.hpp: a chunk of a column is screened by a vector loop that
    // passes a pure cell whose density is positive and finite and whose energy is finite and
    // at least every material's floor; only a chunk with another cell, a mixed one or one
    // nearer a floor, is walked again by point(), which finds the exact key)
    Real top = -std::numeric_limits<Real>::infinity();
    for (int m = 0; m < nmat_; ++m) top = !(fl.e[m] <= top) ? fl.e[m] : top;  // (NaN: all walked)
    const int lo[3] = {ng, ng, ng}, hi[3] = {hx, hy, hz};
    reduce_columns_with(
        "matter::check", lo, hi,
        KOKKOS_LAMBDA(int i, int j, int k0, int k1, long& acc) {
          const auto mt = local(d.mat);
          const auto ra = local(crho), ea = local(ce);
          constexpr Real big = kRealMax;
          constexpr int kChunk = 32;
          Real bad[kChunk];
          for (int kb = k0; kb < k1; kb += kChunk) {
            const int ke = kb + kChunk < k1 ? kb + kChunk : k1;
            using MP_KOKKOS_MATH::fabs;
#pragma GCC ivdep
            for (int k = kb; k < ke; ++k) {
              const Real id = mt(i, j, k);  // (as Real, exact: tests of one width vectorize)
              const Real r = ra(i, j, k), en = ea(i, j, k);
              const bool ok =
                  (id >= 0) & (r > 0) & (fabs(r) <= big) & (fabs(en) <= big) & (en >= top);
              bad[k - kb] = ok ? Real(0) : Real(1);
            }
            bool any = false;
            for (int k = kb; k < ke; ++k) any = any || bad[k - kb] > 0;
            if (any)
              for (int k = kb; k < ke; ++k) point(i, j, k, acc);
          }
        },
        Kokkos::Min<long>(first));
  }
  long global = LONG_MAX;
  MPI_Allreduce(&first, &global, 1, MPI_LONG, MPI_MIN, mesh_.comm());
  if (global == LONG_MAX) return LONG_MAX;
  what = int(global % 4);
  material = int((global / 4) % kM);
  return global / (4 * kM);
}

void MaterialState::set_energy_floors(const std::vector<Real>& floors) {
  for (std::size_t m = 0; m < floors.size() && m < std::size_t(kMaxMaterials); ++m)
    floors_.e[m] = floors[m];
}

long MaterialState::first_bad(double vals[3]) const {
  int material = 0, what = 0;
  const long cell = first_bad(material, what);
  vals[0] = cell == LONG_MAX ? 0 : material;
  vals[1] = cell == LONG_MAX ? 0 : what;
  vals[2] = 0;
  return cell;
}

}  // namespace mp::mat
