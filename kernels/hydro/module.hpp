// The seam between the hydro and a physics module (strength, burn): what every module tells the
// hydro and the driver about itself, host-side, called once per phase and never inside a
// kernel. A module registers its fields once (mesh/field.hpp FieldSpec): the dumps, the
// checkpoints and the cell halo take them from here, so nothing outside the module names them.
// (docs/architecture.md, "The cycle and the modules".)
#pragma once
#include <vector>

#include "mesh/field.hpp"

namespace mp::hydro {

class Module {
 public:
  virtual ~Module() = default;
  // "strength", "burn" (the run log's and the launch profile's word).
  virtual const char* name() const = 0;
  // The module's fields that `use` (FieldUse bits) selects, each with its one description; a
  // field the module keeps in the compact pool is gathered into a cell field when dumped or
  // checkpointed, and is not in the cell halo (the module exchanges the pool itself).
  virtual std::vector<FieldSpec> fields(unsigned use) const = 0;
  // After the material halo exchange of a multi-material scene: the ghosts of what the module
  // keeps beside the materials (the strength module's pooled stress sets).
  virtual void exchange_materials(Halo& halo) { (void)halo; }
  // A multi-material scene's materials are in place (painted, or read from a checkpoint): what
  // the module derives from them (the burn module's lighting times).
  virtual void materials_placed() {}
  // A restart: the checkpoint's values were read into the views fields(kCheckpoint) gave, in
  // that order, and the materials are in place.
  virtual void restore(const std::vector<FieldSpec>& state) { (void)state; }
  // A restart: the run's clock resumes at t.
  virtual void set_time(double t) { (void)t; }
};

}  // namespace mp::hydro
