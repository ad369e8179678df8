#include "materials/layout.hpp"

#include <climits>

#include "core/error.hpp"
#include "core/math.hpp"
#include "core/reduce.hpp"
#include "mesh/halo.hpp"

namespace mp::mat {

namespace {

// The material halo fills the ghosts axis by axis (x, then y, then z), so that edge and corner
// ghosts come through the face neighbours. HaloSource<Dev> is the content of a cell after the
// first `done` sweeps, computed from the received messages without storing anything: a cell in
// a ghost slab of sweep d took its content from that sweep's message (neighbour rank) or from
// its mirror / wall cell (physical boundary) as that cell stood after sweep d-1; every other cell
// kept its content. Walking back through the sweeps gives each ghost exactly the content that a
// pool rebuild after every sweep would have stored, so one update per exchange suffices (in
// place where no ghost's materials change, else one rebuild; MaterialState::assign).
template <class Dev>
struct HaloSource {
  // a ghost's content comes from owned cells (never changed here) and the messages, so ghosts
  // may be written where they are (the dense layout always does)
  static constexpr bool in_place = true;
  Dev dev;
  Field3 rho, e;  // cell arrays (compact reads pure cells from them)
  int ng, nmat, done;
  int ext[3], nl[3];
  int mode[3][2];  // per sweep and side: 0 neighbour rank, 1 reflective, 2 outflow
  // per sweep and side: the message received (ng layers): per cell a head of 3 values, then
  // per cell a full record of nmat x (alpha, rho, e), read only where the head is not negative
  // (a pure cell's head is -(id + 1), rho, e)
  Buffer recv[3][2];

  // 0: low ghost slab of axis d, 1: high ghost slab, -1: owned along d.
  KOKKOS_INLINE_FUNCTION int side_of(int d, int x) const {
    if (x < ng) return 0;
    if (x >= ng + nl[d]) return 1;
    return -1;
  }
  KOKKOS_INLINE_FUNCTION bool changed(int i, int j, int k) const {
    const int idx[3] = {i, j, k};
    for (int d = 0; d < done; ++d)
      if (side_of(d, idx[d]) >= 0) return true;
    return false;
  }
  KOKKOS_INLINE_FUNCTION int read(int i, int j, int k, Real* a, Real* r, Real* en) const;
  // MaterialState::assign's shortcut, and the pack's: true when the content is one material,
  // found without the per-material arrays (a pure stored cell or a pure cell's short record
  // in a message; the compact layout only).
  static constexpr bool has_pure = true;
  KOKKOS_INLINE_FUNCTION bool pure(int i, int j, int k, int& id, Real& r, Real& en) const {
    if constexpr (!std::is_same_v<Dev, CompactDev>) {
      return false;
    } else {
      int idx[3] = {i, j, k};
      for (int d = done - 1; d >= 0; --d) {
        const int x = idx[d];
        const int s = side_of(d, x);
        if (s < 0) continue;
        if (mode[d][s] == 0) {
          int loc[3] = {idx[0], idx[1], idx[2]}, n[3] = {ext[0], ext[1], ext[2]};
          loc[d] = s == 0 ? x : x - (ng + nl[d]);
          n[d] = ng;
          const long o = (loc[0] + long(n[0]) * (loc[1] + long(n[1]) * loc[2])) * 3;
          const Buffer& b = recv[d][s];
          const Real a0 = b(o);
          if (!(a0 < 0)) return false;
          id = int(-a0) - 1;
          r = b(o + 1);
          en = b(o + 2);
          return true;
        }
        if (mode[d][s] == 1)
          idx[d] = s == 0 ? 2 * ng - 1 - x : 2 * (ng + nl[d]) - 1 - x;
        else
          idx[d] = s == 0 ? ng : ng + nl[d] - 1;
      }
      const int m = dev.mat(idx[0], idx[1], idx[2]);
      if (m < 0) return false;
      id = m;
      r = rho(idx[0], idx[1], idx[2]);
      en = e(idx[0], idx[1], idx[2]);
      return true;
    }
  }
  KOKKOS_INLINE_FUNCTION int content(int i, int j, int k, Real* a, Real* r, Real* en) const {
    int idx[3] = {i, j, k};
    for (int d = done - 1; d >= 0; --d) {
      const int x = idx[d];
      const int s = side_of(d, x);
      if (s < 0) continue;  // sweep d left this cell alone
      if (mode[d][s] == 0) {
        // slab cell index with the axis d running over the ng ghost layers
        int loc[3] = {idx[0], idx[1], idx[2]}, n[3] = {ext[0], ext[1], ext[2]};
        loc[d] = s == 0 ? x : x - (ng + nl[d]);
        n[d] = ng;
        const long cell = loc[0] + long(n[0]) * (loc[1] + long(n[1]) * loc[2]);
        const Buffer& b = recv[d][s];
        const Real a0 = b(cell * 3);
        if (a0 < 0) {  // a pure cell's short record (pack): -(id + 1), rho, e
          for (int m = 0; m < nmat; ++m) a[m] = r[m] = en[m] = 0;
          const int id = int(-a0) - 1;
          a[id] = 1;
          r[id] = b(cell * 3 + 1);
          en[id] = b(cell * 3 + 2);
          return 1;
        }
        const long full = 3 * long(n[0]) * n[1] * n[2];  // the full records follow the heads
        int cnt = 0;
        for (int m = 0; m < nmat; ++m) {
          const long o = full + (cell * nmat + m) * 3;
          a[m] = b(o);
          r[m] = b(o + 1);
          en[m] = b(o + 2);
          cnt += a[m] > 0 ? 1 : 0;
        }
        return cnt;
      }
      // a boundary ghost copied the content its source cell had after sweep d-1
      if (mode[d][s] == 1)
        idx[d] = s == 0 ? 2 * ng - 1 - x : 2 * (ng + nl[d]) - 1 - x;  // mirror across the face
      else
        idx[d] = s == 0 ? ng : ng + nl[d] - 1;  // the wall cell
    }
    return read(idx[0], idx[1], idx[2], a, r, en);  // as stored before the exchange
  }
};

template <>
KOKKOS_INLINE_FUNCTION int HaloSource<DenseDev>::read(int i, int j, int k, Real* a, Real* r,
                                                      Real* en) const {
  return read_cell(dev, i, j, k, a, r, en);
}
template <>
KOKKOS_INLINE_FUNCTION int HaloSource<CompactDev>::read(int i, int j, int k, Real* a, Real* r,
                                                        Real* en) const {
  return read_cell(dev, rho, e, i, j, k, a, r, en);
}

}  // namespace

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
}

