// The materials table. Units: cm, g, us -> Mbar (see library.hpp). Every number carries its source.
//
// Materials the issue asked for but that are NOT here, because no source for their parameters
// could be checked when the table was written (add them with a citation once checked, never from
// memory): cyclotol 77/23 (JWL products), PBX 9501 (JWL products), unreacted Composition B
// (solid EOS). What was found and why it was not enough is in docs/materials.md.
#include "materials/library.hpp"

#include "core/error.hpp"

namespace mp::materials {

namespace {

const std::vector<MaterialData>& table() {
  static const std::vector<MaterialData> materials = {
      // ---- gases -------------------------------------------------------------------------
      {"air",
       eos::kIdealGas,
       // U.S. Standard Atmosphere, 1976 (NOAA-S/T 76-1562), sea-level density 1.2250 kg/m^3
       // (T = 288.15 K, p = 101325 Pa).
       1.225e-3,
       // gamma = 7/5: ideal diatomic gas with rotational but no vibrational modes (dry air near
       // room temperature).
       {{"gamma", 1.4}},
       "rho0: U.S. Standard Atmosphere, 1976, NOAA-S/T 76-1562, sea level (1.2250 kg/m^3); "
       "gamma: 7/5, ideal diatomic gas"},
      {"helium",
       eos::kIdealGas,
       // Ideal-gas density at 273.15 K and 101325 Pa: p M / (R T) with M = 4.002602 g/mol
       // (IUPAC standard atomic weight) and R = 8.314462618 J/(mol K) (CODATA 2018):
       // 0.178576 kg/m^3.
       1.78576e-4,
       // gamma = 5/3: ideal monatomic gas.
       {{"gamma", 5.0 / 3.0}},
       "rho0: ideal-gas law at 273.15 K, 101325 Pa, M = 4.002602 g/mol (IUPAC), "
       "R = 8.314462618 J/(mol K) (CODATA 2018); gamma: 5/3, ideal monatomic gas"},

      // ---- liquids -----------------------------------------------------------------------
      {"water",
       eos::kMieGruneisen,
       // M. A. Meyers, "Dynamic Behavior of Materials", Wiley, 1994, ch. 4, table of shock
       // Hugoniot parameters: rho0 = 1.000 g/cm^3, C0 = 1.65 km/s, S = 1.92, Gamma0 = 0.1.
       1.000,
       {{"c0", 0.165}, {"s", 1.92}, {"gamma0", 0.1}},
       "Meyers, Dynamic Behavior of Materials, Wiley, 1994, ch. 4 Hugoniot table: "
       "rho0 1.000 g/cm^3, C0 1.65 km/s, S 1.92, Gamma0 0.1"},
      {"water_stiffened",
       eos::kStiffenedGas,
       // R. Saurel & R. Abgrall, "A multiphase Godunov method for compressible multifluid and
       // multiphase flows", J. Comput. Phys. 150 (1999) 425-467: liquid water as a stiffened gas
       // with gamma = 4.4, p_inf = 6e8 Pa (= 6e-3 Mbar). Nominal density 1.000 g/cm^3.
       1.000,
       {{"gamma", 4.4}, {"p_inf", 6.0e-3}},
       "Saurel & Abgrall, J. Comput. Phys. 150 (1999) 425-467: gamma 4.4, p_inf 6e8 Pa"},

      // ---- metals (Mie-Grueneisen, linear Us-up) -----------------------------------------
      {"copper",
       eos::kMieGruneisen,
       // D. J. Steinberg, "Equation of state and strength properties of selected materials",
       // UCRL-MA-106439 (LLNL, 1991; change 1, 1996), OFHC copper: rho0 = 8.93 g/cm^3,
       // C0 = 0.394 cm/us, S1 = 1.489, Gamma0 = 2.02 (b = 0.47 not used: rho Gamma = rho0 Gamma0).
       8.93,
       {{"c0", 0.394}, {"s", 1.489}, {"gamma0", 2.02}},
       "Steinberg, UCRL-MA-106439 (1991/1996), OFHC copper: rho0 8.93, C0 0.394 cm/us, "
       "S1 1.489, Gamma0 2.02"},
      {"aluminium_6061",
       eos::kMieGruneisen,
       // Steinberg, UCRL-MA-106439, aluminium 6061-T6: rho0 = 2.703 g/cm^3, C0 = 0.524 cm/us,
       // S1 = 1.40, Gamma0 = 1.97 (b = 0.48 not used).
       2.703,
       {{"c0", 0.524}, {"s", 1.40}, {"gamma0", 1.97}},
       "Steinberg, UCRL-MA-106439 (1991/1996), Al 6061-T6: rho0 2.703, C0 0.524 cm/us, "
       "S1 1.40, Gamma0 1.97"},
      {"steel_4340",
       eos::kMieGruneisen,
       // Steinberg, UCRL-MA-106439, 4340 steel (Rc 38): rho0 = 7.81 g/cm^3, C0 = 0.4578 cm/us,
       // S1 = 1.33, Gamma0 = 1.67.
       7.81,
       {{"c0", 0.4578}, {"s", 1.33}, {"gamma0", 1.67}},
       "Steinberg, UCRL-MA-106439 (1991/1996), 4340 steel Rc 38: rho0 7.81, C0 0.4578 cm/us, "
       "S1 1.33, Gamma0 1.67"},
      {"steel_304",
       eos::kMieGruneisen,
       // R. G. McQueen, S. P. Marsh, J. W. Taylor, J. N. Fritz, W. J. Carter, "The equation of
       // state of solids from shock wave studies", in R. Kinslow (ed.), High-Velocity Impact
       // Phenomena, Academic Press, 1970, appendix: 304 stainless steel rho0 = 7.896 g/cm^3,
       // C0 = 4.569 km/s, S = 1.490, Gamma0 = 2.17.
       7.896,
       {{"c0", 0.4569}, {"s", 1.490}, {"gamma0", 2.17}},
       "McQueen et al. in Kinslow (ed.), High-Velocity Impact Phenomena, Academic Press 1970, "
       "appendix: 304 SS rho0 7.896, C0 4.569 km/s, S 1.490, Gamma0 2.17"},
      // ---- rock (quartz: PAGOSA's perforator models the oil-bearing rock as quartz) ---------
      // rho0 = 2.65 g/cm^3 (alpha quartz) and Gamma0 = 0.618 = alpha K0 / (rho0 Cv) from
      // H. J. Melosh, "A hydrocode equation of state for SiO2", Meteoritics & Planetary Science
      // 42 (2007) 2079-2098, table 3 and eq. 21 (read in the open-access copy kept in
      // github.com/ststewart/aneos-forsterite-2019, EOS-docs/). No linear Us-up fit with a range
      // could be read for alpha quartz, so C0 and S are this project's least-squares fits to
      // the principal Hugoniot of Melosh's ANEOS SiO2 model, the table
      // silica-Melosh2007/NEW-SESAME-HUG.TXT of github.com/ststewart/aneos-fused-silica
      // (commit aab6fc9c), which Melosh compares with the measured quartz Hugoniot. Quartz
      // changes phase on its Hugoniot (mixed-phase plateau near 21 GPa), so one line cannot
      // cover both sides; two entries, each with its range (docs/materials.md):
      {"quartz",
       eos::kMieGruneisen,
       // alpha-quartz branch, up 0.05-1.35 km/s (0.5-20 GPa), 104 points: C0 = 3.6574 km/s,
       // S = 1.5313, Us within 0.008 km/s of the model.
       2.65,
       {{"c0", 0.36574}, {"s", 1.5313}, {"gamma0", 0.618}},
       "rho0 2.65, Gamma0 0.618: Melosh, Meteorit. Planet. Sci. 42 (2007) 2079, table 3, eq. 21; "
       "C0 0.36574 cm/us, S 1.5313: fit to Melosh's ANEOS SiO2 Hugoniot (ststewart/"
       "aneos-fused-silica NEW-SESAME-HUG.TXT) for up 0.05-1.35 km/s, 0.5-20 GPa"},
      {"quartz_high_pressure",
       eos::kMieGruneisen,
       // high-pressure branch, up 2.0-4.18 km/s (27-99 GPa), 27 points: C0 = 1.6275 km/s,
       // S = 1.7631, Us within 0.083 km/s of the model. C0 here is an intercept, not a sound
       // speed: below about 20 GPa this entry is far too soft. Gamma0 is the alpha-quartz value.
       2.65,
       {{"c0", 0.16275}, {"s", 1.7631}, {"gamma0", 0.618}},
       "rho0 2.65, Gamma0 0.618: Melosh, Meteorit. Planet. Sci. 42 (2007) 2079, table 3, eq. 21; "
       "C0 0.16275 cm/us, S 1.7631: fit to Melosh's ANEOS SiO2 Hugoniot (ststewart/"
       "aneos-fused-silica NEW-SESAME-HUG.TXT) for up 2.0-4.18 km/s, 27-99 GPa"},
      {"tungsten",
       eos::kMieGruneisen,
       // McQueen et al. in Kinslow (ed.), High-Velocity Impact Phenomena, 1970, appendix: tungsten
       // rho0 = 19.224 g/cm^3, C0 = 4.029 km/s, S = 1.237, Gamma0 = 1.54.
       19.224,
       {{"c0", 0.4029}, {"s", 1.237}, {"gamma0", 1.54}},
       "McQueen et al. in Kinslow (ed.), High-Velocity Impact Phenomena, Academic Press 1970, "
       "appendix: W rho0 19.224, C0 4.029 km/s, S 1.237, Gamma0 1.54"},

      // ---- unreacted explosive (Mie-Grueneisen, linear Us-up) ---------------------------------
      // The solid explosive ahead of the burn (materials[].burn.unreacted; kernels/burn/burn.hpp
      // he_pressure_mixed). PBX 9404, the HOM solid of C. L. Mader, "Numerical Modeling of
      // Explosives and Propellants" (its CD, run/fire.out/9404.OUT; "see also page 219-
      // LA-2900"), read in the transcription kept in LANL EOSlib (github.com/lanl/EOSlib,
      // DATA/HOM.data, entry UsUp=PBX9404, units hydro::HiP = cm, us, g, Mbar): rho0 = 1.844
      // g/cm^3, c0 = 0.2423 cm/us, s = 1.883, G0 = G1 = 0.675. EOSlib's Grueneisen form is
      // Gamma/V = (G0 - G1)/V + G1/V0 (src/EOStypes/MieGruneisen/Subs/UsUpParamsFunc.C), so
      // G0 = G1 is rho Gamma = rho0 Gamma0, the form of eos/mie_gruneisen.hpp. Mader's book and
      // LA-2900 were not read. No cited unreacted Composition B (or cyclotol) set could be read
      // here (docs/materials.md); this is the only explosive whose unreacted solid is in.
      // Its rho0 (1.844) is not the products row's (pbx9404_products, 1.84): explosive at 1.84
      // sits at -2.3e-4 Mbar on this EOS (docs/numerics.md, "Burn").
      {"pbx9404_unreacted",
       eos::kMieGruneisen,
       1.844,
       {{"c0", 0.2423}, {"s", 1.883}, {"gamma0", 0.675}},
       "Mader, Numerical Modeling of Explosives and Propellants, HOM solid PBX 9404 (CD "
       "run/fire.out/9404.OUT; LA-2900 p. 219), as transcribed in LANL EOSlib DATA/HOM.data "
       "UsUp=PBX9404: rho0 1.844, c0 0.2423 cm/us, s 1.883, Gamma 0.675 (rho Gamma const)"},

      // ---- detonation products (JWL) -------------------------------------------------------
      // B. M. Dobratz and P. C. Crawford, "LLNL Explosives Handbook: Properties of Chemical
      // Explosives and Explosive Simulants", UCRL-52997 change 2 (LLNL, 1985), JWL products
      // table: rho0, D, p_cj and A, B, R1, R2, omega, E0. The handbook itself could not be read
      // here; the rows were read in a public MFC (MFlowCode) case-file helper, jwl_products.py,
      // that transcribes them with the handbook as source (SI: A, B in Pa, E0 as rho0 Q in
      // J/m^3; converted with 1 Mbar = 1e11 Pa). Each row reproduces its own tabulated CJ state
      // through the products Hugoniot to 4-5 digits (D and p_cj within 0.03 %, checked in
      // tests/test_eos.cpp), which a mistyped coefficient would not.
      {"pbx9404_products",
       eos::kJwl,
       // PBX 9404 (HMX 94 / NC 3 / CEF 3): rho0 1.84 g/cm^3, A 8.524e11 Pa, B 1.802e10 Pa,
       // R1 4.60, R2 1.30, omega 0.38, E0 10.2e9 J/m^3; D 8.80 km/s, p_cj 37 GPa.
       1.84,
       {{"A", 8.524},
        {"B", 0.1802},
        {"R1", 4.60},
        {"R2", 1.30},
        {"omega", 0.38},
        {"E0", 0.102},
        {"D", 0.880},
        {"p_cj", 0.370}},
       "Dobratz & Crawford, LLNL Explosives Handbook, UCRL-52997 (1985), JWL table, PBX 9404: "
       "rho0 1.84, A 8.524 Mbar, B 0.1802 Mbar, R1 4.6, R2 1.3, omega 0.38, E0 0.102 Mbar, "
       "D 0.880 cm/us, p_cj 0.37 Mbar"},
      {"comp_b_products",
       eos::kJwl,
       // Composition B (RDX/TNT), the 1.717 g/cm^3 row. The transcription labels it
       // "Composition B-3"; which grade the handbook row names could not be read, so the entry
       // is called plain Composition B. rho0 1.717 g/cm^3, A 5.242e11 Pa, B 7.678e9 Pa,
       // R1 4.20, R2 1.10, omega 0.34, E0 8.5e9 J/m^3; D 7.98 km/s, p_cj 29.5 GPa.
       1.717,
       {{"A", 5.242},
        {"B", 0.07678},
        {"R1", 4.20},
        {"R2", 1.10},
        {"omega", 0.34},
        {"E0", 0.085},
        {"D", 0.798},
        {"p_cj", 0.295}},
       "Dobratz & Crawford, LLNL Explosives Handbook, UCRL-52997 (1985), JWL table, "
       "Composition B (row at 1.717 g/cm^3, labelled B-3 in the transcription): rho0 1.717, A "
       "5.242 Mbar, B 0.07678 Mbar, R1 4.2, R2 1.1, omega 0.34, "
       "E0 0.085 Mbar, D 0.798 cm/us, p_cj 0.295 Mbar"},
      {"petn_products",
       eos::kJwl,
       // PETN at 1.77 g/cm^3: A 6.171e11 Pa, B 1.6926e10 Pa, R1 4.40, R2 1.20, omega 0.25,
       // E0 10.1e9 J/m^3; D 8.30 km/s, p_cj 33.5 GPa.
       1.77,
       {{"A", 6.171},
        {"B", 0.16926},
        {"R1", 4.40},
        {"R2", 1.20},
        {"omega", 0.25},
        {"E0", 0.101},
        {"D", 0.830},
        {"p_cj", 0.335}},
       "Dobratz & Crawford, LLNL Explosives Handbook, UCRL-52997 (1985), JWL table, PETN "
       "1.77 g/cm^3: A 6.171 Mbar, B 0.16926 Mbar, R1 4.4, R2 1.2, omega 0.25, E0 0.101 Mbar, "
       "D 0.830 cm/us, p_cj 0.335 Mbar"},
  };
  return materials;
}

}  // namespace

Real MaterialData::param(const std::string& key) const {
  const auto it = params.find(key);
  if (it == params.end()) {
    throw InputError("material '" + name + "' (" + eos::eos_name(eos) + " EOS) has no parameter '" +
                     key + "'");
  }
  return it->second;
}

const MaterialData* find_material(const std::string& name) {
  for (const auto& m : table()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::vector<std::string> material_names() {
  std::vector<std::string> names;
  for (const auto& m : table()) names.push_back(m.name);
  return names;
}

eos::Eos make_eos(const MaterialData& m) {
  switch (m.eos) {
    case eos::kIdealGas:
      return eos::make_eos(eos::IdealGas{m.param("gamma")});
    case eos::kStiffenedGas:
      return eos::make_eos(eos::StiffenedGas{m.param("gamma"), m.param("p_inf")});
    case eos::kMieGruneisen:
      return eos::make_eos(
          eos::MieGruneisen{m.rho0, m.param("c0"), m.param("s"), m.param("gamma0")});
    case eos::kPolynomial:
      return eos::make_eos(eos::Polynomial{m.rho0, m.param("A1"), m.param("A2"), m.param("A3"),
                                           m.param("B0"), m.param("B1")});
    case eos::kJwl:
      return eos::make_eos(eos::Jwl{m.rho0, m.param("A"), m.param("B"), m.param("R1"),
                                    m.param("R2"), m.param("omega")});
  }
  throw InputError("material '" + m.name + "': unknown EOS kind " + std::to_string(int(m.eos)));
}

}  // namespace mp::materials
