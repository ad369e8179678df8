// A scene: everything one run needs, read strictly from a YAML deck (see README, "Scene decks").
#pragma once
#include <array>
#include <map>
#include <string>
#include <vector>

#include "config/deck.hpp"
#include "materials/geometry.hpp"
#include "mesh/mesh.hpp"

namespace mp {

// Strength of a material (materials[].strength; kernels/strength/). model "" means none.
struct StrengthSpec {
  std::string model;         // "" | elastic_plastic | johnson_cook | steinberg_guinan |
                             // zerilli_armstrong
  std::string library;       // strength library entry (kernels/strength/library.hpp)
  double shear_modulus = 0;  // Mbar (0: the library's)
  double yield = 0;          // Mbar, elastic_plastic's constant flow stress
};

// An explosive's burn (materials[].burn; kernels/burn/). on == false means none.
struct DetonatorSpec {
  std::string type = "point";  // point (at) | line (from, to) | plane (at, normal)
  std::array<double, 3> a{}, b{};
  double time = 0;  // firing time
};
struct BurnSpec {
  bool on = false;
  double detonation_speed = 0, cj_pressure = 0;  // cm/us, Mbar (JWL: default D, p_cj)
  double ramp_cells = 2;
  bool programmed = true, volume_burn = false;
  std::vector<DetonatorSpec> detonators;
  // The unreacted solid's EOS (library entry; "" for none: p = F P_products). With one the
  // explosive's pressure is (1 - F) P_unreacted(rho, e - e0) + F P_products(rho, e),
  // e0 = E0 / rho0 of the JWL products (kernels/burn/burn.hpp he_pressure_mixed).
  std::string unreacted;
  double unreacted_e0 = 0;  // cm^2/us^2
};

struct MaterialSpec {
  std::string name;
  std::string library;  // library entry it starts from ("" for a custom material)
  std::string eos = "ideal_gas";
  double rho0 = 0;                       // reference density (0: none given)
  std::map<std::string, double> params;  // EOS parameters, library values overridden
  std::string citation;
  bool has_p_min = false;  // tension cutoff given (materials[].p_min, Mbar, <= 0)
  double p_min = 0;
  StrengthSpec strength;
  BurnSpec burn;
};

struct ShapeSpec {
  std::string kind = "all";  // of the primary: all | box | sphere | cylinder | cone | shell
  geom::Shape shape;         // (primary ∪ union terms) − minus terms
  bool contains(double x, double y, double z) const { return shape.contains(x, y, z); }
};

struct RegionSpec {
  std::string material;
  int material_index = 0;
  ShapeSpec shape;
  double density = 1;
  bool has_pressure = false;
  double pressure = 0;  // either pressure or specific internal energy is given
  double energy = 0;
  std::array<double, 3> velocity{};
  bool radial_velocity = false;  // velocity[0] is a speed along the unit vector from `center`
  std::array<double, 3> velocity_center{};
  double deposit =
      0;  // total internal energy added over the region (point blasts), split by volume
  // A smooth density wave: rho * (1 + amplitude * sin(2 pi (x_axis - lo) / length of the box)),
  // averaged exactly over each cell (for convergence studies). amplitude 0: none.
  double wave_amplitude = 0;
  int wave_axis = 0;
};

struct TimeSpec {
  double end = 0;
  double cfl = 0.5;
  double dt_initial = 1e-4;
  double dt_max = 1e30;
  double growth = 1.1;
  long max_cycles = 1000000;
};

struct NumericsSpec {
  std::string advection = "second";  // second | first
  std::string remap = "split";       // split (alternating sweeps) | unsplit
  double q_linear = 0.2;             // linear (Landshoff) artificial viscosity coefficient
  double q_quadratic = 0.75;         // quadratic (von Neumann–Richtmyer) coefficient
  // the isotropic part of the tensor viscosity, Q = q ((1 - b) S + b I): 0 the tensor (the
  // default), 1 a scalar q added to the pressure (docs/numerics.md, "Tensor viscosity")
  double q_isotropic = 0.0;
  // Noh's artificial heat flux, its coefficient h (kernels/hydro/conduction.cpp); 0 off
  double heat_flux = 16.0;
  // the Lagrangian step's geometry: midstep (forces and work on the faces moved by dt/2; single-
  // material scenes without strength; docs/numerics.md "Mid-step geometry") | fixed (the
  // undeformed faces: first-order in dt u / r in converging flow, the cheaper cycle)
  std::string geometry = "midstep";
  // the free-expansion rule (kernels/hydro/point.hpp expansion_share; docs/numerics.md "Free
  // expansion to the nodes"): the density ratio below which a face's gas entering a lighter
  // cell keeps only its isentropically expanded energy, the rest the kinetic energy of the node
  // pairs it pushes apart; 0 off. Single-material ideal-gas scenes on split sweeps, KE fix on.
  double free_expansion = 0.7;
  bool ke_fix = true;                 // return the kinetic energy the momentum remap dissipates
  std::string ke_fix_share = "mass";  // multi-material: a node's loss to its cells by mass | equal
  // single-material: redo the momentum remap with donor values at the nodes that made more
  // kinetic energy than their cells can pay (hydro.hpp, ke_redo); false leaves it to the floor
  bool ke_fix_redo = true;
  int samples = 4;                   // sub-cell samples per axis for the initial volume fractions
  std::string layout = "compact";    // per-material storage: compact | dense
  std::string interface = "youngs";  // material fluxes: youngs (PLIC) | slic | none
  double min_fraction = 1e-14;       // a material below this volume fraction leaves a cell
  std::string closure = "equal_strain";  // mixed cells: equal_strain | relaxation
  int relaxation_iterations = 20;        // most pressure-relaxation Newton updates per cycle
  double void_density = 0;  // g/cm^3: below it a material has no pressure, no sound (0: off)
  double solid_floor = 0;   // mixed cells: least rho/rho0 of a Mie-Grueneisen material (0: none)
};

struct OutputSpec {
  std::string dir = "output";
  std::string basename;  // default: the scene name
  double interval = 0;   // simulated time between dumps; 0: first and last only
  bool write = true;     // false: no HDF5 dumps, only the summary
  long log_every = 10;   // cycles between log lines
  // Checkpoints (output.checkpoint_every: {cycles: N, seconds: S}; 0: not by that measure)
  // and how many of the newest to keep (output.checkpoint_keep).
  long checkpoint_cycles = 0;
  double checkpoint_seconds = 0;
  int checkpoint_keep = 2;
};

struct Scene {
  std::string file;
  std::string name;
  std::string description;
  MeshSpec mesh;
  TimeSpec time;
  NumericsSpec numerics;
  std::vector<MaterialSpec> materials;
  std::vector<RegionSpec> regions;
  OutputSpec output;
  std::map<std::string, std::string> deck_values;  // Deck::values(), for restart checks
};

// Reads and validates the whole deck; throws InputError naming file:line and key.
Scene read_scene(const Deck& deck);

// Every numerics.* value and the time.* values that shape the solution after the start (cfl,
// growth, dt_max), as the run uses them: the deck's where it sets them, else this build's
// defaults. Keyed as in the deck (numerics.viscosity.linear); reals in the fewest of 15 or 17
// digits that read back exactly. A checkpoint records them, so a restart by a build with other
// defaults is refused naming the key (deck_values alone hold only what the deck sets).
std::map<std::string, std::string> resolved_numerics(const Scene& s);

}  // namespace mp