void MaterialState::exchange() {
  Kokkos::Profiling::pushRegion("matter::exchange");  // named for profiling tools
  const int ng = Mesh::ng;
  const int nmat = nmat_;
  const int ext[3] = {ex_, ey_, ez_};
  // Message sizes per sweep; the receive buffers hold all three sweeps' messages (the final
  // update reads them all), the send buffers one at a time. Kept between calls.
  long count[3], offset[3], total = 0, largest = 0;
  for (int d = 0; d < 3; ++d) {
    int n[3] = {ext[0], ext[1], ext[2]};
    n[d] = ng;
    count[d] = long(n[0]) * n[1] * n[2] * (3 + nmat * 3);  // heads, then full records
    offset[d] = total;
    total += count[d];
    largest = std::max(largest, count[d]);
  }
  for (int s = 0; s < 2; ++s) {
    bool neighbour = false;
    for (int d = 0; d < 3; ++d) neighbour = neighbour || !mesh_.physical_boundary(d, s);
    if (!neighbour) continue;
    if (long(send_[s].extent(0)) < largest)
      send_[s] = Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "matter::send"), largest);
    if (long(recv_[s].extent(0)) < total)
      recv_[s] = Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "matter::recv"), total);
  }
  auto run = [&](const auto& dev) {
    using Dev = std::decay_t<decltype(dev)>;
    HaloSource<Dev> src{dev, rho_, e_, ng, nmat, 0, {ext[0], ext[1], ext[2]}, {}, {}, {}};
    for (int d = 0; d < 3; ++d) src.nl[d] = mesh_.owned_cells(d);
    for (int d = 0; d < 3; ++d) {
      const int nl = src.nl[d];
      bool any = false;
      for (int s = 0; s < 2; ++s) {
        if (mesh_.physical_boundary(d, s)) {
          src.mode[d][s] = mesh_.boundary(d, s) == BoundaryKind::Reflective ? 1 : 2;
          continue;
        }
        any = true;
        src.mode[d][s] = 0;
        src.recv[d][s] = Kokkos::subview(recv_[s], std::make_pair(offset[d], offset[d] + count[d]));
        // pack the ng owned layers next to face s, as they stand after the sweeps before d
        const int first = s == 0 ? ng : nl;
        int lo[3] = {0, 0, 0}, hi[3] = {ext[0], ext[1], ext[2]};
        lo[d] = first;
        hi[d] = first + ng;
        auto buf = send_[s];
        const int n0 = d == 0 ? ng : ext[0], n1 = d == 1 ? ng : ext[1];  // slab extents
        const long full = 3 * long(n0) * n1 * (d == 2 ? ng : ext[2]);
        const HaloSource<Dev> before = src;  // done == d
        Kokkos::parallel_for(
            "matter::pack", Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}),
            KOKKOS_LAMBDA(int i, int j, int k) {
              int loc[3] = {i, j, k};
              loc[d] -= first;
              const long cell = loc[0] + long(n0) * (loc[1] + long(n1) * loc[2]);
              int id = 0;
              Real pr = 0, pe = 0;
              if (before.pure(i, j, k, id, pr, pe)) {
                // a pure cell: its head only, -(id + 1), rho, e (its full record is left
                // unwritten; content() reads the head)
                buf(cell * 3) = -Real(id + 1);
                buf(cell * 3 + 1) = pr;
                buf(cell * 3 + 2) = pe;
                return;
              }
              buf(cell * 3) = 1;  // (not negative: read the full record)
              Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
              before.content(i, j, k, a, r, en);
              for (int m = 0; m < nmat; ++m) {
                const long o = full + (cell * nmat + m) * 3;
                buf(o) = a[m];
                buf(o + 1) = r[m];
                buf(o + 2) = en[m];
              }
            });
      }
      if (any) {
        const Buffer recv[2] = {src.recv[d][0], src.recv[d][1]};
        exchange_buffers(mesh_, d, send_, recv, count[d], 100);
      }
      src.done = d + 1;
    }
    // one update of every ghost cell (one pool rebuild in the compact layout)
    assign("matter::halo", src);
  };
  if (kind_ == LayoutKind::Dense)
    run(dense_);
  else
    run(compact_);
  Kokkos::Profiling::popRegion();
}

