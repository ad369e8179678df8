// Parallel HDF5 output: a dump written by 4 ranks on an uneven split equals, element for element,
// the dump of the same fields written by one rank, and both equal the analytic fill. Node fields
// are written once per global node; the temporary file is gone; the XDMF sidecar lists the dumps.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/types.hpp"
#include "io/hdf5_writer.hpp"
#include "mesh/mesh.hpp"

namespace fs = std::filesystem;

namespace {

constexpr int kNx = 13, kNy = 10, kNz = 7;

// Distinct for every global index here, and exact in float too (all values stay below 2^22, so
// the quarter survives a 24-bit mantissa).
KOKKOS_INLINE_FUNCTION double analytic(int gi, int gj, int gk) {
  return gi + 1000.0 * gj + 1.0e5 * gk + 0.25;
}

mp::MeshSpec test_spec() {
  mp::MeshSpec spec;
  spec.cells = {{kNx, kNy, kNz}};
  spec.lo = {{-1.0, 0.0, 2.0}};
  spec.hi = {{1.6, 2.0, 3.4}};
  return spec;
}

// Ghosts hold a sentinel, owned entries the analytic function of the global index.
mp::Field3 fill(const mp::Mesh& mesh, mp::Centering c, const char* name) {
  mp::Field3 f = mesh.new_field(name, c);
  Kokkos::deep_copy(f, mp::Real(-7.5));
  const mp::Geometry geo = mesh.geometry();
  Kokkos::parallel_for(
      "fill", mesh.policy(c, mp::Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
        f(i, j, k) = mp::Real(
            analytic(geo.global_index(0, i), geo.global_index(1, j), geo.global_index(2, k)));
      });
  Kokkos::fence();
  return f;
}

std::string write_dump(const mp::Mesh& mesh, mp::Hdf5Writer& writer, double time, int cycle) {
  std::vector<mp::OutputField> fields{
      {"density", mp::Centering::Cell, fill(mesh, mp::Centering::Cell, "density")},
      {"velocity_x", mp::Centering::Node, fill(mesh, mp::Centering::Node, "velocity_x")}};
  return writer.write(fields, time, cycle);
}

// A temporary directory made by rank 0, known to every rank, removed at the end.
std::string shared_tmpdir() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  char buf[256] = {0};
  if (rank == 0) {
    std::string templ = (fs::temp_directory_path() / "mp_test_hdf5_XXXXXX").string();
    std::vector<char> name(templ.begin(), templ.end());
    name.push_back('\0');
    if (mkdtemp(name.data()) != nullptr) std::snprintf(buf, sizeof buf, "%s", name.data());
  }
  MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, MPI_COMM_WORLD);
  return buf;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + what.size()))
    ++n;
  return n;
}

// Minimal well-formedness check: every element closes in order. Returns "" when balanced.
std::string xml_balance_error(const std::string& text) {
  std::vector<std::string> open;
  for (size_t p = text.find('<'); p != std::string::npos; p = text.find('<', p + 1)) {
    const size_t e = text.find('>', p);
    if (e == std::string::npos) return "unterminated tag";
    const std::string tag = text.substr(p + 1, e - p - 1);
    if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
    if (tag.back() == '/') continue;
    const size_t name_end = tag.find_first_of(" \t\n/");
    if (tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (open.empty() || open.back() != name) return "unexpected </" + name + ">";
      open.pop_back();
    } else {
      open.push_back(tag.substr(0, name_end));
    }
  }
  return open.empty() ? "" : "unclosed <" + open.back() + ">";
}

template <class T>
T read_root_attribute(const std::string& file, const char* name, hid_t type) {
  T value{};
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0);
  hid_t a = H5Aopen(f, name, H5P_DEFAULT);
  EXPECT_GE(a, 0);
  EXPECT_GE(H5Aread(a, type, &value), 0);
  H5Aclose(a);
  H5Fclose(f);
  return value;
}

