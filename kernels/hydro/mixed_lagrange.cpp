// The multi-material Lagrangian step (DESIGN.md §4 items 2, 4): per-material EOS and mixture
// closure, and the equal-strain predictor and corrector of mixed cells (the compact layout's
// pure cells as k-columns). Every kernel here runs on both layouts through MaterialState's
// accessors and the same point functions.
//
// Mixture rules (documented in docs/numerics.md):
//  - equal strain: every material of a cell takes the cell's relative volume change, so
//    rho_m' = rho_m V / V' and e_m' = e_m - (p_m + q) dV / (rho_m V);
//  - cell pressure p = sum alpha_m p_m (volume-fraction weighted, as in PAGOSA);
//  - cell sound speed from rho c^2 = sum alpha_m rho_m c_m^2, the stiffness of the equal-strain
//    mixture (dp/d(ln rho) at fixed strain sharing); a pure cell keeps its material's c.
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/point.hpp"
#include "hydro/relax.hpp"

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
  bool equilibrium = false;  // mixed: the pressure-equilibrium closure (reactive.hpp)
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

BurnHook burn_hook(const eos::Reactive* r) {
  if (!r) return {};
  return {r->material, r->fraction, r->d_cj, r->mixed, r->unreacted, r->e0, r->equilibrium};
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
        pm = eos::he_pressure_mixed_cut(bh.unreacted, mats.eos[m.m], bh.e0, f, *m.rho, *m.e,
                                        bh.equilibrium);
        cm = eos::he_sound_speed_mixed(bh.unreacted, mats.eos[m.m], bh.e0, f, *m.rho, *m.e,
                                       bh.equilibrium);
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
        pm = eos::he_pressure_mixed_cut(bh.unreacted, mats.eos[m.m], bh.e0, bh.f(i, j, k),
                                        mass / v_half, e_half, bh.equilibrium);
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
          ps = eos::he_pressure_mixed(bh.unreacted, eq, bh.e0, f, r, en, bh.equilibrium);
          c2 = bh.equilibrium ? eos::he_sound_speed2_equilibrium(bh.unreacted, eq, bh.e0, f, r, en)
                              : eos::he_sound_speed2_mixed(bh.unreacted, eq, bh.e0, f, r, en);
        } else {
          const Real f = bh.f(i, j, k);
          ps = eos::he_pressure(eq, f, r, en);
          c2 = eos::he_sound_speed2(eq, f, r, en);
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
  KOKKOS_INLINE_FUNCTION static constexpr int params() {
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
  Kokkos::Array<Field3, 6> qt;         // (std::array's operator[] is a host function to nvcc)
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
  const BurnHook bh = burn_hook(reactive_);
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
  const BurnHook bh = burn_hook(reactive_);
  const Field3 bf = bh.material >= 0 ? bh.f : rho;  // (read only with a burn)
  const mat::MaterialState& mm = *mm_;
  with_pure_columns(mm, bh, "lagrange::predictor", all_lo(), all_hi(mesh_),
                    MixedPredictor{mats, bh, Q, ph, rho, u, v, w, ax, ay, az, vol}, [&](auto burn) {
                      return PurePredictor<decltype(burn)::value>{
                          EosTable(mats),
                          mm.compact().mat,
                          u,
                          v,
                          w,
                          rho,
                          e,
                          p,
                          {qt[0], qt[1], qt[2], qt[3], qt[4], qt[5]},
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
  const BurnHook bh = burn_hook(reactive_);
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

}  // namespace mp::hydro
