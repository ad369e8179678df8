#include "config/scene.hpp"

#include "config/options.hpp"
#include "config/readers.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace mp {

namespace {

BoundaryKind boundary_kind(const DeckNode& n, const std::string& key) {
  const std::string v = n.get_enum(key, {"reflective", "outflow", "periodic"});
  if (v == "reflective") return BoundaryKind::Reflective;
  if (v == "outflow") return BoundaryKind::Outflow;
  return BoundaryKind::Periodic;
}

void read_mesh(const DeckNode& root, Scene& s) {
  const DeckNode m = root.child("mesh");
  m.expect_keys({"cells", "zone", "lo", "hi", "ranks"});
  s.mesh.lo = m.get_real3("lo", -kState, kState, {0, 0, 0});
  s.mesh.hi = m.get_real3("hi", -kState, kState);
  s.mesh.ranks = m.get_int3("ranks", 0, 1 << 20, {0, 0, 0});
  for (int d = 0; d < 3; ++d)
    if (!(s.mesh.hi[d] > s.mesh.lo[d]))
      m.child("hi").fail(std::string("upper corner must exceed the lower corner along ") +
                         "xyz"[d]);

  // The resolution is 'cells' (per axis) or 'zone' (one cell size, cm: cells = round((hi - lo) /
  // zone), at least 1), exactly one of them in the file. A --set override of one replaces the
  // other (--set mesh.cells=[16,16,16] coarsens a zone deck, as it does every other deck).
  const bool has_cells = m.has("cells"), has_zone = m.has("zone");
  bool use_zone = has_zone;
  if (has_cells && has_zone) {
    const auto overridden = [&](const char* key) {
      return m.child(key).where().compare(0, 6, "--set ") == 0;
    };
    if (overridden("cells") == overridden("zone"))
      m.fail("give exactly one of 'cells' (cells per axis) or 'zone' (one cell size), not both");
    use_zone = overridden("zone");
  } else if (!has_cells && !has_zone) {
    m.fail("missing required key 'cells' (cells per axis) or 'zone' (one cell size)");
  }
  if (!use_zone) {
    s.mesh.cells = m.get_int3("cells", 1, 1 << 20);
  } else {
    const double zone = m.get_real("zone", -kHuge, kHuge);
    if (!(zone > 0)) m.child("zone").fail("the zone size must be positive");
    for (int d = 0; d < 3; ++d) {
      const double n = std::round((s.mesh.hi[d] - s.mesh.lo[d]) / zone);
      if (!(n <= double(1 << 20)))
        m.child("zone").fail(std::string("the zone size gives more than 2^20 cells along ") +
                             "xyz"[d]);
      s.mesh.cells[d] = std::max(1, static_cast<int>(n));
    }
  }

  for (int d = 0; d < 3; ++d) s.mesh.bc[d] = {BoundaryKind::Reflective, BoundaryKind::Reflective};
  if (!root.has("boundaries")) return;
  const DeckNode b = root.child("boundaries");
  b.expect_keys({"x", "y", "z"});
  for (int d = 0; d < 3; ++d) {
    const std::string axis(1, "xyz"[d]);
    if (!b.has(axis)) continue;
    const DeckNode a = b.child(axis);
    if (a.is_scalar()) {
      const BoundaryKind k = boundary_kind(b, axis);
      s.mesh.bc[d] = {k, k};
    } else {
      a.expect_keys({"lo", "hi"});
      s.mesh.bc[d] = {a.has("lo") ? boundary_kind(a, "lo") : BoundaryKind::Reflective,
                      a.has("hi") ? boundary_kind(a, "hi") : BoundaryKind::Reflective};
      if ((s.mesh.bc[d][0] == BoundaryKind::Periodic) !=
          (s.mesh.bc[d][1] == BoundaryKind::Periodic))
        a.fail("periodic must be set on both faces of an axis (or as '" + axis + ": periodic')");
    }
  }
}

const std::vector<std::string> kShapeKinds = {"all", "box", "sphere", "cylinder", "cone", "shell"};
const std::vector<std::string> kShapeKeys = {
    "lo", "hi", "center", "radius", "base", "top", "radius_top", "inner_radius", "outer_radius"};

void copy3(const std::array<double, 3>& v, double* out) {
  for (int d = 0; d < 3; ++d) out[d] = v[d];
}

// One primitive from the keys of `n` (its kind under `kind_key`).
geom::Primitive read_primitive(const DeckNode& n, const std::string& kind) {
  geom::Primitive p;
  if (kind == "all") {
    p.kind = geom::kAll;
  } else if (kind == "box") {
    p.kind = geom::kBox;
    const auto lo = n.get_real3("lo", -kHuge, kHuge), hi = n.get_real3("hi", -kHuge, kHuge);
    for (int d = 0; d < 3; ++d)
      if (!(hi[d] > lo[d]))
        n.child("hi").fail(std::string("box upper corner must exceed its lower corner along ") +
                           "xyz"[d]);
    copy3(lo, p.a);
    copy3(hi, p.b);
  } else if (kind == "sphere") {
    p.kind = geom::kSphere;
    copy3(n.get_real3("center", -kHuge, kHuge), p.a);
    p.r0 = n.get_real("radius", 0, kHuge);
    if (!(p.r0 > 0)) n.child("radius").fail("sphere radius must be positive");
  } else if (kind == "shell") {
    p.kind = geom::kShell;
    copy3(n.get_real3("center", -kHuge, kHuge), p.a);
    p.r0 = n.get_real("inner_radius", 0, kHuge);
    p.r1 = n.get_real("outer_radius", 0, kHuge);
    if (!(p.r1 > p.r0)) n.child("outer_radius").fail("outer radius must exceed the inner radius");
  } else {  // cylinder, cone
    p.kind = kind == "cylinder" ? geom::kCylinder : geom::kCone;
    const auto base = n.get_real3("base", -kHuge, kHuge), top = n.get_real3("top", -kHuge, kHuge);
    double len2 = 0;
    for (int d = 0; d < 3; ++d) len2 += (top[d] - base[d]) * (top[d] - base[d]);
    if (!(len2 > 0)) n.child("top").fail("the axis from 'base' to 'top' has zero length");
    copy3(base, p.a);
    copy3(top, p.b);
    p.r0 = n.get_real("radius", 0, kHuge);
    if (!(p.r0 > 0)) n.child("radius").fail(kind + " radius must be positive");
    if (kind == "cone") p.r1 = n.get_real("radius_top", 0, kHuge, 0);
  }
  return p;
}

void read_shape(const DeckNode& r, const Scene& s, ShapeSpec& shape) {
  shape.kind = r.get_enum("shape", kShapeKinds, "all");
  shape.shape.primary = read_primitive(r, shape.kind);
  const char* lists[2] = {"union", "minus"};
  for (const char* key : lists) {
    if (!r.has(key)) continue;
    const DeckNode list = r.child(key);
    if (!list.is_sequence() || list.size() == 0) list.fail("expected a list of shapes");
    if (list.size() > std::size_t(geom::kMaxTerms))
      list.fail("at most " + std::to_string(geom::kMaxTerms) + " shapes");
    for (const DeckNode& item : list.items()) {
      std::vector<std::string> keys = kShapeKeys;
      keys.insert(keys.begin(), "shape");
      item.expect_keys(keys);
      const std::string kind = item.get_enum("shape", kShapeKinds);
      if (kind == "all") item.child("shape").fail("'all' cannot be combined");
      const geom::Primitive p = read_primitive(item, kind);
      if (std::string(key) == "union") {
        shape.shape.add[shape.shape.n_add++] = p;
      } else {
        shape.shape.remove[shape.shape.n_remove++] = p;
      }
    }
  }
  if (shape.kind == "all") return;
  double lo[3], hi[3];
  shape.shape.bounds(lo, hi);
  // reported at the key that places the shape
  const std::string where = shape.kind == "box"                                ? "lo"
                            : shape.kind == "cylinder" || shape.kind == "cone" ? "base"
                                                                               : "center";
  for (int d = 0; d < 3; ++d)
    if (hi[d] <= s.mesh.lo[d] || lo[d] >= s.mesh.hi[d])
      r.child(where).fail("the " + shape.kind + " lies outside the mesh");
}

// Cell centres of the global mesh inside a shape (searched within its bounding box).
long count_cell_centres(const MeshSpec& m, const ShapeSpec& shape) {
  int lo[3], hi[3];
  double blo[3], bhi[3];
  shape.shape.bounds(blo, bhi);
  for (int d = 0; d < 3; ++d) {
    const double h = (m.hi[d] - m.lo[d]) / m.cells[d];
    const double a = std::max(blo[d], m.lo[d]), b = std::min(bhi[d], m.hi[d]);
    lo[d] = std::max(0, static_cast<int>(std::floor((a - m.lo[d]) / h - 0.5)));
    hi[d] = std::min(m.cells[d], static_cast<int>(std::ceil((b - m.lo[d]) / h + 0.5)));
  }
  long n = 0;
  for (int k = lo[2]; k < hi[2]; ++k)
    for (int j = lo[1]; j < hi[1]; ++j)
      for (int i = lo[0]; i < hi[0]; ++i) {
        const double x = m.lo[0] + (i + 0.5) * (m.hi[0] - m.lo[0]) / m.cells[0];
        const double y = m.lo[1] + (j + 0.5) * (m.hi[1] - m.lo[1]) / m.cells[1];
        const double z = m.lo[2] + (k + 0.5) * (m.hi[2] - m.lo[2]) / m.cells[2];
        if (shape.contains(x, y, z)) ++n;
      }
  return n;
}

void read_regions(const DeckNode& root, Scene& s) {
  const DeckNode list = root.child("regions");
  if (!list.is_sequence() || list.size() == 0) list.fail("expected a non-empty list of regions");
  std::vector<std::string> names;
  for (const auto& m : s.materials) names.push_back(m.name);
  bool first = true;
  for (const DeckNode& r : list.items()) {
    std::vector<std::string> keys = {"material",        "shape",    "union",  "minus",
                                     "density",         "pressure", "energy", "velocity",
                                     "radial_velocity", "deposit",  "wave"};
    keys.insert(keys.end(), kShapeKeys.begin(), kShapeKeys.end());
    r.expect_keys(keys);
    RegionSpec reg;
    reg.material = r.get_string("material");
    bool found = false;
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == reg.material) {
        reg.material_index = static_cast<int>(i);
        found = true;
      }
    if (!found)
      r.child("material")
          .fail("unknown material '" + reg.material + "'; did you mean '" +
                nearest(reg.material, names) + "'?");
    read_shape(r, s, reg.shape);
    if (first && reg.shape.kind != "all")
      r.fail("the first region must be 'shape: all' (it fills the whole mesh)");
    reg.density = r.get_real("density", 0, kState);
    if (!(reg.density > 0)) r.child("density").fail("density must be positive");
    if (r.has("pressure") == r.has("energy"))
      r.fail("give exactly one of 'pressure' or 'energy' (specific internal energy)");
    reg.has_pressure = r.has("pressure");
    if (reg.has_pressure) {
      reg.pressure = r.get_real("pressure", 0, kState);
    } else {
      reg.energy = r.get_real("energy", 0, kState);
    }
    if (r.has("velocity") && r.has("radial_velocity"))
      r.fail("give 'velocity' or 'radial_velocity', not both");
    reg.velocity = r.get_real3("velocity", -kState, kState, {0, 0, 0});
    if (r.has("radial_velocity")) {
      const DeckNode rv = r.child("radial_velocity");
      rv.expect_keys({"speed", "center"});
      reg.radial_velocity = true;
      reg.velocity[0] = rv.get_real("speed", -kState, kState);
      reg.velocity_center = rv.get_real3("center", -kHuge, kHuge, {0, 0, 0});
    }
    reg.deposit = r.get_real("deposit", 0, kState, 0);
    if (reg.deposit > 0 && count_cell_centres(s.mesh, reg.shape) == 0)
      r.child("deposit").fail("the region holds no cell centre to deposit energy in; enlarge it");
    if (r.has("wave")) {
      const DeckNode wv = r.child("wave");
      wv.expect_keys({"amplitude", "axis", "shape"});
      reg.wave_amplitude = wv.get_real("amplitude", 0, 0.999);
      const std::string axis = wv.get_enum("axis", {"x", "y", "z", "diagonal"}, "x");
      reg.wave_axis = axis == "diagonal" ? 3 : axis[0] - 'x';
      reg.wave_shape = wv.get_enum("shape", {"sine", "plateau"}, "sine") == "plateau" ? 1 : 0;
      const auto& c = s.mesh.cells;
      if (reg.wave_axis == 3 && !(c[0] == c[1] && c[1] == c[2]))
        wv.child("axis").fail(
            "a diagonal wave needs the same number of cells along every axis (its exact cell "
            "means assume a cell of one width in box lengths)");
    }
    s.regions.push_back(reg);
    first = false;
  }
}

