// Mesh decomposition: the owned blocks of all ranks tile the global box, every block is thick
// enough for the ghost layers, the geometry agrees with the offsets, and bad meshes are refused.
// Every assertion is collective: errors are counted locally, summed over the ranks, and each
// rank checks the total, so a failure on one rank fails the test everywhere.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/reduce.hpp"
#include "mesh/mesh.hpp"
#include "precision.hpp"

namespace {

using mp::BoundaryKind;
using mp::Centering;
using mp::Mesh;
using mp::MeshSpec;
using mp::Region;

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

// Counts local failures and prints the first few, with the rank, to stderr.
struct Errors {
  std::string what;
  long count = 0;
  explicit Errors(std::string w) : what(std::move(w)) {}
  template <class... A>
  void fail(const char* fmt, A... args) {
    if (count++ < 8) {
      std::fprintf(stderr, "[rank %d] %s: ", world_rank(), what.c_str());
      std::fprintf(stderr, fmt, args...);
      std::fprintf(stderr, "\n");
    }
  }
  void fail(const char* msg) { fail("%s", msg); }
  void check(bool ok, const char* msg) {
    if (!ok) fail(msg);
  }
  long total() const {
    long t = 0;
    MPI_Allreduce(&count, &t, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
    return t;
  }
};

std::string name_of(const MeshSpec& s) {
  return std::to_string(s.cells[0]) + "x" + std::to_string(s.cells[1]) + "x" +
         std::to_string(s.cells[2]);
}

// What one rank reports about its block, gathered on every rank.
struct BlockInfo {
  int coords[3], offset[3], nl[3], neighbor[3][2];
};

void check_decomposition(const MeshSpec& spec) {
  SCOPED_TRACE(name_of(spec));
  const int np = world_size();
  Errors e("decomposition " + name_of(spec));
  Mesh mesh(spec, MPI_COMM_WORLD);

  e.check(mesh.nranks() == np, "nranks != world size");
  e.check(mesh.dims()[0] * mesh.dims()[1] * mesh.dims()[2] == np, "dims product != nranks");
  for (int d = 0; d < 3; ++d) {
    if (mesh.owned_cells(d) < Mesh::ng)
      e.fail("axis %d owns %d cells < ng=%d", d, mesh.owned_cells(d), Mesh::ng);
    if (mesh.global_cells(d) != spec.cells[d]) e.fail("axis %d global_cells wrong", d);
  }

  // Gather every rank's block (in the mesh communicator's rank order).
  BlockInfo mine{};
  for (int d = 0; d < 3; ++d) {
    mine.coords[d] = mesh.coords()[d];
    mine.offset[d] = mesh.offset(d);
    mine.nl[d] = mesh.owned_cells(d);
    for (int s = 0; s < 2; ++s) mine.neighbor[d][s] = mesh.neighbor(d, s);
  }
  const int nint = static_cast<int>(sizeof(BlockInfo) / sizeof(int));
  std::vector<BlockInfo> all(np);
  MPI_Allgather(&mine, nint, MPI_INT, all.data(), nint, MPI_INT, mesh.comm());

  // Sum of owned cells equals the global count.
  long long owned = mesh.owned_cell_count(), sum = 0;
  MPI_Allreduce(&owned, &sum, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (sum != mesh.global_cell_count())
    e.fail("sum of owned cells %lld != global %lld", sum, mesh.global_cell_count());

  // Each coordinate tuple appears exactly once, and the block at coordinate c along d has one
  // offset and size, shared by every rank in that slab; offsets are contiguous from 0 to N.
  const auto dims = mesh.dims();
  std::vector<int> seen(np, 0);
  for (int r = 0; r < np; ++r) {
    const auto& b = all[r];
    bool in = true;
    for (int d = 0; d < 3; ++d) in = in && b.coords[d] >= 0 && b.coords[d] < dims[d];
    if (!in) {
      e.fail("rank %d coords out of range", r);
      continue;
    }
    seen[b.coords[0] + dims[0] * (b.coords[1] + dims[1] * b.coords[2])]++;
  }
  for (int i = 0; i < np; ++i)
    if (seen[i] != 1) e.fail("coordinate tuple %d held by %d ranks", i, seen[i]);

  for (int d = 0; d < 3; ++d) {
    std::vector<int> off(dims[d], -1), cnt(dims[d], -1);
    for (int r = 0; r < np; ++r) {
      const auto& b = all[r];
      const int c = b.coords[d];
      if (c < 0 || c >= dims[d]) continue;
      if (off[c] < 0) {
        off[c] = b.offset[d];
        cnt[c] = b.nl[d];
      } else if (off[c] != b.offset[d] || cnt[c] != b.nl[d]) {
        e.fail("axis %d coord %d: rank %d has offset/count %d/%d, another %d/%d", d, c, r,
               b.offset[d], b.nl[d], off[c], cnt[c]);
      }
    }
    int expect = 0;
    int lo = spec.cells[d], hi = 0;
    for (int c = 0; c < dims[d]; ++c) {
      if (off[c] != expect) e.fail("axis %d coord %d offset %d, expected %d", d, c, off[c], expect);
      if (cnt[c] < Mesh::ng) e.fail("axis %d coord %d has %d cells", d, c, cnt[c]);
      lo = std::min(lo, cnt[c]);
      hi = std::max(hi, cnt[c]);
      expect = off[c] + cnt[c];
    }
    if (expect != spec.cells[d])
      e.fail("axis %d blocks end at %d, not %d", d, expect, spec.cells[d]);
    if (hi - lo > 1) e.fail("axis %d blocks unbalanced: %d..%d cells", d, lo, hi);
  }

  // Neighbours: the rank at coords +-1 along d, wrapped when periodic, MPI_PROC_NULL at a wall.
  for (int d = 0; d < 3; ++d) {
    const bool periodic = spec.bc[d][0] == BoundaryKind::Periodic;
    for (int s = 0; s < 2; ++s) {
      int c[3] = {mine.coords[0], mine.coords[1], mine.coords[2]};
      c[d] += s == 0 ? -1 : 1;
      int expect = MPI_PROC_NULL;
      if (periodic || (c[d] >= 0 && c[d] < dims[d])) {
        c[d] = (c[d] + dims[d]) % dims[d];
        for (int r = 0; r < np; ++r)
          if (all[r].coords[0] == c[0] && all[r].coords[1] == c[1] && all[r].coords[2] == c[2])
            expect = r;
      }
      if (mesh.neighbor(d, s) != expect)
        e.fail("neighbor(%d,%d) = %d, expected %d", d, s, mesh.neighbor(d, s), expect);
      if (mesh.physical_boundary(d, s) != (expect == MPI_PROC_NULL))
        e.fail("physical_boundary(%d,%d) wrong", d, s);
      if (mesh.boundary(d, s) != spec.bc[d][s]) e.fail("boundary(%d,%d) wrong", d, s);
    }
  }

  // Extents, ranges and policies.
  for (int d = 0; d < 3; ++d) {
    const int nl = mesh.owned_cells(d), ng = Mesh::ng;
    e.check(mesh.extent(Centering::Cell, d) == nl + 2 * ng, "cell extent");
    e.check(mesh.extent(Centering::Node, d) == nl + 2 * ng + 1, "node extent");
    const auto co = mesh.range(Centering::Cell, Region::Owned, d);
    const auto ca = mesh.range(Centering::Cell, Region::All, d);
    const auto no = mesh.range(Centering::Node, Region::Owned, d);
    const auto na = mesh.range(Centering::Node, Region::All, d);
    e.check(co[0] == ng && co[1] == ng + nl, "owned cell range");
    e.check(ca[0] == 0 && ca[1] == nl + 2 * ng, "all cell range");
    e.check(no[0] == ng && no[1] == ng + nl + 1, "owned node range");
    e.check(na[0] == 0 && na[1] == nl + 2 * ng + 1, "all node range");
    const auto f = mesh.new_field("f", Centering::Node);
    e.check(static_cast<int>(f.extent(d)) == mesh.extent(Centering::Node, d), "field extent");
    const auto p = mesh.cells(Region::Owned);
    e.check(p.m_lower[d] == co[0] && p.m_upper[d] == co[1], "owned cell policy");
    const auto q = mesh.nodes(Region::All);
    e.check(q.m_lower[d] == na[0] && q.m_upper[d] == na[1], "all node policy");
    const auto pp = mesh.cells_padded(1);
    e.check(pp.m_lower[d] == ng - 1 && pp.m_upper[d] == ng + nl + 1, "padded policy");
  }

  // Geometry, computed here independently from the spec and the gathered offsets.
  const mp::Geometry g = mesh.geometry();
  e.check(g.ng == Mesh::ng, "geometry ng");
  // Round-off bounds (`worst` holds the largest observed error in units of its bound; it must
  // stay below 1). A coordinate lo + n dx in Real rounds four times, each by eps/2 of what it
  // rounds: lo and the sum (|x| <= X = max(|lo|, |hi|) + ng dx), dx (times |n| dx <= the
  // ghost-padded extent E = L + 2 ng dx) and the product (<= E): eps (E + X) with eps of Real;
  // the reference, computed in double the same way, adds as much again in a double build. The
  // bound, 2 eps (E + X), is the worst case of roundings all of one sign; in double the
  // largest errors are 0 to 0.19 of their bound (printed; 1 to 8 ranks). The cell volume, a
  // product of three rounded dx, is within 2.5 eps (3 roundings of dx, 2 of the products) and
  // the reference as much again: 5 eps.
  double worst = 0;
  const double vol = (spec.hi[0] - spec.lo[0]) * (spec.hi[1] - spec.lo[1]) *
                     (spec.hi[2] - spec.lo[2]) / double(mesh.global_cell_count());
  const double vol_tol = 5 * mp::test::kEps * vol;
  worst = std::max(worst, std::abs(double(g.cell_volume()) - vol) / vol_tol);
  if (std::abs(double(g.cell_volume()) - vol) > vol_tol) e.fail("cell volume");
  for (int d = 0; d < 3; ++d) {
    const double dx = (spec.hi[d] - spec.lo[d]) / spec.cells[d];
    const double pad = Mesh::ng * dx;
    const double tol = 2 * mp::test::kEps *
                       ((spec.hi[d] - spec.lo[d]) + 2 * pad +
                        std::max(std::abs(spec.lo[d]), std::abs(spec.hi[d])) + pad);
    // records the error in units of tol and says whether it is beyond it
    const auto off = [&](double got, double want) {
      worst = std::max(worst, std::abs(got - want) / tol);
      return std::abs(got - want) > tol;
    };
    if (g.offset[d] != mesh.offset(d) || g.nl[d] != mesh.owned_cells(d))
      e.fail("geometry offset/nl axis %d", d);
    if (off(double(mesh.dx(d)), dx)) e.fail("dx axis %d", d);
    for (int i = 0; i < mesh.extent(Centering::Node, d); ++i) {
      const int gi = mine.offset[d] + i - Mesh::ng;
      if (g.global_index(d, i) != gi)
        e.fail("global_index(%d,%d) = %d, expected %d", d, i, g.global_index(d, i), gi);
      const double node = spec.lo[d] + gi * dx;
      if (off(double(g.node_coord(d, i)), node))
        e.fail("node_coord(%d,%d) = %g, expected %g", d, i, double(g.node_coord(d, i)), node);
      if (i < mesh.extent(Centering::Cell, d)) {
        const double center = spec.lo[d] + (gi + 0.5) * dx;
        if (off(double(g.cell_center(d, i)), center))
          e.fail("cell_center(%d,%d) = %g, expected %g", d, i, double(g.cell_center(d, i)), center);
      }
    }
    // The owned range spans exactly [lo + offset dx, lo + (offset + nl) dx]; the last block
    // ends on the upper corner.
    const int first = Mesh::ng, last = Mesh::ng + mesh.owned_cells(d);
    if (mesh.offset(d) == 0 && off(double(g.node_coord(d, first)), spec.lo[d]))
      e.fail("first block does not start at lo on axis %d", d);
    if (mesh.offset(d) + mesh.owned_cells(d) == spec.cells[d] &&
        off(double(g.node_coord(d, last)), spec.hi[d]))
      e.fail("last block does not end at hi on axis %d", d);
  }
  double worst_all = 0;
  MPI_Allreduce(&worst, &worst_all, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (world_rank() == 0)
    std::printf("%s on %d ranks: largest coordinate / volume error %.3f of its round-off bound\n",
                e.what.c_str(), np, worst_all);
  EXPECT_FALSE(mesh.describe().empty());
  EXPECT_EQ(e.total(), 0) << e.what;
}

MeshSpec make(int nx, int ny, int nz) {
  MeshSpec s;
  s.cells = {{nx, ny, nz}};
  s.lo = {{-1.0, 0.0, 2.5}};
  s.hi = {{1.0, 3.0, 3.0}};
  return s;
}

TEST(Mesh, TilesGlobalBox) {
  for (const auto& n : std::vector<std::array<int, 3>>{
           {{17, 10, 9}}, {{8, 8, 8}}, {{40, 4, 4}}, {{4, 40, 4}}, {{5, 6, 41}}, {{13, 11, 9}}})
    check_decomposition(make(n[0], n[1], n[2]));
}

TEST(Mesh, TilesWithPeriodicAndMixedBoundaries) {
  MeshSpec s = make(17, 10, 9);
  s.bc[0] = {{BoundaryKind::Periodic, BoundaryKind::Periodic}};
  s.bc[1] = {{BoundaryKind::Reflective, BoundaryKind::Outflow}};
  s.bc[2] = {{BoundaryKind::Periodic, BoundaryKind::Periodic}};
  check_decomposition(s);
  s.bc[0] = {{BoundaryKind::Outflow, BoundaryKind::Outflow}};
  s.bc[1] = {{BoundaryKind::Periodic, BoundaryKind::Periodic}};
  s.bc[2] = {{BoundaryKind::Outflow, BoundaryKind::Reflective}};
  check_decomposition(s);
}

TEST(Mesh, TilesWithUserRanks) {
  // All ranks along one axis, the thinnest legal split (2 cells, the first block 3).
  const int np = world_size();
  for (int d = 0; d < 3; ++d) {
    MeshSpec s = make(6, 5, 4);
    s.cells[d] = 2 * np + 1;
    s.ranks = {{1, 1, 1}};
    s.ranks[d] = np;
    check_decomposition(s);
    Mesh m(s, MPI_COMM_WORLD);
    Errors e("user ranks");
    for (int a = 0; a < 3; ++a)
      if (m.dims()[a] != (a == d ? np : 1)) e.fail("dims[%d] = %d", a, m.dims()[a]);
    EXPECT_EQ(e.total(), 0);
  }
}

// Runs `make_mesh` and expects InputError whose message contains `needle`, on every rank.
template <class F>
void expect_input_error(F make_mesh, const std::string& needle, const std::string& what) {
  Errors e(what);
  try {
    make_mesh();
    e.fail("no exception");
  } catch (const mp::InputError& ex) {
    const std::string msg = ex.what();
    if (msg.find(needle) == std::string::npos)
      e.fail("message '%s' does not mention '%s'", msg.c_str(), needle.c_str());
  } catch (const std::exception& ex) {
    e.fail("wrong exception type: %s", ex.what());
  }
  EXPECT_EQ(e.total(), 0) << what;
}

TEST(Mesh, RefusesTooSmallForRanks) {
  const int np = world_size();
  if (np == 1) {
    // One rank still needs ng cells on every axis for the ghost-layer stencils.
    for (int d = 0; d < 3; ++d) {
      MeshSpec s = make(5, 6, 7);
      s.cells[d] = 1;
      expect_input_error([&] { Mesh m(s, MPI_COMM_WORLD); }, std::string("along ") + "xyz"[d],
                         "1-cell axis");
    }
  } else {
    // 3 cells on every axis: whichever axis gets >= 2 ranks has a block of 1 cell.
    expect_input_error([&] { Mesh m(make(3, 3, 3), MPI_COMM_WORLD); }, "along ", "3x3x3");
    // Forced decomposition: np ranks along d with 2*np - 1 cells leaves some block 1 cell thick.
    for (int d = 0; d < 3; ++d) {
      MeshSpec s = make(40, 40, 40);
      s.cells[d] = 2 * np - 1;
      s.ranks = {{1, 1, 1}};
      s.ranks[d] = np;
      expect_input_error([&] { Mesh m(s, MPI_COMM_WORLD); }, std::string("along ") + "xyz"[d],
                         "forced split");
    }
  }
  // A long thin box whose short axis is too thin for any rank count.
  for (int d = 0; d < 3; ++d) {
    MeshSpec s = make(64, 64, 64);
    s.cells[d] = 1;
    expect_input_error([&] { Mesh m(s, MPI_COMM_WORLD); }, std::string("along ") + "xyz"[d],
                       "thin axis");
  }
}

TEST(Mesh, RefusesBadSpecs) {
  for (int d = 0; d < 3; ++d) {
    for (int s = 0; s < 2; ++s) {
      MeshSpec spec = make(16, 16, 16);
      spec.bc[d][s] = BoundaryKind::Periodic;
      spec.bc[d][1 - s] = s == 0 ? BoundaryKind::Reflective : BoundaryKind::Outflow;
      expect_input_error([&] { Mesh m(spec, MPI_COMM_WORLD); }, std::string("axis ") + "xyz"[d],
                         "periodic on one face");
    }
    MeshSpec spec = make(16, 16, 16);
    spec.cells[d] = 0;
    expect_input_error([&] { Mesh m(spec, MPI_COMM_WORLD); }, std::string("along ") + "xyz"[d],
                       "zero cells");
    spec = make(16, 16, 16);
    spec.hi[d] = spec.lo[d];
    expect_input_error([&] { Mesh m(spec, MPI_COMM_WORLD); }, std::string("along ") + "xyz"[d],
                       "empty box");
  }
}

TEST(Mesh, BoundaryNames) {
  EXPECT_STREQ(mp::to_string(BoundaryKind::Reflective), "reflective");
  EXPECT_STREQ(mp::to_string(BoundaryKind::Outflow), "outflow");
  EXPECT_STREQ(mp::to_string(BoundaryKind::Periodic), "periodic");
}

}  // namespace

TEST(Mesh, FallsBackToAFeasibleSplit) {
  // 40x3x3: MPI_Dims_create would cut a 3-cell axis on 4 or 8 ranks; only x can be split.
  const int np = world_size();
  MeshSpec s = make(40, 3, 3);
  Errors e("40x3x3 fallback");
  try {
    Mesh m(s, MPI_COMM_WORLD);
    if (m.dims()[0] != np || m.dims()[1] != 1 || m.dims()[2] != 1)
      e.fail("dims %dx%dx%d, expected %dx1x1", m.dims()[0], m.dims()[1], m.dims()[2], np);
  } catch (const std::exception& ex) {
    e.fail("threw: %s", ex.what());
  }
  EXPECT_EQ(e.total(), 0);
}

// The conservation totals' sums (core/reduce.hpp, CompensatedSumN): a million copies of 0.1
// (each the double nearest 0.1, so the exact sum is 1e6 times it, exact in long double to far
// below a double's rounding) summed by one parallel_reduce are that sum to about one rounding,
// on any thread count. The plain sum (SumN) of the same terms is thousands of roundings off
// (observed 9.2e4 ulps, 1.3e-11 relative, on one thread; -6.1e4 on two): the kind of error the
// totals had read as a change in a conserved quantity.
namespace {
// n copies of x summed by one parallel_reduce each way: compensated, then plain. (A free
// function: nvcc allows no extended lambda in a gtest body, a private member function.)
std::pair<double, double> sums_of(long n, double x) {
  mp::CompensatedSumN<1> c;
  mp::SumN<1> plain;
  Kokkos::parallel_reduce(
      "test::compensated", mp::Policy1(0, n),
      KOKKOS_LAMBDA(int, mp::CompensatedSumN<1>& acc) { acc.add(0, x); },
      Kokkos::Sum<mp::CompensatedSumN<1>>(c));
  Kokkos::parallel_reduce(
      "test::plain", mp::Policy1(0, n), KOKKOS_LAMBDA(int, mp::SumN<1>& acc) { acc.v[0] += x; },
      Kokkos::Sum<mp::SumN<1>>(plain));
  return {c.value(0), plain.v[0]};
}
}  // namespace

TEST(Reduce, CompensatedSumIsTheExactSumToARounding) {
  const long n = 1000000;
  const double x = 0.1;
  const long double exact = static_cast<long double>(n) * static_cast<long double>(x);
  const auto [compensated, plain] = sums_of(n, x);
  const double ulp = std::nextafter(double(exact), 2e5) - double(exact);
  const double err = double(static_cast<long double>(compensated) - exact) / ulp;
  const double plain_err = double(static_cast<long double>(plain) - exact) / ulp;
  std::printf("sum of %ld x 0.1: compensated %.1f ulps, plain %.1f ulps from the exact sum\n", n,
              err, plain_err);
  EXPECT_LE(std::abs(err), 1.0);
  EXPECT_GT(std::abs(plain_err), 100.0);  // (the case is one a plain sum gets wrong)
}
