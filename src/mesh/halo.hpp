// Ghost-layer exchange of cell and node fields, with the physical boundary conditions.
//
// The exchange runs axis by axis (x, then y, then z). Each axis sends the whole extent of the
// other two axes, ghosts included, so after the y sweep the x-ghosts of the y-ghost layers are
// right, and after z every edge and corner ghost is filled: three rounds of two messages reach
// all 26 neighbours. Physical boundaries are applied inside the same sweep, so a corner ghost
// next to a reflective wall and a periodic seam gets both treatments in a defined order.
// Buffers are packed by Kokkos kernels, one message per neighbour per axis for all fields.
// Launches: a block with no neighbour rank (every side a physical boundary or a periodic axis
// it holds alone) fills every ghost of every field of an exchange, walls included, in one
// launch per 8 fields; otherwise, per axis, one pack kernel for both sides (where another rank
// neighbours) and one fill kernel for every ghost layer of both sides of every field (up to 8
// fields a launch): what a neighbour sent, the mirror or copy of a physical boundary, the zero of a
// reflective wall node, or the opposite side of the block itself (periodic, no message).
// A single-material cycle at one rank: 11 fills (tests/test_launches.cpp); it was 93 launches
// of one slab and one side each.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace mp {

// A field as the halo sees it. `parity[d]` is the sign the field takes under reflection in a
// plane normal to axis d: +1 for scalars, -1 for the d-component of a vector.
struct HaloField {
  Field3 view;
  Centering centering = Centering::Cell;
  std::array<int, 3> parity{{1, 1, 1}};
  // A face field normal to this axis (0..2): node-like along it, cell-like along the others,
  // stored in a node-extent view. -1: a plain cell or node field.
  int face_axis = -1;
  Centering along(int d) const {
    if (face_axis < 0) return centering;
    return d == face_axis ? Centering::Node : Centering::Cell;
  }
};

// Messages go from and into the buffers themselves where MPI can address them: on a host
// backend, and on a device backend when the MPI library is CUDA-aware (Open MPI's
// MPIX_Query_cuda_support(), asked once). MINIPAGOSA_MPI_DEVICE_BUFFERS=1 asserts that it is
// (another CUDA-aware MPI); =0 stages every message through host arrays kept between exchanges
// (no allocation in a cycle), which a device backend does by itself with an MPI that is not,
// and which the tests use to check the staged path on a host. message_path() says which, for
// the run log.
bool message_in_place();
std::string message_path();

// Sends send[s] (count values) to the neighbour rank on side s of axis d and receives recv[s]
// from it, for each side that is not a physical boundary; tags start at tag_base so that
// several kinds of exchange cannot pair up wrongly. Returns the bytes sent. T is float or
// double (Buffer's Real, or double where a message must carry doubles whatever Real is).
template <class T>
double exchange_buffers(const Mesh& mesh, int d, const Kokkos::View<T*, MemSpace> send[2],
                        const Kokkos::View<T*, MemSpace> recv[2], long count, int tag_base);

// The same for messages whose length varies: send[s] carries send_count[s] values, and what
// arrives from side s (its length found with MPI_Probe) is received into recv[s], which is
// reallocated (labelled recv_label), a quarter larger than the message, only when it is too short.
// Returns the bytes sent.
double exchange_sized(const Mesh& mesh, int d, const Buffer send[2], const long send_count[2],
                      Buffer recv[2], int tag_base, const std::string& recv_label);

class Halo {
 public:
  explicit Halo(const Mesh& mesh);
  // Fills every ghost cell/node of every field; all fields must share one layout.
  void exchange(const std::vector<HaloField>& fields);
  // Bytes sent by this rank so far (for the perf harness); a periodic axis held by this rank
  // alone counts what its messages to itself would carry, though it copies in place.
  double bytes_sent() const { return bytes_sent_; }

 private:
  void exchange_axis(const std::vector<HaloField>& fields, int d);

  const Mesh& mesh_;
  Buffer send_[2], recv_[2];
  double bytes_sent_ = 0;
};

}  // namespace mp
