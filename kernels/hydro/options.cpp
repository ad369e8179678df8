// hydro::Options from the deck's typed numerics (numerics.hpp): the one place where a deck's
// choices become the cycle's switches and Real coefficients.
#include "hydro/hydro.hpp"

namespace mp::hydro {

Options::Options(const Numerics& n, const StepControl& t)
    : order(advection_order(n.advection)),
      q_linear(Real(n.q_linear)),
      q_quadratic(Real(n.q_quadratic)),
      q_isotropic(Real(n.q_isotropic)),
      heat_flux(Real(n.heat_flux)),
      mid_geometry(n.geometry == StepGeometry::MidStep),
      free_expansion(Real(n.free_expansion)),
      cfl(Real(t.cfl)),
      rule(t.rule),
      cfl_transport(Real(t.transport())),
      growth(Real(t.growth)),
      dt_max(Real(t.dt_max)),
      ke_fix(n.ke_fix),
      ke_fix_by_mass(n.ke_fix_share == KeFixShare::Mass),
      ke_fix_redo(n.ke_fix_redo),
      unsplit(n.remap == Remap::Unsplit),
      layout(n.layout),
      interface(n.interface),
      min_fraction(Real(effective_min_fraction(n.min_fraction))),
      relax(n.closure == Closure::Relaxation),
      relax_iterations(n.relaxation_iterations),
      solid_floor(Real(n.solid_floor)) {}

}  // namespace mp::hydro
