// The burn module of a single-material scene whose material is an explosive (DESIGN.md §4 item 6
// and §4.1): it owns the burn fraction F of every cell and the cells' lighting times, and the
// cycle calls it at four seams — the pressure after the EOS and at the half step (p = F P(rho,
// e), the products EOS scaled by F: burn.hpp he_pressure; or, with an unreacted EOS (mixed()),
// p = (1 - F) P_u(rho, e - e0) + F P(rho, e): burn.hpp he_pressure_mixed, evaluated in the
// hydro's EOS and predictor kernels), the burn-fraction update after the Lagrangian step, and
// the remap (F per unit mass). Point functions in burn.hpp; the Huygens lighting-time
// construction in lighting_device.hpp (Kokkos kernels on each rank's block, the default) and its
// host reference over the global grid in lighting.hpp (`burn.lighting: host`).
//
// The explosive's internal energy includes its chemical energy (the region's `energy`), so the
// products EOS at (rho0, e0) is the constant-volume explosion state and F releases it; total
// energy is kept by the hydro as usual. The sound speed stays the products' own at (rho, e) and
// is raised to D where F < 1, so the time step keeps the programmed front within a cell per
// step (docs/numerics.md, "Burn").
//
// Multi-material scenes (one explosive material, `BurnSetup::material`): F stays a cell field,
// the burn fraction of the cell's explosive, carried per unit mass of the explosive with the
// explosive's own material mass flux (kernels/hydro/hydro.hpp, "carriers"); only the explosive's
// pressure is scaled (the hydro's multi-material EOS and predictor read fraction()), it burns at
// its own density, and a cell holding unburnt explosive gets c >= D. Lighting times run through
// the cells at least half explosive (inert cells shadow); a cell with less explosive takes the
// earliest time of a lit neighbour plus the distance between their centres over D, so no
// explosive is left unlit behind a thin layer of mixed cells (a kernel over the rank's cells that
// reads its neighbours' times through one ghost layer).
#pragma once
#include <string>
#include <vector>

#include "burn/burn.hpp"
#include "burn/forest_fire.hpp"
#include "burn/lighting.hpp"
#include "hydro/module.hpp"
#include "materials/layout.hpp"
#include "mesh/field.hpp"
#include "mesh/halo.hpp"
#include "mesh/mesh.hpp"

namespace mp::burn {

struct BurnSetup {
  bool on = false;
  Real d_cj = 0, p_cj = 0, rho0 = 0;
  Real ramp_cells = kDefaultRampCells;
  bool programmed = true, volume_burn = false;
  std::vector<Detonator> detonators;
  int material = -1;  // the explosive's material id in a multi-material scene
  // The unreacted solid's EOS (burn.hpp he_pressure_mixed), off unless mixed: then the
  // explosive's pressure is (1 - F) P_u(rho, e - e0) + F P_products(rho, e) instead of F P.
  bool mixed = false;
  eos::Eos unreacted;
  Real e0 = 0;  // unreacted energy origin, cm^2/us^2 (E0 / rho0 of the products)
  // mixed: the two phases at one pressure (reactive.hpp he_equilibrium, burn.closure:
  // pressure_equilibrium) instead of both at the cell's (rho, e)
  bool equilibrium = false;
  // Forest Fire (forest_fire.hpp): F also grows at the rate R(p) of the explosive's pressure;
  // needs the unreacted EOS (mixed), whose Hugoniot and the products' EOS `ff` carries.
  bool forest_fire = false;
  ForestFire ff;
  // Lighting times by the host reference construction over the global grid (lighting.hpp)
  // instead of the per-rank kernels (lighting_device.hpp).
  bool host_lighting = false;
};

class Burn : public hydro::Module {
 public:
  Burn(const Mesh& mesh, const BurnSetup& setup);
  // A multi-material scene: call light() once the materials are in place.
  Burn(const Mesh& mesh, const BurnSetup& setup, const mat::MaterialState* materials);
  // Lighting times from the explosive's volume fraction (multi-material scenes; collective).
  void light();
  int material() const { return material_; }

