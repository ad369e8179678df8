// Small shared pieces of the HDF5 output and checkpoint code: RAII handles, attributes, the
// owned-block hyperslab of a field, and root-only work whose failure every rank learns.
#pragma once
#include <hdf5.h>
#include <mpi.h>

#include <string>
#include <type_traits>
#include <vector>

#include "core/error.hpp"
#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace mp {

// Throws RunError naming the HDF5 call (HDF5_CHECK, below), where it failed and the HDF5 error
// stack's first entry.
[[noreturn]] void throw_hdf5_error(const char* call, const char* file, int line);

// Writes `text` to <path>.tmp, flushes it to the disk, and renames it to `path`; on failure
// removes the temporary file and throws RunError naming the file and the system's reason
// ("No space left on device").
void write_text_atomically(const std::string& path, const std::string& text);
// "; no space left on device (N KiB free ...)" when the file system holding `path` is (nearly)
// full, else "": HDF5's MPI-IO layer reports a failed write without the system's reason.
std::string disk_space_note(const std::string& path);
}  // namespace mp

namespace mp::h5 {

// Owns one hid_t and closes it with the matching H5?close, so an exception never leaks it.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  ~Handle() {
    if (id_ >= 0) closer_(id_);  // best effort: an error is already in flight or was reported
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  // Takes ownership of id when it is valid; returns id so HDF5_CHECK sees the raw result.
  hid_t reset(hid_t id, Closer closer) {
    if (id_ >= 0) closer_(id_);
    id_ = id >= 0 ? id : -1;
    closer_ = closer;
    return id;
  }
  // Closes now and returns the closer's status, for the handles whose close can fail (files).
  herr_t close() {
    if (id_ < 0) return 0;
    const hid_t id = id_;
    id_ = -1;
    return closer_(id);
  }
  hid_t get() const { return id_; }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

inline hid_t native_real_type() {
  return std::is_same<Real, double>::value ? H5T_NATIVE_DOUBLE : H5T_NATIVE_FLOAT;
}

// Writes a small attribute (scalar when n == 0, else a 1-D array of n) on the object `loc`.
void write_attribute(hid_t loc, const char* name, hid_t type, hsize_t n, const void* data);
// A string attribute (fixed length, the string's own size).
void write_string_attribute(hid_t loc, const char* name, const std::string& value);
// Reads attributes back; throws RunError naming the attribute when it is missing or misshapen.
std::string read_string_attribute(hid_t loc, const char* name);
std::vector<double> read_double_attribute(hid_t loc, const char* name);
long read_long_attribute(hid_t loc, const char* name);

// Collective: creates dataset `name` of the global shape of a `centering` field and writes this
// rank's owned block of `view` (shared face nodes by the lower rank only).
void write_block(hid_t file, hid_t dxpl, const Mesh& mesh, const std::string& name,
                 Centering centering, const Field3& view);
// Collective: reads this rank's owned block of dataset `name` into `view` (nodes: every owned
// node, the shared face nodes included). Throws RunError when the dataset's shape or type
// does not match.
void read_block(hid_t file, hid_t dxpl, const Mesh& mesh, const std::string& name,
                Centering centering, const Field3& view);

// Rank 0 does `work` (which reports failure by throwing), the others learn the outcome, and
// every rank throws the same RunError if it failed: no rank is left waiting.
template <class F>
void on_root(MPI_Comm comm, F&& work) {
  int rank = 0;
  MPI_CHECK(MPI_Comm_rank(comm, &rank));
  std::string msg;
  if (rank == 0) {
    try {
      work();
    } catch (const std::exception& e) {
      msg = e.what();
      if (msg.empty()) msg = "unknown error";
    }
  }
  int len = static_cast<int>(msg.size());
  MPI_CHECK(MPI_Bcast(&len, 1, MPI_INT, 0, comm));
  if (len > 0) {
    msg.resize(static_cast<size_t>(len));
    MPI_CHECK(MPI_Bcast(&msg[0], len, MPI_CHAR, 0, comm));
    throw CollectiveError(msg);
  }
}

// Every rank runs `work`; if it failed on any rank, every rank throws (the first failing
// rank's message), so a collective that follows is never entered by only some ranks.
template <class F>
void on_all(MPI_Comm comm, F&& work) {
  std::string msg;
  try {
    work();
  } catch (const std::exception& e) {
    msg = e.what();
    if (msg.empty()) msg = "unknown error";
  }
  int rank = 0, bad = 0;
  MPI_CHECK(MPI_Comm_rank(comm, &rank));
  int mine = msg.empty() ? 1 << 30 : rank;
  MPI_CHECK(MPI_Allreduce(&mine, &bad, 1, MPI_INT, MPI_MIN, comm));
  if (bad == 1 << 30) return;
  int len = static_cast<int>(msg.size());
  MPI_CHECK(MPI_Bcast(&len, 1, MPI_INT, bad, comm));
  msg.resize(static_cast<size_t>(len));
  MPI_CHECK(MPI_Bcast(&msg[0], len, MPI_CHAR, bad, comm));
  throw CollectiveError(msg);
}

// rename(2) with the reason in the error.
void rename_or_throw(const std::string& from, const std::string& to);

}  // namespace mp::h5

#define HDF5_CHECK(call)                                               \
  do {                                                                 \
    if ((call) < 0) ::mp::throw_hdf5_error(#call, __FILE__, __LINE__); \
  } while (0)
