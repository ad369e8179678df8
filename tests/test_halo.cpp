// Halo exchange: after one exchange every ghost cell/node (faces, edges, corners, both layers)
// holds what the boundary definitions say it should, on any rank count and uneven splits.
//
// The expected values are computed here from the definitions, independently of halo.cpp: the
// owned entries hold a function f of the global index; a ghost maps, axis by axis, to a source
// global index and a sign (periodic: wrap; reflective: mirror times parity; outflow: clamp), and
// its expected value is the product of the signs times f at the source. The mesh is
// block-structured and each axis rule only moves the index along its own axis, so applying the
// rules in the order x, y, z is this composition. A reflective wall node of a field with parity
// -1 along that axis is 0 (and so is every ghost copied from it).
//
// Every Halo's bytes_sent() equals, exactly, the bytes the exchanges it ran must send (ng layers
// of the whole extent of the other two axes, per field, to each side with a neighbour rank):
// nothing at all with walls on every face on one rank.
//
// Assertions are collective: errors are counted locally, summed over the ranks, and checked on
// every rank; the first few bad entries are printed with the rank to stderr.
#include <gtest/gtest.h>
#include <mpi.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "mesh/halo.hpp"
#include "mesh/mesh.hpp"

namespace {

using mp::BoundaryKind;
using mp::Centering;
using mp::Field3;
using mp::Halo;
using mp::HaloField;
using mp::Mesh;
using mp::MeshSpec;
using mp::Real;
using mp::Region;

constexpr BoundaryKind kR = BoundaryKind::Reflective;
constexpr BoundaryKind kO = BoundaryKind::Outflow;
constexpr BoundaryKind kP = BoundaryKind::Periodic;
using Bc = std::array<std::array<BoundaryKind, 2>, 3>;
using Parity = std::array<int, 3>;

const Real kSentinel = Real(-1e30);

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int world_size() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

long sum_over_ranks(long local) {
  long total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return total;
}

// The test function of field `id` at global index g: unique per entry and per field.
double f_global(int id, const long g[3]) {
  return double(g[0]) + 1000.0 * double(g[1]) + 1000000.0 * double(g[2]) + 0.5 + 100000000.0 * id;
}

// Where a global index along one axis takes its value from.
struct AxisSource {
  long src;
  int sign;
  bool zero;  // a reflective wall node of an odd field
};

// The boundary definitions along one axis with n global cells. `node`: node-centred along it.
AxisSource map_axis(long g, long n, bool node, BoundaryKind lo, BoundaryKind hi, int parity) {
  if (lo == kP) return {((g % n) + n) % n, 1, false};  // node n is node 0
  const long top = node ? n : n - 1;                   // last global index
  if (g < 0) {
    if (lo == kO) return {0, 1, false};
    return {node ? -g : -1 - g, parity, false};
  }
  if (g > top) {
    if (hi == kO) return {top, 1, false};
    return {node ? 2 * n - g : 2 * n - 1 - g, parity, false};
  }
  const bool wall = node && parity < 0 && ((g == 0 && lo == kR) || (g == n && hi == kR));
  return {g, 1, wall};
}

struct Layout {
  Centering centering;
  int face_axis;
  const char* name;
  Centering along(int d) const {
    if (face_axis < 0) return centering;
    return d == face_axis ? Centering::Node : Centering::Cell;
  }
};

const Layout kCell{Centering::Cell, -1, "cell"};
const Layout kNode{Centering::Node, -1, "node"};
const std::vector<Layout> kAllLayouts{kCell,
                                      kNode,
                                      {Centering::Node, 0, "face-x"},
                                      {Centering::Node, 1, "face-y"},
                                      {Centering::Node, 2, "face-z"}};

struct FieldDef {
  int id;
  Parity parity;
};

std::string bc_name(const Bc& bc) {
  std::string s;
  for (int d = 0; d < 3; ++d) {
    s += std::string(d ? " " : "") + "xyz"[d] + ":" + mp::to_string(bc[d][0]);
    if (bc[d][1] != bc[d][0]) s += std::string("/") + mp::to_string(bc[d][1]);
  }
  return s;
}

// Expected value of field `def` at local index (i, j, k), ghosts included. `after`: after the
// exchange (wall nodes of odd fields zeroed); otherwise the value the owned entries start with.
Real expected(const Mesh& mesh, const Layout& L, const FieldDef& def, const int idx[3],
              bool after) {
  long src[3];
  int sign = 1;
  bool zero = false;
  for (int d = 0; d < 3; ++d) {
    const long g = long(mesh.offset(d)) + idx[d] - Mesh::ng;
    const AxisSource a = map_axis(g, mesh.global_cells(d), L.along(d) == Centering::Node,
                                  mesh.boundary(d, 0), mesh.boundary(d, 1), def.parity[d]);
    src[d] = a.src;
    sign *= a.sign;
    zero = zero || a.zero;
  }
  if (after && zero) return Real(0);
  return Real(sign) * Real(f_global(def.id, src));
}

bool in_range(const std::array<int, 2>& r, int i) {
  return i >= r[0] && i < r[1];
}

// One exchange of the fields `defs` of layout L; returns the number of wrong entries here.
long exchange_and_check(const Mesh& mesh, Halo& halo, const Layout& L,
                        const std::vector<FieldDef>& defs, const std::string& label) {
  std::array<std::array<int, 2>, 3> owned, all;
  for (int d = 0; d < 3; ++d) {
    owned[d] = mesh.range(L.along(d), Region::Owned, d);
    all[d] = mesh.range(L.along(d), Region::All, d);
  }
  std::vector<HaloField> fields;
  std::vector<Field3::HostMirror> hosts;
  for (const auto& def : defs) {
    HaloField hf;
    hf.view = mesh.new_field("f" + std::to_string(def.id),
                             L.face_axis >= 0 ? Centering::Node : L.centering);
    hf.centering = L.centering;
    hf.face_axis = L.face_axis;
    hf.parity = def.parity;
    auto h = Kokkos::create_mirror_view(hf.view);
    for (int k = 0; k < int(h.extent(2)); ++k)
      for (int j = 0; j < int(h.extent(1)); ++j)
        for (int i = 0; i < int(h.extent(0)); ++i) {
          const int idx[3] = {i, j, k};
          const bool own = in_range(owned[0], i) && in_range(owned[1], j) && in_range(owned[2], k);
          h(i, j, k) = own ? expected(mesh, L, def, idx, false) : kSentinel;
        }
    Kokkos::deep_copy(hf.view, h);
    fields.push_back(hf);
    hosts.push_back(h);
  }

  halo.exchange(fields);

  long bad = 0, ghosts = 0;
  for (size_t n = 0; n < defs.size(); ++n) {
    auto& h = hosts[n];
    Kokkos::deep_copy(h, fields[n].view);
    for (int k = 0; k < int(h.extent(2)); ++k)
      for (int j = 0; j < int(h.extent(1)); ++j)
        for (int i = 0; i < int(h.extent(0)); ++i) {
          const int idx[3] = {i, j, k};
          const bool used = in_range(all[0], i) && in_range(all[1], j) && in_range(all[2], k);
          const bool own = in_range(owned[0], i) && in_range(owned[1], j) && in_range(owned[2], k);
          // Entries outside the layout's range (the spare index of a face field) stay untouched.
          const Real want = used ? expected(mesh, L, defs[n], idx, true) : kSentinel;
          if (used && !own) ++ghosts;
          if (h(i, j, k) != want) {
            if (bad++ < 6) {
              std::fprintf(stderr,
                           "[rank %d] %s field %d (parity %d,%d,%d): local (%d,%d,%d) global "
                           "(%d,%d,%d) %s: got %.17g, expected %.17g\n",
                           world_rank(), label.c_str(), defs[n].id, defs[n].parity[0],
                           defs[n].parity[1], defs[n].parity[2], i, j, k,
                           mesh.offset(0) + i - Mesh::ng, mesh.offset(1) + j - Mesh::ng,
                           mesh.offset(2) + k - Mesh::ng, own ? "owned" : "ghost",
                           double(h(i, j, k)), double(want));
            }
          }
        }
  }
  if (ghosts == 0) {
    std::fprintf(stderr, "[rank %d] %s: no ghost entries checked\n", world_rank(), label.c_str());
    ++bad;
  }
  return bad;
}

// Bytes one exchange of `nfields` fields of layout L sends from this rank, from the definition
// of the exchange (not from halo.cpp): along each axis, to each side with a neighbour rank (a
// periodic rank can be its own), ng layers of the whole extent of the other two axes, ghosts
// included, per field; nothing towards a physical boundary.
double expected_bytes(const Mesh& mesh, const Layout& L, int nfields) {
  double bytes = 0;
  for (int d = 0; d < 3; ++d) {
    double slab = Mesh::ng;
    for (int a = 0; a < 3; ++a)
      if (a != d) {
        const auto r = mesh.range(L.along(a), Region::All, a);
        slab *= r[1] - r[0];
      }
    for (int s = 0; s < 2; ++s)
      if (!mesh.physical_boundary(d, s)) bytes += nfields * slab * sizeof(Real);
  }
  return bytes;
}

// Every rank's bytes_sent() equals its expected count exactly; returns the ranks that differ.
long wrong_byte_counts(const Halo& halo, double expected, const std::string& label) {
  const bool ok = halo.bytes_sent() == expected;
  if (!ok)
    std::fprintf(stderr, "[rank %d] %s: bytes sent %.0f, expected %.0f\n", world_rank(),
                 label.c_str(), halo.bytes_sent(), expected);
  return sum_over_ranks(ok ? 0 : 1);
}

MeshSpec spec_of(std::array<int, 3> cells, const Bc& bc, std::array<int, 3> ranks = {{0, 0, 0}}) {
  MeshSpec s;
  s.cells = cells;
  s.lo = {{0.0, -1.0, 2.0}};
  s.hi = {{1.0, 1.0, 3.5}};
  s.bc = bc;
  s.ranks = ranks;
  return s;
}

std::string mesh_label(const Mesh& mesh) {
  const auto& s = mesh.spec();
  return std::to_string(s.cells[0]) + "x" + std::to_string(s.cells[1]) + "x" +
         std::to_string(s.cells[2]) + " on " + std::to_string(mesh.dims()[0]) + "x" +
         std::to_string(mesh.dims()[1]) + "x" + std::to_string(mesh.dims()[2]) + " [" +
         bc_name(s.bc) + "]";
}

// Runs every (layout, field set) on one mesh, one collective expectation per combination.
void check_mesh(const MeshSpec& spec, const std::vector<Layout>& layouts,
                const std::vector<std::vector<FieldDef>>& sets) {
  Mesh mesh(spec, MPI_COMM_WORLD);
  Halo halo(mesh);
  double bytes = 0;
  for (const auto& L : layouts)
    for (const auto& defs : sets) {
      std::string label = mesh_label(mesh) + " " + L.name + " x" + std::to_string(defs.size());
      const long total = sum_over_ranks(exchange_and_check(mesh, halo, L, defs, label));
      EXPECT_EQ(total, 0) << label;
      bytes += expected_bytes(mesh, L, int(defs.size()));
    }
  EXPECT_EQ(wrong_byte_counts(halo, bytes, mesh_label(mesh)), 0) << mesh_label(mesh);
}

const std::vector<std::array<int, 3>> kSizes{{{13, 11, 9}}, {{10, 7, 6}}, {{6, 14, 5}}};
const Parity kEven{{1, 1, 1}};
const std::vector<std::vector<FieldDef>> kScalar{{{0, kEven}}};
// A scalar and the three components of a vector, each alone and all in one exchange.
const std::vector<std::vector<FieldDef>> kParities{
    {{0, kEven}},
    {{1, {{-1, 1, 1}}}},
    {{2, {{1, -1, 1}}}},
    {{3, {{1, 1, -1}}}},
    {{0, kEven}, {1, {{-1, 1, 1}}}, {2, {{1, -1, 1}}}, {3, {{1, 1, -1}}}}};

TEST(Halo, PeriodicEveryGhost) {
  const Bc bc{{{{kP, kP}}, {{kP, kP}}, {{kP, kP}}}};
  for (const auto& n : kSizes) check_mesh(spec_of(n, bc), {kCell, kNode}, kScalar);
  check_mesh(spec_of({{8, 8, 8}}, bc), kAllLayouts, kScalar);
}

TEST(Halo, SeveralFieldsInOneExchange) {
  const std::vector<std::vector<FieldDef>> three{{{0, kEven}, {1, kEven}, {2, kEven}}};
  const Bc periodic{{{{kP, kP}}, {{kP, kP}}, {{kP, kP}}}};
  const Bc mixed{{{{kP, kP}}, {{kR, kR}}, {{kO, kO}}}};
  for (const auto& n : kSizes) {
    check_mesh(spec_of(n, periodic), {kCell, kNode}, three);
    check_mesh(spec_of(n, mixed), {kCell, kNode}, three);
  }
}

TEST(Halo, MoreFieldsThanOneLaunchTakes) {
  // Eleven fields, every parity (an exchange takes up to 8 fields a launch: two batches), on
  // blocks of every shape, walls and periodic axes mixed.
  std::vector<FieldDef> eleven;
  for (int id = 0; id < 11; ++id) eleven.push_back(kParities[id % 4][0]);
  for (int id = 0; id < 11; ++id) eleven[id].id = id;
  const Bc bc{{{{kR, kO}}, {{kP, kP}}, {{kR, kR}}}};
  for (const auto& n : kSizes) check_mesh(spec_of(n, bc), kAllLayouts, {eleven});
  check_mesh(spec_of({{40, 3, 3}}, bc), kAllLayouts, {eleven});
  check_mesh(spec_of({{3, 40, 3}}, bc), kAllLayouts, {eleven});
}

TEST(Halo, ReflectiveWithParity) {
  const Bc bc{{{{kR, kR}}, {{kR, kR}}, {{kR, kR}}}};
  for (const auto& n : kSizes) check_mesh(spec_of(n, bc), kAllLayouts, kParities);
}

TEST(Halo, Outflow) {
  const Bc bc{{{{kO, kO}}, {{kO, kO}}, {{kO, kO}}}};
  for (const auto& n : kSizes) check_mesh(spec_of(n, bc), kAllLayouts, kParities);
}

TEST(Halo, MixedBoundaries) {
  const std::vector<Bc> bcs{
      {{{{kP, kP}}, {{kR, kR}}, {{kO, kO}}}},  // x periodic, y reflective, z outflow
      {{{{kR, kO}}, {{kO, kR}}, {{kP, kP}}}},  // different kinds on the two faces
      {{{{kO, kR}}, {{kP, kP}}, {{kR, kO}}}},
  };
  for (const auto& bc : bcs)
    for (const auto& n : kSizes) check_mesh(spec_of(n, bc), kAllLayouts, kParities);
}

TEST(Halo, ThinBlocks) {
  // All ranks along one axis, blocks exactly ng thick (the first one ng + 1).
  const int np = world_size();
  const std::vector<Bc> bcs{{{{{kP, kP}}, {{kP, kP}}, {{kP, kP}}}},
                            {{{{kR, kO}}, {{kO, kR}}, {{kR, kR}}}}};
  for (int d = 0; d < 3; ++d)
    for (const auto& bc : bcs) {
      std::array<int, 3> cells{{5, 4, 3}}, ranks{{1, 1, 1}};
      cells[d] = 2 * np + 1;
      ranks[d] = np;
      check_mesh(spec_of(cells, bc, ranks), {kCell, kNode}, kParities);
    }
}

TEST(Halo, QuasiOneDimensionalBlocks) {
  // Blocks long along one axis and a few cells across the other two (a 1-D run's mesh): on a
  // host backend the one-launch fill of a block with no neighbour rank runs its columns along
  // the long axis there (src/mesh/halo.cpp, column_axis), and along z otherwise. (One rank:
  // with more, the long axis is split and the per-axis exchange, checked above, runs instead.)
  if (world_size() > 1) GTEST_SKIP() << "the one-launch fill is one rank's: test_halo_np1";
  const std::vector<Bc> bcs{{{{{kR, kR}}, {{kP, kP}}, {{kP, kP}}}},
                            {{{{kR, kO}}, {{kO, kR}}, {{kR, kR}}}},
                            {{{{kO, kR}}, {{kP, kP}}, {{kR, kO}}}}};
  // (three cells across a reflective axis: with two, a node field's second mirrored ghost
  // layer is the opposite wall node, which the halo reads as the zero it is and the definitions
  // here do not)
  const std::vector<std::array<int, 3>> sizes{{{40, 3, 3}}, {{3, 40, 3}}, {{3, 3, 40}},
                                              {{33, 3, 4}}, {{3, 29, 3}}, {{12, 5, 4}}};
  for (const auto& bc : bcs)
    for (const auto& n : sizes) check_mesh(spec_of(n, bc), kAllLayouts, kParities);
  // a 1-D deck's mesh: two cells across periodic y and z
  check_mesh(spec_of({{40, 2, 2}}, bcs[0]), kAllLayouts, kParities);
}

TEST(Halo, ReusesBuffersAndRepeats) {
  // Growing and shrinking field counts on one Halo, and a second exchange of the same fields
  // leaves them as they were.
  const Bc bc{{{{kP, kP}}, {{kR, kO}}, {{kR, kR}}}};
  Mesh mesh(spec_of({{13, 11, 9}}, bc), MPI_COMM_WORLD);
  Halo halo(mesh);
  long bad = 0;
  double bytes = 0;
  const std::vector<std::vector<FieldDef>> sets{
      {{0, kEven}}, kParities.back(), {{5, {{1, -1, 1}}}}, kParities.back()};
  for (const auto& L : {kCell, kNode, kAllLayouts[3]})
    for (const auto& defs : sets) {
      bad += exchange_and_check(mesh, halo, L, defs, "reuse");
      bytes += expected_bytes(mesh, L, int(defs.size()));
    }

  HaloField hf;
  hf.view = mesh.new_field("g", Centering::Cell);
  hf.parity = {{1, -1, 1}};
  auto h = Kokkos::create_mirror_view(hf.view);
  for (size_t n = 0; n < h.size(); ++n) h.data()[n] = Real(n % 977) - Real(400);
  Kokkos::deep_copy(hf.view, h);
  halo.exchange({hf});
  auto once = Kokkos::create_mirror_view(hf.view);
  Kokkos::deep_copy(once, hf.view);
  halo.exchange({hf});
  Kokkos::deep_copy(h, hf.view);
  for (size_t n = 0; n < h.size(); ++n)
    if (h.data()[n] != once.data()[n] && bad++ < 6)
      std::fprintf(stderr, "[rank %d] repeat: entry %zu changed\n", world_rank(), n);
  // x is periodic: even one rank sends (to itself) on every exchange
  bytes += 2 * expected_bytes(mesh, kCell, 1);
  EXPECT_GT(bytes, 0.0);
  std::printf("reuse: rank %d sent %.0f bytes (expected %.0f)\n", world_rank(), halo.bytes_sent(),
              bytes);
  EXPECT_EQ(wrong_byte_counts(halo, bytes, "reuse"), 0);
  EXPECT_EQ(sum_over_ranks(bad), 0);
}

TEST(Halo, RefusesMixedLayouts) {
  Mesh mesh(spec_of({{8, 8, 8}}, Bc{}), MPI_COMM_WORLD);
  Halo halo(mesh);
  HaloField c, n;
  c.view = mesh.new_field("c", Centering::Cell);
  n.view = mesh.new_field("n", Centering::Node);
  n.centering = Centering::Node;
  long bad = 0;
  try {
    halo.exchange({c, n});
    ++bad;
  } catch (const mp::RunError&) {
  }
  halo.exchange({});  // nothing to do, and no communication
  EXPECT_EQ(sum_over_ranks(bad), 0);
  // neither the refused exchange nor the empty one sent anything
  EXPECT_EQ(wrong_byte_counts(halo, 0.0, "refused and empty exchanges"), 0);
}

TEST(Halo, NoNeighbourNoCommunication) {
  // Walls on every face: a rank sends only to neighbour ranks, so one rank sends nothing at
  // all, and a rank of a split sends exactly its faces' slabs (expected_bytes, > 0 then).
  const Bc bc{{{{kR, kO}}, {{kO, kR}}, {{kR, kR}}}};
  Mesh mesh(spec_of({{10, 7, 6}}, bc), MPI_COMM_WORLD);
  Halo halo(mesh);
  long bad = 0;
  for (const auto& L : {kCell, kNode})
    bad += exchange_and_check(mesh, halo, L, kParities.back(), "walls");
  const double bytes = expected_bytes(mesh, kCell, 4) + expected_bytes(mesh, kNode, 4);
  std::printf("walls only: rank %d sent %.0f bytes (expected %.0f)\n", world_rank(),
              halo.bytes_sent(), bytes);
  if (world_size() == 1) {
    EXPECT_EQ(halo.bytes_sent(), 0.0);
  }
  EXPECT_EQ(wrong_byte_counts(halo, bytes, "walls"), 0);
  EXPECT_EQ(sum_over_ranks(bad), 0);
}

}  // namespace
