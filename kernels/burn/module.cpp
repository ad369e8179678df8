// The burn module's set-up and kernels (module.hpp says what each seam does).
#include "burn/module.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "hydro/per_mass.hpp"

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
  if (!setup.programmed) return;
  // Lighting times on the whole global mesh (every cell is explosive in a single-material
  // scene, so the Huygens construction is the straight-line distance), each rank keeping its
  // block. Host-side, once.
  LightingGrid grid;
  for (int d = 0; d < 3; ++d) {
    grid.n[d] = mesh.global_cells(d);
    grid.origin[d] = double(g.lo[d]);
    grid.h[d] = double(g.dx[d]);
  }
  const std::vector<std::uint8_t> explosive(grid.cells(), 1);
  std::vector<double> times;
  try {
    times = lighting_times(grid, explosive, setup.detonators, double(setup.d_cj));
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("burn: ") + e.what());
  }
  auto h = Kokkos::create_mirror_view(t_light_);
  Kokkos::deep_copy(h, t_light_);
  const int ng = Mesh::ng;
  for (int k = ng; k < ng + mesh.owned_cells(2); ++k)
    for (int j = ng; j < ng + mesh.owned_cells(1); ++j)
      for (int i = ng; i < ng + mesh.owned_cells(0); ++i)
        h(i, j, k) = Real(times[grid.index(mesh.offset(0) + i - ng, mesh.offset(1) + j - ng,
                                           mesh.offset(2) + k - ng)]);
  Kokkos::deep_copy(t_light_, h);
}

void Burn::scale_pressure(const Field3& p) const {
  auto f = f_;
  Kokkos::parallel_for(
      "burn::pressure", mesh_.cells(Region::All),
      KOKKOS_LAMBDA(int i, int j, int k) { p(i, j, k) *= f(i, j, k); });
}

void Burn::raise_sound_speed(const Field3& c) const {
  auto f = f_;
  const Real d = params_.d_cj;
  Kokkos::parallel_for(
      "burn::sound_speed", mesh_.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
        if (f(i, j, k) < 1) c(i, j, k) = mmax(c(i, j, k), d);
      });
}

void Burn::update(const Field3& rho, double dt) {
  time_ += dt;
  const BurnParams b = params_;
  const Real t = Real(time_);
  auto f = f_, tl = t_light_;
  Kokkos::parallel_for(
      "burn::fraction", mesh_.cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
        f(i, j, k) = update_burn_fraction(b, f(i, j, k), t, tl(i, j, k), rho(i, j, k));
      });
}

void Burn::remap(const std::array<bool, 3>& axes, const std::array<Field3, 3>& mass_flux,
                 const Field3& rho, const Field3& pre, int order) {
  hydro::remap_per_mass(mesh_, axes, mass_flux, rho, pre, {f_}, scratch_, order);
}

std::vector<HaloField> Burn::halo_fields() const {
  return {{f_, Centering::Cell, {1, 1, 1}}};
}

std::vector<OutputField> Burn::output_fields() const {
  return {{"burn_fraction", Centering::Cell, f_}, {"lighting_time", Centering::Cell, t_light_}};
}

}  // namespace mp::burn
