// The material halo (MaterialState::exchange, kernels/materials/halo.cpp) in both layouts:
// after one exchange every ghost cell's per-material content (alpha, rho, e of each material)
// and its cell averages equal, bit for bit, those of the owned cell it stands for: the mirror
// image across a reflective wall, the wall cell itself at an outflow wall, the periodic image,
// or the neighbour rank's cell; faces, edges and corners, both ghost layers.
//
// The expected values come from the definitions, not from halo.cpp: owned cells hold a
// content that is a function of the global cell index (pure cells of each of three materials,
// and mixed cells of two and three); ghosts start as a sentinel material with negative density
// and energy, so a ghost the exchange missed fails. Each axis maps a ghost's global index to its
// source independently (reflective: -1 - g below, 2n - 1 - g above; outflow: the wall cell;
// periodic: wrap), so the composition over the axes is order-free.
#include <gtest/gtest.h>
#include <mpi.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "materials/layout.hpp"
#include "mesh/mesh.hpp"

namespace {

using namespace mp;
using mp::mat::kMaxMaterials;

constexpr int kNmat = 3;
constexpr BoundaryKind kR = BoundaryKind::Reflective;
constexpr BoundaryKind kO = BoundaryKind::Outflow;
constexpr BoundaryKind kP = BoundaryKind::Periodic;
using Bc = std::array<std::array<BoundaryKind, 2>, 3>;

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// The content of global cell g: one of six kinds (three pure, three mixed), exact binary
// fractions, and densities and energies unique to the cell and material.
KOKKOS_INLINE_FUNCTION int global_content(long gx, long gy, long gz, long nx, long ny, Real* a,
                                          Real* r, Real* e) {
  const long lin = gx + nx * (gy + ny * gz);
  const int kind = int((gx * 7 + gy * 13 + gz * 29) % 6);
  for (int m = 0; m < kNmat; ++m) a[m] = r[m] = e[m] = 0;
  const Real fractions[6][kNmat] = {{1, 0, 0},       {0, 1, 0},     {0, 0, 1},
                                    {0.25, 0.75, 0}, {0, 0.5, 0.5}, {0.125, 0.375, 0.5}};
  int n = 0;
  for (int m = 0; m < kNmat; ++m) {
    a[m] = fractions[kind][m];
    if (a[m] > 0) {
      r[m] = Real(1 + 0.5 * m) + Real(lin) * Real(1e-3);
      e[m] = Real(2 + m) + Real(lin) * Real(1e-4);
      ++n;
    }
  }
  return n;
}

// Owned cells get their global content; ghosts a sentinel (material 2, negative state).
struct Paint {
  Geometry g;
  long nx, ny;
  int lo[3], hi[3];
  KOKKOS_INLINE_FUNCTION bool changed(int, int, int) const { return true; }
  KOKKOS_INLINE_FUNCTION int content(int i, int j, int k, Real* a, Real* r, Real* e) const {
    const bool owned =
        i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1] && k >= lo[2] && k < hi[2];
    if (!owned) {
      for (int m = 0; m < kNmat; ++m) a[m] = r[m] = e[m] = 0;
      a[kNmat - 1] = 1;
      r[kNmat - 1] = -5;
      e[kNmat - 1] = -7;
      return 1;
    }
    return global_content(g.global_index(0, i), g.global_index(1, j), g.global_index(2, k), nx, ny,
                          a, r, e);
  }
};

// The global cell a (possibly ghost) global index along one axis stands for.
long source(long g, long n, BoundaryKind lo, BoundaryKind hi) {
  if (g >= 0 && g < n) return g;
  if (lo == kP) return ((g % n) + n) % n;
  if (g < 0) return lo == kO ? 0 : -1 - g;
  return hi == kO ? n - 1 : 2 * n - 1 - g;
}