// A numerics key that applies to the other kind of scene (config/options.hpp,
// numerics_scopes) is refused where the deck (or a --set) gives it.
void check_numerics_scope(const DeckNode& root, const Scene& s) {
  if (!root.has("numerics")) return;
  const DeckNode n = root.child("numerics");
  const bool multi = s.materials.size() > 1;
  for (const NumericsScope& k : numerics_scopes()) {
    if (!n.has(k.key)) continue;
    if (k.applies == hydro::Applies::SingleMaterial && multi)
      n.child(k.key).fail(std::string("applies to single-material scenes only (") + k.why +
                          "); this scene has " + std::to_string(s.materials.size()) +
                          " materials: remove the key");
    if (k.applies == hydro::Applies::MultiMaterial && !multi)
      n.child(k.key).fail(std::string("applies to multi-material scenes only (") + k.why +
                          "); this scene has one material: remove the key");
  }
}

}  // namespace

std::map<std::string, std::string> resolved_numerics(const Scene& s) {
  const auto real = [](double x) {  // the shortest of 15 or 17 digits that reads back as x
    char b[32];
    std::snprintf(b, sizeof b, "%.15g", x);
    if (std::strtod(b, nullptr) != x) std::snprintf(b, sizeof b, "%.17g", x);
    return std::string(b);
  };
  const NumericsSpec& n = s.numerics;
  return {{"numerics.advection", name_of(n.advection)},
          {"numerics.remap", name_of(n.remap)},
          {"numerics.viscosity.linear", real(n.q_linear)},
          {"numerics.viscosity.quadratic", real(n.q_quadratic)},
          {"numerics.viscosity.isotropic", real(n.q_isotropic)},
          {"numerics.heat_flux", real(n.heat_flux)},
          {"numerics.geometry", name_of(n.geometry)},
          {"numerics.free_expansion", real(n.free_expansion)},
          {"numerics.ke_fix", n.ke_fix ? "true" : "false"},
          {"numerics.ke_fix_share", name_of(n.ke_fix_share)},
          {"numerics.ke_fix_redo", n.ke_fix_redo ? "true" : "false"},
          {"numerics.samples", std::to_string(n.samples)},
          {"numerics.layout", name_of(n.layout)},
          {"numerics.interface", name_of(n.interface)},
          {"numerics.min_fraction", real(n.min_fraction)},
          {"numerics.closure", name_of(n.closure)},
          {"numerics.relaxation_iterations", std::to_string(n.relaxation_iterations)},
          {"numerics.void_density", real(n.void_density)},
          {"numerics.solid_floor", real(n.solid_floor)},
          {"time.cfl", real(s.time.cfl)},
          {"time.rule", name_of(s.time.rule)},
          {"time.cfl_transport", real(s.time.cfl_transport)},
          {"time.growth", real(s.time.growth)},
          {"time.dt_max", real(s.time.dt_max)}};
}

