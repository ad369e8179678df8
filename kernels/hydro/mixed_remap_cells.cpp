// The multi-material remap's cell update (DESIGN.md §4 item 7): each cell's materials gain the
// fluxes through its faces; then the module carriers' densities and the clearing of the cells
// a carrier left.
#include "core/axis.hpp"
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/mixed_detail.hpp"

namespace mp::hydro {

using mat::kMaxMaterials;
using mixed_detail::read_donor;
using mixed_detail::set_sweep_fields;

namespace {

// Adds sign x the per-material fluxes through face (fi, fj, fk), whose donor is (di, dj, dk)
// and leaves the donor through its low (side 0) or high (side 1) face.
KOKKOS_INLINE_FUNCTION void add_face(const mat::DenseDev& d, const Field3&, const Field3&,
                                     const Field3&, int fi, int fj, int fk, int, int, int, int,
                                     Real sign, Real* V, Real* M, Real* E) {
  for (int m = 0; m < d.nmat; ++m) {
    V[m] += sign * d.fv(m, fi, fj, fk);
    M[m] += sign * d.fm(m, fi, fj, fk);
    E[m] += sign * d.fe(m, fi, fj, fk);
  }
}

KOKKOS_INLINE_FUNCTION void add_face(const mat::CompactDev& d, const Field3& vf, const Field3& mf,
                                     const Field3& ef, int fi, int fj, int fk, int di, int dj,
                                     int dk, int side, Real sign, Real* V, Real* M, Real* E) {
  const int id = d.mat(di, dj, dk);
  if (id >= 0) {
    V[id] += sign * vf(fi, fj, fk);
    M[id] += sign * mf(fi, fj, fk);
    E[id] += sign * ef(fi, fj, fk);
    return;
  }
  const int f = d.first(di, dj, dk), n = d.nm(di, dj, dk);
  for (int q = f; q < f + n; ++q) {
    const int m = d.smat(q);
    V[m] += sign * d.sfv[side](q);
    M[m] += sign * d.sfm[side](q);
    E[m] += sign * d.sfe[side](q);
  }
}

// The cell update of one remap sweep as a content source for MaterialState::assign: owned
// cells gain the fluxes through their two faces along d; other cells keep their content (the
// halo exchange that follows replaces the ghosts).
// (The sweep's axis D is a template parameter: the face offsets are then constants.)
template <class Dev, int D>
struct RemapSource {
  // content(i, j, k) reads cell (i, j, k) and the fluxes through its faces only
  static constexpr bool own_cell_only = true;
  static constexpr bool in_place = true;  // (so a cell may be written where it is)
  static constexpr int d = D;
  Dev dev;
  Field3 rho, e, pre, post, vf, mf, ef;
  int nmat;
  int lo[3], hi[3];
  Real min_fraction;

  KOKKOS_INLINE_FUNCTION bool changed(int i, int j, int k) const {
    return i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1] && k >= lo[2] && k < hi[2];
  }

