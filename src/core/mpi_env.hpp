// Environment settings that must be in place before MPI_Init.
#pragma once
#include <cstdlib>

namespace mp {

// Open MPI's OMPIO collective-write component "vulcan" (the default in Debian 12's Open MPI
// 4.1.4) intermittently leaves a rank's block of a collective parallel-HDF5 write as zeros
// (open-mpi/ompi issue 12718, fixed upstream in 2024). Seen here: 4 of 20 runs of test_hdf5 on
// 4 ranks. Excluding it lets OMPIO pick another fcoll component (0 of 24 runs failed). A value
// the user already set wins; other MPI implementations ignore the variable.
inline void prepare_mpi_environment() {
  setenv("OMPI_MCA_fcoll", "^vulcan", 0);
}

}  // namespace mp
