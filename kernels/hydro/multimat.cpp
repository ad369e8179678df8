// The multi-material pieces of the cycle (DESIGN.md §4 items 2, 4, 7): per-material EOS and
// mixture closure, the equal-strain Lagrangian update of mixed cells, and the remap of the
// material volumes, masses and energies by Youngs' PLIC with onion skin ordering. Every kernel
// here runs on both layouts through MaterialState's accessors and the same point functions.
//
// Mixture rules (documented in docs/numerics.md):
//  - equal strain: every material of a cell takes the cell's relative volume change, so
//    rho_m' = rho_m V / V' and e_m' = e_m - (p_m + q) dV / (rho_m V);
//  - cell pressure p = sum alpha_m p_m (volume-fraction weighted, as in PAGOSA);
//  - cell sound speed from rho c^2 = sum alpha_m rho_m c_m^2, the stiffness of the equal-strain
//    mixture (dp/d(ln rho) at fixed strain sharing); a pure cell keeps its material's c.
#include "core/axis.hpp"
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/point.hpp"
#include "hydro/relax.hpp"
#include "remap/plic.hpp"

namespace mp::hydro {

using mat::kMaxMaterials;
using mat::MatRef;

namespace {

// The whole block, ghosts included.
std::array<int, 3> all_hi(const Mesh& m) {
  return {m.extent(Centering::Cell, 0), m.extent(Centering::Cell, 1), m.extent(Centering::Cell, 2)};
}
std::array<int, 3> all_lo() {
  return {0, 0, 0};
}

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

// Stores the per-material fluxes of one face computed from its donor.
KOKKOS_INLINE_FUNCTION void store_face(const mat::DenseDev& d, int fi, int fj, int fk, int, int,
                                       int, int, const Real* V, const Real* M, const Real* E) {
  for (int m = 0; m < d.nmat; ++m) {
    d.fv(m, fi, fj, fk) = V[m];
    d.fm(m, fi, fj, fk) = M[m];
    d.fe(m, fi, fj, fk) = E[m];
  }
}

KOKKOS_INLINE_FUNCTION void store_face(const mat::CompactDev& d, int, int, int, int di, int dj,
                                       int dk, int side, const Real* V, const Real* M,
                                       const Real* E) {
  if (d.mat(di, dj, dk) >= 0) return;  // a pure donor's flux is the face total
  const int f = d.first(di, dj, dk), n = d.nm(di, dj, dk);
  for (int q = f; q < f + n; ++q) {
    const int m = d.smat(q);
    d.sfv[side](q) = V[m];
    d.sfm[side](q) = M[m];
    d.sfe[side](q) = E[m];
  }
}

KOKKOS_INLINE_FUNCTION int read_donor(const mat::DenseDev& d, const Field3&, const Field3&, int i,
                                      int j, int k, Real* a, Real* r, Real* e) {
  return mat::read_cell(d, i, j, k, a, r, e);
}
KOKKOS_INLINE_FUNCTION int read_donor(const mat::CompactDev& d, const Field3& rho, const Field3& en,
                                      int i, int j, int k, Real* a, Real* r, Real* e) {
  return mat::read_cell(d, rho, en, i, j, k, a, r, e);
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

// Per-material volume, mass and energy fluxes through one face from its donor: a pure donor
// uses the single-material van Leer face values (second order inside a material); a mixed
// donor splits the volume flux by PLIC onion skin and carries the donor's material density
// and energy (first order at interfaces).
// (The sweep's axis D is a template parameter, as RemapSource's.)
template <class Dev, int D>
struct FaceFluxes {
  static constexpr int d = D;
  Dev dev;
  Field3 rho, e, pre, vf, mf, ef;
  int nmat, order;
  Interface iface;
  Real dx, dy, dz;
  // module carriers (hydro.hpp): the summed mass flux of the materials of each mask
  int nc;
  unsigned cmask[kMaxCarriers];
  Field3 cflux[kMaxCarriers];

  // A mixed donor's face: the volume, mass and energy each material takes through it, into
  // V, M, E, and their sums into mf, ef. Entries c < nm are materials mat_of(c) in ascending
  // order (every material, or the donor's slots), with fractions a, densities r and energies
  // en; count of them are present.
  template <class MatOf>
  KOKKOS_INLINE_FUNCTION void mixed_face(int i, int j, int k, int di, int dj, int dk, Real f,
                                         int nm, int count, const MatOf& mat_of, const Real* a,
                                         const Real* r, const Real* en, Real* V, Real* M,
                                         Real* E) const {
    const int sx = d == 0, sy = d == 1, sz = d == 2;
    const Real pd = pre(di, dj, dk);
    // Onion skin (plic::onion_volumes): the plane normal of each layer but the last (which
    // takes what is left), from the cumulative fractions around the donor
    auto normal = [&](int entry, Real* n) {
      const int m = mat_of(entry);
      n[0] = n[1] = n[2] = 0;
      if (iface == Interface::Youngs) {
        Real st3[3][3][3];
        for (int c = 0; c < 3; ++c)
          for (int b = 0; b < 3; ++b)
            for (int q = 0; q < 3; ++q)
              st3[q][b][c] = mat::cumulative_fraction(dev, di - 1 + q, dj - 1 + b, dk - 1 + c, m);
        plic::youngs_normal(st3, dx, dy, dz, n);
      } else if (iface == Interface::Slic) {
        const Real g = mat::cumulative_fraction(dev, di + sx, dj + sy, dk + sz, m) -
                       mat::cumulative_fraction(dev, di - sx, dj - sy, dk - sz, m);
        n[d] = g > 0 ? Real(-1) : g < 0 ? Real(1) : Real(0);
      }
    };
    Real vm[kMaxMaterials];
    // A face with no volume flux (f == +-0: a flow at rest, or along another axis) moves no
    // material: onion_volumes clamps every layer to [0, |f|] and gives +0 to each, whatever
    // the normals, and limit_pair only scales down. The same +0s without the reconstruction
    // (the normals' 27 cumulative fractions per layer), bit for bit.
    const bool none = f == 0;
    if (none)
      for (int m = 0; m < nm; ++m) vm[m] = 0;
    else
      plic::onion_volumes(nm, count, a, normal, pd, dx, dy, dz, d, f, vm);
    // the donor's other face along d: where it empties through it too, the pair takes no
    // more of a material than the donor holds (plic::limit_pair; the normals computed again,
    // as this is rare)
    const int oi = f > 0 ? di : di + sx, oj = f > 0 ? dj : dj + sy, ok = f > 0 ? dk : dk + sz;
    const Real fo = vf(oi, oj, ok);
    if (!none && (f > 0 ? fo < 0 : fo > 0)) {
      Real vo[kMaxMaterials];
      plic::onion_volumes(nm, count, a, normal, pd, dx, dy, dz, d, fo, vo);
      plic::limit_pair(nm, a, pd, vm, vo);
    }
    Real mtot = 0, etot = 0;
    for (int m = 0; m < nm; ++m) {
      if (!(a[m] > 0)) continue;
      const Real sv = f > 0 ? vm[m] : -vm[m];
      V[m] = sv;
      M[m] = sv * r[m];
      E[m] = M[m] * en[m];
      mtot += M[m];
      etot += E[m];
    }
    mf(i, j, k) = mtot;
    ef(i, j, k) = etot;
  }

  // (force-inlined: past GCC's size limits the loop called it once per face; inlined, the
  // compact layout's remap::material_flux takes about 10 % less, 1.23 -> 1.08 ms per cycle on
  // the layout study's 2-material, 1 %-mixed block, 1.63 -> 1.50 at 5 %)
  KOKKOS_FORCEINLINE_FUNCTION void operator()(int i, int j, int k) const {
    const int sx = d == 0, sy = d == 1, sz = d == 2;
    const Real f = vf(i, j, k);
    const int dn = f > 0 ? -1 : 0;
    const int st = f > 0 ? 1 : -1;
    const int di = i + dn * sx, dj = j + dn * sy, dk = k + dn * sz;
    const int ui = di - st * sx, uj = dj - st * sy, uk = dk - st * sz;
    const int wi = di + st * sx, wj = dj + st * sy, wk = dk + st * sz;
    const int side = f > 0 ? 1 : 0;
    if constexpr (std::is_same_v<Dev, mat::CompactDev>) {
      // A pure donor (most faces): the branch below for one material, without its nmat-long
      // arrays (store_face keeps nothing for a pure donor); the same operations, bit for bit.
      const int m0 = dev.mat(di, dj, dk);
      if (m0 >= 0) {
        const bool smooth = mat::pure_of(dev, ui, uj, uk, m0) && mat::pure_of(dev, wi, wj, wk, m0);
        Real Mm = 0, Em = 0;
        donor_flux(f, pre(di, dj, dk), rho(ui, uj, uk), rho(di, dj, dk), rho(wi, wj, wk),
                   e(ui, uj, uk), e(di, dj, dk), e(wi, wj, wk), smooth ? order : 1, Mm, Em);
        mf(i, j, k) = Mm;
        ef(i, j, k) = Em;
        for (int c = 0; c < nc; ++c)
          cflux[c](i, j, k) = ((cmask[c] >> m0) & 1u) ? Real(0) + Mm : Real(0);
        return;
      }
      // A mixed donor: the branch below over its slots (its materials, ascending) as entries,
      // without nmat-long arrays; the same operations on the same values in the same order
      // (an absent material's zeros add +0 to the carriers' sums there).
      const int q0 = dev.first(di, dj, dk), cnt = dev.nm(di, dj, dk);
      Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
      Real V[kMaxMaterials], M[kMaxMaterials], E[kMaxMaterials];
      for (int c = 0; c < cnt; ++c) {
        a[c] = dev.salpha(q0 + c);
        r[c] = dev.srho(q0 + c);
        en[c] = dev.se(q0 + c);
        V[c] = M[c] = E[c] = 0;
      }
      const auto slot_mat = [&](int c) { return int(dev.smat(q0 + c)); };
      mixed_face(i, j, k, di, dj, dk, f, cnt, cnt, slot_mat, a, r, en, V, M, E);
      for (int c = 0; c < cnt; ++c) {
        dev.sfv[side](q0 + c) = V[c];
        dev.sfm[side](q0 + c) = M[c];
        dev.sfe[side](q0 + c) = E[c];
      }
      for (int x = 0; x < nc; ++x) {
        Real sum = 0;
        for (int c = 0; c < cnt; ++c)
          if ((cmask[x] >> slot_mat(c)) & 1u) sum += M[c];
        cflux[x](i, j, k) = sum;
      }
      return;
    }
    Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
    const int count = read_donor(dev, rho, e, di, dj, dk, a, r, en);
    Real V[kMaxMaterials], M[kMaxMaterials], E[kMaxMaterials];
    for (int m = 0; m < nmat; ++m) V[m] = M[m] = E[m] = 0;
    const Real pd = pre(di, dj, dk);
    if (count == 1) {
      int m0 = 0;
      for (int m = 0; m < nmat; ++m)
        if (a[m] > 0) m0 = m;
      const bool smooth = mat::pure_of(dev, ui, uj, uk, m0) && mat::pure_of(dev, wi, wj, wk, m0);
      donor_flux(f, pd, rho(ui, uj, uk), rho(di, dj, dk), rho(wi, wj, wk), e(ui, uj, uk),
                 e(di, dj, dk), e(wi, wj, wk), smooth ? order : 1, M[m0], E[m0]);
      V[m0] = f;
      mf(i, j, k) = M[m0];
      ef(i, j, k) = E[m0];
    } else {
      mixed_face(
          i, j, k, di, dj, dk, f, nmat, count, [](int m) { return m; }, a, r, en, V, M, E);
    }
    store_face(dev, i, j, k, di, dj, dk, side, V, M, E);
    for (int c = 0; c < nc; ++c) {
      Real sum = 0;
      for (int m = 0; m < nmat; ++m)
        if ((cmask[c] >> m) & 1u) sum += M[m];
      cflux[c](i, j, k) = sum;
    }
  }

  // The compact layout a k-column at a time (issue #15; core/columns.hpp): every face of the
  // column as if its donor were pure (the fast path above, its stencil selected from the four
  // cells along d as remap::cell_flux does), then the faces whose donor is mixed again through
  // operator() (which overwrites what the first loop wrote for them). GCC vectorizes the first
  // loop in some of its instantiations and leaves it scalar ("control flow") in others; either
  // way plain column offsets replace the MDRange's per-point view indexing. (On a GPU backend
  // it runs per face and computes a pure flux for a mixed donor too before operator(): more
  // work per face there than the plain launch; not measured.)
  KOKKOS_INLINE_FUNCTION void column(int i, int j, int k0, int k1) const {
    if constexpr (std::is_same_v<Dev, mat::CompactDev>) {
      constexpr int sx = d == 0, sy = d == 1, sz = d == 2;
      // (one type per declaration: the int and Real accessors differ)
      const auto mt = local(dev.mat);
      const auto v = local(vf), pa = local(pre), ra = local(rho), ea = local(e), mfa = local(mf),
                 efa = local(ef);
      // The ids of the four cells around every face of the column (an int loop of its own,
      // which vectorizes): `diff` is 0 where they are all one material, and `ids` < 0 where one
      // of them is mixed. A column of one pure material (most of them) takes the
      // single-material loop: every face smooth, no first-order flux to select from, no id
      // loads; the same bits as the general loop's selects give there.
      int diff = 0, ids = 0;
      for (int k = k0; k < k1; ++k) {
        auto at = [&](int o) { return mt(i + o * sx, j + o * sy, k + o * sz); };
        const int m2 = at(-2), m1 = at(-1), m0 = at(0), p1 = at(1);
        diff |= (m2 ^ m1) | (m1 ^ m0) | (m0 ^ p1);
        ids |= m1 | m0;  // (the faces' possible donors)
      }
      const bool uniform = diff == 0 && ids >= 0;
      // (the advection order a template argument: as a loop-invariant select GCC left the loop
      // scalar, "unsupported use in stmt"; so is `uniform`)
      auto faces = [&](auto ord, auto one) {
        constexpr int Ord = decltype(ord)::value;
        constexpr bool One = decltype(one)::value;
#pragma GCC ivdep
        for (int k = k0; k < k1; ++k) {
          const Real f = v(i, j, k);
          auto at = [&](const auto& a, int o) { return a(i + o * sx, j + o * sy, k + o * sz); };
          Real Mm, Em;
          column_face_flux(f, at, ra, ea, pa, Ord, Mm, Em);
          if constexpr (Ord != 1 && !One) {
            const bool pos = f > 0;
            // (the ids as Real, exact: tests of one width with the wind's, which GCC
            // vectorizes; int tests beside a Real one it did not, "unsupported use in stmt")
            const Real nm2 = at(mt, -2), nm1 = at(mt, -1), n0 = at(mt, 0), n1 = at(mt, 1);
            // (pure_of of the up- and downwind cells, for either wind; the donor's own test is
            // the last loop's)
            const bool smooth = pos ? (nm2 == nm1) & (n0 == nm1) : (n1 == n0) & (nm1 == n0);
            // (both orders found and one selected: a per-face order left the loop scalar; the
            // first-order values are donor_flux's for order 1, bit for bit)
            Real M1, E1;
            column_face_flux(f, at, ra, ea, pa, 1, M1, E1);
            Mm = smooth ? Mm : M1;
            Em = smooth ? Em : E1;
          }
          mfa(i, j, k) = Mm;
          efa(i, j, k) = Em;
        }
      };
      auto with_order = [&](auto one) {
        if (order == 2)
          faces(std::integral_constant<int, 2>{}, one);
        else
          faces(std::integral_constant<int, 1>{}, one);
      };
      if (uniform)
        with_order(std::true_type{});
      else
        with_order(std::false_type{});
      for (int c = 0; c < nc; ++c) {
        const auto cf = local(cflux[c]);
        const unsigned mask = cmask[c];
        for (int k = k0; k < k1; ++k) {
          const int md = v(i, j, k) > 0 ? mt(i - sx, j - sy, k - sz) : mt(i, j, k);
          cf(i, j, k) = md >= 0 && ((mask >> md) & 1u) ? Real(0) + mfa(i, j, k) : Real(0);
        }
      }
      // a column whose possible donors are all pure skips the loop below
      if (ids < 0)
        for (int k = k0; k < k1; ++k) {
          const int md = v(i, j, k) > 0 ? mt(i - sx, j - sy, k - sz) : mt(i, j, k);
          if (md < 0) (*this)(i, j, k);
        }
    } else {
      for (int k = k0; k < k1; ++k) (*this)(i, j, k);
    }
  }
};

}  // namespace

namespace {

// The burn fraction of a multi-material scene's explosive (burn.hpp: p = F P_products), or no
// explosive (material -1).
struct BurnHook {
  int material = -1;
  Field3 f;
  Real d_cj = 0;
  // with an unreacted EOS: p = (1 - F) P_u(rho, e - e0) + F P(rho, e) (burn.hpp)
  bool mixed = false;
  eos::Eos unreacted;
  Real e0 = 0;
};

// The viscous work W of a mixed cell (point.hpp viscous_work: the tensor viscosity's work
// over the step) goes to its materials in proportion to their mass (the same specific energy
// to each: -W / (rho_cell V)), not by equal strain, which would give each material W / (rho_m V)
// and so heat (or, where the cell expands along one axis while compressed along another, cool) a
// light material in a heavy one's shock by the density ratio: air beside copper went to
// negative energy in a cycle. A material then takes W rho_m / rho_cell as the viscous term of
// pdv_energy; a pure cell takes W itself. The predictor finds W from the start-of-step
// velocities; the corrector reads the cell's from the face launch (s_.qw, written by
// lagrange::volume_flux). docs/numerics.md, "Mixed cells".
// (mat::holds_several tells the two apart.)

BurnHook burn_hook(const burn::Burn* b) {
  if (!b) return {};
  return {b->material(), b->fraction(), b->params().d_cj, b->mixed(), b->unreacted(), b->e0()};
}

// The for_cells bodies of the multi-material kernels below (functors at namespace scope, not
// generic extended lambdas, which nvcc rejects inside for_cells' own lambdas).

// eos::pressure_sound_speed (Hydro::mm_equation_of_state)
struct MixedEos {
  mat::MaterialSet mats;
  BurnHook bh;
  Field3 p, c, rho;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    Real psum = 0, k2 = 0, plast = 0, clast = 0;
    int n = 0;
    bool unburnt = false;
    for (int s = 0; s < cell.count(); ++s) {
      const MatRef m = cell.get(s);
      if (!(m.alpha > 0)) continue;
      Real pm, cm;
      if (bh.mixed && m.m == bh.material) {
        const Real f = bh.f(i, j, k);
        pm = burn::he_pressure_mixed_cut(bh.unreacted, mats.eos[m.m], bh.e0, f, *m.rho, *m.e);
        cm = burn::he_sound_speed_mixed(bh.unreacted, mats.eos[m.m], bh.e0, f, *m.rho, *m.e);
        unburnt = f < 1;
      } else {
        pm = mats.eos[m.m].pressure_cut(*m.rho, *m.e);
        cm = mats.eos[m.m].sound_speed_cut(*m.rho, *m.e);
        if (m.m == bh.material) {
          const Real f = bh.f(i, j, k);
          pm *= f;
          unburnt = f < 1;
        }
      }
      *m.p = pm;
      psum += m.alpha * pm;
      k2 += m.alpha * *m.rho * cm * cm;
      plast = pm;
      clast = cm;
      ++n;
    }
    if (n == 1) {
      p(i, j, k) = plast;
      c(i, j, k) = clast;
    } else {
      p(i, j, k) = psum;
      c(i, j, k) = msqrt(k2 / rho(i, j, k));
    }
    // the programmed front crosses at most a cell per step
    if (unburnt) c(i, j, k) = mmax(c(i, j, k), bh.d_cj);
  }
};

// lagrange::predictor (Hydro::mm_predictor)
struct MixedPredictor {
  mat::MaterialSet mats;
  BurnHook bh;
  Sym6At<Field3> Q;
  Field3 ph, rho;
  Field3 u, v, w;
  Real ax, ay, az;
  Real vol;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    const CellFaceFluxes f = cell_face_fluxes(u, v, w, i, j, k, ax, ay, az);
    const Real dv = f.net();
    const Real v_half = vol + dv;
    Real sum = 0, last = 0;
    int n = 0;
    const bool several = mat::holds_several(cell);
    const Real wq = viscous_work(Q(i, j, k), f.xh - f.xl, f.yh - f.yl, f.zh - f.zl, u, v, w, i, j,
                                 k, ax, ay, az);
    const Real ws = wq / rho(i, j, k);
    for (int s = 0; s < cell.count(); ++s) {
      const MatRef m = cell.get(s);
      if (!(m.alpha > 0)) continue;
      const Real mass = *m.rho * vol;
      const Real e_half = pdv_energy(*m.e, *m.p, dv, several ? ws * *m.rho : wq, mass);
      Real pm;
      if (bh.mixed && m.m == bh.material) {
        pm = burn::he_pressure_mixed_cut(bh.unreacted, mats.eos[m.m], bh.e0, bh.f(i, j, k),
                                         mass / v_half, e_half);
      } else {
        pm = mats.eos[m.m].pressure_cut(mass / v_half, e_half);
        if (m.m == bh.material) pm *= bh.f(i, j, k);
      }
      *m.ph = pm;
      sum += m.alpha * pm;
      last = pm;
      ++n;
    }
    ph(i, j, k) = n == 1 ? last : sum;
  }
};

// lagrange::corrector (Hydro::mm_corrector)
struct MixedCorrector {
  mat::MaterialSet mats;
  bool relax;
  int iters;
  Real tol, fmin, sfloor;
  BurnHook bh;
  Field3 qw, rho, e;
  Field3 fx, fy, fz;
  Real vol;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    const Real dv = net_volume_flux(fx, fy, fz, i, j, k);
    const Real vnew = vol + dv;
    // equal strain: every material takes the cell's relative volume change
    int slot[kMaxMaterials], id[kMaxMaterials];
    Real mv[kMaxMaterials], mm[kMaxMaterials], me[kMaxMaterials], pm[kMaxMaterials];
    int n = 0;
    const bool several = mat::holds_several(cell);
    const Real wq = qw(i, j, k), ws = wq / rho(i, j, k);
    for (int s = 0; s < cell.count(); ++s) {
      const MatRef m = cell.get(s);
      if (!(m.alpha > 0)) continue;
      const Real mass = *m.rho * vol;
      *m.e = pdv_energy(*m.e, *m.ph, dv, several ? ws * *m.rho : wq, mass);
      *m.rho = mass / vnew;
      slot[n] = s;
      id[n] = m.m;
      mv[n] = m.alpha * vnew;
      mm[n] = *m.rho * mv[n];
      me[n] = *m.e;
      ++n;
    }
    if (relax && n > 1) {
      // each material at its own EOS; an explosive at its burn closure, frozen F (its
      // pressure as the EOS kernel forms it, without the tension cutoffs, as for the others)
      const auto pc = [&](int s, Real r, Real en, Real& ps, Real& c2) {
        const eos::Eos& eq = mats.eos[id[s]];
        if (id[s] != bh.material) {
          ps = eq.pressure(r, en);
          c2 = eq.sound_speed2(r, en);
        } else if (bh.mixed) {
          const Real f = bh.f(i, j, k);
          ps = burn::he_pressure_mixed(bh.unreacted, eq, bh.e0, f, r, en);
          c2 = burn::he_sound_speed2_mixed(bh.unreacted, eq, bh.e0, f, r, en);
        } else {
          const Real f = bh.f(i, j, k);
          ps = burn::he_pressure(eq, f, r, en);
          c2 = burn::he_sound_speed2(eq, f, r, en);
        }
      };
      relax_pressures_with(n, pc, mv, mm, me, pm, iters, tol, fmin * vnew);
    }
    bool moved = relax && n > 1;
    if (sfloor > 0 && n > 1) moved = solid_floor(n, mats.eos, id, mv, mm, me, sfloor) || moved;
    if (moved) {
      Real vsum = 0;
      for (int s = 0; s < n; ++s) vsum += mv[s];
      for (int s = 0; s < n; ++s) {
        const MatRef m = cell.get(slot[s]);
        cell.set_alpha(slot[s], mv[s] / vsum);
        *m.rho = mm[s] / mv[s];
        *m.e = me[s];
      }
    }
    if (cell.aliases() || n == 0) return;
    if (n == 1) {
      const MatRef m = cell.get(slot[0]);
      rho(i, j, k) = *m.rho;
      e(i, j, k) = *m.e;
      return;
    }
    Real rsum = 0, esum = 0;
    for (int s = 0; s < n; ++s) {
      const MatRef m = cell.get(slot[s]);
      rsum += m.alpha * *m.rho;
      esum += m.alpha * *m.rho * *m.e;
    }
    rho(i, j, k) = rsum;
    e(i, j, k) = esum / rsum;
  }
};