  // The shortcut of MaterialState::assign (compact layout), a k-column at a time: a pure cell
  // whose two face donors are the same pure material stays that material. The arithmetic is
  // content()'s for one material, operand for operand, so the result is the same bit for bit.
  // Every operand is loaded and the tests are selects, so GCC vectorizes the loop; a cell that
  // is not written keeps its values (stored back unchanged). `dev` must be the pool assign
  // starts from (reads_pool).
  static constexpr bool pure_columns = true;
  // Returns whether every cell of the column was written (then the caller's general path has
  // nothing to do there).
  template <class Stamp>
  KOKKOS_INLINE_FUNCTION bool pure_column(int i, int j, int k0, int k1, const Field3& crho,
                                          const Field3& ce, const Stamp& stamp) const {
    if constexpr (!std::is_same_v<Dev, mat::CompactDev>) {
      for (int k = k0; k < k1; ++k) stamp(i, j, k) = 0;
      return k0 >= k1;
    } else {
      // (one type per declaration: the int, unsigned char and Real accessors differ)
      const auto mt = local(dev.mat);
      const auto st = local(stamp);
      const auto v = local(vf), m = local(mf), en = local(ef), p0 = local(pre), p1 = local(post),
                 r = local(rho), es = local(e), cr = local(crho), cen = local(ce);
      // (in blocks, the stamps stored by a second loop: a one-byte store in the loop made GCC
      // take 16 cells per vector iteration, in 16-byte vectors spilled to the stack, 3x the
      // single-material cell update's time)
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
      constexpr int B = 1;
#else
      constexpr int B = 32;
#endif
      // (1 when every cell was written: an AND over the stamps, in their own loop; a min
      // reduction in the Real loop left it scalar)
      unsigned char all = 1;
      // A column whose cells and their two neighbours along d are all one pure material (an
      // int loop of its own, which vectorizes) skips the id loads and tests: every cell there
      // stays that material where its volume stays positive.
      int diff = 0, ids = 0;
      {
        constexpr int sx = d == 0, sy = d == 1, sz = d == 2;
        for (int k = k0; k < k1; ++k) {
          const int c = mt(i, j, k);
          diff |= (mt(i - sx, j - sy, k - sz) ^ c) | (c ^ mt(i + sx, j + sy, k + sz));
          ids |= c;
        }
      }
      const bool uniform = diff == 0 && ids >= 0;
      auto loop = [&](auto several, auto one) {
        for (int kb = k0; kb < k1; kb += B) {
          const int ke = k1 - kb < B ? k1 : kb + B;
          Real okv[B];
#pragma GCC ivdep
          for (int k = kb; k < ke; ++k) {
            Real ro, eo;
            const bool ok = pure_update<decltype(several)::value, decltype(one)::value>(
                mt, v, m, en, p0, p1, r, es, i, j, k, ro, eo);
            const Real r0 = cr(i, j, k), e0 = cen(i, j, k);  // (loaded unconditionally)
            cr(i, j, k) = select_bits(ok, ro, r0);
            cen(i, j, k) = select_bits(ok, eo, e0);
            okv[k - kb] = ok ? Real(1) : Real(0);
          }
          for (int k = kb; k < ke; ++k) {
            const unsigned char sk = okv[k - kb] != 0 ? 1 : 0;
            st(i, j, k) = sk;
            all &= sk;
          }
        }
      };
      auto with_several = [&](auto one) {
        if (nmat > 1)
          loop(std::true_type{}, one);
        else
          loop(std::false_type{}, one);
      };
      if (uniform)
        with_several(std::true_type{});
      else
        with_several(std::false_type{});
      return all != 0;
    }
  }
  bool reads_pool(const mat::CompactDev& pool) const {
    if constexpr (std::is_same_v<Dev, mat::CompactDev>)
      return dev.mat.data() == pool.mat.data();
    else
      return true;
  }
  // pure_column's arithmetic on any accessors (views, or core/columns.hpp's locals): whether the
  // cell stays its pure material, and its density and energy if so (computed either way)
  // (One: the caller knows the cell and its two neighbours along d are one pure material)
  template <bool several, bool One = false, class I, class F>
  KOKKOS_INLINE_FUNCTION bool pure_update(const I& mt, const F& vf_, const F& mf_, const F& ef_,
                                          const F& pre_, const F& post_, const F& rho_, const F& e_,
                                          int i, int j, int k, Real& r_out, Real& e_out) const {
    const int sx = d == 0, sy = d == 1, sz = d == 2;
    const int fi = i + sx, fj = j + sy, fk = k + sz;
    const Real flo = vf_(i, j, k), fhi = vf_(fi, fj, fk);
    bool same = true;
    if constexpr (!One) {
      const int m = mt(i, j, k);
      // (bitwise & of the tests: no branch in the loop)
      same = (m >= 0) & (!(flo > 0) | (mt(i - sx, j - sy, k - sz) == m)) &
             ((fhi > 0) | (mt(fi, fj, fk) == m));
    }
    Real V = 0, M = 0, E = 0;
    V += Real(1) * flo;
    M += Real(1) * mf_(i, j, k);
    E += Real(1) * ef_(i, j, k);
    V += Real(-1) * fhi;
    M += Real(-1) * mf_(fi, fj, fk);
    E += Real(-1) * ef_(fi, fj, fk);
    const Real p0 = pre_(i, j, k), p1 = post_(i, j, k);
    const Real a = 1, v0 = a * p0;
    const Real m0 = v0 * rho_(i, j, k);
    const Real vol = v0 + V;
    Real mass = m0 + M, ener = e_(i, j, k) * m0 + E;
    if (several) {  // content() adds the (empty) others' zeros to the largest material
      mass += Real(0);
      ener += Real(0);
    }
    // (content()'s fraction vol / (0 + vol) is exactly 1 for a finite vol > 0, the only case
    // whose result is kept, and 1 * p1 is p1: its division left out, the same bits)
    r_out = mass / p1;
    e_out = ener / mass;
    return same & (vol > 0);
  }

