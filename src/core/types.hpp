// Kokkos aliases and the floating-point type. Nothing else lives here (STYLE.md practice 1).
#pragma once
#include <Kokkos_Core.hpp>

namespace mp {

#ifdef MINIPAGOSA_REAL_FLOAT
using Real = float;
#else
using Real = double;
#endif

using ExecSpace = Kokkos::DefaultExecutionSpace;
using MemSpace = ExecSpace::memory_space;
using HostSpace = Kokkos::HostSpace;

// A cell or node field on one rank's block, ghosts included, indexed (i, j, k).
using Field3 = Kokkos::View<Real***, MemSpace>;
using IntField3 = Kokkos::View<int***, MemSpace>;
using Buffer = Kokkos::View<Real*, MemSpace>;

using Policy3 = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>;
using Policy1 = Kokkos::RangePolicy<ExecSpace>;

}  // namespace mp