// remap::ke_fix (Hydro::mm_ke_fix)
struct MixedKeFix {
  Field3 kel, rho, e, post;
  bool by_mass;
  Kokkos::View<double, MemSpace> unpaid;  // State::ke_unpaid

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    // kel: each node's loss per unit mass of its 8 cells (remap.cpp, by_mass), so the cell
    // takes the sum over its corners as specific energy; or (equal shares) the node's loss,
    // of which the cell takes an eighth. The same specific energy to every material keeps
    // the cell average consistent; where it is taken away (< 0), no material gives more
    // than ke_fix_floor allows
    const Real sum = corner_sum(kel, i, j, k);
    const Real share = by_mass ? sum : Real(0.125) * sum / (rho(i, j, k) * post(i, j, k));
    Real de = share;
    for (int s = 0; s < cell.count(); ++s) {
      const MatRef m = cell.get(s);
      if (m.alpha > 0) de = mmax(de, ke_fix_floor(*m.e));
    }
    // what the floor left unpaid (every material takes de, the cell's mass rho post in all)
    add_unpaid(unpaid, rho(i, j, k) * post(i, j, k) * (de - share));
    for (int s = 0; s < cell.count(); ++s) {
      const MatRef m = cell.get(s);
      if (m.alpha > 0) *m.e += de;
    }
    if (!cell.aliases()) e(i, j, k) += de;
  }
};

