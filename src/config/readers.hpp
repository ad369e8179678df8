// The scene reader's parts (scene.cpp reads the deck's sections; materials.cpp the materials
// with their EOS, strength and burn blocks) and the bounds they share. (src/config only.)
#pragma once
#include <limits>

#include "config/deck.hpp"
#include "config/scene.hpp"

namespace mp {

inline constexpr double kHuge = std::numeric_limits<double>::max();
// Largest initial density, pressure, energy or speed: beyond it the products a cycle forms
// (rho e V, rho u^2, c^2) overflow a double, and a float field holds at most 3.4e38.
inline constexpr double kState = 1e30;

// materials: each material's library entry, EOS and its parameters' physical ranges, strength
// and burn blocks, into s.materials.
void read_materials(const DeckNode& root, Scene& s);

}  // namespace mp
