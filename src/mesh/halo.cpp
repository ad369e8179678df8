#include "mesh/halo.hpp"

#include "core/error.hpp"

namespace mp {

namespace {

// The slab [lo, hi) along axis d, whole extent along the other axes.
struct Slab {
  int lo[3], hi[3];
  int size() const { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
  Policy3 policy() const { return Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}); }
};

Slab slab(const Mesh& mesh, const HaloField& f, int d, int first, int last) {
  Slab s{};
  for (int a = 0; a < 3; ++a) {
    const auto r = mesh.range(f.along(a), Region::All, a);
    s.lo[a] = r[0];
    s.hi[a] = r[1];
  }
  s.lo[d] = first;
  s.hi[d] = last;
  return s;
}

// A reflective wall node of a field odd under reflection in d (the normal velocity) is zero.
// Done before the sweep along d packs anything: a block only ng cells thick sends its wall node
// to the neighbour, which must receive the zero, not the value the wall node had before.
void zero_wall_node(const Mesh& mesh, const HaloField& hf, int d, int side) {
  if (hf.along(d) != Centering::Node || hf.parity[d] >= 0) return;
  if (!mesh.physical_boundary(d, side) || mesh.boundary(d, side) != BoundaryKind::Reflective)
    return;
  const int wall = side == 0 ? Mesh::ng : Mesh::ng + mesh.owned_cells(d);
  const Slab w = slab(mesh, hf, d, wall, wall + 1);
  auto f = hf.view;
  Kokkos::parallel_for(
      "halo::wall_node", w.policy(), KOKKOS_LAMBDA(int i, int j, int k) { f(i, j, k) = 0; });
}

// Index ranges along d for what side s sends and what it receives.
// Cells: send the ng owned layers next to the face, receive into the ng ghost layers.
// Nodes: the face node is shared and never sent; send the ng layers inside it.
void send_range(const Mesh& m, Centering c, int d, int s, int& first, int& last) {
  const int ng = Mesh::ng, nl = m.owned_cells(d);
  if (c == Centering::Cell) {
    first = s == 0 ? ng : nl;
  } else {
    first = s == 0 ? ng + 1 : nl;
  }
  last = first + ng;
}
void recv_range(const Mesh& m, Centering c, int d, int s, int& first, int& last) {
  const int ng = Mesh::ng, nl = m.owned_cells(d);
  if (c == Centering::Cell) {
    first = s == 0 ? 0 : ng + nl;
  } else {
    first = s == 0 ? 0 : ng + nl + 1;
  }
  last = first + ng;
}

// Up to kBatch fields of one layout handled by one kernel (one launch per slab instead of one
// per field); exchanges carry two or three fields.
constexpr int kBatch = 4;
struct Batch {
  Kokkos::Array<Field3, kBatch> f;
  Kokkos::Array<Real, kBatch> sign;  // parity under reflection along the sweep's axis
  int n = 0;
  int first = 0;  // index of the batch's first field in the exchange
};

std::vector<Batch> batches(const std::vector<HaloField>& fields, int d) {
  std::vector<Batch> out;
  for (std::size_t q = 0; q < fields.size(); ++q) {
    if (q % kBatch == 0) {
      out.emplace_back();
      out.back().first = int(q);
    }
    Batch& b = out.back();
    b.f[b.n] = fields[q].view;
    b.sign[b.n] = Real(fields[q].parity[d]);
    ++b.n;
  }
  return out;
}

void pack(const Batch& b, const Buffer& buf, const Slab& sl, int per_field) {
  const int n0 = sl.hi[0] - sl.lo[0], n1 = sl.hi[1] - sl.lo[1];
  const int l0 = sl.lo[0], l1 = sl.lo[1], l2 = sl.lo[2];
  Kokkos::parallel_for(
      "halo::pack", sl.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const int at = (i - l0) + n0 * ((j - l1) + n1 * (k - l2));
        for (int q = 0; q < b.n; ++q) buf((b.first + q) * per_field + at) = b.f[q](i, j, k);
      });
}

void unpack(const Batch& b, const Buffer& buf, const Slab& sl, int per_field) {
  const int n0 = sl.hi[0] - sl.lo[0], n1 = sl.hi[1] - sl.lo[1];
  const int l0 = sl.lo[0], l1 = sl.lo[1], l2 = sl.lo[2];
  Kokkos::parallel_for(
      "halo::unpack", sl.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const int at = (i - l0) + n0 * ((j - l1) + n1 * (k - l2));
        for (int q = 0; q < b.n; ++q) b.f[q](i, j, k) = buf((b.first + q) * per_field + at);
      });
}

