// The burn module's set-up and kernels (module.hpp says what each seam does).
#include "burn/module.hpp"

#include <algorithm>
#include <cmath>

#include "burn/lighting_device.hpp"
#include "core/error.hpp"
#include "remap/per_mass.hpp"

namespace mp::burn {

Burn::Burn(const Mesh& mesh, const BurnSetup& setup) : mesh_(mesh) {
  const Geometry g = mesh.geometry();
  params_ = make_burn_params(setup.rho0, setup.d_cj, setup.p_cj,
                             Real(std::max({g.dx[0], g.dx[1], g.dx[2]})), setup.programmed,
                             setup.volume_burn, setup.ramp_cells);
  f_ = mesh.new_field("burn_fraction", Centering::Cell);
  t_light_ = mesh.new_field("lighting_time", Centering::Cell);
  scratch_ = mesh.new_field("burn_remap_scratch", Centering::Cell);
  Kokkos::deep_copy(t_light_, Real(kNeverLit));
  detonators_ = setup.detonators;
  programmed_ = setup.programmed;
  mixed_ = setup.mixed;
  unreacted_ = setup.unreacted;
  e0_ = setup.e0;
  ff_on_ = setup.forest_fire;
  ff_ = setup.ff;
  c_floor_ = setup.programmed || setup.volume_burn ? params_.d_cj : Real(0);
  reactive_ = {-1, f_, c_floor_, mixed_, unreacted_, e0_, setup.equilibrium};
  host_lighting_ = setup.host_lighting;
  if (!setup.programmed || setup.material >= 0) return;
  // every cell is explosive in a single-material scene, so the Huygens construction is the
  // straight-line distance
  if (!host_lighting_) {
    light_device(nullptr);
    return;
  }
  long n = 1;
  for (int d = 0; d < 3; ++d) n *= mesh.global_cells(d);
  set_lighting(std::vector<std::uint8_t>(n, 1), setup.detonators);
}

Burn::Burn(const Mesh& mesh, const BurnSetup& setup, const mat::MaterialState* materials)
    : Burn(mesh, setup) {
  mm_ = materials;
  material_ = setup.material;
  reactive_.material = material_;
}

LightingGrid Burn::lighting_grid() const {
  const Geometry g = mesh_.geometry();
  LightingGrid grid;
  for (int d = 0; d < 3; ++d) {
    grid.n[d] = mesh_.global_cells(d);
    grid.origin[d] = double(g.lo[d]);
    grid.h[d] = double(g.dx[d]);
  }
  return grid;
}

namespace {

// The lighting times of the rank's cells from the per-rank construction: an explosive cell's own;
// a cell with some explosive but less than half (frac > 0, not in the mask), the earliest lit
// explosive neighbour's time plus the distance between the centres over D (as set_lighting).
struct WriteTimes {
  Field3 tl, frac;
  bool partial;
  Kokkos::View<LightingLabel***, MemSpace> lab;
  ExplosiveBits bits;
  Geometry geo;
  double d_cj;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k) const {
    const int g[3] = {geo.global_index(0, i), geo.global_index(1, j), geo.global_index(2, k)};
    const double never = double(kNeverLit);
    if (bits.explosive(g[0], g[1], g[2])) {
      tl(i, j, k) = Real(lab(i, j, k).t);
      return;
    }
    double best = never;
    if (partial && frac(i, j, k) > 0) {
      const double* h = bits.box.h;
      for (int c = -1; c <= 1; ++c)
        for (int b = -1; b <= 1; ++b)
          for (int a = -1; a <= 1; ++a) {
            if (!bits.in_grid(g[0] + a, g[1] + b, g[2] + c) ||
                !bits.explosive(g[0] + a, g[1] + b, g[2] + c))
              continue;
            const double tq = lab(i + a, j + b, k + c).t;
            if (!(tq < never)) continue;
            const double dist = MP_KOKKOS_MATH::sqrt(a * a * h[0] * h[0] + b * b * h[1] * h[1] +
                                                     c * c * h[2] * h[2]);
            const double v = tq + dist / d_cj;
            best = v < best ? v : best;
          }
    }
    tl(i, j, k) = Real(best);
  }
};

}  // namespace

// Lighting times built per rank by kernels (lighting_device.hpp) from the cells at least half
// explosive (frac null: every cell).
void Burn::light_device(const Field3* frac) {
  const LightingGrid grid = lighting_grid();
  const ExplosiveBits bits = explosive_bits(mesh_, grid, frac, Real(0.5));
  LightingRun run;
  try {
    run = lighting_times_device(mesh_, grid, bits, detonators_, double(params_.d_cj));
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("burn: ") + e.what());
  }
  sweeps_ = run.sweeps;
  Kokkos::parallel_for("burn::lighting_write", mesh_.cells(Region::Owned),
                       WriteTimes{t_light_, frac ? *frac : Field3(), frac != nullptr, run.label,
                                  bits, mesh_.geometry(), double(params_.d_cj)});
  Kokkos::fence();
}