// Exchanges (twice, see below) and compares every cell of the block (ghosts included); returns the
// number of wrong entries on this rank, after printing the first few.
long exchange_and_check(const MeshSpec& spec, mat::LayoutKind kind, const std::string& label,
                        long& ghosts) {
  Mesh mesh(spec, MPI_COMM_WORLD);
  const auto C = Centering::Cell;
  Field3 rho = mesh.new_field("rho", C), e = mesh.new_field("e", C), p = mesh.new_field("p", C),
         ph = mesh.new_field("ph", C);
  mat::MaterialState mm(mesh, kind, kNmat, rho, e, p, ph);
  const auto end = mesh.owned_end();
  const Paint paint{mesh.geometry(),
                    mesh.global_cells(0),
                    mesh.global_cells(1),
                    {Mesh::ng, Mesh::ng, Mesh::ng},
                    {end[0], end[1], end[2]}};
  mm.assign("test::paint", paint);
  mm.exchange();
  // A second exchange after spoiling every ghost's cell averages: the ghosts' layout is already
  // right, so the compact layout takes only its in-place path (over the ghost shell) and must
  // write every ghost again; a ghost it skipped keeps the sentinel and fails below.
  {
    const int e0 = end[0], e1 = end[1], e2 = end[2], ng = Mesh::ng;
    Kokkos::parallel_for(
        "test::spoil_ghosts", mesh.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
          if (i < ng || j < ng || k < ng || i >= e0 || j >= e1 || k >= e2) {
            rho(i, j, k) = Real(-7);
            e(i, j, k) = Real(-7);
          }
        });
  }
  mm.exchange();

  // Read every cell's content through the layout's own accessor, and its cell averages.
  const int ex = mesh.extent(C, 0), ey = mesh.extent(C, 1), ez = mesh.extent(C, 2);
  Kokkos::View<Real****, MemSpace> out("out", ex, ey, ez, 3 * kNmat + 2);
  const mat::DenseDev dd = mm.dense();
  const mat::CompactDev cd = mm.compact();
  const bool dense = kind == mat::LayoutKind::Dense;
  Kokkos::parallel_for(
      "test::read_cells", mesh.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
        Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
        if (dense)
          mat::read_cell(dd, i, j, k, a, r, en);
        else
          mat::read_cell(cd, rho, e, i, j, k, a, r, en);
        for (int m = 0; m < kNmat; ++m) {
          out(i, j, k, 3 * m) = a[m];
          out(i, j, k, 3 * m + 1) = r[m];
          out(i, j, k, 3 * m + 2) = en[m];
        }
        out(i, j, k, 3 * kNmat) = rho(i, j, k);
        out(i, j, k, 3 * kNmat + 1) = e(i, j, k);
      });
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);

  long bad = 0;
  const char* names[3] = {"alpha", "rho", "e"};
  for (int k = 0; k < ez; ++k)
    for (int j = 0; j < ey; ++j)
      for (int i = 0; i < ex; ++i) {
        const int idx[3] = {i, j, k};
        long src[3];
        bool ghost = false;
        for (int d = 0; d < 3; ++d) {
          const long g = mesh.offset(d) + idx[d] - Mesh::ng;
          src[d] = source(g, mesh.global_cells(d), mesh.boundary(d, 0), mesh.boundary(d, 1));
          ghost = ghost || idx[d] < Mesh::ng || idx[d] >= end[d];
        }
        if (ghost) ++ghosts;
        Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
        global_content(src[0], src[1], src[2], mesh.global_cells(0), mesh.global_cells(1), a, r,
                       en);
        Real want[3 * kNmat + 2];
        for (int m = 0; m < kNmat; ++m) {
          want[3 * m] = a[m];
          want[3 * m + 1] = r[m];
          want[3 * m + 2] = en[m];
        }
        mat::cell_average(kNmat, a, r, en, want[3 * kNmat], want[3 * kNmat + 1]);
        for (int q = 0; q < 3 * kNmat + 2; ++q) {
          if (h(i, j, k, q) == want[q]) continue;
          if (bad++ < 6) {
            const std::string what =
                q < 3 * kNmat ? std::string(names[q % 3]) + " of material " + std::to_string(q / 3)
                : q == 3 * kNmat ? "cell rho"
                                 : "cell e";
            std::fprintf(stderr,
                         "[rank %d] %s: local (%d,%d,%d) %s, source global (%ld,%ld,%ld): %s "
                         "%.17g, expected %.17g\n",
                         world_rank(), label.c_str(), i, j, k, ghost ? "ghost" : "owned", src[0],
                         src[1], src[2], what.c_str(), double(h(i, j, k, q)), double(want[q]));
          }
        }
      }
  return bad;
}

