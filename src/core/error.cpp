#include "core/error.hpp"

#include <hdf5.h>
#include <mpi.h>

#include <sstream>

namespace mp {

void throw_mpi_error(int code, const char* call, const char* file, int line) {
  char text[MPI_MAX_ERROR_STRING] = {0};
  int len = 0;
  std::ostringstream os;
  os << call << " failed at " << file << ":" << line;
  if (MPI_Error_string(code, text, &len) == MPI_SUCCESS && len > 0)
    os << ": " << std::string(text, static_cast<size_t>(len));
  else
    os << ": MPI error code " << code;
  throw RunError(os.str());
}

namespace {
// Keeps the most specific entry of the HDF5 error stack (where the error was first detected).
herr_t first_hdf5_error(unsigned n, const H5E_error2_t* err, void* data) {
  if (n == 0 && err != nullptr) {
    auto* out = static_cast<std::string*>(data);
    *out = std::string(err->func_name ? err->func_name : "?") + ": " +
           (err->desc ? err->desc : "no description");
  }
  return 0;
}
}  // namespace

void throw_hdf5_error(const char* call, const char* file, int line) {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, first_hdf5_error, &detail);
  H5Eclear2(H5E_DEFAULT);
  std::ostringstream os;
  os << call << " failed at " << file << ":" << line;
  if (!detail.empty()) os << " (" << detail << ")";
  throw RunError(os.str());
}

}  // namespace mp
