#include "config/catalogue.hpp"

#include <sstream>
#include <vector>

#include "config/scene.hpp"

namespace mp {

namespace {

// Decks that between them take every branch of the reader (every section, EOS kind, strength
// model, detonator type and shape), so that every key it accepts is listed and read once.
const char* const kCatalogueDecks[] = {
    R"(scene: single
description: every single-material key
mesh: {cells: [4, 4, 4], lo: [0, 0, 0], hi: [1, 1, 1], ranks: [0, 0, 0]}
boundaries: {x: reflective, y: {lo: reflective, hi: outflow}, z: periodic}
time: {end: 1, cfl: 0.5, rule: combined, cfl_transport: 0.5, dt_initial: 1.0e-4, dt_max: 1,
       growth: 1.1, max_cycles: 10}
numerics:
  advection: second
  remap: split
  viscosity: {linear: 0.2, quadratic: 0.75, isotropic: 0}
  heat_flux: 16
  geometry: midstep
  free_expansion: 0.7
  ke_fix: true
  ke_fix_redo: true
  samples: 4
  void_density: 0
materials: [{name: gas, eos: ideal_gas, gamma: 1.4, p_min: -1.0e-3}]
regions:
  - {material: gas, shape: all, density: 1, pressure: 1, wave: {amplitude: 0.1, axis: x}}
  - {material: gas, shape: box, lo: [0, 0, 0], hi: [0.5, 1, 1], density: 1, energy: 1,
     velocity: [0, 0, 0], deposit: 1}
  - {material: gas, shape: sphere, center: [0.5, 0.5, 0.5], radius: 0.3, density: 1,
     pressure: 1, radial_velocity: {speed: -1, center: [0, 0, 0]}}
output: {dir: out, interval: 0.1, write: true, log_every: 10,
         checkpoint_every: {cycles: 0, seconds: 0}, checkpoint_keep: 2,
         mass_ledger: false}
)",
    R"(scene: multi
mesh: {zone: 0.25, lo: [0, 0, 0], hi: [1, 1, 1]}
time: {end: 1}
numerics: {layout: compact, interface: youngs, min_fraction: 1.0e-14, closure: equal_strain,
           relaxation_iterations: 20, solid_floor: 0, ke_fix_share: mass}
materials:
  - {name: cu, library: copper, params: {gamma0: 2.0},
     strength: {model: johnson_cook, library: copper, shear_modulus: 0.45}}
  - {name: water, eos: stiffened_gas, params: {gamma: 4.4, p_inf: 6.0e-3}}
  - {name: metal, eos: mie_gruneisen, rho0: 8.9, params: {c0: 0.39, s: 1.5, gamma0: 2.0},
     strength: {model: elastic_plastic, shear_modulus: 0.45, yield: 0.001}}
  - {name: solid, eos: polynomial, rho0: 2.7, params: {A1: 0.7, A2: 0.5, A3: 0.1, B0: 2.0, B1: 0}}
  - {name: he, eos: jwl, rho0: 1.84, params: {A: 8.5, B: 0.18, R1: 4.6, R2: 1.3, omega: 0.38,
     E0: 0.1, D: 0.88, p_cj: 0.37}}
  - name: pbx
    library: pbx9404_products
    burn:
      ramp_cells: 2
      programmed: true
      volume_burn: true
      unreacted: pbx9404_unreacted
      forest_fire: {pop_plot: pbx9404}
      detonators:
        - {type: point, at: [0, 0, 0], time: 0}
        - {type: line, from: [0, 0, 0], to: [0, 0, 1]}
        - {type: plane, at: [0, 0, 0], normal: [0, 0, 1]}
regions:
  - {material: water, shape: all, density: 1, pressure: 1.0e-6}
  - {material: cu, shape: cylinder, base: [0.5, 0.5, 0], top: [0.5, 0.5, 1], radius: 0.2,
     density: 8.9, pressure: 0}
  - {material: metal, shape: cone, base: [0.5, 0.5, 0], top: [0.5, 0.5, 1], radius: 0.2,
     radius_top: 0.1, density: 8.9, pressure: 0}
  - material: pbx
    shape: shell
    center: [0.5, 0.5, 0.5]
    inner_radius: 0.1
    outer_radius: 0.3
    density: 1.84
    energy: 0.05
    union:
      - {shape: box, lo: [0, 0, 0], hi: [0.1, 0.1, 0.1]}
      - {shape: sphere, center: [0, 0, 0], radius: 0.1}
      - {shape: cylinder, base: [0, 0, 0], top: [0, 0, 0.1], radius: 0.1}
      - {shape: cone, base: [0, 0, 0], top: [0, 0, 0.1], radius: 0.1, radius_top: 0}
      - {shape: shell, center: [0, 0, 0], inner_radius: 0.1, outer_radius: 0.2}
    minus:
      - {shape: box, lo: [0, 0, 0], hi: [0.1, 0.1, 0.1]}
      - {shape: sphere, center: [0, 0, 0], radius: 0.1}
      - {shape: cylinder, base: [0, 0, 0], top: [0, 0, 0.1], radius: 0.1}
      - {shape: cone, base: [0, 0, 0], top: [0, 0, 0.1], radius: 0.1, radius_top: 0}
      - {shape: shell, center: [0, 0, 0], inner_radius: 0.1, outer_radius: 0.2}
  - {material: solid, shape: box, lo: [0, 0, 0], hi: [0.2, 0.2, 0.2], density: 2.7, pressure: 0}
  - {material: he, shape: box, lo: [0.8, 0.8, 0.8], hi: [1, 1, 1], density: 1.84, pressure: 0}
)",
    R"(scene: forest_fire
mesh: {cells: [2, 2, 4], hi: [0.1, 0.1, 0.2]}
time: {end: 1}
materials:
  - name: pbx
    library: pbx9404_products
    burn: {programmed: false, unreacted: pbx9404_unreacted,
           forest_fire: {a: -2.37, b: -1.54}}
regions: [{material: pbx, density: 1.844, energy: 0.0554}]
)",
    R"(scene: faces