// Rank 0 only. A helper, so that a failed ASSERT returns here and never skips a collective.
void check_dumps(const std::string& dir, const std::string& serial_file,
                 const std::string& parallel_file, const std::string& parallel_file2) {
  EXPECT_EQ(fs::path(serial_file).filename().string(), "serial_000003.h5");
  EXPECT_EQ(fs::path(parallel_file).filename().string(), "parallel_000003.h5");
  EXPECT_EQ(fs::path(parallel_file2).filename().string(), "parallel_000017.h5");
  ASSERT_TRUE(fs::exists(serial_file));
  ASSERT_TRUE(fs::exists(parallel_file));
  ASSERT_TRUE(fs::exists(parallel_file2));
  struct Case {
    const char* name;
    std::array<hsize_t, 3> dims;
  };
  const Case cases[] = {{"density", {{kNz, kNy, kNx}}},
                        {"velocity_x", {{kNz + 1, kNy + 1, kNx + 1}}}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    std::array<hsize_t, 3> ds{}, dp{};
    const std::vector<double> s = mp::read_dataset(serial_file, c.name, &ds);
    const std::vector<double> p = mp::read_dataset(parallel_file, c.name, &dp);
    EXPECT_EQ(ds, c.dims);
    EXPECT_EQ(dp, c.dims);
    ASSERT_EQ(s.size(), c.dims[0] * c.dims[1] * c.dims[2]);
    ASSERT_EQ(p.size(), s.size());
    long mismatch_sp = 0, mismatch_analytic = 0;
    size_t n = 0;
    for (hsize_t k = 0; k < c.dims[0]; ++k)
      for (hsize_t j = 0; j < c.dims[1]; ++j)
        for (hsize_t i = 0; i < c.dims[2]; ++i, ++n) {
          const double expect = analytic(int(i), int(j), int(k));
          if (s[n] != p[n]) ++mismatch_sp;
          if (p[n] != expect) {
            if (mismatch_analytic < 5)
              ADD_FAILURE() << "at (k,j,i)=(" << k << "," << j << "," << i << ") read " << p[n]
                            << ", expected " << expect;
            ++mismatch_analytic;
          }
        }
    std::printf(
        "  %-10s %zu values: %ld differ between the serial and parallel dumps, %ld from "
        "the analytic fill\n",
        c.name, p.size(), mismatch_sp, mismatch_analytic);
    EXPECT_EQ(mismatch_sp, 0);
    EXPECT_EQ(mismatch_analytic, 0);
  }

  for (const auto& [file, time, cycle] :
       {std::tuple<std::string, double, int>{parallel_file, 0.5, 3}, {parallel_file2, 1.25, 17}}) {
    const double t = read_root_attribute<double>(file, "time", H5T_NATIVE_DOUBLE);
    const int c = read_root_attribute<int>(file, "cycle", H5T_NATIVE_INT);
    std::printf("  %s: time %.17g, cycle %d\n", fs::path(file).filename().c_str(), t, c);
    EXPECT_EQ(t, time);
    EXPECT_EQ(c, cycle);
  }

  // No temporary file is left behind.
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();

  // The sidecars.
  const std::string xmf = dir + "/parallel.xmf";
  ASSERT_TRUE(fs::exists(xmf));
  ASSERT_TRUE(fs::exists(dir + "/serial.xmf"));
  const std::string text = slurp(xmf);
  EXPECT_EQ(xml_balance_error(text), "");
  EXPECT_NE(text.find("<Xdmf"), std::string::npos);
  EXPECT_NE(text.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_NE(text.find("3DCoRectMesh"), std::string::npos);
  EXPECT_NE(text.find("ORIGIN_DXDYDZ"), std::string::npos);
  EXPECT_NE(text.find("Dimensions=\"8 11 14\""), std::string::npos);
  EXPECT_NE(text.find("Dimensions=\"7 10 13\""), std::string::npos);
  EXPECT_EQ(count_of(text, "<Time "), 2u);
  EXPECT_EQ(count_of(text, "GridType=\"Uniform\""), 2u);
  EXPECT_EQ(count_of(text, "parallel_000003.h5:/density"), 1u);
  EXPECT_EQ(count_of(text, "parallel_000003.h5:/velocity_x"), 1u);
  EXPECT_EQ(count_of(text, "parallel_000017.h5:/density"), 1u);
  EXPECT_EQ(count_of(text, "parallel_000017.h5:/velocity_x"), 1u);
  EXPECT_EQ(count_of(text, "Center=\"Cell\""), 2u);
  EXPECT_EQ(count_of(text, "Center=\"Node\""), 2u);
  EXPECT_EQ(count_of(slurp(dir + "/serial.xmf"), "<Time "), 1u);
}

TEST(Hdf5, ParallelDumpEqualsSerialDumpAndAnalytic) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const std::string dir = shared_tmpdir();
  ASSERT_FALSE(dir.empty());  // same outcome on every rank

  // The same mesh written by rank 0 alone and by all ranks.
  std::string serial_file, parallel_file, parallel_file2;
  if (rank == 0) {
    try {
      mp::Mesh serial(test_spec(), MPI_COMM_SELF);
      mp::Hdf5Writer writer(serial, dir, "serial");
      serial_file = write_dump(serial, writer, 0.5, 3);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "serial write: " << e.what();
    }
  }
  {
    // A failure here is collective: every rank throws the same error.
    mp::Mesh mesh(test_spec(), MPI_COMM_WORLD);
    EXPECT_EQ(mesh.nranks(), size);
    mp::Hdf5Writer writer(mesh, dir, "parallel");
    parallel_file = write_dump(mesh, writer, 0.5, 3);
    parallel_file2 = write_dump(mesh, writer, 1.25, 17);
  }
  MPI_Barrier(MPI_COMM_WORLD);

  if (rank == 0) {
    try {
      check_dumps(dir, serial_file, parallel_file, parallel_file2);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "reading the dumps back: " << e.what();
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
    EXPECT_FALSE(ec) << ec.message();
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

}  // namespace