  // p = F p on every cell (after the EOS, and at the half step), and c = max(c, D) where F < 1.
  void scale_pressure(const Field3& p) const;
  void raise_sound_speed(const Field3& c) const;
  // After the Lagrangian step of length dt (rho the new density): advances the module's clock
  // and burns the owned cells.
  void update(const Field3& rho, double dt);
  void remap(const std::array<bool, 3>& axes, const std::array<Field3, 3>& mass_flux,
             const Field3& rho, const Field3& pre, int order);
  // The module seam (hydro/module.hpp). Fields: the burn fraction (dumped, checkpointed, in the
  // cell halo) and the lighting times (dumped, and checkpointed in programmed burn: they are built
  // from the materials as painted at the start, which a restart no longer has).
  const char* name() const override { return "burn"; }
  // The explosive's EOS closure for the hydro's EOS kernels; the pressure scaled by F where
  // they do not apply it (a single-material explosive without an unreacted EOS), c raised to D
  // where F < 1 (the multi-material kernels do both themselves); F advanced after the
  // Lagrangian step; F per mass of the explosive in the remap.
  const eos::Reactive* reactive() const override { return &reactive_; }
  std::vector<unsigned> carriers() const override { return {mm_ ? 1u << material_ : 1u}; }
  void after_eos(const Field3& rho, const Field3& e, const Field3& p,
                 const Field3& c) const override;
  void half_step_pressure(const Field3& p_half) const override {
    if (!mm_ && !mixed_) scale_pressure(p_half);
  }
  void after_lagrange(const Field3& rho, Real dt) override { update(rho, double(dt)); }
  void remap(const std::vector<hydro::Carrier>& mine, const std::array<bool, 3>& axes,
             const Field3& pre, int order) override {
    remap(axes, mine[0].flux, mine[0].rho, pre, order);
  }
  std::vector<Field3> carried_fields(int) const override { return {f_}; }
  std::vector<FieldSpec> fields(unsigned use) const override;
  // Lighting times from the explosive's volume fraction as painted (multi-material scenes; a
  // restart reads them from the checkpoint instead).
  void materials_placed() override { light(); }

  const Field3& fraction() const { return f_; }
  const Field3& lighting_time() const { return t_light_; }
  double time() const { return time_; }
  // Sweeps the per-rank lighting construction took (0: none ran).
  int lighting_sweeps() const { return sweeps_; }
  // Builds the lighting times with the per-rank kernels from the cells whose fraction is at
  // least half (frac null: every cell; collective). Public: it launches kernels.
  void light_device(const Field3* frac);
  // The clock a restart resumes from (the run's time; the module's starts at 0 with the run).
  void set_time(double t) override { time_ = t; }
  const BurnParams& params() const { return params_; }
  // The closure with the unreacted solid's EOS (BurnSetup::mixed), its EOS and energy origin.
  bool mixed() const { return mixed_; }
  // Forest Fire on, and its rate's data.
  bool forest_fire() const { return ff_on_; }
  const ForestFire& forest_fire_data() const { return ff_; }
  const eos::Eos& unreacted() const { return unreacted_; }
  Real e0() const { return e0_; }

 private:
  LightingGrid lighting_grid() const;
  void set_lighting(const std::vector<std::uint8_t>& explosive,
                    const std::vector<Detonator>& detonators);

  const Mesh& mesh_;
  const mat::MaterialState* mm_ = nullptr;
  int material_ = -1;
  std::vector<Detonator> detonators_;
  bool programmed_ = true;
  bool mixed_ = false;
  eos::Eos unreacted_;
  Real e0_ = 0;
  bool ff_on_ = false;
  ForestFire ff_;
  // The sound speed's floor where F < 1: D with programmed or volume burn (their fronts run at
  // D), none (0) with Forest Fire alone.
  Real c_floor_ = 0;
  // The single-material scene's cell energy (the hydro's, handed to after_eos): Forest Fire's
  // pressure after the Lagrangian step.
  mutable Field3 e_;
  BurnParams params_;
  Field3 f_, t_light_, scratch_;
  eos::Reactive reactive_;
  double time_ = 0;
  bool host_lighting_ = false;
  int sweeps_ = 0;
};

}  // namespace mp::burn