mesh: {cells: [4, 4, 4], hi: [1, 1, 1]}
boundaries: {x: {lo: outflow, hi: outflow}, y: outflow, z: {lo: periodic, hi: periodic}}
time: {end: 1}
materials: [{name: gas, eos: ideal_gas, params: {gamma: 1.4}}]
regions: [{material: gas, density: 1, pressure: 1}]
)",
};

// A default the reader's fallback cannot say on its own (it depends on another key).
const std::map<std::string, std::string>& default_overrides() {
  static const std::map<std::string, std::string> d{
      {"materials[].rho0", "the library entry's; none for a custom material"},
      {"materials[].strength.library", "the material's own `library`"},
      {"materials[].strength.shear_modulus", "the strength library's G0"},
      {"materials[].burn.detonation_speed", "a JWL EOS's `D`; else required"},
      {"materials[].burn.cj_pressure", "a JWL EOS's `p_cj`; else required"},
      {"materials[].burn.detonators[].type", "required"},
      {"materials[].burn.detonators", "required with `programmed: true`"},
      {"materials[].params", "the library entry's"},
      {"materials[].eos", "required without `library`"},
      {"time.cfl_transport", "the deck's `time.cfl`"},
      {"boundaries.x", "`reflective`"},
      {"boundaries.y", "`reflective`"},
      {"boundaries.z", "`reflective`"},
      {"boundaries.x.lo", "`reflective`"},
      {"boundaries.x.hi", "`reflective`"},
      {"boundaries.y.lo", "`reflective`"},
      {"boundaries.y.hi", "`reflective`"},
      {"boundaries.z.lo", "`reflective`"},
      {"boundaries.z.hi", "`reflective`"},
  };
  return d;
}

