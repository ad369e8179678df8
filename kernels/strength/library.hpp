// Strength data of the library materials, keyed by the names of the EOS library
// (kernels/materials/library.cpp): shear modulus, specific heat, Johnson-Cook,
// Steinberg-Guinan and Zerilli-Armstrong parameters, every value cited. Units: cm, g, us -> Mbar; K
// (1 GPa = 0.01 Mbar, 1 MPa = 1e-5 Mbar, 1 J/(kg K) = 1e-8 (cm/us)^2/K, 1/s = 1e-6/us).
//
// How each set was read (details and what is missing: docs/materials.md, "Strength"):
//  - Steinberg-Guinan sets and specific heats: D. J. Steinberg, "Equation of state and strength
//    properties of selected materials", UCRL-MA-106439 (LLNL, 1991; change 1, 1996). The report
//    itself could not be opened here; its rows were read in the Uintah code's transcription
//    (github.com/Uintah/Uintah, src/StandAlone/inputs/MPM/MaterialData/SCGMaterials/, whose
//    README says the values were copied verbatim from the report). The same files repeat the
//    report's Mie-Grueneisen rows, which agree digit for digit with the EOS entries of this
//    library read earlier from the report (copper 0.394 / 1.489 / 2.02, Al 6061-T6
//    0.524 / 1.40 / 1.97), and the specific heats agree with a second transcription of the
//    same report (FronTier's mg-eos.c: Cu 0.383e-5, Al 6061-T6 0.885e-5, W 0.129e-5,
//    4340 0.448e-5 Mbar cm^3/(g K)). In those files A carries the label "Pa^-1" but the values
//    (2.83 for copper) are Steinberg's G'_p/G0 in 1/Mbar (the older Uintah copper file gives
//    28.0e-12 /Pa = 2.8 /Mbar); they are used here in 1/Mbar.
//  - Johnson-Cook sets: G. R. Johnson and W. H. Cook, Proc. 7th Int. Symp. on Ballistics, The
//    Hague, 1983, pp. 541-547, table of constants (OFHC copper, 4340 steel, tungsten alloy),
//    read in Uintah's transcription (MaterialData/JohnsonCookPlasticOFHCCopper.xml,
//    JohnsonCookPlastic4340Steel.xml, JohnsonCookPlasticW.xml; the Uintah MPM manual,
//    doc/Components/MPM/MPMMaterialModels.tex, attributes the model and the 4340 set to
//    Johnson & Cook 1983). Aluminium 6061-T6: D. R. Lesuer, G. J. Kay, M. M. LeBlanc,
//    UCRL-JC-134118 (LLNL, 2001), read in Uintah's JCPlastic6061T6Al.xml (Uintah's
//    bibliography cites Lesuer01 for it). The JC paper itself could not be opened here; its
//    melting and room temperatures were not read (the values below are Uintah's, noted).
//  - Zerilli-Armstrong (copper only): F. J. Zerilli and R. W. Armstrong, J. Appl. Phys. 61
//    (1987) 1816, read in B. Banerjee's Uintah copper inputs that cite it (adiCuZA*.ups,
//    MaterialData/ZerilliArmstrongPlasticOFHCCopper.xml); the paper could not be opened here.
//  - The 4340 shear modulus: ASM International's MatWeb datasheet for AISI 4340 (normalized),
//    80 GPa, which the sheet labels "typical for steel" (Steinberg's 4340 row, which would carry
//    G0 and its derivatives, was not found in a readable transcription).
#pragma once
#include <string>
#include <vector>

#include "core/error.hpp"
#include "strength/flow_stress.hpp"