// Reflective: the ghost layer is the mirror image of the interior, times the field's parity
// (a velocity normal to the wall changes sign; it vanishes on the wall node itself, which
// zero_wall_node set at the start of the sweep).
// Outflow: zero gradient, every ghost layer copies the boundary cell or node.
void apply_boundary(const Mesh& mesh, const HaloField& hf, const std::vector<Batch>& bs, int d,
                    int side) {
  // hf: the first field; every field of an exchange shares its layout
  const int ng = Mesh::ng, nl = mesh.owned_cells(d);
  const bool node = hf.along(d) == Centering::Node;
  const BoundaryKind kind = mesh.boundary(d, side);
  // The wall: the owned layer adjacent to the face (cells) or the face node itself (nodes).
  const int wall = side == 0 ? ng : (node ? ng + nl : ng + nl - 1);
  const int dir = side == 0 ? -1 : 1;  // from the wall outwards
  const int first_ghost = node ? wall + dir : (side == 0 ? ng - 1 : ng + nl);
  int first = 0, last = 0;
  recv_range(mesh, hf.along(d), d, side, first, last);
  const Slab sl = slab(mesh, hf, d, first, last);
  const bool reflective = kind == BoundaryKind::Reflective;
  for (const Batch& b : bs)
    Kokkos::parallel_for(
        "halo::boundary", sl.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
          int idx[3] = {i, j, k};
          const int layer = (idx[d] - first_ghost) * dir;  // 0 next to the wall, 1 beyond
          int src[3] = {i, j, k};
          // cells: mirror across the face; nodes: mirror across the wall node; outflow: the
          // wall value
          src[d] = reflective ? (node ? wall - dir * (layer + 1) : wall - dir * layer) : wall;
          for (int q = 0; q < b.n; ++q) {
            const auto& f = b.f[q];
            f(i, j, k) =
                reflective ? b.sign[q] * f(src[0], src[1], src[2]) : f(src[0], src[1], src[2]);
          }
        });
}

MPI_Datatype mpi_real() {
  return sizeof(Real) == sizeof(double) ? MPI_DOUBLE : MPI_FLOAT;
}

}  // namespace

double exchange_buffers(const Mesh& mesh, int d, const Buffer send[2], const Buffer recv[2],
                        long count, int tag_base) {
  Kokkos::fence();
  // MPI works on host memory; on a host backend the mirrors are the device buffers.
  typename Buffer::HostMirror hsend[2], hrecv[2];
  MPI_Request req[4];
  int nreq = 0;
  double bytes = 0;
  for (int s = 0; s < 2; ++s) {
    if (mesh.physical_boundary(d, s)) continue;
    hsend[s] = Kokkos::create_mirror_view(send[s]);
    hrecv[s] = Kokkos::create_mirror_view(recv[s]);
    Kokkos::deep_copy(hsend[s], send[s]);
  }
  for (int s = 0; s < 2; ++s) {
    if (mesh.physical_boundary(d, s)) continue;
    // What arrives from side s was sent by that neighbour towards side 1-s: tag by the
    // sending side so a rank that is its own periodic neighbour pairs messages correctly.
    MPI_CHECK(MPI_Irecv(hrecv[s].data(), int(count), mpi_real(), mesh.neighbor(d, s),
                        tag_base + 10 * d + 1 - s, mesh.comm(), &req[nreq++]));
  }
  for (int s = 0; s < 2; ++s) {
    if (mesh.physical_boundary(d, s)) continue;
    MPI_CHECK(MPI_Isend(hsend[s].data(), int(count), mpi_real(), mesh.neighbor(d, s),
                        tag_base + 10 * d + s, mesh.comm(), &req[nreq++]));
    bytes += double(count) * sizeof(Real);
  }
  MPI_CHECK(MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE));
  for (int s = 0; s < 2; ++s)
    if (!mesh.physical_boundary(d, s)) Kokkos::deep_copy(recv[s], hrecv[s]);
  return bytes;
}

Halo::Halo(const Mesh& mesh) : mesh_(mesh) {}

void Halo::exchange(const std::vector<HaloField>& fields) {
  if (fields.empty()) return;
  for (const auto& f : fields)
    if (f.centering != fields[0].centering || f.face_axis != fields[0].face_axis)
      throw RunError("halo: one exchange takes fields of one layout");
  for (int d = 0; d < 3; ++d) exchange_axis(fields, d);
}

void Halo::exchange_axis(const std::vector<HaloField>& fields, int d) {
  for (int s = 0; s < 2; ++s)
    for (const auto& f : fields) zero_wall_node(mesh_, f, d, s);

  const HaloField& f0 = fields[0];
  const Centering c = f0.along(d);
  const int nf = static_cast<int>(fields.size());
  int first = 0, last = 0;
  send_range(mesh_, c, d, 0, first, last);
  const int per_field = slab(mesh_, f0, d, first, last).size();
  const int count = nf * per_field;
  const std::vector<Batch> bs = batches(fields, d);  // up to kBatch fields per launch

  bool any = false;
  for (int s = 0; s < 2; ++s) {
    if (mesh_.physical_boundary(d, s)) continue;
    any = true;
    if (static_cast<int>(send_[s].extent(0)) < count) {
      send_[s] = Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "halo::send"), count);
      recv_[s] = Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "halo::recv"), count);
    }
    send_range(mesh_, c, d, s, first, last);
    const Slab sl = slab(mesh_, f0, d, first, last);
    for (const Batch& b : bs) pack(b, send_[s], sl, per_field);
  }

  if (any) {
    bytes_sent_ += exchange_buffers(mesh_, d, send_, recv_, count, 0);
    for (int s = 0; s < 2; ++s) {
      if (mesh_.physical_boundary(d, s)) continue;
      recv_range(mesh_, c, d, s, first, last);
      const Slab sl = slab(mesh_, f0, d, first, last);
      for (const Batch& b : bs) unpack(b, recv_[s], sl, per_field);
    }
  }
  for (int s = 0; s < 2; ++s)
    if (mesh_.physical_boundary(d, s)) apply_boundary(mesh_, fields[0], bs, d, s);
}

}  // namespace mp
