// The block-structured Cartesian mesh of one MPI rank: its place in the global box, its ghost
// layers, and the typed index ranges every kernel loops over (STYLE.md practice 3).
//
// Index convention (same on every axis d):
//   cells  0 .. nl+2*ng-1     owned cells are [ng, ng+nl)
//   nodes  0 .. nl+2*ng       owned nodes are [ng, ng+nl]  (node i is the low corner of cell i)
// A node on the face between two ranks is computed by both ranks from identical data, so it
// takes the same value on both; the halo exchange never sends it.
#pragma once
#include <mpi.h>

#include <array>
#include <string>

#include "core/types.hpp"

namespace mp {

enum class Centering { Cell, Node };
enum class Region { Owned, All };  // Owned: computed here; All: owned plus ghost layers
enum class BoundaryKind { Reflective, Outflow, Periodic };

const char* to_string(BoundaryKind b);

struct MeshSpec {
  std::array<int, 3> cells{{10, 10, 10}};  // global cell counts
  std::array<double, 3> lo{{0, 0, 0}};
  std::array<double, 3> hi{{1, 1, 1}};
  // [axis][side]: side 0 is the low face, 1 the high face. Periodic must be set on both sides.
  std::array<std::array<BoundaryKind, 2>, 3> bc{};
  std::array<int, 3> ranks{{0, 0, 0}};  // ranks per axis; 0 lets MPI_Dims_create choose
};

// Device-copyable geometry of one block: what a kernel needs to know about where it is.
struct Geometry {
  Real lo[3];     // global low corner of the box
  Real dx[3];     // cell sizes
  int offset[3];  // global index of this block's first owned cell
  int nl[3];      // owned cells per axis
  int ng;         // ghost layers

  KOKKOS_INLINE_FUNCTION Real cell_center(int d, int i) const {
    return lo[d] + (Real(offset[d] + i - ng) + Real(0.5)) * dx[d];
  }
  KOKKOS_INLINE_FUNCTION Real node_coord(int d, int i) const {
    return lo[d] + Real(offset[d] + i - ng) * dx[d];
  }
  KOKKOS_INLINE_FUNCTION int global_index(int d, int i) const { return offset[d] + i - ng; }
  // Global linear index (x fastest) of local cell (i, j, k) on a global nx x ny x nz mesh.
  KOKKOS_INLINE_FUNCTION long global_cell(int i, int j, int k, long nx, long ny) const {
    return global_index(0, i) + nx * (global_index(1, j) + ny * global_index(2, k));
  }
  KOKKOS_INLINE_FUNCTION Real cell_volume() const { return dx[0] * dx[1] * dx[2]; }
};

class Mesh {
 public:
  static constexpr int ng = 2;  // the second-order remap stencil reads two cells upwind

  // Splits the global box over the ranks of `comm`; throws InputError when the split would
  // leave a rank with fewer than `ng` cells along an axis.
  Mesh(const MeshSpec& spec, MPI_Comm comm);
  ~Mesh();
  Mesh(const Mesh&) = delete;
  Mesh& operator=(const Mesh&) = delete;

  const MeshSpec& spec() const { return spec_; }
  MPI_Comm comm() const { return cart_; }
  int rank() const { return rank_; }
  int nranks() const { return nranks_; }
  const std::array<int, 3>& dims() const { return dims_; }
  const std::array<int, 3>& coords() const { return coords_; }

  int global_cells(int d) const { return spec_.cells[d]; }
  long long global_cell_count() const {
    return 1LL * spec_.cells[0] * spec_.cells[1] * spec_.cells[2];
  }
  int owned_cells(int d) const { return nl_[d]; }
  // One past the last owned cell along each axis (the owned cells start at ng).
  std::array<int, 3> owned_end() const { return {ng + nl_[0], ng + nl_[1], ng + nl_[2]}; }
  long long owned_cell_count() const { return 1LL * nl_[0] * nl_[1] * nl_[2]; }
  int offset(int d) const { return offset_[d]; }
  Real dx(int d) const { return geo_.dx[d]; }
  const Geometry& geometry() const { return geo_; }

  // Extent of a field's view along d, ghosts included.
  int extent(Centering c, int d) const { return nl_[d] + 2 * ng + (c == Centering::Node ? 1 : 0); }
  // Half-open index range [first, last) along d.
  std::array<int, 2> range(Centering c, Region r, int d) const;

  Policy3 cells(Region r) const { return policy(Centering::Cell, r); }
  Policy3 nodes(Region r) const { return policy(Centering::Node, r); }
  Policy3 policy(Centering c, Region r) const;
  // The same index box as bounds [lo, hi) (for core/columns.hpp's for_columns).
  void box(Centering c, Region r, int lo[3], int hi[3]) const {
    for (int d = 0; d < 3; ++d) {
      const auto x = range(c, r, d);
      lo[d] = x[0];
      hi[d] = x[1];
    }
  }
  // Cells [ng - lo_pad, ng + nl + hi_pad) along every axis, for stencils that reach into ghosts.
  Policy3 cells_padded(int pad) const;

  // Neighbour rank along d on side s (0 low, 1 high); MPI_PROC_NULL at a physical boundary.
  int neighbor(int d, int s) const { return neighbor_[d][s]; }
  bool physical_boundary(int d, int s) const { return neighbor_[d][s] == MPI_PROC_NULL; }
  BoundaryKind boundary(int d, int s) const { return spec_.bc[d][s]; }

  Field3 new_field(const std::string& name, Centering c) const;

  std::string describe() const;

 private:
  MeshSpec spec_;
  MPI_Comm cart_ = MPI_COMM_NULL;
  int rank_ = 0, nranks_ = 1;
  std::array<int, 3> dims_{}, coords_{}, nl_{}, offset_{};
  std::array<std::array<int, 2>, 3> neighbor_{};
  Geometry geo_{};
};

}  // namespace mp
