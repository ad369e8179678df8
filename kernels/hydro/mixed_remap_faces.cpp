// The multi-material remap's face fluxes (DESIGN.md §4 item 7): the volume, mass and energy
// each material takes through the faces of a sweep (Youngs' PLIC with onion skin ordering at
// a mixed donor), and the module carriers' mass fluxes.
#include "core/axis.hpp"
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/mixed_detail.hpp"
#include "hydro/point.hpp"
#include "remap/plic.hpp"

namespace mp::hydro {

using mat::kMaxMaterials;
using mixed_detail::read_donor;
using mixed_detail::set_sweep_fields;

namespace {

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
      if (iface == Interface::Youngs || iface == Interface::Elvira) {
        Real st3[3][3][3];
        for (int c = 0; c < 3; ++c)
          for (int b = 0; b < 3; ++b)
            for (int q = 0; q < 3; ++q)
              st3[q][b][c] = mat::cumulative_fraction(dev, di - 1 + q, dj - 1 + b, dk - 1 + c, m);
        if (iface == Interface::Youngs)
          plic::youngs_normal(st3, dx, dy, dz, n);
        else
          plic::elvira_normal(st3, dx, dy, dz, n);
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
  // Third: the third-order loops alone (a launch of their own, ColumnBody<FF, true>: two more
  // instantiations inside the second-order kernel made GCC inline its loops worse, +3.7 %
  // instructions along y on the triple point, callgrind).
  template <bool Third = false>
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
      if constexpr (Third) {
        if (uniform)
          faces(std::integral_constant<int, 3>{}, std::true_type{});
        else
          faces(std::integral_constant<int, 3>{}, std::false_type{});
      } else if (uniform) {
        with_order(std::true_type{});
      } else {
        with_order(std::false_type{});
      }
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

// ff.column(i, j, k0, k1) as a for_columns body (a functor, not an extended lambda: nvcc
// allows none inside the generic lambda with_axis calls).
template <class FF, bool Third = false>
struct ColumnBody {
  FF ff;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    ff.template column<Third>(i, j, k0, k1);
  }
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
    if constexpr (std::is_same_v<Dev, mat::CompactDev>) {
      if (opt_.order == 3)
        for_columns("remap::material_flux", lo, hi, ColumnBody<decltype(ff), true>{ff});
      else
        for_columns("remap::material_flux", lo, hi, ColumnBody<decltype(ff)>{ff});
    } else
      Kokkos::parallel_for("remap::material_flux", faces, ff);
  });
}

void Hydro::mm_remap_faces(int d) {
  if (mm_->kind() == mat::LayoutKind::Dense)
    mm_face_fluxes(mm_->dense(), d);
  else
    mm_face_fluxes(mm_->compact(), d);
}

// Explicit instantiations for the layouts' device handles.
template void Hydro::mm_face_fluxes(const mat::DenseDev&, int);
template void Hydro::mm_face_fluxes(const mat::CompactDev&, int);

}  // namespace mp::hydro