// Lighting times on the whole global mesh, each rank keeping its block. Host-side, once (the
// reference construction, `burn.lighting: host`).
void Burn::set_lighting(const std::vector<std::uint8_t>& explosive,
                        const std::vector<Detonator>& detonators) {
  const LightingGrid grid = lighting_grid();
  std::vector<double> times;
  try {
    times = lighting_times(grid, explosive, detonators, double(params_.d_cj));
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("burn: ") + e.what());
  }
  auto h = Kokkos::create_mirror_view(t_light_);
  Kokkos::deep_copy(h, t_light_);
  const int ng = Mesh::ng;
  for (int k = ng; k < ng + mesh_.owned_cells(2); ++k)
    for (int j = ng; j < ng + mesh_.owned_cells(1); ++j)
      for (int i = ng; i < ng + mesh_.owned_cells(0); ++i)
        h(i, j, k) = Real(times[grid.index(mesh_.offset(0) + i - ng, mesh_.offset(1) + j - ng,
                                           mesh_.offset(2) + k - ng)]);
  if (mm_) {
    // cells with some explosive but less than half: the earliest lit neighbour's time plus the
    // distance between the centres over D
    auto frac = Kokkos::create_mirror_view(mm_->fraction(material_));
    Kokkos::deep_copy(frac, mm_->fraction(material_));
    const double d_cj = double(params_.d_cj);
    for (int k = ng; k < ng + mesh_.owned_cells(2); ++k)
      for (int j = ng; j < ng + mesh_.owned_cells(1); ++j)
        for (int i = ng; i < ng + mesh_.owned_cells(0); ++i) {
          if (!(frac(i, j, k) > 0) ||
              explosive[grid.index(mesh_.offset(0) + i - ng, mesh_.offset(1) + j - ng,
                                   mesh_.offset(2) + k - ng)])
            continue;
          double best = double(kNeverLit);
          for (int c = -1; c <= 1; ++c)
            for (int b = -1; b <= 1; ++b)
              for (int a = -1; a <= 1; ++a) {
                const int gi = mesh_.offset(0) + i - ng + a, gj = mesh_.offset(1) + j - ng + b,
                          gk = mesh_.offset(2) + k - ng + c;
                if (gi < 0 || gj < 0 || gk < 0 || gi >= grid.n[0] || gj >= grid.n[1] ||
                    gk >= grid.n[2])
                  continue;
                const long q = grid.index(gi, gj, gk);
                if (!explosive[q] || !(times[q] < double(kNeverLit))) continue;
                const double dist =
                    std::sqrt(a * a * grid.h[0] * grid.h[0] + b * b * grid.h[1] * grid.h[1] +
                              c * c * grid.h[2] * grid.h[2]);
                best = std::min(best, times[q] + dist / d_cj);
              }
          h(i, j, k) = Real(best);
        }
  }
  Kokkos::deep_copy(t_light_, h);
}

void Burn::light() {
  if (!mm_ || !programmed_) return;
  const Field3 frac = mm_->fraction(material_);
  if (!host_lighting_) {
    light_device(&frac);
    return;
  }
  // the cells at least half explosive, gathered over the ranks
  auto hf = Kokkos::create_mirror_view(frac);
  Kokkos::deep_copy(hf, frac);
  long n = 1;
  int gn[3];
  for (int d = 0; d < 3; ++d) {
    gn[d] = mesh_.global_cells(d);
    n *= gn[d];
  }
  std::vector<std::uint8_t> local(n, 0), global(n, 0);
  const int ng = Mesh::ng;
  for (int k = ng; k < ng + mesh_.owned_cells(2); ++k)
    for (int j = ng; j < ng + mesh_.owned_cells(1); ++j)
      for (int i = ng; i < ng + mesh_.owned_cells(0); ++i) {
        const long gi = mesh_.offset(0) + i - ng, gj = mesh_.offset(1) + j - ng,
                   gk = mesh_.offset(2) + k - ng;
        local[gi + gn[0] * (gj + long(gn[1]) * gk)] = hf(i, j, k) >= Real(0.5) ? 1 : 0;
      }
  MPI_Allreduce(local.data(), global.data(), int(n), MPI_UNSIGNED_CHAR, MPI_MAX, mesh_.comm());
  set_lighting(global, detonators_);
}

void Burn::scale_pressure(const Field3& p) const {
  auto f = f_;
  Kokkos::parallel_for(
      "burn::pressure", mesh_.cells(Region::All),
      KOKKOS_LAMBDA(int i, int j, int k) { p(i, j, k) *= f(i, j, k); });
}

