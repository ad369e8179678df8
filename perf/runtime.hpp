// MPI and Kokkos for the life of a perf program's main(): construct first, before any Kokkos
// object; every View of the program must be gone when it is destroyed (keep them in a nested
// scope or a function called from main).
#pragma once
#include <mpi.h>

#include <Kokkos_Core.hpp>

#include "core/mpi_env.hpp"

namespace mp::perf {

struct Runtime {
  Runtime(int& argc, char**& argv) {
    mp::prepare_mpi_environment();
    MPI_Init(&argc, &argv);
    Kokkos::initialize(argc, argv);
  }
  ~Runtime() {
    Kokkos::finalize();
    MPI_Finalize();
  }
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;
};

}  // namespace mp::perf