// The pure cells of the compact layout as k-columns (issue #15). for_cells runs them through
// the same functors as the mixed cells, one MDRange point at a time with the EOS kind switched
// per point; GCC leaves that scalar, and it cost the compact cycle as much as the single-material
// cycle's whole Lagrange step. The bodies below are those functors' arithmetic for a PureCell,
// operand for operand (so the fields are the same bits): a column is cut into runs of one pure
// material (a mixed cell joins the run it is in: its values are computed with the run's
// material from its cell averages and stored, and the [mixed] launch after overwrites them:
// MixedEos and MixedPredictor write every mixed cell's p, c and ph), each run's EOS record is
// read once and its kind is a template argument, so the loop over a run is the single-material
// loop (GCC vectorizes it; gathering the record per cell kept it scalar, 4x the
// single-material predictor's time; so did a select that stored only the pure cells' values,
// beside the EOS's own selects: the ideal-gas predictor ran scalar, 2.2x the single-material
// one's profile samples). An explosive with an unreacted EOS (BurnHook::mixed) keeps the
// per-point functors.

// body.template run<K>(i, j, ka, kb, m) for each run [ka, kb) of the column's cells whose pure
// cells are all material m, of kind K (body: a PureEos or PurePredictor, whose material ids and
// EosTable it reads). Where materials alternate cell by cell a run is a cell.
template <class Body>
struct PureColumns {
  Body body;

  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    const auto mt = local(body.mat);
    const int* kinds = body.tab.kind;
    int k = k0;
    while (k < k1) {
      int m = mt(i, j, k);
      if (m < 0) {  // a mixed cell before any pure one: nothing to store
        ++k;
        continue;
      }
      int kb = k + 1;
      while (kb < k1) {
        const int n = mt(i, j, kb);
        if (n >= 0 && n != m) break;
        ++kb;
      }
      eos::run_kind(kinds[m], body, i, j, k, kb, m);
      k = kb;
    }
  }
};