Scene read_scene(const Deck& deck) {
  const DeckNode root = deck.root();
  root.expect_keys({"scene", "description", "mesh", "boundaries", "time", "numerics", "materials",
                    "regions", "output"});
  Scene s;
  s.file = deck.file();
  s.name = root.get_string("scene");
  if (s.name.empty())
    root.child("scene").fail("the scene name is empty; it names the output files");
  if (s.name.size() > 128)
    root.child("scene").fail("the scene name has " + std::to_string(s.name.size()) +
                             " characters; at most 128 (it names the output files)");
  for (char ch : s.name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-'))
      root.child("scene").fail("scene name may hold only letters, digits, '_' and '-'");
  s.description = root.get_string("description", "");
  read_mesh(root, s);

  const DeckNode t = root.child("time");
  t.expect_keys(
      {"end", "cfl", "rule", "cfl_transport", "dt_initial", "dt_max", "growth", "max_cycles"});
  s.time.end = t.get_real("end", 0, kHuge);
  if (!(s.time.end > 0)) t.child("end").fail("end time must be positive");
  s.time.cfl = t.get_real("cfl", 1e-3, 1.0, s.time.cfl);
  s.time.rule = t.get_choice("rule", choices(s.time.rule), s.time.rule);
  s.time.cfl_transport = t.get_real("cfl_transport", 1e-3, 1.0, s.time.transport());
  s.time.dt_initial = t.get_real("dt_initial", 1e-300, kHuge, s.time.dt_initial);
  s.time.dt_max = t.get_real("dt_max", 1e-300, kHuge, s.time.dt_max);
  s.time.growth = t.get_real("growth", 1.0, 10.0, s.time.growth);
  s.time.max_cycles = t.get_int("max_cycles", 1, 1000000000L, s.time.max_cycles);

  if (root.has("numerics")) {
    const DeckNode n = root.child("numerics");
    n.expect_keys({"advection", "remap", "viscosity", "ke_fix", "ke_fix_share", "ke_fix_redo",
                   "samples", "layout", "interface", "min_fraction", "closure",
                   "relaxation_iterations", "solid_floor", "void_density", "heat_flux", "geometry",
                   "free_expansion"});
    NumericsSpec& x = s.numerics;
    const auto choose = [&](const char* key, auto& v) { v = n.get_choice(key, choices(v), v); };
    x.heat_flux = n.get_real("heat_flux", 0, 100, x.heat_flux);
    x.free_expansion = n.get_real("free_expansion", 0, 0.99, x.free_expansion);
    choose("geometry", x.geometry);
    choose("closure", x.closure);
    x.solid_floor = n.get_real("solid_floor", 0, 0.99, x.solid_floor);
    x.void_density = n.get_real("void_density", 0, 1.0, x.void_density);
    x.relaxation_iterations =
        static_cast<int>(n.get_int("relaxation_iterations", 1, 1000, x.relaxation_iterations));
    choose("layout", x.layout);
    choose("interface", x.interface);
    x.min_fraction = n.get_real("min_fraction", 0, 1e-3, x.min_fraction);
    x.samples = static_cast<int>(n.get_int("samples", 1, 16, x.samples));
    choose("remap", x.remap);
    x.ke_fix = n.get_bool("ke_fix", x.ke_fix);
    choose("ke_fix_share", x.ke_fix_share);
    x.ke_fix_redo = n.get_bool("ke_fix_redo", x.ke_fix_redo);
    choose("advection", x.advection);
    if (n.has("viscosity")) {
      const DeckNode q = n.child("viscosity");
      q.expect_keys({"linear", "quadratic", "isotropic"});
      s.numerics.q_linear = q.get_real("linear", 0, 10, s.numerics.q_linear);
      s.numerics.q_quadratic = q.get_real("quadratic", 0, 10, s.numerics.q_quadratic);
      s.numerics.q_isotropic = q.get_real("isotropic", 0, 1, s.numerics.q_isotropic);
    }
  }

  read_materials(root, s);
  read_regions(root, s);
  if (s.materials.size() > 1 && s.numerics.remap == hydro::Remap::Unsplit)
    root.child("numerics")
        .child("remap")
        .fail("the unsplit remap runs single-material scenes only; use 'split' with " +
              std::to_string(s.materials.size()) + " materials");
  check_numerics_scope(root, s);

  s.output.basename = s.name;
  if (root.has("output")) {
    const DeckNode o = root.child("output");
    o.expect_keys({"dir", "interval", "write", "log_every", "checkpoint_every", "checkpoint_keep",
                   "mass_ledger"});
    s.output.dir = o.get_string("dir", s.output.dir);
    s.output.interval = o.get_real("interval", 0, kHuge, 0);
    s.output.write = o.get_bool("write", true);
    s.output.log_every = o.get_int("log_every", 1, 1000000000L, s.output.log_every);
    s.output.mass_ledger = o.get_bool("mass_ledger", false);
    if (o.has("checkpoint_every")) {
      const DeckNode c = o.child("checkpoint_every");
      c.expect_keys({"cycles", "seconds"});
      s.output.checkpoint_cycles = c.get_int("cycles", 0, 1000000000L, 0);
      s.output.checkpoint_seconds = c.get_real("seconds", 0, 1e9, 0);
    }
    s.output.checkpoint_keep =
        static_cast<int>(o.get_int("checkpoint_keep", 1, 1000, s.output.checkpoint_keep));
  }
  s.deck_values = deck.values();
  return s;
}

}  // namespace mp
