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
// Multi-material scenes (docs/numerics.md, "Strength in mixed cells"): every material with
// strength has its own deviator and plastic strain (a "stress set", cell fields that hold that
// material's values where it is present and 0 elsewhere). Each material's deviator advances
// under the cell's velocity gradient (equal strain, as the hydro's mixed cells) with its own
// shear modulus and returns to its own yield surface, both from its own flow-stress model at its
// own state (rho_m, e_m, p_m, its own plastic strain). The cell's stress on its nodes is the
// volume-fraction weighted sum of its materials' deviators, sum alpha_m s_m, so a fluid (no
// strength) carries none and a cell that is half fluid transmits half of its solid's stress;
// each material takes the work of its own part, alpha_m s_m : L V dt, so total energy is kept.
// The remap carries each material's set per unit mass of that material, with its own material
// mass flux (the per-material "carriers" of kernels/hydro/hydro.hpp). A single-material scene
// has one set, the cell's. Both layouts run the same point functions in material-id order, so
// they give the same bits.
//
// Storage (issue #12): the dense layout keeps each set as cell fields (every cell holds every
// material with strength: the paper's layout). The compact layout keeps a set only where its
// material is: a pure cell's deviator and plastic strain in 7 cell arrays shared by all sets (a
// pure cell holds one material), a mixed cell's in the pool's per-slot extras (6 + 1, carried
// across rebuilds) and 6 slot buffers of the half-step deviator; a material alone in its cell takes
// the cell's half-step stress as its own (both layouts read it there, so they agree bit for bit).
// Its remap runs after the material update: each component of every set is gathered from the
// pool as it stood before the update (MaterialState::previous) into a cell field, remapped with
// the same kernel as the dense sets, and scattered into the new pool; its halo gathers the owned
// shell (the owned cells within ng of a face), exchanges it with the field halo (the same
// parities) and scatters the ghosts. The
// gather fields are the cell's half-step stress (dead between the corrector and the next
// predictor), one more field and the remap scratch: a set costs the compact layout no cell
// array (up to 7 sets).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "hydro/module.hpp"
#include "materials/layout.hpp"
#include "mesh/field.hpp"
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

// One material's deviator (xx, yy, zz, xy, yz, zx), its half-step value and its equivalent
// plastic strain, as cell fields; `material` is its material id (-1 in a single-material scene).
struct StressSet {
  int material = -1;
  std::array<Field3, 6> s, s_half;
  Field3 eps_p;
};

class Strength : public hydro::Module {
 public:
  // Pooled sets: component x (0-5 deviator, 6 plastic strain) of set q, as a cell field.
  struct Target {
    int q, x;
    Field3 field;
  };
  // `rho0` is the material's reference density (the Steinberg–Guinan compression rho/rho0).
  Strength(const Mesh& mesh, const FlowStress& model, Real rho0);
  // A multi-material scene: the per-material state comes from `materials` (owned by the hydro,
  // it outlives the module); `names` are the materials' names (the dumps' field suffixes).
  Strength(const Mesh& mesh, const MaterialModels& models, mat::MaterialState* materials,
           const std::vector<std::string>& names);

  // Adds 4 G / (3 rho) to c^2 (c the EOS sound speed on every cell).
  void stiffen_sound_speed(const Field3& rho, const Field3& e, const Field3& p,
                           const Field3& c) const;
  // Predictor: the half-step deviator from the start-of-step velocities on the owned cells and
  // one ghost layer (the owned nodes' cells), then its force on every owned node into force_*
  // (returned: the hydro's acceleration adds them).
  const std::array<Field3, 3>* predictor(const Field3& u, const Field3& v, const Field3& w,
                                         const Field3& rho, const Field3& e, const Field3& p_half,
                                         Real dt) override;
  // Corrector, before the hydro's own (it reads rho^n, e^n): the full-step deviator and plastic
  // strain from the time-centred velocities on the owned cells, and the work of the half-step
  // deviator into e.
  void corrector(const Field3& ub, const Field3& vb, const Field3& wb, const Field3& rho,
                 const Field3& e, const Field3& p_half, Real dt) override;
  // One remap step over the faces normal to `axes` of stress set q: its quantities per unit
  // mass, with the cell mass fluxes of the step (owned cells; call before the cell densities
  // change). A multi-material scene passes set q's material's density (alpha_m rho_m) and
  // material mass fluxes instead of the cell's.
  void remap(int q, const std::array<bool, 3>& axes, const std::array<Field3, 3>& mass_flux,
             const Field3& rho, const Field3& pre, int order);
  // The compact layout's remap of every set (after the material update of a sweep along the
  // axes of `axes`; `flux[q]`, `rho[q]` are set q's carrier mass fluxes and its density before
  // the update).
  void remap_compact(const std::array<bool, 3>& axes, const std::vector<Field3>& flux,
                     const std::vector<Field3>& rho, const Field3& pre, int order);
  // True when the sets live in the compact pool (remap_compact and exchange_compact, not
  // remap and the cell halo).
  bool pooled() const { return pooled_; }
  // Pooled sets: the ghosts' values of every set, after the material exchange.
  void exchange_compact(Halo& halo);
  // Set q's deviator and plastic strain as cell fields (0 where its material is absent): the
  // set's own fields (dense), or new fields gathered from the pool (compact).
  StressSet gathered(int q) const;