std::vector<double> MaterialState::material_masses() const {
  const Geometry g = mesh_.geometry();
  const double vol = g.cell_volume();
  SumN<kMaxMaterials> sum;
  const int ng = Mesh::ng;
  const std::array<int, 3> lo{ng, ng, ng}, hi = mesh_.owned_end();
  if (kind_ == LayoutKind::Dense) {
    const DenseDev d = dense_;
    const int nmat = nmat_;
    Kokkos::parallel_reduce(
        "matter::masses", Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}),
        KOKKOS_LAMBDA(int i, int j, int k, SumN<kMaxMaterials>& acc) {
          for (int m = 0; m < nmat; ++m)
            acc.v[m] += double(d.alpha(m, i, j, k)) * double(d.rho(m, i, j, k)) * vol;
        },
        Kokkos::Sum<SumN<kMaxMaterials>>(sum));
  } else {
    const CompactDev d = compact_;
    auto rho = rho_;
    SumN<kMaxMaterials> pure, mixed;
    Kokkos::parallel_reduce(
        "matter::masses[pure]", Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}),
        KOKKOS_LAMBDA(int i, int j, int k, SumN<kMaxMaterials>& acc) {
          const int m = d.mat(i, j, k);
          if (m >= 0) acc.v[m] += double(rho(i, j, k)) * vol;
        },
        Kokkos::Sum<SumN<kMaxMaterials>>(pure));
    const int ey = ey_, ez = ez_;
    Kokkos::parallel_reduce(
        "matter::masses[mixed]", Policy1(0, d.nmixed),
        KOKKOS_LAMBDA(int r, SumN<kMaxMaterials>& acc) {
          const int lin = d.mixed(r);
          const int k = lin % ez, j = (lin / ez) % ey, i = lin / (ez * ey);
          if (i < lo[0] || i >= hi[0] || j < lo[1] || j >= hi[1] || k < lo[2] || k >= hi[2]) return;
          const int f = d.first(i, j, k);
          for (int q = f; q < f + d.nm(i, j, k); ++q)
            acc.v[d.smat(q)] += double(d.salpha(q)) * double(d.srho(q)) * vol;
        },
        Kokkos::Sum<SumN<kMaxMaterials>>(mixed));
    for (int m = 0; m < kMaxMaterials; ++m) sum.v[m] = pure.v[m] + mixed.v[m];
  }
  std::vector<double> out(nmat_);
  MPI_Allreduce(sum.v, out.data(), nmat_, MPI_DOUBLE, MPI_SUM, mesh_.comm());
  return out;
}

void MaterialState::carrier_density(unsigned mask, const Field3& out) const {
  for_cells(
      "matter::carrier_density", {0, 0, 0}, {ex_, ey_, ez_},
      KOKKOS_LAMBDA(int i, int j, int k, const auto& cell) {
        Real r = 0;
        for (int s = 0; s < cell.count(); ++s) {
          const MatRef m = cell.get(s);
          if (m.alpha > 0 && (mask >> m.m) & 1u) r += m.alpha * *m.rho;
        }
        out(i, j, k) = r;
      });
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
  // the mixed list; one byte per cell marks the cells an assign wrote in place
  double b = cells;
  for (const CompactDev* c : {&compact_, &next_})
    b += 3 * sizeof(int) * cells + double(c->smat.extent(0)) * (sizeof(int) + 11 * sizeof(Real)) +
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
    const int ey = ey_, ez = ez_;
    Kokkos::parallel_reduce(
        "matter::check", Policy1(0, d.nmixed),
        KOKKOS_LAMBDA(int r, long& acc) {
          const int lin = d.mixed(r);
          const int k = lin % ez, j = (lin / ez) % ey, i = lin / (ez * ey);
          if (i < ng || i >= hx || j < ng || j >= hy || k < ng || k >= hz) return;
          const int f = d.first(i, j, k);
          for (int q = f; q < f + d.nm(i, j, k); ++q) {
            const int c = code(d.smat(q), d.srho(q), d.se(q));
            if (c < 0) continue;
            const long key = (g.global_cell(i, j, k, nx, ny) * kM + d.smat(q)) * 4 + c;
            if (key < acc) acc = key;
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