// A shape's placing keys (regions[].lo, regions[].union[].radius, ...) are required by the
// shapes that have them and refused by none (the others ignore them).
bool shape_key(const std::string& key) {
  for (const char* k :
       {"lo", "hi", "center", "radius", "base", "top", "inner_radius", "outer_radius"}) {
    const std::string tail = std::string("].") + k;
    if (key.compare(0, 8, "regions[") == 0 && key.size() > tail.size() &&
        key.compare(key.size() - tail.size(), tail.size(), tail) == 0)
      return true;
  }
  return false;
}

std::string section_of(const std::string& key) {
  const std::string first = key.substr(0, key.find('.'));
  const std::string name = first.substr(0, first.find('['));
  return name == "scene" || name == "description" ? "" : name;
}

std::string cell(std::string s) {  // a table cell: no '|' breaks the row
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

std::map<std::string, KeyInfo> accepted_keys() {
  KeyCatalogue catalogue;
  KeyCatalogue*& active = KeyCatalogue::active();
  KeyCatalogue* before = active;
  active = &catalogue;
  try {
    for (const char* text : kCatalogueDecks) read_scene(Deck::parse(text, "catalogue"));
  } catch (...) {
    active = before;
    throw;
  }
  active = before;
  return catalogue.keys;
}

const std::map<std::string, std::string>& key_notes() {
  static const std::map<std::string, std::string> n{
      {"scene", "names the output files (1-128 letters, digits, _ and -)"},
      {"description", "free text"},
      {"mesh", "the global box and its cells"},
      {"mesh.cells", "cells per axis (>= 2 per rank per axis); give `cells` or `zone`"},
      {"mesh.zone", "one cell size instead: cells = round((hi - lo) / zone), > 0"},
      {"mesh.lo", "low corner of the box"},
      {"mesh.hi", "high corner (above lo on every axis)"},
      {"mesh.ranks", "ranks per axis; 0: MPI_Dims_create chooses; must match the rank count"},
      {"boundaries", "per axis (`x: outflow`) or per face (`y: {lo: .., hi: ..}`)"},
      {"boundaries.x", "both faces of x"},
      {"boundaries.y", "both faces of y"},
      {"boundaries.z", "both faces of z"},
      {"boundaries.x.lo", "face x = lo (periodic only on both faces)"},
      {"boundaries.x.hi", "face x = hi"},
      {"boundaries.y.lo", "face y = lo"},
      {"boundaries.y.hi", "face y = hi"},
      {"boundaries.z.lo", "face z = lo"},
      {"boundaries.z.hi", "face z = hi"},
      {"time", "end time and the time step's controls"},
      {"time.end", "simulated end time, > 0"},
      {"time.cfl", "Courant number"},
      {"time.rule",
       "combined: dx / (c + |u|); separate: dx / c and dx / |u| apart; cloverleaf: "
       "CloverLeaf3D's (docs/numerics.md)"},
      {"time.cfl_transport",
       "safety factor of the |u| (and div u) limits of the separate and cloverleaf rules"},
      {"time.dt_initial", "first step at most this"},
      {"time.dt_max", "largest step"},
      {"time.growth", "step grows at most this factor per cycle"},
      {"time.max_cycles", "stop after this many cycles (exit 0, status max_cycles)"},
      {"numerics", "the method's options (docs/numerics.md)"},
      {"numerics.advection",
       "second: van Leer; first: donor cell; third: QUICKEST 3-point slope, van Leer's bound"},
      {"numerics.remap",
       "split: alternating sweeps; unsplit: one axis-symmetric step (single "
       "material)"},
      {"numerics.viscosity", "artificial viscosity coefficients"},
      {"numerics.viscosity.linear", "c_L, on the sum of the limited jumps"},
      {"numerics.viscosity.quadratic", "c_Q, on the norm of the limited jumps"},
      {"numerics.viscosity.isotropic", "0: tensor q .. 1: scalar q"},
      {"numerics.heat_flux", "Noh's heat flux h in converging shocks; 0 off (single material)"},
      {"numerics.geometry", "Lagrangian faces moved by dt/2, or fixed (single material)"},
      {"numerics.free_expansion",
       "density ratio below which entering gas's expansion energy "
       "goes to the nodes; 0 off (single material)"},
      {"numerics.ke_fix", "return the remap's kinetic-energy loss as heat"},
      {"numerics.ke_fix_share",
       "a node's loss to its cells by mass, or 1/8 each (multi "
       "material)"},
      {"numerics.ke_fix_redo", "donor values where the cells cannot pay (single material)"},
      {"numerics.samples", "sub-cell samples per axis for the initial fractions"},
      {"numerics.layout", "per-material storage (multi material)"},
      {"numerics.interface",
       "material fluxes: PLIC (Youngs or ELVIRA-type normal), SLIC, or none (multi material)"},
      {"numerics.min_fraction", "a material below this fraction leaves a cell (multi material)"},
      {"numerics.closure", "mixed cells: equal strain or pressure relaxation (multi material)"},
      {"numerics.relaxation_iterations",
       "most relaxation updates per cell and cycle (multi "
       "material)"},
      {"numerics.solid_floor",
       "least rho/rho0 of a Mie-Grueneisen solid in a mixed cell; 0 off "
       "(multi material)"},
      {"numerics.void_density", "g/cm3: below it a material has no pressure, no sound; 0 off"},
      {"materials", "1 to 16; two or more make a multi-material scene"},
      {"materials[].name", "the name regions refer to"},
      {"materials[].library", "a cited library entry (kernels/materials/library.hpp)"},
      {"materials[].eos", "the EOS of a custom material"},
      {"materials[].rho0", "reference density, g/cm3 (required but for the gases)"},
      {"materials[].params", "EOS parameters; override a library entry's"},
      {"materials[].params.gamma", "ideal and stiffened gas: ratio of specific heats, (1, 100]"},
      {"materials[].params.p_inf", "stiffened gas: stiffening pressure, >= 0"},
      {"materials[].params.c0", "Mie-Grueneisen: bulk sound speed, > 0"},
      {"materials[].params.s", "Mie-Grueneisen: Us-up slope, [0, 100]"},
      {"materials[].params.gamma0", "Mie-Grueneisen: Grueneisen coefficient, [0, 100]"},
      {"materials[].params.A1", "polynomial: bulk modulus, > 0"},
      {"materials[].params.A2", "polynomial: second-order coefficient"},
      {"materials[].params.A3", "polynomial: third-order coefficient"},
      {"materials[].params.B0", "polynomial: energy coefficient"},
      {"materials[].params.B1", "polynomial: energy coefficient"},
      {"materials[].params.A", "JWL: A, >= 0"},
      {"materials[].params.B", "JWL: B, >= 0"},
      {"materials[].params.R1", "JWL: R1, (0, 1000]"},
      {"materials[].params.R2", "JWL: R2, (0, 1000]"},
      {"materials[].params.omega", "JWL: omega, (0, 10]"},
      {"materials[].params.E0", "JWL: detonation energy per unit initial volume, >= 0"},
      {"materials[].params.D", "JWL: detonation speed, > 0"},
      {"materials[].params.p_cj", "JWL: CJ pressure, > 0"},
      {"materials[].gamma", "shorthand for params.gamma (the gases)"},
      {"materials[].p_min", "tension cutoff (Mbar, <= 0); off unless given"},
      {"materials[].strength", "elastic-plastic strength (docs/numerics.md, Strength)"},
      {"materials[].strength.model", "flow stress model"},
      {"materials[].strength.library", "strength library entry (kernels/strength/library.hpp)"},
      {"materials[].strength.shear_modulus", "shear modulus G, Mbar"},
      {"materials[].strength.yield",
       "elastic_plastic's constant yield stress, Mbar (required "
       "there, refused otherwise)"},
      {"materials[].burn", "high-explosive burn; one explosive per scene"},
      {"materials[].burn.detonation_speed", "D, cm/us"},
      {"materials[].burn.cj_pressure", "p_cj, Mbar (below rho0 D^2)"},
      {"materials[].burn.detonators", "required with programmed: true"},
      {"materials[].burn.detonators[].type", "point (at), line (from, to), plane (at, normal)"},
      {"materials[].burn.detonators[].at", "a point detonator's place, or a point on a plane"},
      {"materials[].burn.detonators[].from", "a line detonator's first end"},
      {"materials[].burn.detonators[].to", "a line detonator's second end"},
      {"materials[].burn.detonators[].normal", "a plane detonator's normal (non-zero)"},
      {"materials[].burn.detonators[].time", "firing time"},
      {"materials[].burn.ramp_cells", "programmed burn's ramp, in largest cell edges"},
      {"materials[].burn.programmed", "programmed burn from lighting times"},
      {"materials[].burn.volume_burn", "CJ volume burn"},
      {"materials[].burn.lighting",
       "lighting times by per-rank kernels (device) or the host reference over the global grid "
       "(host; kernels/burn/lighting.hpp)"},
      {"materials[].burn.closure",
       "with `unreacted`: both phases at the cell's state, or at one pressure (docs/numerics.md)"},
      {"materials[].burn.forest_fire",
       "Forest Fire reactive burn from a Pop plot (needs `unreacted`)"},
      {"materials[].burn.forest_fire.pop_plot",
       "a cited Pop plot (kernels/burn/forest_fire.hpp: pbx9404); or give a and b"},
      {"materials[].burn.forest_fire.a", "Pop plot log10(x*/cm) = a + b log10(P/Mbar): a"},
      {"materials[].burn.forest_fire.b", "the Pop plot's slope b, < 0"},
      {"materials[].burn.unreacted",
       "library entry of the unreacted solid (Mie-Grueneisen; "
       "JWL products with E0)"},
      {"regions", "painted in order; the first is `shape: all`"},
      {"regions[].material", "a material's name"},
      {"regions[].shape", "the region's primary shape"},
      {"regions[].union", "shapes added to the primary"},
      {"regions[].union[].shape", "an added shape (not all), with its placing keys"},
      {"regions[].minus[].shape", "a shape taken away (not all), with its placing keys"},
      {"regions[].minus", "shapes taken away"},
      {"regions[].density", "initial density, > 0"},
      {"regions[].pressure", "initial pressure; give `pressure` or `energy`"},
      {"regions[].energy", "initial specific internal energy"},
      {"regions[].velocity", "initial velocity"},
      {"regions[].radial_velocity", "or a radial velocity (not both)"},
      {"regions[].radial_velocity.speed", "speed along the unit vector from center"},
      {"regions[].radial_velocity.center", "centre"},
      {"regions[].deposit", "total energy added over the region's cells (point blasts)"},
      {"regions[].wave", "a smooth density wave (convergence studies)"},
      {"regions[].wave.amplitude", "relative amplitude"},
      {"regions[].wave.axis", "axis of the wave (diagonal: along (1, 1, 1))"},
      {"regions[].wave.shape", "sine, or plateau (flat extrema: smooth joints, for order studies)"},
      {"regions[].lo", "box: low corner"},
      {"regions[].hi", "box: high corner"},
      {"regions[].center", "sphere, shell: centre"},
      {"regions[].radius", "sphere, cylinder, cone (base): radius, > 0"},
      {"regions[].base", "cylinder, cone: centre of the base"},
      {"regions[].top", "cylinder, cone: centre of the top"},
      {"regions[].radius_top", "cone: radius at the top"},
      {"regions[].inner_radius", "shell: inner radius"},
      {"regions[].outer_radius", "shell: outer radius (above inner)"},
      {"output", "dumps, log and checkpoints"},
      {"output.dir", "output directory (--output overrides)"},
      {"output.interval", "simulated time between dumps; 0: first and last only"},
      {"output.write", "false: only summary.json (and checkpoints)"},
      {"output.log_every", "cycles between log lines"},
      {"output.checkpoint_every", "checkpoints by cycles and/or wall seconds; 0: off"},
      {"output.checkpoint_every.cycles", "cycles between checkpoints"},
      {"output.checkpoint_every.seconds", "wall seconds between checkpoints"},
      {"output.checkpoint_keep", "newest checkpoints kept"},
      {"output.mass_ledger", "each material's mass out through each boundary face (summary.json)"},
  };
  return n;
}

namespace {
// A key's meaning; the keys of union[] and minus[] items mean what the region's own do.
std::string note_of(const std::string& key) {
  const auto& n = key_notes();
  auto it = n.find(key);
  if (it != n.end()) return it->second;
  for (const char* list : {"regions[].union[].", "regions[].minus[]."}) {
    const std::string p = list;
    if (key.compare(0, p.size(), p) == 0) {
      it = n.find("regions[]." + key.substr(p.size()));
      if (it != n.end()) return it->second;
    }
  }
  return "";
}
}  // namespace

std::string options_markdown() {
  const auto keys = accepted_keys();
  std::ostringstream os;
  os << "# Deck keys\n\n"
        "Every key the scene reader accepts, with its type, range or choices, and default. "
        "Generated by\n`minipagosa --list-keys > docs/options.md` from the reader itself "
        "(src/config/catalogue.cpp);\nthe CTest test `test_docs` fails when this file and "
        "the reader differ. The deck format,\nannotated: [decks.md](decks.md); what each "
        "numerics option does: [numerics.md](numerics.md).\n\n"
        "Units: any consistent set for the gas problems; the materials library uses cm, g, us "
        "(pressure in\nMbar, velocity in cm/us, specific energy in cm2/us2). `[]` marks a list "
        "item. A default of \"none\"\nmeans the key is optional and has no value unless given; "
        "\"required\" that the deck must give it.\nA numerics key marked single or multi "
        "material is refused on the other kind of scene.\n";
  const char* const sections[] = {"",         "mesh",      "boundaries", "time",
                                  "numerics", "materials", "regions",    "output"};
  for (const char* section : sections) {
    os << "\n## " << (*section ? section : "top level") << "\n\n"
       << "| key | type | range / choices | default | meaning |\n|---|---|---|---|---|\n";
    for (const auto& [key, info] : keys) {
      if (section_of(key) != section) continue;
      bool has_children = false;
      for (const auto& other : keys)
        if (other.first.size() > key.size() && other.first.compare(0, key.size(), key) == 0 &&
            (other.first[key.size()] == '.' || other.first[key.size()] == '['))
          has_children = true;
      const auto item = keys.lower_bound(key + "[].");
      const bool is_list =
          item != keys.end() && item->first.compare(0, key.size() + 3, key + "[].") == 0;
      std::string type = info.type;
      if (has_children) {
        const std::string shape = is_list ? "list" : "map";
        type = type.empty() ? shape : type + " or " + shape;
      }
      std::string def;
      const auto over = default_overrides().find(key);
      if (over != default_overrides().end()) {
        def = over->second;
      } else if (shape_key(key) && info.defaults.empty()) {
        def = "required by its shape";
      } else if (!info.defaults.empty()) {
        for (const auto& d : info.defaults)
          def += (def.empty() ? "" : " / ") + ("`" + (d.empty() ? std::string("\"\"") : d) + "`");
      } else if (info.type.empty()) {
        def = info.probed ? "optional" : "required";  // a section
      } else {
        def = info.probed ? "none" : "required";
      }
      // an EOS parameter's physical range depends on the EOS (in the meaning column)
      const std::string range =
          key.compare(0, 19, "materials[].params.") == 0 ? "by EOS (meaning)" : info.range;
      os << "| `" << key << "` | " << type << " | " << cell(range) << " | " << cell(def) << " | "
         << cell(note_of(key)) << " |\n";
    }
  }
  return os.str();
}

}  // namespace mp
