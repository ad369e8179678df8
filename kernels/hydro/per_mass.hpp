// Cell quantities carried per unit mass through the remap (DESIGN.md §4.1, "material scalars"
// of single-material scenes): the strength module's deviator and plastic strain, the burn
// module's burn fraction. One path for all of them, the internal energy's: van Leer face values
// time-centred by the donor's mass Courant number, with the cell mass fluxes of the step.
#pragma once
#include <array>
#include <vector>

#include "mesh/mesh.hpp"

namespace mp::hydro {

// One remap step over the faces normal to `axes` for every field in `fields`, on the owned cells
// (the halo fills the ghosts after the step). `rho` and `pre` are the cell density and volume
// before the step (call before the cell update changes rho); `scratch` is a cell field the
// function overwrites.
void remap_per_mass(const Mesh& mesh, const std::array<bool, 3>& axes,
                    const std::array<Field3, 3>& mass_flux, const Field3& rho, const Field3& pre,
                    const std::vector<Field3>& fields, const Field3& scratch, int order);

// The same step for one quantity whose values before the step are `old` (every cell the owned
// cells' fluxes read: the owned cells and two layers of ghosts), written to `phi` on the owned
// cells; the arithmetic of remap_per_mass, operand for operand.
void remap_per_mass_from(const Mesh& mesh, const std::array<bool, 3>& axes,
                         const std::array<Field3, 3>& mass_flux, const Field3& rho,
                         const Field3& pre, const Field3& old, const Field3& phi, int order);

}  // namespace mp::hydro