  // content() over the materials of the cell and of its two faces' donors alone (compact
  // layout): entry c of a, r, en is material ids[c], ascending, and the count is returned.
  // Every other material is absent before and after and adds exact zeros to content()'s sums
  // (+0: a sum that starts at +0 never becomes -0), so the values are content()'s bit for bit,
  // without its nmat-long loops (with 16 materials most of the general path's time).
  static constexpr bool sparse = std::is_same_v<Dev, mat::CompactDev>;
  KOKKOS_INLINE_FUNCTION int sparse_content(int i, int j, int k, int* ids, Real* a, Real* r,
                                            Real* en) const {
    if constexpr (!sparse) {
      return 0;
    } else {
      const int sx = d == 0, sy = d == 1, sz = d == 2;
      const int fi = i + sx, fj = j + sy, fk = k + sz;
      const Real flo = vf(i, j, k), fhi = vf(fi, fj, fk);
      // the donors of the low and high faces, and which of their faces the flux leaves by
      const int li = flo > 0 ? i - sx : i, lj = flo > 0 ? j - sy : j, lk = flo > 0 ? k - sz : k;
      const int hi_ = fhi > 0 ? i : fi, hj = fhi > 0 ? j : fj, hk = fhi > 0 ? k : fk;
      const int lside = flo > 0 ? 1 : 0, hside = fhi > 0 ? 1 : 0;
      auto materials = [&](int ci, int cj, int ck) {
        const int id = dev.mat(ci, cj, ck);
        if (id >= 0) return 1u << id;
        unsigned mask = 0;
        const int f = dev.first(ci, cj, ck), n = dev.nm(ci, cj, ck);
        for (int q = f; q < f + n; ++q) mask |= 1u << dev.smat(q);
        return mask;
      };
      const unsigned mask = materials(i, j, k) | materials(li, lj, lk) | materials(hi_, hj, hk);
      int pos[kMaxMaterials];  // (written for the materials of the mask only, read for them)
      int nc = 0;
      for (int m = 0; (mask >> m) != 0u; ++m)
        if ((mask >> m) & 1u) {
          pos[m] = nc;
          ids[nc++] = m;
        }
      Real V[kMaxMaterials], M[kMaxMaterials], E[kMaxMaterials];
      for (int c = 0; c < nc; ++c) a[c] = r[c] = en[c] = V[c] = M[c] = E[c] = 0;
      // the cell's own content (read_cell)
      {
        const int id = dev.mat(i, j, k);
        if (id >= 0) {
          a[pos[id]] = 1;
          r[pos[id]] = rho(i, j, k);
          en[pos[id]] = e(i, j, k);
        } else {
          const int f = dev.first(i, j, k), n = dev.nm(i, j, k);
          for (int q = f; q < f + n; ++q) {
            const int c = pos[dev.smat(q)];
            a[c] = dev.salpha(q);
            r[c] = dev.srho(q);
            en[c] = dev.se(q);
          }
        }
      }
      // the two faces (add_face), low face first as in content()
      auto face = [&](int ffi, int ffj, int ffk, int di, int dj, int dk, int side, Real sign) {
        const int id = dev.mat(di, dj, dk);
        if (id >= 0) {
          V[pos[id]] += sign * vf(ffi, ffj, ffk);
          M[pos[id]] += sign * mf(ffi, ffj, ffk);
          E[pos[id]] += sign * ef(ffi, ffj, ffk);
          return;
        }
        const int f = dev.first(di, dj, dk), n = dev.nm(di, dj, dk);
        for (int q = f; q < f + n; ++q) {
          const int c = pos[dev.smat(q)];
          V[c] += sign * dev.sfv[side](q);
          M[c] += sign * dev.sfm[side](q);
          E[c] += sign * dev.sfe[side](q);
        }
      };
      face(i, j, k, li, lj, lk, lside, Real(1));
      face(fi, fj, fk, hi_, hj, hk, hside, Real(-1));
      finish(nc, pre(i, j, k), post(i, j, k), a, r, en, V, M, E);
      return nc;
    }
  }