// The materials' EOS records as arrays over the materials: at<K>(m) is material m's record as
// far as kind K reads it (its parameters, p_min, rho_void), read once per run of a column.
// (Copying the whole record from the MaterialSet instead made the pure predictor slower: 650
// -> 880 profile samples on the 16-material stripes, 1 thread, tried 2026-12-04.)
struct EosTable {
  int kind[kMaxMaterials];
  Real par[eos::Eos::max_params][kMaxMaterials];
  Real p_min[kMaxMaterials], rho_void[kMaxMaterials];

  explicit EosTable(const mat::MaterialSet& mats) {
    for (int m = 0; m < kMaxMaterials; ++m) {
      const eos::Eos& e = mats.eos[m < mats.n ? m : 0];
      kind[m] = e.kind;
      for (int q = 0; q < eos::Eos::max_params; ++q) par[q][m] = e.params[q];
      p_min[m] = e.p_min;
      rho_void[m] = e.rho_void;
    }
  }
  // the number of parameters kind K reads (all for K = -1, any kind)
  template <int K>
  static constexpr int params() {
    return K == eos::kIdealGas       ? 1
           : K == eos::kStiffenedGas ? 2
           : K == eos::kMieGruneisen ? 4
           : K < 0                   ? eos::Eos::max_params
                                     : 6;
  }
  template <int K>
  KOKKOS_INLINE_FUNCTION eos::Eos at(int m) const {
    eos::Eos e;
    e.kind = K < 0 ? kind[m] : K;
    for (int q = 0; q < params<K>(); ++q) e.params[q] = par[q][m];
    e.p_min = p_min[m];
    e.rho_void = rho_void[m];
    return e;
  }
};

