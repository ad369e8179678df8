// The scene's physics as the kernels take it (modules.hpp), and the run log's module lines.
#include "driver/modules.hpp"

#include <memory>
#include <sstream>

#include "config/options.hpp"
#include "driver/simulation.hpp"
#include "materials/library.hpp"
#include "strength/library.hpp"

namespace mp {

eos::Eos material_eos(const MaterialSpec& m, double void_density) {
  materials::MaterialData d;
  d.name = m.name;
  d.eos = m.eos_kind;
  d.rho0 = Real(m.rho0);
  for (const auto& [k, v] : m.params) d.params[k] = Real(v);
  eos::Eos eos = materials::make_eos(d);
  if (m.has_p_min) eos.p_min = Real(m.p_min);
  eos.rho_void = Real(void_density);
  return eos;
}

std::vector<eos::Eos> material_eoses(const Scene& s) {
  std::vector<eos::Eos> eos;
  for (const auto& m : s.materials) eos.push_back(material_eos(m, s.numerics.void_density));
  return eos;
}

strength::FlowStress material_strength(const MaterialSpec& m) {
  const StrengthSpec& st = m.strength;
  strength::FlowStress f;
  if (st.kind == strength::kNoStrength) return f;
  const strength::StrengthData* data =
      st.library.empty() ? nullptr : strength::find_strength(st.library);
  if (st.kind == strength::kConstantYield) {
    f.kind = strength::kConstantYield;
    f.constant = {Real(st.shear_modulus > 0 ? st.shear_modulus : double(data->G0)), Real(st.yield)};
    return f;
  }
  // a deck's shear modulus replaces the library's (and stands in where it cites none)
  strength::StrengthData d = *data;
  if (st.shear_modulus > 0) d.G0 = d.jc.G0 = d.sg.G0 = d.za.G0 = Real(st.shear_modulus);
  return strength::make_flow_stress(d, strength::FlowStressKind(st.kind));
}

burn::BurnSetup material_burn(const MaterialSpec& m) {
  burn::BurnSetup b;
  const BurnSpec& bs = m.burn;
  if (!bs.on) return b;
  b.on = true;
  b.d_cj = Real(bs.detonation_speed);
  b.p_cj = Real(bs.cj_pressure);
  b.rho0 = Real(m.rho0);
  b.ramp_cells = Real(bs.ramp_cells);
  b.programmed = bs.programmed;
  b.volume_burn = bs.volume_burn;
  b.host_lighting = bs.host_lighting;
  if (!bs.unreacted.empty()) {
    // the deck reader checked the entry (a mie_gruneisen library material)
    b.mixed = true;
    b.unreacted = materials::make_eos(*materials::find_material(bs.unreacted));
    b.e0 = Real(bs.unreacted_e0);
    b.equilibrium = bs.equilibrium;
    if (bs.forest_fire) {
      const materials::MaterialData& u = *materials::find_material(bs.unreacted);
      b.forest_fire = true;
      b.ff.pop = {Real(bs.pop_a), Real(bs.pop_b)};
      b.ff.rho0 = u.rho0;
      b.ff.c0 = u.param("c0");
      b.ff.s = u.param("s");
      b.ff.e0 = b.e0;
      b.ff.p_max = b.p_cj;
      b.ff.unreacted = b.unreacted;
      b.ff.products = material_eos(m, 0.0);
      b.ff.equilibrium = b.equilibrium;
    }
  }
  for (const DetonatorSpec& d : bs.detonators) {
    burn::Detonator det;
    det.kind = d.type == DetonatorKind::Point  ? burn::Detonator::Kind::Point
               : d.type == DetonatorKind::Line ? burn::Detonator::Kind::Line
                                               : burn::Detonator::Kind::Plane;
    det.a = d.a;
    det.b = d.b;
    det.t0 = d.time;
    b.detonators.push_back(det);
  }
  return b;
}

hydro::Options hydro_options(const Scene& s) {
  return hydro::Options(s.numerics, s.time);
}

void add_modules(const Scene& s, const Mesh& mesh, hydro::Hydro& h) {
  if (s.materials.size() == 1) {
    const MaterialSpec& m = s.materials[0];
    const strength::FlowStress f = material_strength(m);
    if (f.kind != strength::kNoStrength)
      h.add_module(std::make_unique<strength::Strength>(mesh, f, Real(m.rho0 > 0 ? m.rho0 : 1.0)));
    const burn::BurnSetup b = material_burn(m);
    if (b.on) h.add_module(std::make_unique<burn::Burn>(mesh, b));
    return;
  }
  // per material: one stress set per material with strength, and the one explosive (the scene
  // reader allows one)
  strength::MaterialModels models;
  models.n = int(s.materials.size());
  std::vector<std::string> names;
  burn::BurnSetup b;
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    const MaterialSpec& ms = s.materials[m];
    names.push_back(ms.name);
    models.f[m] = material_strength(ms);
    models.rho0[m] = Real(ms.rho0 > 0 ? ms.rho0 : 1.0);
    if (ms.burn.on) {
      b = material_burn(ms);
      b.material = int(m);
    }
  }
  if (models.carriers() != 0)
    h.add_module(std::make_unique<strength::Strength>(mesh, models, h.materials(), names));
  if (b.on) h.add_module(std::make_unique<burn::Burn>(mesh, b, h.materials()));
}

