// The deck's materials: library entries, EOS parameters checked against their physical
// ranges, strength and burn blocks (readers.hpp).
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "burn/forest_fire.hpp"
#include "config/options.hpp"
#include "config/readers.hpp"
#include "materials/library.hpp"
#include "strength/library.hpp"

namespace mp {

namespace {

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

// EOS parameter names by kind (units: docs/options.md; kernels/materials/library.hpp).
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

// materials[].burn.forest_fire: {pop_plot: <a cited Pop plot of kernels/burn/forest_fire.hpp>}
// or {a: .., b: ..} with log10(x*/cm) = a + b log10(P/Mbar), b < 0.
void read_forest_fire(const DeckNode& n, BurnSpec& b) {
  n.expect_keys({"pop_plot", "a", "b"});
  b.forest_fire = true;
  if (n.has("pop_plot")) {
    if (n.has("a") || n.has("b"))
      n.fail("give either 'pop_plot' (a cited Pop plot) or 'a' and 'b', not both");
    b.pop_plot = n.get_string("pop_plot");
    const burn::PopPlotData* d = burn::find_pop_plot(b.pop_plot.c_str());
    if (!d) {
      std::vector<std::string> names;
      for (const auto& x : burn::kPopPlots) names.push_back(x.name);
      n.child("pop_plot")
          .fail("no Pop plot '" + b.pop_plot + "'; did you mean '" + nearest(b.pop_plot, names) +
                "'?");
    }
    const burn::PopPlot pp = burn::pop_plot_from_gpa_mm(d->A, d->B);
    b.pop_a = double(pp.a);
    b.pop_b = double(pp.b);
    return;
  }
  if (!n.has("a") || !n.has("b"))
    n.fail("forest_fire needs 'pop_plot' (one of the cited Pop plots) or both 'a' and 'b'");
  b.pop_a = n.get_real("a", -100, 100);
  // the run distance must shrink as the pressure grows
  b.pop_b = n.get_real("b", -100, -1e-6);
}

// materials[].burn: {detonation_speed: D, cj_pressure: p_cj (JWL materials default to their
// D and p_cj), detonators: [{type: point, at: [x, y, z]} | {type: line, from: [..], to: [..]} |
// {type: plane, at: [..], normal: [..]}, each with an optional firing time], ramp_cells: 2,
// programmed: true, volume_burn: false, unreacted: <library name of the unreacted solid>,
// forest_fire: {pop_plot: <name>} | {a: .., b: ..}, lighting: device | host}.
void read_burn(const DeckNode& n, MaterialSpec& spec) {
  n.expect_keys({"detonation_speed", "cj_pressure", "detonators", "ramp_cells", "programmed",
                 "volume_burn", "unreacted", "forest_fire", "closure", "lighting"});
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
  b.host_lighting =
      n.get_choice("lighting", Choices<bool>{{"device", false}, {"host", true}}, false);
  if (n.has("forest_fire")) read_forest_fire(n.child("forest_fire"), b);
  if (!b.programmed && !b.volume_burn && !b.forest_fire)
    n.fail("burn needs programmed and/or volume_burn true, or a forest_fire block");
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
    if (data->eos != eos::kMieGruneisen)
      u.fail("'" + lib + "' has EOS " + std::string(eos::eos_name(data->eos)) +
             "; the unreacted explosive needs a mie_gruneisen (solid) entry");
    if (spec.eos != "jwl" || !spec.params.count("E0"))
      u.fail(
          "an unreacted EOS needs JWL products with E0 (it sets the unreacted energy origin "
          "e0 = E0 / rho0)");
    b.unreacted = lib;
    b.unreacted_e0 = spec.params.at("E0") / spec.rho0;
    b.equilibrium = n.get_choice(
        "closure", Choices<bool>{{"shared_state", false}, {"pressure_equilibrium", true}}, false);
  } else if (n.has("closure")) {
    n.child("closure").fail("closure needs the unreacted solid's EOS ('unreacted')");
  } else if (b.forest_fire) {
    n.child("forest_fire")
        .fail(
            "forest_fire needs the unreacted solid's EOS ('unreacted': its Hugoniot and the "
            "mixture closure build the rate)");
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

}  // namespace

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
      spec.eos = eos::eos_name(data->eos);
      spec.rho0 = data->rho0;
      spec.citation = data->citation;
      for (const auto& [k, v] : data->params) spec.params[k] = v;
    } else {
      spec.eos = m.get_enum("eos", kEosKinds);
    }
    for (int k = 0; k < eos::kEosKindCount; ++k)
      if (spec.eos == eos::eos_name(eos::EosKind(k))) spec.eos_kind = eos::EosKind(k);
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

}  // namespace mp