// MixedEos for the pure cells. Burn: the explosive (material bm) scales p by its burn fraction.
template <bool Burn>
struct PureEos {
  EosTable tab;
  IntField3 mat;
  Field3 rho, e, p, c, bf;
  int bm;
  Real d_cj;
  template <int K>
  KOKKOS_INLINE_FUNCTION void run(int i, int j, int k0, int k1, int mr) const {
    const auto r = local(rho), en = local(e), pa = local(p), ca = local(c), f = local(bf);
    const bool he = mr == bm;
    const Real dcj = d_cj;
    const eos::Eos eq = tab.template at<K>(mr);
#pragma GCC ivdep
    for (int k = k0; k < k1; ++k) {
      const Real rv = r(i, j, k), ev = en(i, j, k);
      Real pm = eq.template pressure_cut<K>(rv, ev);
      Real cm = eq.template sound_speed_cut<K>(rv, ev);
      if constexpr (Burn) {
        const Real fv = f(i, j, k);
        pm = he ? pm * fv : pm;
        cm = he && fv < 1 ? mmax(cm, dcj) : cm;
      }
      pa(i, j, k) = pm;
      ca(i, j, k) = cm;
    }
  }
};

// MixedPredictor for the pure cells.
template <bool Burn>
struct PurePredictor {
  EosTable tab;
  IntField3 mat;
  Field3 u, v, w, rho, e, p;
  std::array<Field3, 6> qt;
  Kokkos::View<int**, MemSpace> qcol;  // (columns without a viscous stress: no viscous work)
  Field3 ph, bf;
  Real ax, ay, az, vol;
  int bm;
  template <int K>
  KOKKOS_INLINE_FUNCTION void run(int i, int j, int k0, int k1, int mr) const {
    const auto U = local(u), V = local(v), W = local(w), r = local(rho), en = local(e),
               pa = local(p), out = local(ph), f = local(bf);
    const auto Q = sym6_local(qt[0], qt[1], qt[2], qt[3], qt[4], qt[5]);
    const Real fx = ax, fy = ay, fz = az, v0 = vol;
    const bool he = mr == bm;
    const eos::Eos eq = tab.template at<K>(mr);
    const auto loop = [&](auto stress) {
#pragma GCC ivdep
      for (int k = k0; k < k1; ++k) {
        const CellFaceFluxes ff = cell_face_fluxes(U, V, W, i, j, k, fx, fy, fz);
        const Real dv = ff.net();
        const Real v_half = v0 + dv;
        const Real mass = r(i, j, k) * v0;
        Real wq = 0;
        if constexpr (decltype(stress)::value)
          wq = viscous_work(Q(i, j, k), ff.xh - ff.xl, ff.yh - ff.yl, ff.zh - ff.zl, U, V, W, i, j,
                            k, fx, fy, fz);
        const Real e_half = pdv_energy(en(i, j, k), pa(i, j, k), dv, wq, mass);
        Real pm = eq.template pressure_cut<K>(mass / v_half, e_half);
        if constexpr (Burn) {
          const Real fv = f(i, j, k);
          pm = he ? pm * fv : pm;
        }
        out(i, j, k) = pm;
      }
    };
    if (qcol(i, j))
      loop(std::true_type{});
    else
      loop(std::false_type{});
  }
};