namespace {
// The run log's words for the advection choice.
std::string advection_words(hydro::Advection a) {
  switch (a) {
    case hydro::Advection::First:
      return "first-order donor cell";
    case hydro::Advection::Second:
      return "second-order van Leer";
    case hydro::Advection::Third:
      return "third-order (Courant-weighted 3-point slope, van Leer bound)";
  }
  return "";
}
}  // namespace

std::vector<std::string> Simulation::modules() const {
  std::vector<std::string> m;
  m.push_back("hydro: staggered Lagrange (predictor-corrector) + remap, " +
              advection_words(scene_.numerics.advection) +
              " advection, " + name_of(scene_.numerics.remap) + " remap, KE fix " +
              (!scene_.numerics.ke_fix ? std::string("off")
               : scene_.materials.size() < 2
                   ? std::string(scene_.numerics.ke_fix_redo
                                     ? "on"
                                     : "on (no donor-value redo, numerics.ke_fix_redo: false)")
               : scene_.numerics.ke_fix_share == hydro::KeFixShare::Mass
                   ? std::string("on (a node's loss shared by its cells' mass)")
                   : std::string("on (a node's loss in eighths, numerics.ke_fix_share: equal)")) +
              // Noh's heat flux (kernels/hydro/conduction.cpp): single-material scenes
              (scene_.numerics.heat_flux > 0 && scene_.materials.size() < 2
                   ? ", heat flux h = " +
                         [&] {
                           std::ostringstream os;
                           os << scene_.numerics.heat_flux;
                           return os.str();
                         }() +
                         " in converging shocks"
                   : std::string()) +
              // the Lagrangian step's geometry, as the hydro decided it (single material, no
              // strength)
              (hydro_->mid_geometry() ? ", mid-step geometry" : ", fixed geometry") +
              // the free-expansion rule, where the hydro allocated it
              (hydro_->free_expansion_acts() ? [&] {
                std::ostringstream os;
                os << ", free expansion to the nodes below density ratio "
                   << scene_.numerics.free_expansion;
                return os.str();
              }()
                                             : std::string()));
  if (scene_.numerics.void_density > 0) {
    std::ostringstream os;
    os << "void: a material below " << scene_.numerics.void_density
       << " g/cm3 has no pressure and no sound speed (numerics.void_density)";
    m.push_back(os.str());
  }
  for (const MaterialSpec& mat : scene_.materials) {
    std::string eos = "eos: " + mat.eos + " (" + mat.name;
    if (!mat.library.empty()) eos += ", library '" + mat.library + "'";
    for (const auto& [k, v] : mat.params) {
      std::ostringstream os;
      os << ", " << k << "=" << v;
      eos += os.str();
    }
    if (mat.has_p_min) {
      std::ostringstream os;
      os << "; tension cutoff p_min=" << mat.p_min;
      eos += os.str();
    }
    m.push_back(eos + ")");
    if (mat.strength.kind != strength::kNoStrength) {
      std::ostringstream os;
      os << "strength: " << mat.strength.model << " (" << mat.name;
      if (!mat.strength.library.empty() && mat.strength.kind != strength::kConstantYield)
        os << ", library '" << mat.strength.library << "'";
      const strength::FlowStress f = material_strength(mat);
      if (f.kind == strength::kConstantYield)
        os << ", G=" << f.constant.G0 << " Mbar, Y=" << f.constant.Y0 << " Mbar";
      os << "; Jaumann rate, radial return; fields ";
      if (scene_.materials.size() == 1)
        os << "stress_xx..zx, plastic_strain)";
      else  // its own stress set (kernels/strength/module.hpp, "Multi-material scenes")
        os << "stress_xx_" << mat.name << "..zx_" << mat.name << ", plastic_strain_" << mat.name
           << ")";
      m.push_back(os.str());
    }
    if (mat.burn.on) {
      std::ostringstream os;
      std::string kinds;
      for (const auto& [on, word] :
           {std::pair<bool, const char*>{mat.burn.programmed, "programmed"},
            {mat.burn.volume_burn, "CJ volume"},
            {mat.burn.forest_fire, "Forest Fire"}})
        if (on) kinds += (kinds.empty() ? "" : " + ") + std::string(word);
      os << "burn: " << kinds << " (" << mat.name << ", D=" << mat.burn.detonation_speed
         << " cm/us, p_cj=" << mat.burn.cj_pressure << " Mbar, ";
      if (mat.burn.programmed || mat.burn.volume_burn)
        os << mat.burn.detonators.size() << " detonator(s), ramp " << mat.burn.ramp_cells
           << " cells; ";
      os << (mat.burn.unreacted.empty()
                 ? std::string("p = F P_products")
                 : "p = (1-F) P_unreacted(rho, e-e0) + F P_products, unreacted '" +
                       mat.burn.unreacted + "'")
         << (mat.burn.forest_fire
                 ? "; Pop plot log10 x*/cm = " + std::to_string(mat.burn.pop_a) + " + " +
                       std::to_string(mat.burn.pop_b) + " log10 P/Mbar" +
                       (mat.burn.pop_plot.empty() ? "" : " ('" + mat.burn.pop_plot + "')")
                 : std::string())
         << (mat.burn.programmed || mat.burn.volume_burn ? "; Huygens lighting times" : "")
         << "; fields burn_fraction, lighting_time)";
      m.push_back(os.str());
    }
  }
  if (scene_.materials.size() == 1) {
    m.push_back("materials: single material (no mixed cells, no interface reconstruction)");
  } else {
    const double asked = scene_.numerics.min_fraction;
    const double used = hydro::effective_min_fraction(asked);
    std::ostringstream os;
    os << "materials: " << scene_.materials.size() << " materials, "
       << name_of(scene_.numerics.layout) << " layout, "
       << (scene_.numerics.closure == hydro::Closure::Relaxation
               ? "equal-strain + pressure-relaxation (at most " +
                     std::to_string(scene_.numerics.relaxation_iterations) +
                     " iterations/cycle) mixed cells"
               : std::string("equal-strain mixed cells"))
       << ", interface reconstruction "
       << (scene_.numerics.interface == hydro::Interface::Youngs ? "Youngs PLIC (onion skin)"
           : scene_.numerics.interface == hydro::Interface::Elvira
               ? "ELVIRA-type PLIC (onion skin)"
               : name_of(scene_.numerics.interface))
       << ", min fraction " << used;
    if (used > asked)
      os << " (the deck's " << asked << " raised to 4 ulps of 1 in this build's "
         << (sizeof(Real) == 4 ? "float" : "double") << " fields)";
    m.push_back(os.str());
  }
  return m;
}

}  // namespace mp
