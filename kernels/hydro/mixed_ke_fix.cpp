// The multi-material KE fix (Hydro::mm_ke_fix): the remap's kinetic-energy loss given to the
// materials' energies, the mixed cells per point and the compact layout's pure cells as
// k-columns (why k-columns: mixed_lagrange.cpp, above PureColumns).
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/point.hpp"

namespace mp::hydro {

using mat::MatRef;

namespace {

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

}  // namespace

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

}  // namespace mp::hydro