MeshSpec spec_of(std::array<int, 3> cells, const Bc& bc) {
  MeshSpec s;
  s.cells = cells;
  s.lo = {{0.0, 0.0, 0.0}};
  s.hi = {{1.0, 1.0, 1.0}};
  s.bc = bc;
  return s;
}

void check(const Bc& bc, const std::string& name) {
  for (const auto kind : {mat::LayoutKind::Dense, mat::LayoutKind::Compact})
    for (const auto cells : {std::array<int, 3>{9, 7, 6}, std::array<int, 3>{6, 10, 5}}) {
      const std::string label = name + (kind == mat::LayoutKind::Dense ? " dense " : " compact ") +
                                std::to_string(cells[0]) + "x" + std::to_string(cells[1]) + "x" +
                                std::to_string(cells[2]);
      long ghosts = 0;
      long bad = exchange_and_check(spec_of(cells, bc), kind, label, ghosts);
      long total[2] = {bad, ghosts}, sum[2];
      MPI_Allreduce(total, sum, 2, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
      if (world_rank() == 0)
        std::printf("%s: %ld ghost cells checked, %ld wrong entries\n", label.c_str(), sum[1],
                    sum[0]);
      EXPECT_EQ(sum[0], 0) << label;
      EXPECT_GT(sum[1], 0) << label;
    }
}

TEST(MaterialHalo, ReflectiveWallsMirror) {
  check(Bc{{{{kR, kR}}, {{kR, kR}}, {{kR, kR}}}}, "reflective");
}

TEST(MaterialHalo, OutflowWallsClamp) {
  check(Bc{{{{kO, kO}}, {{kO, kO}}, {{kO, kO}}}}, "outflow");
}

TEST(MaterialHalo, MixedWallsAndPeriodic) {
  check(Bc{{{{kR, kO}}, {{kO, kR}}, {{kP, kP}}}}, "reflective/outflow, periodic z");
}

// Every axis periodic: at one rank each is held by this rank alone and its ghosts are copied
// from the owned cells with no message (mode "this rank" of the material halo); at 2 and 4 ranks
// the split axes send messages and the others do not.
TEST(MaterialHalo, AllPeriodic) {
  check(Bc{{{{kP, kP}}, {{kP, kP}}, {{kP, kP}}}}, "periodic x, y, z");
}

// The ghost shell the halo's in-place update runs over (mat::shell_cell) visits every cell with
// an index in the ng layers of some side exactly once, and no other cell.
TEST(MaterialHalo, GhostShellEnumeration) {
  const int ng = Mesh::ng;
  for (const std::array<int, 3>& ext :
       {std::array<int, 3>{6, 7, 8}, std::array<int, 3>{2 * ng + 1, 9, 2 * ng + 3},
        std::array<int, 3>{11, 2 * ng + 1, 5}}) {
    const int ex = ext[0], ey = ext[1], ez = ext[2];
    std::vector<int> seen(std::size_t(ex) * ey * ez, 0);
    const long n = mat::shell_cells(ex, ey, ez, ng);
    for (long r = 0; r < n; ++r) {
      int i = -1, j = -1, k = -1;
      mat::shell_cell(r, ex, ey, ez, ng, i, j, k);
      ASSERT_TRUE(i >= 0 && i < ex && j >= 0 && j < ey && k >= 0 && k < ez) << r;
      ++seen[(std::size_t(i) * ey + j) * ez + k];
    }
    long ghosts = 0;
    for (int i = 0; i < ex; ++i)
      for (int j = 0; j < ey; ++j)
        for (int k = 0; k < ez; ++k) {
          auto g = [&](int x, int e) { return x < ng || x >= e - ng; };
          const bool ghost = g(i, ex) || g(j, ey) || g(k, ez);
          ghosts += ghost;
          EXPECT_EQ(seen[(std::size_t(i) * ey + j) * ez + k], ghost ? 1 : 0)
              << ex << "x" << ey << "x" << ez << " cell " << i << "," << j << "," << k;
        }
    EXPECT_EQ(n, ghosts);
  }
}

}  // namespace
