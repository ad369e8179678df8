// Environment settings that must be in place before MPI_Init.
#pragma once
#include <cstdlib>
#include <string>

namespace mp {

// Open MPI's OMPIO collective-write component "vulcan" (the default in Debian 12's Open MPI
// 4.1.4) intermittently leaves a rank's block of a collective parallel-HDF5 write as zeros
// (open-mpi/ompi issue 12718, fixed upstream in 2024). Seen here: 4 of 20 runs of test_hdf5 on
// 4 ranks. Excluding it lets OMPIO pick another fcoll component (0 of 24 runs failed). A value
// the user already set wins; other MPI implementations ignore the variable.
//
// Open MPI's shared-file-pointer component "sm" guards each file it opens with a named POSIX
// semaphore in /dev/shm; a process killed inside MPI_File_open (a crash, SIGKILL, a batch
// system's kill) leaves that semaphore taken, and every later run that opens a file of the same
// name waits on it for ever (seen here: a restart after a SIGKILL during a checkpoint write hung
// in mca_sharedfp_sm_file_open). Parallel HDF5 never uses shared file pointers, so the component
// is excluded too.
inline void prepare_mpi_environment() {
  setenv("OMPI_MCA_fcoll", "^vulcan", 0);
  setenv("OMPI_MCA_sharedfp", "^sm", 0);
}

// Kokkos 3.x's OpenMP backend prints a four-line warning on every start where OMP_PROC_BIND is
// unset (it reads only that variable). With neither OMP_PROC_BIND nor OMP_PLACES set, the
// OpenMP runtime (GCC's libgomp reads both when it loads, before main) binds no thread, which is
// what OMP_PROC_BIND=false says: setting it before Kokkos starts changes nothing but the
// warning. Where the user set either, nothing is touched. Returns the run log's words for the
// binding (the kokkos line).
inline std::string prepare_openmp_environment() {
  const char* bind = std::getenv("OMP_PROC_BIND");
  const char* places = std::getenv("OMP_PLACES");
  if (!bind && !places) {
    setenv("OMP_PROC_BIND", "false", 0);
    return "threads not bound (OMP_PROC_BIND unset: set to false, the OpenMP default, "
           "silencing Kokkos' warning; OMP_PROC_BIND=spread OMP_PLACES=threads binds them)";
  }
  std::string s = "OMP_PROC_BIND=" + std::string(bind ? bind : "(unset)");
  if (places) s += " OMP_PLACES=" + std::string(places);
  return s;
}

// The binding's words, as prepare_openmp_environment found them (main sets them).
inline std::string& openmp_binding() {
  static std::string words;
  return words;
}

}  // namespace mp
