// The scene's physics as the kernels take it: each material's EOS, strength and burn set-up, the
// hydro's options (numerics, step controls), the modules the scene needs (the factory), and the
// run log's module lines. (Driver-internal: setup.cpp, simulation.cpp, restart.cpp.)
#pragma once
#include <string>
#include <vector>

#include "burn/module.hpp"
#include "config/scene.hpp"
#include "eos/eos.hpp"
#include "hydro/hydro.hpp"
#include "mesh/mesh.hpp"
#include "strength/module.hpp"

namespace mp {

// A material's EOS (library values overridden by the deck's, its tension cutoff, the void).
eos::Eos material_eos(const MaterialSpec& m, double void_density);
// Every material's EOS, in deck order.
std::vector<eos::Eos> material_eoses(const Scene& s);
// The flow-stress model of a material's strength block (kNoStrength when it has none).
strength::FlowStress material_strength(const MaterialSpec& m);
// The burn module's set-up of a material's burn block (burn.on false when it has none).
burn::BurnSetup material_burn(const MaterialSpec& m);
// The hydro's options for a scene: its numerics and step controls.
hydro::Options hydro_options(const Scene& s);
// The physics modules the scene needs, built and added to the hydro (the factory: strength
// where a material has a strength block, burn where one is an explosive; nothing else).
void add_modules(const Scene& s, const Mesh& mesh, hydro::Hydro& h);
// The build's Real by name (checkpoints and summary.json record it).
inline const char* real_name() {
  return sizeof(Real) == 8 ? "double" : "float";
}

}  // namespace mp