  // The module seam (hydro/module.hpp). Fields: each set's deviator stress_xx..zx and plastic
  // strain, dumped as a single-material scene's stress_xx..zx, plastic_strain, or a multi-
  // material scene's with the material's name appended (stress_xx_copper), checkpointed with
  // the material id appended (as the checkpoint's per-material fields are), in the cell halo
  // unless pooled.
  const char* name() const override { return "strength"; }
  // Its deviator's nodal forces (the fixed face geometry), one carrier per stress set (its
  // material), c stiffened after the EOS.
  bool adds_forces() const override { return true; }
  std::vector<unsigned> carriers() const override;
  void after_eos(const Field3& rho, const Field3& e, const Field3& p,
                 const Field3& c) const override {
    stiffen_sound_speed(rho, e, p, c);
  }
  // The sets' per-mass remap: each set on its carrier (dense sets, before the cell update), or
  // the pooled sets from the pool before the material update into the one after it.
  void remap(const std::vector<hydro::Carrier>& mine, const std::array<bool, 3>& axes,
             const Field3& pre, int order) override;
  void remap_materials(const std::vector<hydro::Carrier>& mine, const std::array<bool, 3>& axes,
                       const Field3& pre, int order) override;
  // Set q's deviator and plastic strain (none when pooled: the pool holds nothing where the
  // set's material is absent).
  std::vector<Field3> carried_fields(int q) const override;
  std::vector<FieldSpec> fields(unsigned use) const override;
  // Pooled sets take the owned cells' values of the restored fields (cells that hold the set's
  // material).
  void restore(const std::vector<FieldSpec>& state) override;
  // Pooled sets: their ghosts (exchange_compact).
  void exchange_materials(Halo& halo) override {
    if (pooled_) exchange_compact(halo);
  }

  // Nodal forces of the half-step deviator (owned nodes), read by the acceleration.
  const std::array<Field3, 3>& force() const { return force_; }
  // The stress sets: one in a single-material scene, one per material with strength (in
  // material-id order) in a multi-material scene. A pooled set's fields are empty (material
  // only; gathered(q) has its values).
  int sets() const { return int(sets_.size()); }
  const StressSet& set(int q) const { return sets_[q]; }
  // The stress set of material m (multi-material scenes), or -1 when m has no strength.
  int set_of(int m) const { return m >= 0 && m < mat::kMaxMaterials ? set_of_[m] : -1; }
  // Set 0's deviator and plastic strain (a single-material scene's).
  const std::array<Field3, 6>& stress() const { return sets_[0].s; }
  const Field3& plastic_strain() const { return sets_[0].eps_p; }
  const FlowStress& model() const { return model_; }
  // The multi-material scene's models (n == 0 in a single-material scene).
  const MaterialModels& models() const { return models_; }

 private:
  void allocate();
  StressSet new_set(int material, const std::string& suffix) const;

 public:
  // Kernel launchers (public: nvcc requires the function enclosing an extended
  // __host__ __device__ lambda to be public).
  void mm_stiffen_sound_speed(const Field3& rho, const Field3& c) const;
  void mm_predictor(const Field3& u, const Field3& v, const Field3& w, Real dt);
  void mm_corrector(const Field3& ub, const Field3& vb, const Field3& wb, Real dt);
  // Where a gather or scatter runs: the whole block, the owned cells, the owned cells with the
  // ghost layers along one axis (what a remap sweep along it reads), the owned cells within ng
  // of a face (what the halo reads), the ghost cells.
  enum class Where { Block, Owned, SweepX, SweepY, SweepZ, OwnedShell, GhostShell };
  template <class F>
  void for_where(const std::string& name, Where w, F f) const;
  // Each target's values from pool `dev` (0 where the set's material is absent), at most 16
  // targets; and back into the current pool, for the cells that hold the set's material.
  void gather(const mat::CompactDev& dev, const std::vector<Target>& targets, Where w) const;
  void scatter(const std::vector<Target>& targets, Where w) const;

 private:
  const Mesh& mesh_;
  FlowStress model_;
  Real rho0_;
  MaterialModels models_;
  const mat::MaterialState* mm_ = nullptr;
  bool pooled_ = false;
  std::array<Field3, 7> pure_;  // pooled: a pure cell's deviator and plastic strain
  std::vector<Field3> gather_;  // pooled: gather fields beyond the six of cell_half_
  Buffer half_[6];              // pooled: a mixed cell's half-step deviators, per slot
  std::vector<std::string> names_;
  std::vector<StressSet> sets_;
  int set_of_[mat::kMaxMaterials];
  // The cell's half-step stress on its nodes (xx, yy, zz, xy, yz, zx): set 0's s_half in a
  // single-material scene, sum alpha_m s_half_m in a multi-material one.
  std::array<Field3, 6> cell_half_;
  std::array<Field3, 3> force_;
  Field3 scratch_;  // remap: the carried quantity before the step
};

}  // namespace mp::strength
