// A scene: everything one run needs, read strictly from a YAML deck (docs/decks.md; every key:
// docs/options.md).
#pragma once
#include <array>
#include <map>
#include <string>
#include <vector>

#include "config/deck.hpp"
#include "eos/eos.hpp"
#include "hydro/numerics.hpp"
#include "materials/geometry.hpp"
#include "mesh/mesh.hpp"
#include "strength/flow_stress.hpp"

namespace mp {

// Strength of a material (materials[].strength; kernels/strength/). model "" means none.
struct StrengthSpec {
  strength::FlowStressKind kind = strength::kNoStrength;  // the model, typed
  std::string model;         // "" | elastic_plastic | johnson_cook | steinberg_guinan |
                             // zerilli_armstrong
  std::string library;       // strength library entry (kernels/strength/library.hpp)
  double shear_modulus = 0;  // Mbar (0: the library's)
  double yield = 0;          // Mbar, elastic_plastic's constant flow stress
};

// An explosive's burn (materials[].burn; kernels/burn/). on == false means none.
enum class DetonatorKind { Point, Line, Plane };
struct DetonatorSpec {
  DetonatorKind type = DetonatorKind::Point;  // point (at) | line (from, to) | plane (at, normal)
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
  // closure: pressure_equilibrium puts the two phases at one pressure (kernels/eos/reactive.hpp
  // he_equilibrium); shared_state (the default) both at the cell's (rho, e)
  bool equilibrium = false;
  // Forest Fire (kernels/burn/forest_fire.hpp): the Pop plot log10(x*/cm) = pop_a + pop_b
  // log10(P/Mbar), from the cited table (pop_plot: its name) or given.
  bool forest_fire = false;
  std::string pop_plot;
  double pop_a = 0, pop_b = 0;
  // lighting: host builds the lighting times by the host reference construction over the
  // global grid (kernels/burn/lighting.hpp) instead of the per-rank kernels (the default, device)
  bool host_lighting = false;
};

struct MaterialSpec {
  std::string name;
  std::string library;  // library entry it starts from ("" for a custom material)
  std::string eos = "ideal_gas";
  mp::eos::EosKind eos_kind = mp::eos::kIdealGas;  // the same, typed
  double rho0 = 0;                                 // reference density (0: none given)
  std::map<std::string, double> params;            // EOS parameters, library values overridden
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
  // A smooth density wave: rho * (1 + amplitude * P(s)), s = (x_axis - lo) / length of the box
  // (axis 0, 1, 2) or the sum of the three (3: the diagonal), P the profile of wave_shape
  // (driver/wave.hpp: 0 sine, 1 plateau), averaged exactly over each cell (for convergence
  // studies). amplitude 0: none.
  double wave_amplitude = 0;
  int wave_axis = 0;
  int wave_shape = 0;
};

// time.*: the step's controls (cfl, growth, dt_max) with the hydro's defaults, and the run's
// span.
struct TimeSpec : hydro::StepControl {
  double end = 0;
  double dt_initial = 1e-4;
  long max_cycles = 1000000;
};

// numerics.*: the hydro's typed numerics (kernels/hydro/numerics.hpp, their one set of
// defaults) and what the set-up alone uses.
struct NumericsSpec : hydro::Numerics {
  int samples = 4;          // sub-cell samples per axis for the initial volume fractions
  double void_density = 0;  // g/cm^3: below it a material has no pressure, no sound (0: off)
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
  // The boundary mass ledger (output.mass_ledger): each material's mass out through each face
  // of the mesh, in summary.json and the run log.
  bool mass_ledger = false;
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