namespace mp::strength {

struct StrengthData {
  std::string name;  // the EOS library name it belongs to
  Real G0;           // shear modulus at the reference state, Mbar (0: none cited)
  Real cv;           // specific heat, (cm/us)^2/K
  Real T_ref;        // temperature at e = 0, K
  bool has_jc;       // Johnson-Cook set present
  JohnsonCook jc;    // (jc.G0 = G0)
  bool has_sg;       // Steinberg-Guinan set present
  SteinbergGuinan sg;
  bool has_za;          // Zerilli-Armstrong set present
  ZerilliArmstrong za;  // (za.G0 = G0)
  std::string citation;
};

// 1/s in 1/us: the Johnson-Cook sets are normalised to a reference rate of 1/s.
inline constexpr Real kPerSecond = Real(1e-6);
// Specific heat, J/(kg K) -> (cm/us)^2/K.
inline constexpr Real kJPerKgK = Real(1e-8);

inline const std::vector<StrengthData>& strength_table() {
  static const std::vector<StrengthData> table = {
      {"copper",
       // Steinberg UCRL-MA-106439, OFHC copper (1/2 hard): G0 = 47.7 GPa.
       Real(0.477),
       // Steinberg UCRL-MA-106439 (Uintah SCG_CopperOFHC.xml, FronTier mg-eos.c): 383 J/(kg K).
       Real(383) * kJPerKgK, Real(300),
       // Johnson & Cook 1983, OFHC copper: A 90 MPa, B 292 MPa, n 0.31, C 0.025, m 1.09;
       // T_melt 1356 K (the other transcription that could be read, LA-UR-22-29965 as quoted
       // in a public impact-code material table, gives the same five constants and 1356 K);
       // T_room 298 K (Uintah's JC input), rate normalised to 1/s.
       true,
       JohnsonCook{Real(90e-5), Real(292e-5), Real(0.31), Real(0.025), Real(1.09), kPerSecond,
                   Real(298), Real(1356), Real(0.477)},
       // Steinberg UCRL-MA-106439, OFHC copper: G0 47.7 GPa, Y0 0.12 GPa, Ymax 0.64 GPa,
       // beta 36, n 0.45, G'p/G0 2.83 /Mbar, G'T/G0 -3.77e-4 /K, Tm0 1790 K, Gamma0 2.02, a 1.5.
       true,
       SteinbergGuinan{Real(0.477), Real(0.0012), Real(0.0064), Real(36), Real(0.45), Real(0),
                       Real(2.83), Real(3.77e-4), Real(1790), Real(2.02), Real(1.5)},
       // Zerilli & Armstrong 1987, OFHC copper (FCC): Delta sigma_G' 46.5 MPa + k l^-1/2 =
       // 5 MPa x 3.7 -> C0 65 MPa, C2 890 MPa, C3 0.0028 /K, C4 0.000115 /K, the rate in 1/s;
       // read in Uintah's copper inputs (src/StandAlone/inputs/MPM/adiCuZA4000s696K.ups and
       // IMPM/adiCuZA01s296K.ups: sigma_g, k_H, sqrt_l_inv, B_0, alpha_0, alpha_1; ZAFlow.cc
       // forms c_0 = sigma_g + k_H sqrt_l_inv and cites the 1987 paper) and the older
       // MaterialData/ZerilliArmstrongPlasticOFHCCopper.xml (c2, c3, c4), B. Banerjee's
       // transcription. T_melt 1356 K as for the Johnson-Cook set (the form has no melt term).
       true,
       ZerilliArmstrong{Real(65e-5), Real(890e-5), Real(0.0028), Real(0.000115), kPerSecond,
                        Real(1356), Real(0.477)},
       "G0, cv, Steinberg-Guinan: Steinberg UCRL-MA-106439 change 1 (1996), OFHC copper, read in "
       "Uintah SCGMaterials/SCG_CopperOFHC.xml; Johnson-Cook: Johnson & Cook, 7th Int. Symp. "
       "Ballistics (1983), read in Uintah JohnsonCookPlasticOFHCCopper.xml, T_melt 1356 K; "
       "Zerilli-Armstrong: Zerilli & Armstrong, J. Appl. Phys. 61 (1987) 1816, read in Uintah "
       "adiCuZA*.ups / ZerilliArmstrongPlasticOFHCCopper.xml"},
      {"aluminium_6061",
       // Steinberg UCRL-MA-106439, 6061-T6: G0 27.6 GPa; cv 885 J/(kg K).
       Real(0.276), Real(885) * kJPerKgK, Real(300),
       // Lesuer, Kay & LeBlanc, UCRL-JC-134118 (2001), 6061-T6: A 324 MPa, B 114 MPa, n 0.42,
       // C 0.002, m 1.34 (Uintah JCPlastic6061T6Al.xml); T_melt 933.47 K is Uintah's value
       // there (the melting point of pure aluminium, not the alloy's solidus); T_room 298 K.
       true,
       JohnsonCook{Real(324e-5), Real(114e-5), Real(0.42), Real(0.002), Real(1.34), kPerSecond,
                   Real(298), Real(933.47), Real(0.276)},
       // Steinberg UCRL-MA-106439, 6061-T6: G0 27.6 GPa, Y0 0.29 GPa, Ymax 0.68 GPa, beta 125,
       // n 0.10, G'p/G0 6.52 /Mbar, G'T/G0 -6.16e-4 /K, Tm0 1220 K, Gamma0 1.97, a 1.5.
       true,
       SteinbergGuinan{Real(0.276), Real(0.0029), Real(0.0068), Real(125), Real(0.10), Real(0),
                       Real(6.52), Real(6.16e-4), Real(1220), Real(1.97), Real(1.5)},
       false, ZerilliArmstrong{0, 0, 0, 0, 1, 0, 0},
       "G0, cv, Steinberg-Guinan: Steinberg UCRL-MA-106439 change 1 (1996), Al 6061-T6, read in "
       "Uintah SCGMaterials/SCG_Aluminum6061-T6.xml; Johnson-Cook: Lesuer, Kay & LeBlanc "
       "UCRL-JC-134118 (2001), read in Uintah JCPlastic6061T6Al.xml"},
      {"steel_4340",
       // ASM International / MatWeb datasheet "AISI 4340 Steel, normalized, 100 mm (4 in.)
       // round" (asm.matweb.com, bassnum M434AE): shear modulus 80 GPa (11600 ksi), marked there
       // "Typical for steel" (a generic steel value, not measured on 4340; the same sheet gives
       // E 205 GPa, typical, and Poisson's ratio 0.29, calculated: E/(2(1+nu)) = 79.5 GPa).
       // Steinberg's 4340 strength row (and with it G'_p, G'_T) was still not found in a readable
       // transcription.
       Real(0.80),
       // Steinberg UCRL-MA-106439, 4340 steel (Rc 38), cv 0.448e-5 Mbar cm^3/(g K) (FronTier
       // mg-eos.c transcription) = 448 J/(kg K).
       Real(448) * kJPerKgK, Real(300),
       // Johnson & Cook 1983, 4340 steel: A 792 MPa, B 510 MPa, n 0.26, C 0.014, m 1.03
       // (Uintah JohnsonCookPlastic4340Steel.xml and MPM manual); T_melt 1793 K (Uintah's
       // MaterialConst4340Steel.xml, JC's own value not read); T_room 298 K.
       true,
       JohnsonCook{Real(792e-5), Real(510e-5), Real(0.26), Real(0.014), Real(1.03), kPerSecond,
                   Real(298), Real(1793), Real(0.80)},
       false, SteinbergGuinan{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, false,
       ZerilliArmstrong{0, 0, 0, 0, 1, 0, 0},
       "G0: ASM/MatWeb datasheet AISI 4340 normalized (M434AE), 80 GPa 'typical for steel'; cv: "
       "Steinberg UCRL-MA-106439 (FronTier mg-eos.c transcription); Johnson-Cook: Johnson & "
       "Cook, 7th Int. Symp. Ballistics (1983), read in Uintah JohnsonCookPlastic4340Steel.xml, "
       "T_melt 1793 K (Uintah); no Steinberg-Guinan set"},
      {"tungsten",
       // Steinberg UCRL-MA-106439, tungsten: G0 160 GPa; cv 129 J/(kg K).
       Real(1.60), Real(129) * kJPerKgK, Real(300),
       // Johnson & Cook 1983, "tungsten alloy" (a W-Ni-Fe heavy alloy, not the pure tungsten
       // of this library's EOS entry): A 1506.96 MPa, B 176.64 MPa, n 0.12, C 0.016, m 1.00
       // (Uintah JohnsonCookPlasticW.xml); T_melt 3695 K is Uintah's value (the melting point
       // of pure W), T_room 298 K.
       true,
       JohnsonCook{Real(1506.96e-5), Real(176.64e-5), Real(0.12), Real(0.016), Real(1.00),
                   kPerSecond, Real(298), Real(3695), Real(1.60)},
       // Steinberg UCRL-MA-106439, tungsten: G0 160 GPa, Y0 2.2 GPa, Ymax 4.0 GPa, beta 24,
       // n 0.19, G'p/G0 0.938 /Mbar, G'T/G0 -1.38e-4 /K, Tm0 4520 K, Gamma0 1.67, a 1.3.
       true,
       SteinbergGuinan{Real(1.60), Real(0.022), Real(0.040), Real(24), Real(0.19), Real(0),
                       Real(0.938), Real(1.38e-4), Real(4520), Real(1.67), Real(1.3)},
       false, ZerilliArmstrong{0, 0, 0, 0, 1, 0, 0},
       "G0, cv, Steinberg-Guinan: Steinberg UCRL-MA-106439 change 1 (1996), tungsten, read in "
       "Uintah SCGMaterials/SCG_Tungsten.xml; Johnson-Cook: Johnson & Cook (1983) tungsten "
       "alloy, read in Uintah JohnsonCookPlasticW.xml, T_melt 3695 K (Uintah)"},
  };
  return table;
}

// The entry for an EOS library name, or nullptr (a material with no strength data).
inline const StrengthData* find_strength(const std::string& name) {
  for (const auto& d : strength_table()) {
    if (d.name == name) return &d;
  }
  return nullptr;
}

inline std::vector<std::string> strength_names() {
  std::vector<std::string> names;
  for (const auto& d : strength_table()) names.push_back(d.name);
  return names;
}

// The device record for a library material and model. Throws mp::InputError when the material
// has no such set, or no cited shear modulus.
inline FlowStress make_flow_stress(const StrengthData& d, FlowStressKind kind) {
  FlowStress f;
  f.kind = kind;
  f.cv = d.cv;
  f.T_ref = d.T_ref;
  switch (kind) {
    case kJohnsonCook:
      if (!d.has_jc) throw InputError("material '" + d.name + "' has no Johnson-Cook set");
      if (!(d.jc.G0 > 0)) {
        throw InputError("material '" + d.name +
                         "': no cited shear modulus; give strength.shear_modulus in the scene");
      }
      f.jc = d.jc;
      return f;
    case kSteinbergGuinan:
      if (!d.has_sg) throw InputError("material '" + d.name + "' has no Steinberg-Guinan set");
      f.sg = d.sg;
      return f;
    case kZerilliArmstrong:
      if (!d.has_za) throw InputError("material '" + d.name + "' has no Zerilli-Armstrong set");
      if (!(d.G0 > 0)) {
        throw InputError("material '" + d.name +
                         "': no cited shear modulus; give strength.shear_modulus in the scene");
      }
      f.za = d.za;
      f.za.G0 = d.G0;
      return f;
    default:
      throw InputError("material '" + d.name +
                       "': the library holds johnson_cook, steinberg_guinan and "
                       "zerilli_armstrong sets only");
  }
}

}  // namespace mp::strength
