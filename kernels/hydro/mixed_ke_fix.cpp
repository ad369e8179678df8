// The multi-material KE fix (Hydro::mm_ke_fix): the remap's kinetic-energy loss given to the
// materials' energies, the mixed cells per point and the compact layout's pure cells as
// k-columns (why k-columns: mixed_lagrange.cpp, above PureColumns).
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/mixed_detail.hpp"
#include "hydro/point.hpp"

namespace mp::hydro {

using mat::kMaxMaterials;
using mat::MatRef;

namespace {

// numerics.ke_fix_share: pressure. A node's positive loss L goes, by mass, to the materials of
// its 8 cells whose pressure is below half the highest material pressure among them (the
// materials the flow there is compressing: the gas an explosive's products drive), and by
// mass to all of them where none is (the `mass` rule); a negative loss as in `mass`. Per node:
// `low`, the specific energy a low material takes, `rest` the others', `pmax` the highest
// pressure (State::ke_low, ke_rest, ke_pmax). A material's test against each of its cell's
// nodes is the node's own test on the same values, so the 8 cells take exactly L.
struct PressureShares {
  Field3 low, rest, pmax;
  // the specific energy a material at pressure pm in cell (i, j, k) takes from its 8 nodes
  KOKKOS_INLINE_FUNCTION Real take(int i, int j, int k, Real pm) const {
    Real sum = 0;
    for (int c = 0; c < 2; ++c)
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          const int ni = i + a, nj = j + b, nk = k + c;
          sum += pm < Real(0.5) * pmax(ni, nj, nk) ? low(ni, nj, nk) : rest(ni, nj, nk);
        }
    return sum;
  }
};

// The node values of PressureShares from the node losses kel (per unit mass of the 8 cells,
// remap.cpp by_mass) and the cells' materials (their ghosts brought up to date first).
template <class Dev>
struct NodePressureShares {
  Dev dev;
  Field3 kel, rho, e, post;
  mat::MaterialSet mats;
  PressureShares out;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    Real pmax = 0, mass = 0, mlow = 0;
    Real pm[8][kMaxMaterials], mm[8][kMaxMaterials];
    for (int c = 0; c < 8; ++c) {
      const int ci = i - 1 + (c & 1), cj = j - 1 + ((c >> 1) & 1), ck = k - 1 + (c >> 2);
      Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
      mixed_detail::read_donor(dev, rho, e, ci, cj, ck, a, r, en);
      for (int m = 0; m < mats.n; ++m) {
        const bool here = a[m] > 0;
        pm[c][m] = here ? mats.eos[m].pressure(r[m], en[m]) : Real(0);
        mm[c][m] = here ? a[m] * r[m] * post(ci, cj, ck) : Real(0);
        if (here) pmax = mmax(pmax, pm[c][m]);
      }
    }
    for (int c = 0; c < 8; ++c)
      for (int m = 0; m < mats.n; ++m) {
        mass += mm[c][m];
        if (mm[c][m] > 0 && pm[c][m] < Real(0.5) * pmax) mlow += mm[c][m];
      }
    // kel L / (8 m_node): the loss is kel times the cells' mass
    const Real L = kel(i, j, k);
    const bool shift = L > 0 && mlow > 0;
    out.pmax(i, j, k) = pmax;
    out.low(i, j, k) = shift ? L * mass / mlow : L;
    out.rest(i, j, k) = shift ? Real(0) : L;
  }
};

// remap::ke_fix (Hydro::mm_ke_fix)
struct MixedKeFix {
  Field3 kel, rho, e, post;
  bool by_mass;
  Kokkos::View<double, MemSpace> unpaid;  // State::ke_unpaid
  bool by_pressure = false;               // (ke_fix_share: pressure)
  PressureShares shares;
  mat::MaterialSet mats;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    if (by_pressure) {
      // each material its own share (PressureShares), none giving more than ke_fix_floor
      Real gained = 0, owed = 0;
      for (int s = 0; s < cell.count(); ++s) {
        const MatRef m = cell.get(s);
        if (!(m.alpha > 0)) continue;
        const Real share = shares.take(i, j, k, mats.eos[m.m].pressure(*m.rho, *m.e));
        const Real de = mmax(share, ke_fix_floor(*m.e));
        const Real mass = m.alpha * *m.rho * post(i, j, k);
        owed += mass * (de - share);
        gained += mass * de;
        *m.e += de;
      }
      add_unpaid(unpaid, owed);
      if (!cell.aliases()) e(i, j, k) += gained / (rho(i, j, k) * post(i, j, k));
      return;
    }
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
// (ByPressure: ke_fix_share: pressure, the cell's material tested against each node's pmax)
template <bool ByMass, bool ByPressure = false>
struct PureKeFix {
  static constexpr bool by_mass = ByMass;
  static constexpr bool by_pressure = ByPressure;
  IntField3 mat;
  Field3 kel, rho, e, post;
  Kokkos::View<double, MemSpace> unpaid;  // State::ke_unpaid
  PressureShares shares;
  mat::MaterialSet mats;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    const auto mt = local(mat);
    const auto kl = local(kel), r = local(rho), en = local(e), p1 = local(post);
    if constexpr (ByPressure) {
      Real owed = 0;
      for (int k = k0; k < k1; ++k) {
        const int m = mt(i, j, k);
        if (m < 0) continue;
        const Real e0 = en(i, j, k);
        const Real share = shares.take(i, j, k, mats.eos[m].pressure(r(i, j, k), e0));
        const Real de = mmax(share, ke_fix_floor(e0));
        en(i, j, k) = e0 + de;
        owed += r(i, j, k) * p1(i, j, k) * (de - share);
      }
      add_unpaid(unpaid, owed);
      return;
    }
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
template <bool ByMass, bool ByPressure>
struct PureKeFixAhead {
  PureKeFix<ByMass, ByPressure> fix;
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
  MixedKeFix op{kel, rho, e, post, by_mass, unpaid, false, {}, {}};
  PressureShares shares;
  if (opt_.ke_fix_low_pressure) {
    // the node values read every material of the node's 8 cells: the ghosts' as this sweep left
    // them (the sweep's own exchange comes after the fix)
    mm_->exchange();
    shares = {s_.ke_low, s_.ke_rest, s_.ke_pmax};
    int nlo[3] = {1, 1, 1}, nhi[3];
    for (int a = 0; a < 3; ++a) nhi[a] = mesh_.extent(Centering::Cell, a);
    const Policy3 nodes({nlo[0], nlo[1], nlo[2]}, {nhi[0], nhi[1], nhi[2]});
    auto launch = [&](const auto& dev) {
      using Dev = std::decay_t<decltype(dev)>;
      Kokkos::parallel_for("remap::ke_fix_pressure", nodes,
                           NodePressureShares<Dev>{dev, kel, rho, e, post, mats_, shares});
    };
    if (mm_->kind() == mat::LayoutKind::Dense)
      launch(mm_->dense());
    else
      launch(mm_->compact());
    op.by_pressure = true;
    op.shares = shares;
    op.mats = mats_;
  }
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
    PureKeFixAhead<decltype(fix)::by_mass, decltype(fix)::by_pressure> ahead{
        fix,
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
  if (opt_.ke_fix_low_pressure)
    launch(PureKeFix<true, true>{mt, kel, rho, e, post, unpaid, shares, mats_});
  else if (by_mass)
    launch(PureKeFix<true>{mt, kel, rho, e, post, unpaid, {}, {}});
  else
    launch(PureKeFix<false>{mt, kel, rho, e, post, unpaid, {}, {}});
}

}  // namespace mp::hydro
