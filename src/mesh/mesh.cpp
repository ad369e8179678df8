#include "mesh/mesh.hpp"

#include <sstream>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace mp {

const char* to_string(BoundaryKind b) {
  switch (b) {
    case BoundaryKind::Reflective:
      return "reflective";
    case BoundaryKind::Outflow:
      return "outflow";
    case BoundaryKind::Periodic:
      return "periodic";
  }
  return "?";
}

namespace {
// Cells of coordinate c when n cells are split over p ranks: the first n % p ranks get one more.
int split_count(int n, int p, int c) {
  return n / p + (c < n % p ? 1 : 0);
}
int split_offset(int n, int p, int c) {
  return c * (n / p) + (c < n % p ? c : n % p);
}
}  // namespace

Mesh::Mesh(const MeshSpec& spec, MPI_Comm comm) : spec_(spec) {
  int world_size = 1;
  MPI_CHECK(MPI_Comm_size(comm, &world_size));
  for (int d = 0; d < 3; ++d) {
    if (spec.cells[d] < 1)
      throw InputError(std::string("mesh: cell count along ") + "xyz"[d] +
                       " must be positive (got " + std::to_string(spec.cells[d]) + ")");
    if (!(spec.hi[d] > spec.lo[d]))
      throw InputError(std::string("mesh: upper corner must exceed lower corner along ") +
                       "xyz"[d]);
    if ((spec.bc[d][0] == BoundaryKind::Periodic) != (spec.bc[d][1] == BoundaryKind::Periodic))
      throw InputError(std::string("mesh: periodic boundary on axis ") + "xyz"[d] +
                       " must be set on both faces");
  }

  int dims[3] = {spec.ranks[0], spec.ranks[1], spec.ranks[2]};
  const bool user_dims = dims[0] > 0 || dims[1] > 0 || dims[2] > 0;
  MPI_CHECK(MPI_Dims_create(world_size, 3, dims));
  if (!user_dims) {
    // MPI_Dims_create returns non-increasing factors; give the largest to the longest axis so
    // blocks stay close to cubes and halos small.
    std::array<int, 3> order{{0, 1, 2}};
    for (int a = 0; a < 3; ++a)
      for (int b = a + 1; b < 3; ++b)
        if (spec.cells[order[b]] > spec.cells[order[a]]) std::swap(order[a], order[b]);
    int sorted[3] = {dims[0], dims[1], dims[2]};
    for (int a = 0; a < 3; ++a) dims[order[a]] = sorted[a];
    // When that split leaves a block thinner than the halo (a long thin box, say), take the
    // feasible factorisation with the least halo surface instead.
    auto feasible = [&](const int* p) {
      for (int d = 0; d < 3; ++d)
        if (spec.cells[d] / p[d] < ng) return false;
      return true;
    };
    if (!feasible(dims)) {
      double best = -1;
      for (int px = 1; px <= world_size; ++px)
        for (int py = 1; px * py <= world_size; ++py) {
          if (world_size % (px * py) != 0) continue;
          const int p[3] = {px, py, world_size / (px * py)};
          if (!feasible(p)) continue;
          double surface = 0;  // ghost faces added by the cuts
          for (int d = 0; d < 3; ++d)
            surface += double(p[d] - 1) * spec.cells[(d + 1) % 3] * spec.cells[(d + 2) % 3];
          if (best < 0 || surface < best) {
            best = surface;
            for (int d = 0; d < 3; ++d) dims[d] = p[d];
          }
        }
    }
  }
  for (int d = 0; d < 3; ++d) {
    dims_[d] = dims[d];
    if (spec.cells[d] / dims[d] < ng) {
      std::ostringstream os;
      os << "mesh: " << spec.cells[d] << " cells along "
         << "xyz"[d] << " cannot be split over " << dims[d] << " ranks with at least " << ng
         << " cells each (decomposition " << dims[0] << "x" << dims[1] << "x" << dims[2] << " of "
         << world_size << " ranks)";
      throw InputError(os.str());
    }
  }
  int periods[3];
  for (int d = 0; d < 3; ++d) periods[d] = spec.bc[d][0] == BoundaryKind::Periodic ? 1 : 0;
  MPI_CHECK(MPI_Cart_create(comm, 3, dims, periods, 0, &cart_));
  MPI_CHECK(MPI_Comm_rank(cart_, &rank_));
  MPI_CHECK(MPI_Comm_size(cart_, &nranks_));
  int coords[3];
  MPI_CHECK(MPI_Cart_coords(cart_, rank_, 3, coords));
  for (int d = 0; d < 3; ++d) {
    coords_[d] = coords[d];
    MPI_CHECK(MPI_Cart_shift(cart_, d, 1, &neighbor_[d][0], &neighbor_[d][1]));
    nl_[d] = split_count(spec.cells[d], dims[d], coords[d]);
    offset_[d] = split_offset(spec.cells[d], dims[d], coords[d]);
    geo_.lo[d] = Real(spec.lo[d]);
    geo_.dx[d] = Real((spec.hi[d] - spec.lo[d]) / spec.cells[d]);
    geo_.offset[d] = offset_[d];
    geo_.nl[d] = nl_[d];
  }
  geo_.ng = ng;
}

Mesh::~Mesh() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && cart_ != MPI_COMM_NULL) MPI_Comm_free(&cart_);
}

std::array<int, 2> Mesh::range(Centering c, Region r, int d) const {
  const int extra = c == Centering::Node ? 1 : 0;
  if (r == Region::All) return {0, nl_[d] + 2 * ng + extra};
  return {ng, ng + nl_[d] + extra};
}

Policy3 Mesh::policy(Centering c, Region r) const {
  const auto x = range(c, r, 0), y = range(c, r, 1), z = range(c, r, 2);
  return Policy3({x[0], y[0], z[0]}, {x[1], y[1], z[1]});
}

Policy3 Mesh::cells_padded(int pad) const {
  return Policy3({ng - pad, ng - pad, ng - pad},
                 {ng + nl_[0] + pad, ng + nl_[1] + pad, ng + nl_[2] + pad});
}

Field3 Mesh::new_field(const std::string& name, Centering c) const {
  return Field3(name, extent(c, 0), extent(c, 1), extent(c, 2));
}

std::string Mesh::describe() const {
  std::ostringstream os;
  os << spec_.cells[0] << "x" << spec_.cells[1] << "x" << spec_.cells[2] << " cells on " << nranks_
     << " rank" << (nranks_ > 1 ? "s" : "") << " (" << dims_[0] << "x" << dims_[1] << "x"
     << dims_[2] << "), " << ng << " ghost layers, boundaries x:" << to_string(spec_.bc[0][0])
     << "/" << to_string(spec_.bc[0][1]) << " y:" << to_string(spec_.bc[1][0]) << "/"
     << to_string(spec_.bc[1][1]) << " z:" << to_string(spec_.bc[2][0]) << "/"
     << to_string(spec_.bc[2][1]);
  return os.str();
}

}  // namespace mp
