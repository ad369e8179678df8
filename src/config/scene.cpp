#include "config/scene.hpp"

#include "config/options.hpp"
#include "materials/library.hpp"
#include "strength/library.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace mp {

namespace {
constexpr double kHuge = std::numeric_limits<double>::max();
// Largest initial density, pressure, energy or speed: beyond it the products a cycle forms
// (rho e V, rho u^2, c^2) overflow a double, and a float field holds at most 3.4e38.
constexpr double kState = 1e30;

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

// Physical range of each EOS parameter (a value outside makes the EOS non-physical: no sound
// speed, pressure of the wrong sign under compression, a decay that never ends).
struct ParamRange {
  double lo;
  bool lo_open;
  double hi;
  const char* what;
};
const ParamRange* param_range(const std::string& eos, const std::string& key) {
  static const std::map<std::string, ParamRange> ranges = {
      {"ideal_gas.gamma", {1, true, 100, "in (1, 100]"}},
      {"stiffened_gas.gamma", {1, true, 100, "in (1, 100]"}},
      {"stiffened_gas.p_inf", {0, false, 1e30, ">= 0"}},
      {"mie_gruneisen.c0", {0, true, 1e30, "> 0"}},
      {"mie_gruneisen.s", {0, false, 100, "in [0, 100]"}},
      {"mie_gruneisen.gamma0", {0, false, 100, "in [0, 100]"}},
      {"polynomial.A1", {0, true, 1e30, "> 0 (the bulk modulus)"}},
      {"jwl.A", {0, false, 1e30, ">= 0"}},
      {"jwl.B", {0, false, 1e30, ">= 0"}},
      {"jwl.R1", {0, true, 1e3, "in (0, 1000]"}},
      {"jwl.R2", {0, true, 1e3, "in (0, 1000]"}},
      {"jwl.omega", {0, true, 10, "in (0, 10]"}},
      {"jwl.E0", {0, false, 1e30, ">= 0"}},
      {"jwl.D", {0, true, 1e30, "> 0"}},
      {"jwl.p_cj", {0, true, 1e30, "> 0"}},
  };
  const auto it = ranges.find(eos + "." + key);
  return it == ranges.end() ? nullptr : &it->second;
}

// EOS parameter names by kind (units: README, "Units"; kernels/materials/library.hpp).
const std::map<std::string, std::vector<std::string>> kEosParams = {
    {"ideal_gas", {"gamma"}},
    {"stiffened_gas", {"gamma", "p_inf"}},
    {"mie_gruneisen", {"c0", "s", "gamma0"}},
    {"polynomial", {"A1", "A2", "A3", "B0", "B1"}},
    {"jwl", {"A", "B", "R1", "R2", "omega", "E0", "D", "p_cj"}},
};
const std::vector<std::string> kEosKinds = {"ideal_gas", "stiffened_gas", "mie_gruneisen",
                                            "polynomial", "jwl"};

// materials[].strength: {model: elastic_plastic, shear_modulus: G, yield: Y} (Mbar), or
// {model: johnson_cook | steinberg_guinan | zerilli_armstrong[, library: name][, shear_modulus:
// G]} from the cited sets of kernels/strength/library.hpp (library defaults to the material's
// own library name).
void read_strength(const DeckNode& n, MaterialSpec& spec) {
  n.expect_keys({"model", "library", "shear_modulus", "yield"});
  StrengthSpec& st = spec.strength;
  st.model = n.get_enum(
      "model", {"elastic_plastic", "johnson_cook", "steinberg_guinan", "zerilli_armstrong"});
  st.kind = st.model == "elastic_plastic"     ? strength::kConstantYield
            : st.model == "johnson_cook"      ? strength::kJohnsonCook
            : st.model == "zerilli_armstrong" ? strength::kZerilliArmstrong
                                              : strength::kSteinbergGuinan;
  st.library = n.get_string("library", spec.library);
  const strength::StrengthData* data =
      st.library.empty() ? nullptr : strength::find_strength(st.library);
  if (n.has("library") && !data)
    n.child("library").fail("no strength data for '" + st.library + "'; did you mean '" +
                            nearest(st.library, strength::strength_names()) + "'?");
  st.shear_modulus = n.get_real("shear_modulus", 1e-9, 1e3, 0);
  if (st.model == "elastic_plastic") {
    st.yield = n.get_real("yield", 0, 1e3);
    if (!(st.shear_modulus > 0) && !(data && data->G0 > 0))
      n.fail("elastic_plastic strength needs 'shear_modulus' (Mbar)" +
             std::string(data ? "" : " or a library material with a cited one"));
    return;
  }
  if (n.has("yield")) n.child("yield").fail("'yield' belongs to model elastic_plastic");
  if (!data)
    n.fail("model " + st.model +
           " takes its parameters from the strength library: give "
           "'library' (one of: " +
           [] {
             std::string l;
             for (const auto& x : strength::strength_names()) l += (l.empty() ? "" : ", ") + x;
             return l;
           }() +
           ")");
  if (st.model == "johnson_cook" && !data->has_jc)
    n.child("model").fail("'" + st.library + "' has no Johnson-Cook set in the library");
  if (st.model == "steinberg_guinan" && !data->has_sg)
    n.child("model").fail("'" + st.library + "' has no Steinberg-Guinan set in the library");
  if (st.model == "zerilli_armstrong" && !data->has_za)
    n.child("model").fail("'" + st.library + "' has no Zerilli-Armstrong set in the library");
  if ((st.model == "johnson_cook" || st.model == "zerilli_armstrong") && !(data->G0 > 0) &&
      !(st.shear_modulus > 0))
    n.fail("'" + st.library + "' has no cited shear modulus: give 'shear_modulus' (Mbar)");
  if (st.model == "steinberg_guinan" && !(spec.rho0 > 0))
    n.fail("steinberg_guinan needs the material's reference density 'rho0'");
}

// materials[].burn: {detonation_speed: D, cj_pressure: p_cj (JWL materials default to their
// D and p_cj), detonators: [{type: point, at: [x, y, z]} | {type: line, from: [..], to: [..]} |
// {type: plane, at: [..], normal: [..]}, each with an optional firing time], ramp_cells: 2,
// programmed: true, volume_burn: false, unreacted: <library name of the unreacted solid>}.
void read_burn(const DeckNode& n, MaterialSpec& spec) {
  n.expect_keys({"detonation_speed", "cj_pressure", "detonators", "ramp_cells", "programmed",
                 "volume_burn", "unreacted"});
  BurnSpec& b = spec.burn;
  b.on = true;
  const bool jwl = spec.eos == "jwl";
  const double d0 = jwl && spec.params.count("D") ? spec.params.at("D") : 0;
  const double p0 = jwl && spec.params.count("p_cj") ? spec.params.at("p_cj") : 0;
  if (d0 > 0)
    b.detonation_speed = n.get_real("detonation_speed", 1e-6, 1e3, d0);
  else
    b.detonation_speed = n.get_real("detonation_speed", 1e-6, 1e3);
  if (p0 > 0)
    b.cj_pressure = n.get_real("cj_pressure", 1e-12, 1e3, p0);
  else
    b.cj_pressure = n.get_real("cj_pressure", 1e-12, 1e3);
  b.ramp_cells = n.get_real("ramp_cells", 0.5, 100, 2);
  b.programmed = n.get_bool("programmed", true);
  b.volume_burn = n.get_bool("volume_burn", false);
  if (!b.programmed && !b.volume_burn) n.fail("burn needs programmed and/or volume_burn true");
  if (!(spec.rho0 > 0)) n.fail("burn needs the explosive's reference density 'rho0'");
  // the CJ state must be a compression: 1 - p_cj / (rho0 D^2) in (0, 1)
  if (!(b.cj_pressure < spec.rho0 * b.detonation_speed * b.detonation_speed))
    n.fail("cj_pressure must be below rho0 D^2 (the CJ state is a compression)");
  if (n.has("unreacted")) {
    // the unreacted solid: a Mie-Grueneisen library entry (zero pressure at its rho0 and e = 0),
    // its energy measured from the products' e0 = E0 / rho0
    const DeckNode u = n.child("unreacted");
    const std::string lib = n.get_string("unreacted");
    const materials::MaterialData* data = materials::find_material(lib);
    if (!data)
      u.fail("no material '" + lib + "' in the library; did you mean '" +
             nearest(lib, materials::material_names()) + "'?");
    if (data->eos != "mie_gruneisen")
      u.fail("'" + lib + "' has EOS " + data->eos +
             "; the unreacted explosive needs a mie_gruneisen (solid) entry");
    if (spec.eos != "jwl" || !spec.params.count("E0"))
      u.fail(
          "an unreacted EOS needs JWL products with E0 (it sets the unreacted energy origin "
          "e0 = E0 / rho0)");
    b.unreacted = lib;
    b.unreacted_e0 = spec.params.at("E0") / spec.rho0;
  }
  if (b.programmed) {
    const DeckNode list = n.child("detonators");
    if (!list.is_sequence() || list.size() == 0)
      list.fail("expected a non-empty list of detonators");
    for (const DeckNode& d : list.items()) {
      DetonatorSpec ds;
      d.child("type");  // (required: a missing one is named)
      ds.type = d.get_choice("type",
                             Choices<DetonatorKind>{{"point", DetonatorKind::Point},
                                                    {"line", DetonatorKind::Line},
                                                    {"plane", DetonatorKind::Plane}},
                             DetonatorKind::Point);
      if (ds.type == DetonatorKind::Point) {
        d.expect_keys({"type", "at", "time"});
        ds.a = d.get_real3("at", -kHuge, kHuge);
      } else if (ds.type == DetonatorKind::Line) {
        d.expect_keys({"type", "from", "to", "time"});
        ds.a = d.get_real3("from", -kHuge, kHuge);
        ds.b = d.get_real3("to", -kHuge, kHuge);
      } else {
        d.expect_keys({"type", "at", "normal", "time"});
        ds.a = d.get_real3("at", -kHuge, kHuge);
        ds.b = d.get_real3("normal", -kHuge, kHuge);
        if (!(ds.b[0] * ds.b[0] + ds.b[1] * ds.b[1] + ds.b[2] * ds.b[2] > 0))
          d.child("normal").fail("a plane detonator needs a non-zero normal");
      }
      ds.time = d.get_real("time", 0, kHuge, 0);
      b.detonators.push_back(ds);
    }
  } else if (n.has("detonators")) {
    n.child("detonators").fail("detonators need programmed: true");
  }
}

void read_materials(const DeckNode& root, Scene& s) {
  const DeckNode list = root.child("materials");
  if (!list.is_sequence() || list.size() == 0) list.fail("expected a non-empty list of materials");
  for (const DeckNode& m : list.items()) {
    m.expect_keys(
        {"name", "library", "eos", "rho0", "params", "gamma", "p_min", "strength", "burn"});
    MaterialSpec spec;
    spec.name = m.get_string("name");
    for (const auto& other : s.materials)
      if (other.name == spec.name)
        m.child("name").fail("material '" + spec.name + "' defined twice");
    if (m.has("library")) {
      const std::string lib = m.get_string("library");
      const materials::MaterialData* data = materials::find_material(lib);
      if (!data)
        m.child("library").fail("no material '" + lib + "' in the library; did you mean '" +
                                nearest(lib, materials::material_names()) + "'?");
      if (m.has("eos")) m.child("eos").fail("a library material brings its own EOS; drop 'eos'");
      spec.library = lib;
      spec.eos = data->eos;
      spec.rho0 = data->rho0;
      spec.citation = data->citation;
      for (const auto& [k, v] : data->params) spec.params[k] = v;
    } else {
      spec.eos = m.get_enum("eos", kEosKinds);
    }
    spec.rho0 = m.get_real("rho0", 1e-12, 1e6, spec.rho0);
    if (spec.eos != "ideal_gas" && spec.eos != "stiffened_gas" && !(spec.rho0 > 0))
      m.fail("a " + spec.eos + " material needs a reference density 'rho0'");
    const std::vector<std::string>& names = kEosParams.at(spec.eos);
    // `gamma` beside `eos` is shorthand for params.gamma (the gases)
    if (m.has("gamma")) {
      if (spec.eos != "ideal_gas" && spec.eos != "stiffened_gas")
        m.child("gamma").fail("a " + spec.eos + " EOS has no 'gamma'; see 'params'");
      spec.params["gamma"] = m.get_real("gamma", 1.0 + 1e-6, 100.0);
    }
    if (m.has("params")) {
      const DeckNode p = m.child("params");
      p.expect_keys(names);
      for (const auto& k : names)
        if (p.has(k)) spec.params[k] = p.get_real(k, -1e30, 1e30);
    }
    for (const auto& k : names)
      if (!spec.params.count(k))
        m.fail("the " + spec.eos + " EOS needs parameter '" + k + "' under 'params'");
    // Physical ranges, checked where the value was given (params, or the gamma shorthand).
    for (const auto& k : names) {
      const ParamRange* range = param_range(spec.eos, k);
      if (!range) continue;
      const double v = spec.params[k];
      const bool ok = (range->lo_open ? v > range->lo : v >= range->lo) && v <= range->hi;
      if (ok) continue;
      const DeckNode at = m.has("params") && m.child("params").has(k) ? m.child("params").child(k)
                          : (k == "gamma" && m.has("gamma"))          ? m.child("gamma")
                                                                      : m;
      std::ostringstream os;
      os << "the " << spec.eos << " parameter " << k << " = " << v << " must be " << range->what;
      at.fail(os.str());
    }
    // Tension cutoff: the most tension (Mbar) the material carries before it cavitates or
    // spalls; a floor on the pressure the hydro uses, so never above zero.
    if (m.has("p_min")) {
      spec.has_p_min = true;
      spec.p_min = m.get_real("p_min", -1e3, 0.0);
    }
    if (m.has("strength")) read_strength(m.child("strength"), spec);
    if (m.has("burn")) read_burn(m.child("burn"), spec);
    s.materials.push_back(spec);
  }
  // one explosive per scene (the burn module carries one burn fraction per cell)
  int explosives = 0;
  for (std::size_t q = 0; q < s.materials.size(); ++q)
    if (s.materials[q].burn.on && ++explosives > 1)
      list[q].child("burn").fail("a scene holds at most one explosive (material with 'burn')");
  if (s.materials.size() > 16)
    list.fail("a scene holds at most 16 materials, not " + std::to_string(s.materials.size()));
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
      wv.expect_keys({"amplitude", "axis"});
      reg.wave_amplitude = wv.get_real("amplitude", 0, 0.999);
      const std::string axis = wv.get_enum("axis", {"x", "y", "z"}, "x");
      reg.wave_axis = axis[0] - 'x';
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
  t.expect_keys({"end", "cfl", "dt_initial", "dt_max", "growth", "max_cycles"});
  s.time.end = t.get_real("end", 0, kHuge);
  if (!(s.time.end > 0)) t.child("end").fail("end time must be positive");
  s.time.cfl = t.get_real("cfl", 1e-3, 1.0, s.time.cfl);
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
    o.expect_keys({"dir", "interval", "write", "log_every", "checkpoint_every", "checkpoint_keep"});
    s.output.dir = o.get_string("dir", s.output.dir);
    s.output.interval = o.get_real("interval", 0, kHuge, 0);
    s.output.write = o.get_bool("write", true);
    s.output.log_every = o.get_int("log_every", 1, 1000000000L, s.output.log_every);
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