// MixedCorrector for the pure cells (one material: no relaxation, no solid floor; the EOS is
// not called, so the column runs as K = -1 whatever the kinds).
struct PureCorrector {
  IntField3 mat;
  Field3 qw, rho, e, ph, fx, fy, fz;
  Real vol;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    const auto mt = local(mat);
    const auto qa = local(qw), r = local(rho), en = local(e), pha = local(ph), X = local(fx),
               Y = local(fy), Z = local(fz);
    const Real v0 = vol;
#pragma GCC ivdep
    for (int k = k0; k < k1; ++k) {
      const bool pure = mt(i, j, k) >= 0;
      const Real dv = net_volume_flux(X, Y, Z, i, j, k);
      const Real vnew = v0 + dv;
      const Real r0 = r(i, j, k), e0 = en(i, j, k);
      const Real mass = r0 * v0;
      const Real e1 = pdv_energy(e0, pha(i, j, k), dv, qa(i, j, k), mass);
      en(i, j, k) = select_bits(pure, e1, e0);
      r(i, j, k) = select_bits(pure, mass / vnew, r0);
    }
  }
};

// MixedKeFix for the pure cells.
template <bool ByMass>
struct PureKeFix {
  static constexpr bool by_mass = ByMass;
  IntField3 mat;
  Field3 kel, rho, e, post;
  Kokkos::View<double, MemSpace> unpaid;  // State::ke_unpaid
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    const auto mt = local(mat);
    const auto kl = local(kel), r = local(rho), en = local(e), p1 = local(post);
    Real owed = 0;
#pragma omp simd reduction(+ : owed)
    for (int k = k0; k < k1; ++k) {
      const Real sum = corner_sum(kl, i, j, k);
      Real share;
      if constexpr (ByMass)
        share = sum;
      else
        share = Real(0.125) * sum / (r(i, j, k) * p1(i, j, k));
      const Real e0 = en(i, j, k);
      const Real de = mmax(share, ke_fix_floor(e0));
      const bool pure = mt(i, j, k) >= 0;
      en(i, j, k) = select_bits(pure, e0 + de, e0);
      owed += pure ? r(i, j, k) * p1(i, j, k) * (de - share) : Real(0);
    }
    add_unpaid(unpaid, owed);
  }
};

