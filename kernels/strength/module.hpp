// The strength module of a single-material scene whose material has strength (DESIGN.md §4 item 5
// and §4.1): it owns the stress deviator (6 components) and the equivalent plastic strain of every
// cell, and the cycle calls it at four seams — the sound speed after the EOS, the half-step stress
// and its nodal forces in the predictor, the full-step stress and its work in the corrector, and
// the remap. Point functions (stress_update.hpp, flow_stress.hpp) hold the physics.
//
// Discretisation (docs/numerics.md, "Strength"):
//  - velocity gradient of a cell: L_ij = sum over its 8 nodes of sgn_j u_i / (4 dx_j), sgn_j = +1
//    for the nodes on the cell's high side along j (the node-averaged gradient, as the volume
//    change uses);
//  - nodal force of a cell's deviator on one of its nodes: F_i = -sum_j s_ij sgn_j A_j, A_j the
//    quarter-face area normal to j (the pressure's force is the same with s = -p I), so the power
//    the cell's stress delivers to its nodes is -V s:L and the cell gains exactly that: total
//    energy is conserved to round-off, as for p dV;
//  - time centring: the forces and the work use s^{n+1/2} = return(trial(s^n, L(u^n), dt/2));
//    the stress advances with the time-centred velocities, s^{n+1} = return(trial(s^n,
//    L((u^n + u^{n+1})/2), dt)), elastic_trial_rotated (Hughes–Winget rotation, objective), the
//    radial return on the von Mises surface; G and Y from the flow-stress model at the cell's
//    state (rho^n, e^n, p^{n+1/2}, eps_p^n, the equivalent strain rate of L);
//  - sound speed: c^2 + 4 G / (3 rho), the longitudinal speed, so the time step and the linear
//    viscosity see the elastic waves;
//  - remap: every component and the plastic strain are carried per unit mass with the cell mass
//    fluxes (van Leer face values time-centred by the mass Courant number, as the internal
//    energy), over the owned cells; the halo then fills the ghosts (shear components change sign
//    under the two reflections that flip them).
//
// Multi-material scenes (docs/numerics.md, "Strength in mixed cells"): the deviator and the
// plastic strain stay cell quantities (DESIGN.md §3: "cell-averaged ... deviatoric stress"),
// shared by the materials of a cell that have strength; the cell's shear modulus and flow stress
// are the volume-fraction weighted sums over those materials, each evaluated at its own state
// (rho_m, e_m, p_m), so a fluid (no strength) contributes none and a cell that is half fluid
// carries half the stress; the deviator's work goes to the materials with strength, the same
// specific energy to each; the remap carries the deviator and the plastic strain per unit mass
// of those materials, with their summed material mass fluxes (the "carrier" of
// kernels/hydro/hydro.hpp). Both layouts run the same point functions in material-id order, so
// they give the same bits.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "io/hdf5_writer.hpp"
#include "materials/layout.hpp"
#include "mesh/halo.hpp"
#include "mesh/mesh.hpp"
#include "strength/flow_stress.hpp"

namespace mp::strength {

// The flow-stress model and reference density of every material of a multi-material scene
// (kind kNoStrength for a material without strength).
struct MaterialModels {
  int n = 0;
  FlowStress f[mat::kMaxMaterials];
  Real rho0[mat::kMaxMaterials];
  // Materials whose mass carries the deviator (bit m set when material m has strength).
  unsigned carriers() const {
    unsigned b = 0;
    for (int m = 0; m < n; ++m)
      if (f[m].kind != kNoStrength) b |= 1u << m;
    return b;
  }
};

class Strength {
 public:
  // `rho0` is the material's reference density (the Steinberg–Guinan compression rho/rho0).
  Strength(const Mesh& mesh, const FlowStress& model, Real rho0);
  // A multi-material scene: the per-material state comes from `materials` (owned by the hydro,
  // it outlives the module).
  Strength(const Mesh& mesh, const MaterialModels& models, const mat::MaterialState* materials);

  // Adds 4 G / (3 rho) to c^2 (c the EOS sound speed on every cell).
  void stiffen_sound_speed(const Field3& rho, const Field3& e, const Field3& p,
                           const Field3& c) const;
  // Predictor: the half-step deviator from the start-of-step velocities on the owned cells and
  // one ghost layer (the owned nodes' cells), then its force on every owned node into force_*.
  void predictor(const Field3& u, const Field3& v, const Field3& w, const Field3& rho,
                 const Field3& e, const Field3& p_half, Real dt);
  // Corrector, before the hydro's own (it reads rho^n, e^n): the full-step deviator and plastic
  // strain from the time-centred velocities on the owned cells, and the work of the half-step
  // deviator into e.
  void corrector(const Field3& ub, const Field3& vb, const Field3& wb, const Field3& rho,
                 const Field3& e, const Field3& p_half, Real dt);
  // One remap step over the faces normal to `axes`: every carried quantity per unit mass, with
  // the cell mass fluxes of the step (owned cells; call before the cell densities change). A
  // multi-material scene passes the carriers' density and mass fluxes instead of the cell's.
  void remap(const std::array<bool, 3>& axes, const std::array<Field3, 3>& mass_flux,
             const Field3& rho, const Field3& pre, int order);
  // The halo fields of the carried quantities (exchanged with the cell fields).
  std::vector<HaloField> halo_fields() const;
  std::vector<OutputField> output_fields() const;

  // Nodal forces of the half-step deviator (owned nodes), read by the acceleration.
  const std::array<Field3, 3>& force() const { return force_; }
  const std::array<Field3, 6>& stress() const { return s_; }
  const Field3& plastic_strain() const { return eps_p_; }
  const FlowStress& model() const { return model_; }
  // The multi-material scene's models (n == 0 in a single-material scene).
  const MaterialModels& models() const { return models_; }

 private:
  void allocate();
  void mm_stiffen_sound_speed(const Field3& rho, const Field3& c) const;
  void mm_predictor(const Field3& u, const Field3& v, const Field3& w, Real dt);
  void mm_corrector(const Field3& ub, const Field3& vb, const Field3& wb, Real dt);

  const Mesh& mesh_;
  FlowStress model_;
  Real rho0_;
  MaterialModels models_;
  const mat::MaterialState* mm_ = nullptr;
  std::array<Field3, 6> s_, s_half_;  // xx, yy, zz, xy, yz, zx
  Field3 eps_p_;
  std::array<Field3, 3> force_;
  Field3 scratch_;  // remap: the carried quantity before the step
};

}  // namespace mp::strength
