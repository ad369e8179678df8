#include "core/error.hpp"

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

}  // namespace mp