// PureKeFix on the owned cells of a column of every cell (ghosts included), then the next remap
// step's volumes of the whole column (stored_step_volumes, after the fix has read `post`): the
// next step's remap::volumes launch saved, as the single-material KE fix does.
template <bool ByMass>
struct PureKeFixAhead {
  PureKeFix<ByMass> fix;
  Field3 fx, fy, fz, pre;
  Real vol;
  StepWeights sw;
  int olo[3], ohi[3];
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    if (i >= olo[0] && i < ohi[0] && j >= olo[1] && j < ohi[1]) {
      int b, f;
      inner_run(k0, k1, olo[2], ohi[2], b, f);
      fix(i, j, b, f);
    }
    const auto a = local(fx), bb = local(fy), c = local(fz), p0 = local(pre), p1 = local(fix.post);
#pragma GCC ivdep
    for (int k = k0; k < k1; ++k) stored_step_volumes(a, bb, c, i, j, k, vol, sw, p0, p1);
  }
};

// for_cells(name, lo, hi, op), except on the compact layout without an unreacted explosive:
// there the pure cells as the k-columns of make(std::bool_constant<Burn>{}) (a PureEos or
// PurePredictor; Burn: the scene has an explosive), launched as name + "[pure]", then the mixed
// list through op.
template <class Op, class Make>
void with_pure_columns(const mat::MaterialState& mm, const BurnHook& bh, const std::string& name,
                       const std::array<int, 3>& lo, const std::array<int, 3>& hi, const Op& op,
                       const Make& make) {
  if (mm.kind() == mat::LayoutKind::Dense || bh.mixed) {
    mm.for_cells(name, lo, hi, op);
    return;
  }
  auto launch = [&](const auto& body) {
    using Body = std::decay_t<decltype(body)>;
    for_columns(name + "[pure]", lo.data(), hi.data(), PureColumns<Body>{body});
  };
  if (bh.material >= 0)
    launch(make(std::true_type{}));
  else
    launch(make(std::false_type{}));
  mm.for_mixed(name, lo, hi, op);
}

}  // namespace

void Hydro::mm_equation_of_state() const {
  const auto mats = mats_;
  auto p = s_.p, c = s_.c, rho = s_.rho, e = s_.e;
  const BurnHook bh = burn_hook(burn_.get());
  const Field3 bf = bh.material >= 0 ? bh.f : rho;  // (read only with a burn)
  const mat::MaterialState& mm = *mm_;
  with_pure_columns(mm, bh, "eos::pressure_sound_speed", all_lo(), all_hi(mesh_),
                    MixedEos{mats, bh, p, c, rho}, [&](auto burn) {
                      return PureEos<decltype(burn)::value>{
                          EosTable(mats), mm.compact().mat, rho, e, p, c, bf, bh.material, bh.d_cj};
                    });
}

void Hydro::mm_predictor(Real vol, const std::array<Real, 3>& f) {
  const auto mats = mats_;
  auto ph = s_.p_half, rho = s_.rho, e = s_.e, p = s_.p;
  const auto qt = s_.qt;
  const Sym6At<Field3> Q = sym6_view(qt[0], qt[1], qt[2], qt[3], qt[4], qt[5]);
  auto u = s_.u, v = s_.v, w = s_.w;
  const Real ax = f[0], ay = f[1], az = f[2];
  const BurnHook bh = burn_hook(burn_.get());
  const Field3 bf = bh.material >= 0 ? bh.f : rho;  // (read only with a burn)
  const mat::MaterialState& mm = *mm_;
  with_pure_columns(mm, bh, "lagrange::predictor", all_lo(), all_hi(mesh_),
                    MixedPredictor{mats, bh, Q, ph, rho, u, v, w, ax, ay, az, vol}, [&](auto burn) {
                      return PurePredictor<decltype(burn)::value>{EosTable(mats),
                                                                  mm.compact().mat,
                                                                  u,
                                                                  v,
                                                                  w,
                                                                  rho,
                                                                  e,
                                                                  p,
                                                                  qt,
                                                                  s_.qcol,
                                                                  ph,
                                                                  bf,
                                                                  ax,
                                                                  ay,
                                                                  az,
                                                                  vol,
                                                                  bh.material};
                    });
}

void Hydro::mm_corrector(Real vol) {
  const auto mats = mats_;
  const bool relax = opt_.relax;
  const int iters = opt_.relax_iterations;
  const Real tol = opt_.relax_tol;
  const Real fmin = opt_.min_fraction;
  const Real sfloor = opt_.solid_floor;
  const BurnHook bh = burn_hook(burn_.get());
  auto qw = s_.qw, rho = s_.rho, e = s_.e, ph = s_.p_half;
  auto fx = s_.vol_flux[0], fy = s_.vol_flux[1], fz = s_.vol_flux[2];
  const MixedCorrector op{mats, relax, iters, tol, fmin, sfloor, bh, qw, rho, e, fx, fy, fz, vol};
  const std::array<int, 3> lo = all_lo(), hi = all_hi(mesh_);
  if (mm_->kind() == mat::LayoutKind::Dense) {
    mm_->for_cells("lagrange::corrector", lo, hi, op);
    return;
  }
  for_columns("lagrange::corrector[pure]", lo.data(), hi.data(),
              PureCorrector{mm_->compact().mat, qw, rho, e, ph, fx, fy, fz, vol});
  mm_->for_mixed("lagrange::corrector", lo, hi, op);
}

