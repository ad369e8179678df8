// The burn module of a single-material scene whose material is an explosive (DESIGN.md §4 item 6
// and §4.1): it owns the burn fraction F of every cell and the cells' lighting times, and the
// cycle calls it at four seams — the pressure after the EOS and at the half step (p = F P(rho,
// e), the products EOS scaled by F: burn.hpp he_pressure), the burn-fraction update after the
// Lagrangian step, and the remap (F per unit mass). Point functions in burn.hpp, the Huygens
// lighting-time construction in lighting.hpp.
//
// The explosive's internal energy includes its chemical energy (the region's `energy`), so the
// products EOS at (rho0, e0) is the constant-volume explosion state and F releases it; total
// energy is kept by the hydro as usual. The sound speed stays the products' own at (rho, e) and
// is raised to D where F < 1, so the time step keeps the programmed front within a cell per
// step (docs/numerics.md, "Burn").
#pragma once
#include <string>
#include <vector>

#include "burn/burn.hpp"
#include "burn/lighting.hpp"
#include "io/hdf5_writer.hpp"
#include "mesh/halo.hpp"
#include "mesh/mesh.hpp"

namespace mp::burn {

struct BurnSetup {
  bool on = false;
  Real d_cj = 0, p_cj = 0, rho0 = 0;
  Real ramp_cells = kDefaultRampCells;
  bool programmed = true, volume_burn = false;
  std::vector<Detonator> detonators;
};

class Burn {
 public:
  Burn(const Mesh& mesh, const BurnSetup& setup);

  // p = F p on every cell (after the EOS, and at the half step), and c = max(c, D) where F < 1.
  void scale_pressure(const Field3& p) const;
  void raise_sound_speed(const Field3& c) const;
  // After the Lagrangian step of length dt (rho the new density): advances the module's clock
  // and burns the owned cells.
  void update(const Field3& rho, double dt);
  void remap(const std::array<bool, 3>& axes, const std::array<Field3, 3>& mass_flux,
             const Field3& rho, const Field3& pre, int order);
  std::vector<HaloField> halo_fields() const;
  std::vector<OutputField> output_fields() const;

  const Field3& fraction() const { return f_; }
  const Field3& lighting_time() const { return t_light_; }
  double time() const { return time_; }
  // The clock a restart resumes from (the run's time; the module's starts at 0 with the run).
  void set_time(double t) { time_ = t; }
  const BurnParams& params() const { return params_; }

 private:
  const Mesh& mesh_;
  BurnParams params_;
  Field3 f_, t_light_, scratch_;
  double time_ = 0;
};

}  // namespace mp::burn
