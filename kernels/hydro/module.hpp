// The seam between the hydro and a physics module (strength, burn): everything the hydro and the
// driver ask of a module, host-side, once per phase, never inside a kernel. The hydro knows no
// module by name: the driver builds the modules a scene needs (src/driver/modules.cpp) and hands
// them to Hydro::add_module. A module registers its fields once (mesh/field.hpp FieldSpec): the
// dumps, the checkpoints and the cell halo take them from here, so nothing outside the module
// names them. docs/architecture.md, "The cycle and the modules", has the order of the hooks.
#pragma once
#include <array>
#include <vector>

#include "core/types.hpp"
#include "eos/reactive.hpp"
#include "mesh/field.hpp"

namespace mp::hydro {

// The mass fluxes (face field of each axis) and density a module's per-mass quantity rides on
// in a remap step: a single-material scene's cell ones, or a multi-material scene's carrier's
// (the summed material mass flux and density of the materials of its mask).
struct Carrier {
  std::array<Field3, 3> flux;
  Field3 rho;
};

class Module {
 public:
  virtual ~Module() = default;
  // "strength", "burn" (the run log's and the launch profile's word).
  virtual const char* name() const = 0;

  // ---- what the module changes in the hydro, asked once when it is added ----
  // It adds nodal forces of its own (the predictor's, below): the Lagrangian step then keeps
  // the fixed face geometry.
  virtual bool adds_forces() const { return false; }
  // An explosive's EOS closure for the hydro's EOS kernels (eos/reactive.hpp), or nullptr.
  virtual const eos::Reactive* reactive() const { return nullptr; }
  // Its per-mass cell quantities' carriers in a multi-material scene: one material mask each
  // (the materials whose mass carries it), in the order remap() receives them.
  virtual std::vector<unsigned> carriers() const { return {}; }

  // ---- the cycle ----
  // After the EOS of every cell (p, c from rho, e; the reactive closure already applied).
  virtual void after_eos(const Field3& rho, const Field3& e, const Field3& p,
                         const Field3& c) const {
    (void)rho, (void)e, (void)p, (void)c;
  }
  // The predictor's half-step pressure of a single-material scene, before its forces.
  virtual void half_step_pressure(const Field3& p_half) const { (void)p_half; }
  // The predictor (u, v, w: the start-of-step velocities; rho, e: the start-of-step state):
  // the module's nodal forces on the owned nodes, or nullptr (adds_forces() false).
  virtual const std::array<Field3, 3>* predictor(const Field3& u, const Field3& v, const Field3& w,
                                                 const Field3& rho, const Field3& e,
                                                 const Field3& p_half, Real dt) {
    (void)u, (void)v, (void)w, (void)rho, (void)e, (void)p_half, (void)dt;
    return nullptr;
  }
  // The corrector, before the hydro's own (ub, vb, wb: the time-centred velocities; rho, e
  // still the start-of-step state).
  virtual void corrector(const Field3& ub, const Field3& vb, const Field3& wb, const Field3& rho,
                         const Field3& e, const Field3& p_half, Real dt) {
    (void)ub, (void)vb, (void)wb, (void)rho, (void)e, (void)p_half, (void)dt;
  }
  // After the Lagrangian step of length dt (rho the new density).
  virtual void after_lagrange(const Field3& rho, Real dt) { (void)rho, (void)dt; }
  // A remap step over the faces normal to `axes`, before the cell densities change: the
  // module's per-mass quantities on their carriers (carriers() order; a single-material
  // scene's: the cell's, one per carried set). pre: the cells' volumes before the step.
  virtual void remap(const std::vector<Carrier>& mine, const std::array<bool, 3>& axes,
                     const Field3& pre, int order) {
    (void)mine, (void)axes, (void)pre, (void)order;
  }
  // The same step, after a multi-material scene's material update (what the module keeps in
  // the compact pool).
  virtual void remap_materials(const std::vector<Carrier>& mine, const std::array<bool, 3>& axes,
                               const Field3& pre, int order) {
    (void)mine, (void)axes, (void)pre, (void)order;
  }
  // The cell fields of carrier `slot` (carriers() order) that hold nothing where its materials
  // are absent (the hydro zeroes them there after a multi-material remap step).
  virtual std::vector<Field3> carried_fields(int slot) const {
    (void)slot;
    return {};
  }
  // After the material halo exchange of a multi-material scene: the ghosts of what the module
  // keeps beside the materials (the strength module's pooled stress sets).
  virtual void exchange_materials(Halo& halo) { (void)halo; }

  // ---- fields, set-up and restart ----
  // The module's fields that `use` (FieldUse bits) selects, each with its one description; a
  // field the module keeps in the compact pool is gathered into a cell field when dumped or
  // checkpointed, and is not in the cell halo (the module exchanges the pool itself).
  virtual std::vector<FieldSpec> fields(unsigned use) const = 0;
  // A multi-material scene's materials are painted from the deck (not on a restart): what the
  // module derives from the initial materials (the burn module's lighting times). What it
  // derives from them must be a kCheckpoint field, since a restart does not call this.
  virtual void materials_placed() {}
  // A restart: the checkpoint's values were read into `state`, the module's own
  // fields(kCheckpoint) in that order, and the materials are in place. Every field not flagged
  // kCheckpoint is either derived each cycle or built from the deck alone (the module's
  // constructor).
  virtual void restore(const std::vector<FieldSpec>& state) { (void)state; }
  // A restart: the run's clock resumes at t.
  virtual void set_time(double t) { (void)t; }
};

}  // namespace mp::hydro