void Burn::raise_sound_speed(const Field3& c) const {
  if (!(c_floor_ > 0)) return;
  auto f = f_;
  const Real d = c_floor_;
  Kokkos::parallel_for(
      "burn::sound_speed", mesh_.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
        if (f(i, j, k) < 1) c(i, j, k) = mmax(c(i, j, k), d);
      });
}

namespace {

// The multi-material burn::fraction kernel, a for_cells body (a functor at namespace scope, not
// a generic extended lambda, which nvcc rejects inside for_cells' own lambdas): the burn
// fraction of the cells that hold explosive (material x), at the explosive's own density.
struct MixedFraction {
  BurnParams b;
  Real t;
  Field3 f, tl;
  int x;
  Real never;
  bool ff_on;
  ForestFire ff;
  Real dt;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    for (int s = 0; s < cell.count(); ++s) {
      const mat::MatRef m = cell.get(s);
      if (m.m != x || !(m.alpha > 0)) continue;
      const Real f0 = f(i, j, k);
      if (ff_on) {
        // Forest Fire: at the explosive's own pressure (the mixture closure at F_old); no
        // finish-at-once rule (lighting times mean nothing to it)
        const Real r = *m.rho, e = *m.e;
        const Real p =
            eos::he_pressure_mixed_cut(ff.unreacted, ff.products, ff.e0, f0, r, e, ff.equilibrium);
        f(i, j, k) =
            mmax(update_burn_fraction(b, f0, t, tl(i, j, k), r), forest_fire_step(ff, f0, p, dt));
        continue;
      }
      f(i, j, k) = tl(i, j, k) >= never && f0 > 0
                       ? Real(1)
                       : update_burn_fraction(b, f0, t, tl(i, j, k), *m.rho);
    }
  }
};

}  // namespace

void Burn::update(const Field3& rho, double dt) {
  time_ += dt;
  const BurnParams b = params_;
  const Real t = Real(time_);
  auto f = f_, tl = t_light_;
  if (mm_) {
    // the explosive burns at its own density; explosive that the remap carried, part burnt,
    // into a cell that held none at the start (no lighting time of its own) has been lit
    // already and finishes burning there at once (else it would keep F < 1, and c >= D, for
    // good as the products expand)
    const int x = material_;
    const int ng = Mesh::ng;
    const Real never = Real(kNeverLit);
    mm_->for_cells("burn::fraction", {ng, ng, ng}, mesh_.owned_end(),
                   MixedFraction{b, t, f, tl, x, never, ff_on_, ff_, Real(dt)});
    return;
  }
  if (ff_on_) {
    // Forest Fire at the pressure of the mixture closure at (rho, e) after the Lagrangian step
    // and F_old, with the programmed / volume fractions where those are on too
    const ForestFire ff = ff_;
    const Real h = Real(dt);
    auto e = e_;
    Kokkos::parallel_for(
        "burn::fraction", mesh_.cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
          const Real f0 = f(i, j, k), r = rho(i, j, k), ei = e(i, j, k);
          const Real p = eos::he_pressure_mixed_cut(ff.unreacted, ff.products, ff.e0, f0, r, ei,
                                                    ff.equilibrium);
          f(i, j, k) =
              mmax(update_burn_fraction(b, f0, t, tl(i, j, k), r), forest_fire_step(ff, f0, p, h));
        });
    return;
  }
  Kokkos::parallel_for(
      "burn::fraction", mesh_.cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
        f(i, j, k) = update_burn_fraction(b, f(i, j, k), t, tl(i, j, k), rho(i, j, k));
      });
}

void Burn::remap(const std::array<bool, 3>& axes, const std::array<Field3, 3>& mass_flux,
                 const Field3& rho, const Field3& pre, int order) {
  mp::remap::remap_per_mass(mesh_, axes, mass_flux, rho, pre, {f_}, {scratch_}, order);
}

void Burn::after_eos(const Field3& /*rho*/, const Field3& e, const Field3& p,
                     const Field3& c) const {
  if (mm_) return;  // (the multi-material EOS applies F and D itself)
  e_ = e;
  if (!mixed_) scale_pressure(p);
  raise_sound_speed(c);
}

std::vector<FieldSpec> Burn::fields(unsigned /*use*/) const {
  const auto C = Centering::Cell;
  return {{"burn_fraction", C, f_, kDump | kCheckpoint | kHalo, "burn_fraction", {{1, 1, 1}}, ""},
          {"lighting_time",
           C,
           t_light_,
           kDump | (programmed_ ? unsigned(kCheckpoint) : 0u),
           "lighting_time",
           {{1, 1, 1}},
           "us"}};
}

}  // namespace mp::burn