  KOKKOS_INLINE_FUNCTION int content(int i, int j, int k, Real* a, Real* r, Real* en) const {
    read_donor(dev, rho, e, i, j, k, a, r, en);
    Real V[kMaxMaterials], M[kMaxMaterials], E[kMaxMaterials];
    for (int m = 0; m < nmat; ++m) V[m] = M[m] = E[m] = 0;
    const int sx = d == 0, sy = d == 1, sz = d == 2;
    // low face: index (i,j,k); its donor is the cell below when the flow is positive
    {
      const Real f = vf(i, j, k);
      if (f > 0)
        add_face(dev, vf, mf, ef, i, j, k, i - sx, j - sy, k - sz, 1, Real(1), V, M, E);
      else
        add_face(dev, vf, mf, ef, i, j, k, i, j, k, 0, Real(1), V, M, E);
    }
    {
      const int fi = i + sx, fj = j + sy, fk = k + sz;
      const Real f = vf(fi, fj, fk);
      if (f > 0)
        add_face(dev, vf, mf, ef, fi, fj, fk, i, j, k, 1, Real(-1), V, M, E);
      else
        add_face(dev, vf, mf, ef, fi, fj, fk, fi, fj, fk, 0, Real(-1), V, M, E);
    }
    return finish(nmat, pre(i, j, k), post(i, j, k), a, r, en, V, M, E);
  }

  // The rest of content(): entries 0..nm of the cell's content a, r, en (its start-of-sweep
  // fractions, densities and energies) and of the fluxes V, M, E gained through its faces give
  // its new content in a, r, en; the count of the entries present is returned. An entry is a
  // material (content) or one of a list of them in ascending order (sparse_content): the same
  // operations in the same order on the same values either way. (One difference: where no
  // entry keeps a positive volume the fallback "largest" is entry 0, material 0 or the list's
  // first; every entry then leaves, so the content is empty either way.)
  KOKKOS_INLINE_FUNCTION int finish(int nm, Real p0, Real p1, Real* a, Real* r, Real* en,
                                    const Real* V, const Real* M, const Real* E) const {
    Real vol[kMaxMaterials], mass[kMaxMaterials], ener[kMaxMaterials];
    int big = -1;
    for (int m = 0; m < nm; ++m) {
      const Real v0 = a[m] * p0;
      const Real m0 = v0 * r[m];
      vol[m] = v0 + V[m];
      mass[m] = m0 + M[m];
      ener[m] = en[m] * m0 + E[m];
      if (vol[m] > 0 && (big < 0 || vol[m] > vol[big])) big = m;
    }
    if (big < 0) big = 0;
    // A material below the smallest fraction leaves the cell; the largest material takes its
    // mass and energy, so the cell's totals are unchanged (the material's own total changes by
    // at most min_fraction of a cell's mass per removal: 1e-14 keeps it at round-off).
    // (the largest material's sums in registers: through mass[big] and ener[big] each addition
    // waited for the last one's store, most of the general path's time with many materials)
    Real mbig = mass[big], ebig = ener[big];
    for (int m = 0; m < nm; ++m) {
      if (m == big) continue;
      // A sliver (below 1e-6 of the cell) whose energy went negative by cancellation of nearly
      // equal fluxes stays, at zero energy: the largest material pays the deficit, so the
      // cell's energy is unchanged and every material keeps its mass (until 2026-12-01 the
      // sliver left and its mass went to the largest material, a per-material mass leak of
      // up to 1e-6 of a cell's mass per event, 5.6e-10 of the perforator's mass).
      if (vol[m] < Real(1e-6) * p1 && vol[m] > min_fraction * p1 && mass[m] > 0 &&
          !(ener[m] >= 0)) {
        ebig += ener[m];
        ener[m] = 0;
      }
      const bool present = vol[m] > min_fraction * p1 && mass[m] > 0;
      if (!present) {
        mbig += mass[m];
        ebig += ener[m];
        vol[m] = mass[m] = ener[m] = 0;
      }
    }
    mass[big] = mbig;
    ener[big] = ebig;
    Real vsum = 0;
    for (int m = 0; m < nm; ++m) vsum += vol[m];
    int n = 0;
    for (int m = 0; m < nm; ++m) {
      if (!(vol[m] > 0)) {
        a[m] = r[m] = en[m] = 0;
        continue;
      }
      a[m] = vol[m] / vsum;
      r[m] = mass[m] / (a[m] * p1);
      en[m] = ener[m] / mass[m];
      ++n;
    }
    return n;
  }
};

// A carrier's cell fields that mm_clear_absent zeroes (at namespace scope: nvcc allows no type
// local to a function in an extended lambda's captures).
struct ClearFields {
  Field3 f[7];
  int n = 0;
};

}  // namespace

