// The materials database: reference density, EOS kind and parameters of each named material, every
// value cited (library.cpp).
//
// ---------------------------------------------------------------------------------------------
// UNIT SYSTEM (one for the whole code): centimetre, gram, microsecond.
//   length        cm
//   mass          g
//   time          us  (1e-6 s)
//   density       g/cm^3                      (1 g/cm^3 = 1000 kg/m^3)
//   velocity      cm/us                       (1 cm/us = 10 km/s = 1e4 m/s)
//   pressure      g/(cm us^2) = Mbar          (1 Mbar = 1e12 dyn/cm^2 = 1e11 Pa = 100 GPa)
//   energy        g cm^2/us^2 = Mbar cm^3     (= 1e12 erg = 1e5 J)
//   energy/mass   cm^2/us^2                   (= 1e12 erg/g = 1e8 J/kg = 100 MJ/kg)
//   energy/volume Mbar = Mbar cm^3/cm^3       (handbook JWL E0 values are in these units)
// Sources quoting SI or km/s are converted with the factors above; the conversion is noted next
// to the value.
// ---------------------------------------------------------------------------------------------
#pragma once
#include <map>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "eos/eos.hpp"

namespace mp::materials {

struct MaterialData {
  std::string name;
  // EOS kind (eos.hpp; eos_name gives the decks' word for it)
  eos::EosKind eos;
  Real rho0;  // reference density, g/cm^3
  // EOS parameters by name, in the units above:
  //   ideal_gas:     gamma
  //   stiffened_gas: gamma, p_inf (Mbar)
  //   mie_gruneisen: c0 (cm/us), s, gamma0   (rho Gamma = rho0 Gamma0; see eos/mie_gruneisen.hpp)
  //   polynomial:    A1, A2, A3 (Mbar), B0, B1
  //   jwl:           A, B (Mbar), R1, R2, omega, E0 (Mbar cm^3/cm^3), D (cm/us), p_cj (Mbar)
  std::map<std::string, Real> params;
  std::string citation;  // where every number above comes from

  // A named parameter; throws mp::InputError naming the material and key when absent.
  Real param(const std::string& key) const;
};

// The entry for a name (exact, lower case), or nullptr.
const MaterialData* find_material(const std::string& name);

// Names of every material in the library, in table order.
std::vector<std::string> material_names();

// The device-ready EOS record of a library material. Throws mp::InputError for an unknown kind.
eos::Eos make_eos(const MaterialData& m);

}  // namespace mp::materials
