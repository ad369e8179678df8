// The numerics a scene chooses, typed, with the one set of defaults: the deck reader
// (src/config/scene.cpp) reads numerics.* and time.cfl / growth / dt_max into these structs,
// and hydro::Options (hydro.hpp) is built from them, so a Hydro built from default options runs
// the numerics of a deck that sets nothing. docs/numerics.md says what each one does.
#pragma once

#include "materials/layout_kind.hpp"

namespace mp::hydro {

// numerics.advection: second-order van Leer, first-order donor cell, or the third-order
// Courant-weighted 3-point slope under van Leer's monotonicity bound (remap/advect.hpp)
enum class Advection { Second, First, Third };

// The face values' order (remap::face_value's `order`) of an advection choice.
constexpr int advection_order(Advection a) {
  switch (a) {
    case Advection::First:
      return 1;
    case Advection::Second:
      return 2;
    case Advection::Third:
      return 3;
  }
  return 2;
}
// numerics.remap: alternating split sweeps, or one unsplit step over the three axes
enum class Remap { Split, Unsplit };
// numerics.geometry: the Lagrangian step's forces and work on the faces moved by dt/2
// (mid-step), or on the undeformed faces (fixed)
enum class StepGeometry { MidStep, Fixed };
// numerics.ke_fix_share: a multi-material node's kinetic-energy loss to its 8 cells by their
// mass, or an eighth each
enum class KeFixShare { Mass, Equal };
// numerics.interface: material fluxes from PLIC with Youngs' normal, PLIC with an ELVIRA-type
// normal (remap/plic.hpp elvira_normal), SLIC, or fraction-weighted (none)
enum class Interface { Youngs, Slic, None, Elvira };
// numerics.closure: mixed cells at equal strain, or equal strain then pressure relaxation
enum class Closure { EqualStrain, Relaxation };

// Which numerics apply to which scenes: single-material only (a multi-material deck that sets
// one is refused), multi-material only (the reverse), or every scene.
enum class Applies { Any, SingleMaterial, MultiMaterial };

struct Numerics {
  Advection advection = Advection::Second;
  Remap remap = Remap::Split;  // (single-material)
  // the viscous stress Q = q ((1 - b) S + b I): linear (Landshoff) and quadratic (von Neumann-
  // Richtmyer) coefficients of q, b the isotropic part (0 the tensor, 1 a scalar q added to p)
  double q_linear = 0.2;
  double q_quadratic = 0.75;
  double q_isotropic = 0.0;
  // Noh's artificial heat flux, its coefficient h (conduction.cpp); 0 off (single-material)
  double heat_flux = 16.0;
  // the Lagrangian step's geometry (single-material scenes without strength)
  StepGeometry geometry = StepGeometry::MidStep;
  // the free-expansion rule's density ratio (point.hpp expansion_share); 0 off (single-material
  // ideal gas on split sweeps with the KE fix)
  double free_expansion = 0.7;
  bool ke_fix = true;                          // DeBar's KE fix (Benson 1992)
  KeFixShare ke_fix_share = KeFixShare::Mass;  // (multi-material)
  bool ke_fix_redo = true;  // donor-value redo of flagged nodes (single-material)
  // multi-material scenes
  mat::LayoutKind layout = mat::LayoutKind::Compact;
  Interface interface = Interface::Youngs;
  double min_fraction = 1e-14;  // a material below this volume fraction leaves a cell
  Closure closure = Closure::EqualStrain;
  int relaxation_iterations = 20;  // most pressure-relaxation Newton updates per cycle
  double solid_floor = 0;          // least rho/rho0 of a Mie-Grueneisen material in a mixed cell
};

// time.rule: the time step's stability rule (diagnostics.cpp CflCells; docs/numerics.md, "Time
// step"). Combined: dt = cfl dx / (c_eff + |u|) per axis, with the linear viscosity's bound.
// Separate: dt = min(cfl dx / c_eff, cfl_transport dx / |u|) per axis. CloverLeaf: UK-MAC
// CloverLeaf3D_ref's rule (calc_dt_kernel.f90, subroutine calc_dt_kernel): cfl min(dx) / c_eff,
// cfl_transport dx / |face-averaged u| per axis and cfl_transport / |div u|.
enum class StepRule { Combined, Separate, CloverLeaf };

// The time step's controls (the deck's time.cfl, time.rule, time.cfl_transport, time.growth,
// time.dt_max).
struct StepControl {
  double cfl = 0.5;
  // the default: perf/results/timestep_rules.md's winner at equal work (docs/numerics.md, "Time
  // step", says why)
  StepRule rule = StepRule::CloverLeaf;
  // the transport (and, for CloverLeaf's rule, divergence) limits' safety factor; the combined
  // rule ignores it. 0 (the default): the cfl's value (transport() resolves it).
  double cfl_transport = 0;
  double transport() const { return cfl_transport > 0 ? cfl_transport : cfl; }
  double growth = 1.1;
  double dt_max = 1e30;
};

}  // namespace mp::hydro
