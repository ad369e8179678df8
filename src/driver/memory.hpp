// The memory a run will hold on each rank, known before it allocates (docs/running.md, "Memory
// estimate"): the scene is set up, its dump fields computed and two cycles run on a small probe
// mesh under an AllocationTracker (src/core/memory.hpp), every allocation is sorted by its size
// into a cell array (a multiple of the probe's cell extents), a node array (of its node extents)
// or neither (mixed-cell pools, lists, constants), and each class is scaled to this rank's
// block: cells and nodes by the ratio of the extents, the rest by the number of interface cells
// (the probe's times (h_probe / h)^(D - 1) on a D-dimensional mesh, the rank's share of it).
// Added to it: the programmed burn's lighting-time construction (host arrays over the global
// mesh, every rank), the halo buffers of a block with neighbour ranks, the HDF5 output, and the
// process itself (its resident memory after the probe: MPI, Kokkos, the code).
#pragma once
#include <string>

#include "config/scene.hpp"
#include "mesh/mesh.hpp"

namespace mp {

struct MemoryEstimate {
  // bytes, at the run's peak
  double cells = 0, nodes = 0, other = 0;  // the allocations by class, scaled to the block
  double lighting = 0;                     // lighting-time construction (set-up only)
  double halo = 0;                         // halo exchange buffers
  double output = 0;                       // HDF5 library and one field's host copy
  double process = 0;                      // resident memory without the run's arrays
  double total() const { return cells + nodes + other + lighting + halo + output + process; }
  // "1.21e+03 MiB (cell arrays 700 MiB, node arrays 300 MiB, ...)"
  std::string text() const;
};

// The estimate for `block`, this rank's part of the scene's mesh (not allocated). Runs the
// probe on this rank alone (MPI_COMM_SELF): writes nothing, logs nothing, leaves the physics of
// the real run unchanged; about 0.1 s.
MemoryEstimate estimate_memory(const Scene& scene, const Mesh& block);

// "12.3 MiB"
std::string mib(double bytes);

}  // namespace mp