namespace {

// The fields of sweep d that a FaceFluxes or a RemapSource reads (s: the hydro state).
template <class T, class Dev, class State>
void set_sweep_fields(T& t, const Dev& dev, const State& s, int d, int nmat) {
  t.dev = dev;
  t.rho = s.rho;
  t.e = s.e;
  t.pre = s.pre_vol;
  t.vf = s.vol_flux[d];
  t.mf = s.mass_flux[d];
  t.ef = s.energy_flux[d];
  t.nmat = nmat;
}

// ff.column(i, j, k0, k1) as a for_columns body (a functor, not an extended lambda: nvcc
// allows none inside the generic lambda with_axis calls).
template <class FF>
struct ColumnBody {
  FF ff;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    ff.column(i, j, k0, k1);
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
void Hydro::mm_face_fluxes(const Dev& dev, int d) {
  const Geometry g = mesh_.geometry();
  const int ng = Mesh::ng;
  const auto fr = mesh_.range(Centering::Node, Region::Owned, d);
  // faces of the owned cells along d; one ghost row across (the dual mesh reads it)
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = ng - 1;
    hi[a] = ng + mesh_.owned_cells(a) + 1;
  }
  lo[d] = fr[0];
  hi[d] = fr[1];
  const Policy3 faces({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]});
  auto fill = [&](auto& ff) {
    set_sweep_fields(ff, dev, s_, d, mats_.n);
    ff.order = opt_.order;
    ff.iface = opt_.interface;
    ff.dx = g.dx[0];
    ff.dy = g.dx[1];
    ff.dz = g.dx[2];
    ff.nc = ncarrier_;
    for (int c = 0; c < ncarrier_; ++c) {
      ff.cmask[c] = carrier_mask_[c];
      ff.cflux[c] = carrier_flux_[c];
    }
  };
  with_axis(d, [&](auto a) {
    FaceFluxes<Dev, decltype(a)::value> ff{};
    fill(ff);
    if constexpr (std::is_same_v<Dev, mat::CompactDev>)
      for_columns("remap::material_flux", lo, hi, ColumnBody<decltype(ff)>{ff});
    else
      Kokkos::parallel_for("remap::material_flux", faces, ff);
  });
}

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

void Hydro::mm_remap_faces(int d) {
  if (mm_->kind() == mat::LayoutKind::Dense)
    mm_face_fluxes(mm_->dense(), d);
  else
    mm_face_fluxes(mm_->compact(), d);
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
  for (int c = 0; c < ncarrier_; ++c) {
    ClearFields fs;
    if (c == burn_carrier_) {
      fs.f[fs.n++] = burn_->fraction();
    } else if (strength_->pooled()) {
      continue;  // (a pooled set holds nothing where its material is absent)
    } else {
      const strength::StressSet& st = strength_->set(c);
      for (const Field3& x : st.s) fs.f[fs.n++] = x;
      fs.f[fs.n++] = st.eps_p;
    }
    auto crho = carrier_rho_[c];
    mm_->carrier_density(carrier_mask_[c], crho);
    Kokkos::parallel_for(
        "remap::clear_absent", owned, KOKKOS_LAMBDA(int i, int j, int k) {
          if (crho(i, j, k) > 0) return;
          for (int q = 0; q < fs.n; ++q) fs.f[q](i, j, k) = 0;
        });
  }
}

Hydro::Carrier Hydro::carrier(int slot) const {
  if (!mm_) return {s_.mass_flux, s_.rho};
  const Field3 f = carrier_flux_[slot];
  return {{f, f, f}, carrier_rho_[slot]};
}

void Hydro::mm_ke_fix(const RemapStep* next) {
  auto kel = s_.ke_loss, rho = s_.rho, e = s_.e, post = s_.post_vol;
  const bool by_mass = opt_.ke_fix_by_mass;
  const int ng = Mesh::ng;
  const std::array<int, 3> lo{ng, ng, ng}, hi = mesh_.owned_end();
  const auto unpaid = s_.ke_unpaid;
  const MixedKeFix op{kel, rho, e, post, by_mass, unpaid};
  if (mm_->kind() == mat::LayoutKind::Dense) {
    mm_->for_cells("remap::ke_fix", lo, hi, op);
    return;
  }
  const IntField3 mt = mm_->compact().mat;
  // the mixed cells first: the pure launch may then write every cell's next volumes
  mm_->for_mixed("remap::ke_fix", lo, hi, op);
  auto launch = [&](auto fix) {
    if (!next) {
      for_columns("remap::ke_fix[pure]", lo.data(), hi.data(), fix);
      return;
    }
    PureKeFixAhead<decltype(fix)::by_mass> ahead{fix,
                                                 s_.vol_flux[0],
                                                 s_.vol_flux[1],
                                                 s_.vol_flux[2],
                                                 s_.pre_vol,
                                                 mesh_.geometry().cell_volume(),
                                                 next->weights(),
                                                 {lo[0], lo[1], lo[2]},
                                                 {hi[0], hi[1], hi[2]}};
    int alo[3], ahi[3];
    mesh_.box(Centering::Cell, Region::All, alo, ahi);
    for_columns("remap::ke_fix[pure]", alo, ahi, ahead);
    volumes_ready_ = true;
    volumes_for_ = *next;
  };
  if (by_mass)
    launch(PureKeFix<true>{mt, kel, rho, e, post, unpaid});
  else
    launch(PureKeFix<false>{mt, kel, rho, e, post, unpaid});
}

// Explicit instantiations for the layouts' device handles.
template void Hydro::mm_face_fluxes(const mat::DenseDev&, int);
template void Hydro::mm_face_fluxes(const mat::CompactDev&, int);
template void Hydro::mm_cell_update(const mat::DenseDev&, int);
template void Hydro::mm_cell_update(const mat::CompactDev&, int);

}  // namespace mp::hydro
