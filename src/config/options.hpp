// The deck's names of the typed numerics (kernels/hydro/numerics.hpp), and which scenes each
// numerics key applies to: the scene reader parses with them, the run log and the checkpoint's
// resolved record print with them. Nothing outside src/config compares an option's text.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "hydro/numerics.hpp"

namespace mp {

template <class E>
using Choices = std::vector<std::pair<std::string, E>>;

inline const Choices<hydro::Advection>& choices(hydro::Advection) {
  static const Choices<hydro::Advection> c{{"second", hydro::Advection::Second},
                                           {"first", hydro::Advection::First},
                                           {"third", hydro::Advection::Third}};
  return c;
}
inline const Choices<hydro::Remap>& choices(hydro::Remap) {
  static const Choices<hydro::Remap> c{{"split", hydro::Remap::Split},
                                       {"unsplit", hydro::Remap::Unsplit}};
  return c;
}
inline const Choices<hydro::StepGeometry>& choices(hydro::StepGeometry) {
  static const Choices<hydro::StepGeometry> c{{"midstep", hydro::StepGeometry::MidStep},
                                              {"fixed", hydro::StepGeometry::Fixed}};
  return c;
}
inline const Choices<hydro::KeFixShare>& choices(hydro::KeFixShare) {
  static const Choices<hydro::KeFixShare> c{{"mass", hydro::KeFixShare::Mass},
                                            {"equal", hydro::KeFixShare::Equal}};
  return c;
}
inline const Choices<mat::LayoutKind>& choices(mat::LayoutKind) {
  static const Choices<mat::LayoutKind> c{{"compact", mat::LayoutKind::Compact},
                                          {"dense", mat::LayoutKind::Dense}};
  return c;
}
inline const Choices<hydro::Interface>& choices(hydro::Interface) {
  static const Choices<hydro::Interface> c{{"youngs", hydro::Interface::Youngs},
                                           {"elvira", hydro::Interface::Elvira},
                                           {"slic", hydro::Interface::Slic},
                                           {"none", hydro::Interface::None}};
  return c;
}
inline const Choices<hydro::Closure>& choices(hydro::Closure) {
  static const Choices<hydro::Closure> c{{"equal_strain", hydro::Closure::EqualStrain},
                                         {"relaxation", hydro::Closure::Relaxation}};
  return c;
}
inline const Choices<hydro::StepRule>& choices(hydro::StepRule) {
  static const Choices<hydro::StepRule> c{{"combined", hydro::StepRule::Combined},
                                          {"separate", hydro::StepRule::Separate},
                                          {"cloverleaf", hydro::StepRule::CloverLeaf}};
  return c;
}

// The deck's name of a typed numerics value ("second", "compact", ...).
template <class E>
const std::string& name_of(E v) {
  for (const auto& c : choices(v))
    if (c.second == v) return c.first;
  return choices(v).front().first;  // (every value has a name)
}

// The command line's --restart value that asks for the newest checkpoint of the output
// directory (any other value is a checkpoint's path).
inline bool restart_from_newest(const std::string& restart) {
  return restart == "latest";
}

// The numerics keys that apply to one kind of scene only (the rest apply to every scene): a
// deck that sets one on the other kind is refused, naming the key (the hydro would ignore it).
// (numerics.remap applies to both; its value unsplit to single-material scenes only.)
struct NumericsScope {
  const char* key;  // under numerics.
  hydro::Applies applies;
  const char* why;
};
inline const std::vector<NumericsScope>& numerics_scopes() {
  using hydro::Applies;
  static const std::vector<NumericsScope> s{
      {"heat_flux", Applies::SingleMaterial, "Noh's heat flux conducts in single-material scenes"},
      {"geometry", Applies::SingleMaterial,
       "the mid-step geometry is a single-material scene's (multi-material steps use the fixed "
       "faces)"},
      {"free_expansion", Applies::SingleMaterial,
       "the free-expansion rule acts in single-material ideal-gas scenes"},
      {"ke_fix_redo", Applies::SingleMaterial,
       "the KE fix's donor-value redo is a single-material scene's"},
      {"ke_fix_share", Applies::MultiMaterial,
       "a node's loss is shared among materials' cells only in multi-material scenes"},
      {"layout", Applies::MultiMaterial, "the per-material layout exists in multi-material scenes"},
      {"interface", Applies::MultiMaterial,
       "interface reconstruction exists in multi-material scenes"},
      {"min_fraction", Applies::MultiMaterial, "a volume fraction exists in multi-material scenes"},
      {"closure", Applies::MultiMaterial, "the mixed-cell closure exists in multi-material scenes"},
      {"relaxation_iterations", Applies::MultiMaterial,
       "the mixed-cell closure exists in multi-material scenes"},
      {"solid_floor", Applies::MultiMaterial, "the solid floor acts in mixed cells only"},
  };
  return s;
}

}  // namespace mp
