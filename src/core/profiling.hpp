// A Kokkos Tools profiling region for the lifetime of a scope, so that a profile (Kokkos Tools'
// space-time stack, kernel timer, or a vendor tool through them) groups the cycle's kernels by
// phase: hydro::lagrange, remap::sweep_x, halo::exchange, output::dump, ... (docs/perf.md,
// "Layouts and profiling"). Costs nothing when no tool is loaded.
#pragma once
#include <Kokkos_Core.hpp>
#include <string>

namespace mp {

class ProfileRegion {
 public:
  explicit ProfileRegion(const std::string& name) { Kokkos::Profiling::pushRegion(name); }
  ~ProfileRegion() { Kokkos::Profiling::popRegion(); }
  ProfileRegion(const ProfileRegion&) = delete;
  ProfileRegion& operator=(const ProfileRegion&) = delete;
};

}  // namespace mp
