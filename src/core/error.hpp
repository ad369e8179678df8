// Errors that carry their context and stop cleanly (STYLE.md practice 7).
#pragma once
#include <stdexcept>
#include <string>

namespace mp {

// Bad input: names the deck file, line and key. Caught in main, nothing is written.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run that went non-physical or an I/O / MPI failure.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A RunError that every rank of the communicator throws together (the I/O helpers agree on
// failure before throwing), so the program can end without MPI_Abort.
class CollectiveError : public RunError {
 public:
  using RunError::RunError;
};

[[noreturn]] void throw_mpi_error(int code, const char* call, const char* file, int line);

}  // namespace mp

#define MPI_CHECK(call)                                                                  \
  do {                                                                                   \
    const int mp_rc_ = (call);                                                           \
    if (mp_rc_ != MPI_SUCCESS) ::mp::throw_mpi_error(mp_rc_, #call, __FILE__, __LINE__); \
  } while (0)
