// Programmed-burn lighting times built by Kokkos kernels on each rank's own block (the
// construction the runs use; lighting.hpp's host Lazy Theta* over the global grid is its
// reference, kept as the option `burn.lighting: host`).
//
// Method: an any-angle label-correcting iteration, the parallel form of lighting.hpp's
// construction (same candidates, same line-of-sight walk, detail::sees). Every explosive cell
// holds a label: its time and its parent, a detonator or a pivot point (a cell centre or a
// corner of the inert staircase, nudged 1e-9 into an explosive cell) with the pivot's time; its
// time is the parent's time plus the straight distance over D. Each sweep, every explosive cell
// of the box of the rank's explosive cells weighs the labels its 26 neighbours changed in the
// last sweep (the others it weighed when they changed): the least-time parent among them, if the
// straight segment to it crosses only explosive cells (which makes it the best of all their
// candidates, by the triangle inequality), else (hidden) the best of: a neighbour's centre, a
// neighbour's parent it sees, a corner of a neighbour touching inert cells reached straight from
// that neighbour's parent, and the corners of the inert cell that hides a neighbour's parent
// (lighting.hpp's candidates, in its order). A cell keeps its label unless a
// candidate is strictly earlier, so times only fall and the sweeps end; they run Jacobi-style
// (every cell reads the last sweep's labels), so the result is independent of threads and of
// the decomposition: 1, 2 and 4 ranks give the same bits. Between sweeps one ghost layer of
// labels is exchanged with the neighbour ranks; the sweeps stop when no rank changed a label
// (MPI_Allreduce). Sweeps: about the longest path in cells (plus a few where paths bend).
// Differences from the host construction: no pivot chains (a cell does not "pull the string" to
// its pivot's own parent; the iteration finds that parent through the neighbours instead, where
// the parent's region of sight is connected), and the label correction may improve a
// cell after it first got a time, which the host's Dijkstra closes once. In line of sight of a
// detonator the times are the same bits (the same parent, the same formula); in the shadow within
// 0.11 h/D of the host's on Kenamond 3 at 64^3 (tests/test_lighting_device.cpp).
// Cost on one thread, against the host construction, 2026-12-07 on a shared 2-core VM, back to
// back: Kenamond 3 at 64^3 (all explosive but the ball, 62 sweeps) 0.64 s against 0.53-0.60 s;
// the perforator at zone 0.1 (450,000 cells, 4608 lit, 20 sweeps over the charges' box) 0.029 s
// against 0.012 s. Its work divides over ranks and threads; the host's is done whole on every
// rank.
//
// A mesh has at least two cells along every axis (its ghost layers), so the host construction's
// 2-D case (one cell in z, corners in the plane) does not arise here.
//
// Memory: the labels (two copies, 48 B each) and two change flags per cell of the rank's block
// (the mesh's cell extent, ghosts included), freed when the times are written; the line-of-sight
// walk crosses rank boundaries, so every rank holds the explosive mask of the whole grid packed
// one bit a cell (ExplosiveBits: 1/8 B a global cell, plus as much in a host copy for the MPI
// reduction: kLightingMaskBytesPerCell, counted in the run's memory estimate).
#pragma once
#include <cstdint>
#include <vector>

#include "burn/lighting.hpp"
#include "mesh/mesh.hpp"

namespace mp::burn {

// Bytes per global cell every rank holds for the explosive bit mask (device copy and host copy).
constexpr double kLightingMaskBytesPerCell = 0.25;

// The explosive cells of the global grid, one bit a cell (LightingGrid order), the same on every
// rank.
struct ExplosiveBits {
  Kokkos::View<std::uint32_t*, MemSpace> words;
  LightingBox box{};

  KOKKOS_INLINE_FUNCTION bool in_grid(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < box.n[0] && j < box.n[1] && k < box.n[2];
  }
  // (i, j, k) in the grid
  KOKKOS_INLINE_FUNCTION bool explosive(int i, int j, int k) const {
    const long c = i + long(box.n[0]) * (j + long(box.n[1]) * k);
    return (words(c >> 5) >> (c & 31)) & 1u;
  }
  // inert as detail::sees wants it: a grid cell that is not explosive
  KOKKOS_INLINE_FUNCTION bool operator()(int i, int j, int k) const {
    return in_grid(i, j, k) && !explosive(i, j, k);
  }
};

// The mask gathered over the ranks (collective): each rank marks its owned cells where
// frac(i, j, k) >= threshold (frac null: every cell).
ExplosiveBits explosive_bits(const Mesh& mesh, const LightingGrid& g, const Field3* frac,
                             Real threshold);
// The same from a global host mask (one byte a cell, LightingGrid order), for tests.
ExplosiveBits explosive_bits(const Mesh& mesh, const LightingGrid& g,
                             const std::vector<std::uint8_t>& explosive);

// A cell's label: its time and its parent.
struct LightingLabel {
  double t;      // us; kNeverLit: not reached
  double pt;     // the pivot's time (code 1)
  double px[3];  // the pivot (code 1)
  int code;      // 0: none; -(q + 1): detonator q; 1: the pivot (px, pt)
};

struct LightingRun {
  // labels of the rank's cells (mesh indices, ghosts included; one ghost layer filled)
  Kokkos::View<LightingLabel***, MemSpace> label;
  int sweeps = 0;
};

// The lighting times of the rank's block of grid g (the mesh's global grid; collective). Errors
// as lighting_times (std::invalid_argument, the same text): a detonator lighting no explosive
// cell, a plane detonator with a zero normal.
LightingRun lighting_times_device(const Mesh& mesh, const LightingGrid& g,
                                  const ExplosiveBits& bits,
                                  const std::vector<Detonator>& detonators, double d_cj);

}  // namespace mp::burn