template <class Dev>
void Hydro::mm_cell_update(const Dev& dev, int d) {
  const int ng = Mesh::ng;
  auto update = [&](auto src) {
    set_sweep_fields(src, dev, s_, d, mats_.n);
    src.post = s_.post_vol;
    for (int a = 0; a < 3; ++a) {
      src.lo[a] = ng;
      src.hi[a] = ng + mesh_.owned_cells(a);
    }
    src.min_fraction = opt_.min_fraction;
    mm_->assign("remap::material_update", src);
  };
  with_axis(d, [&](auto a) { update(RemapSource<Dev, decltype(a)::value>{}); });
}

void Hydro::mm_remap_cells(int d) {
  if (mm_->kind() == mat::LayoutKind::Dense)
    mm_cell_update(mm_->dense(), d);
  else
    mm_cell_update(mm_->compact(), d);
}

void Hydro::mm_carriers() {
  // one pass for all carriers (4 % of the zone-0.05 perforator's cycle as one pass each)
  if (ncarrier_ > 0) mm_->carrier_densities(carrier_mask_, carrier_rho_, ncarrier_);
}

void Hydro::mm_clear_absent() {
  const int ng = Mesh::ng;
  const auto end = mesh_.owned_end();
  const Policy3 owned({ng, ng, ng}, {end[0], end[1], end[2]});
  for (std::size_t mi = 0; mi < modules_.size(); ++mi)
    for (int slot = 0; slot < carriers_[mi]; ++slot) {
      const int c = first_carrier_[mi] + slot;
      ClearFields fs;
      // (none: what it carries is kept elsewhere, a pooled set nothing where its material is
      // absent)
      for (const Field3& x : modules_[mi]->carried_fields(slot)) fs.f[fs.n++] = x;
      if (fs.n == 0) continue;
      auto crho = carrier_rho_[c];
      mm_->carrier_density(carrier_mask_[c], crho);
      Kokkos::parallel_for(
          "remap::clear_absent", owned, KOKKOS_LAMBDA(int i, int j, int k) {
            if (crho(i, j, k) > 0) return;
            for (int q = 0; q < fs.n; ++q) fs.f[q](i, j, k) = 0;
          });
    }
}

Carrier Hydro::carrier(int slot) const {
  if (!mm_) return {s_.mass_flux, s_.rho};
  const Field3 f = carrier_flux_[slot];
  return {{f, f, f}, carrier_rho_[slot]};
}

std::vector<Carrier> Hydro::carriers_of(std::size_t i) const {
  std::vector<Carrier> c;
  for (int q = 0; q < carriers_[i]; ++q) c.push_back(carrier(first_carrier_[i] + q));
  return c;
}

// Explicit instantiations for the layouts' device handles.
template void Hydro::mm_cell_update(const mat::DenseDev&, int);
template void Hydro::mm_cell_update(const mat::CompactDev&, int);

}  // namespace mp::hydro
