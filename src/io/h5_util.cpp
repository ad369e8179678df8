#include "io/h5_util.hpp"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace mp {

namespace {
// Keeps the most specific entry of the HDF5 error stack (where the error was first detected).
herr_t first_hdf5_error(unsigned n, const H5E_error2_t* err, void* data) {
  if (n == 0 && err != nullptr) {
    auto* out = static_cast<std::string*>(data);
    *out = std::string(err->func_name ? err->func_name : "?") + ": " +
           (err->desc ? err->desc : "no description");
  }
  return 0;
}
}  // namespace

void throw_hdf5_error(const char* call, const char* file, int line) {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, first_hdf5_error, &detail);
  H5Eclear2(H5E_DEFAULT);
  std::ostringstream os;
  os << call << " failed at " << file << ":" << line;
  if (!detail.empty()) os << " (" << detail << ")";
  throw RunError(os.str());
}

void write_text_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw RunError("cannot write " + tmp + ": " + std::strerror(errno));
  size_t done = 0;
  int err = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    done += static_cast<size_t>(n);
  }
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) {
    std::remove(tmp.c_str());
    throw RunError("cannot write " + path + ": " + std::strerror(err) +
                   " (partial file removed; the earlier " + path.substr(path.rfind('/') + 1) +
                   ", if any, is intact)");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    err = errno;
    std::remove(tmp.c_str());
    throw RunError("cannot rename " + tmp + " to " + path + ": " + std::strerror(err));
  }
}

std::string disk_space_note(const std::string& path) {
  const auto slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash);
  struct statvfs st;
  if (statvfs(dir.c_str(), &st) != 0) return "";
  const double free_bytes = double(st.f_bavail) * double(st.f_frsize);
  if (free_bytes >= 4.0 * 1024 * 1024) return "";
  char text[160];
  std::snprintf(text, sizeof text, "; no space left on device (%.0f KiB free on the file system)",
                free_bytes / 1024);
  return text;
}

}  // namespace mp

namespace mp::h5 {

void write_attribute(hid_t loc, const char* name, hid_t type, hsize_t n, const void* data) {
  Handle space, attr;
  if (n == 0) {
    HDF5_CHECK(space.reset(H5Screate(H5S_SCALAR), H5Sclose));
  } else {
    HDF5_CHECK(space.reset(H5Screate_simple(1, &n, nullptr), H5Sclose));
  }
  HDF5_CHECK(
      attr.reset(H5Acreate2(loc, name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose));
  HDF5_CHECK(H5Awrite(attr.get(), type, data));
  HDF5_CHECK(attr.close());
  HDF5_CHECK(space.close());
}

void write_string_attribute(hid_t loc, const char* name, const std::string& value) {
  Handle type;
  HDF5_CHECK(type.reset(H5Tcopy(H5T_C_S1), H5Tclose));
  HDF5_CHECK(H5Tset_size(type.get(), value.empty() ? 1 : value.size()));
  const std::string v = value.empty() ? std::string(1, '\0') : value;
  write_attribute(loc, name, type.get(), 0, v.data());
}

namespace {
void need_attribute(hid_t loc, const char* name) {
  const htri_t there = H5Aexists(loc, name);
  HDF5_CHECK(there);
  if (!there) throw RunError(std::string("attribute '") + name + "' is missing");
}
}  // namespace

std::string read_string_attribute(hid_t loc, const char* name) {
  need_attribute(loc, name);
  Handle attr, type, mem;
  HDF5_CHECK(attr.reset(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose));
  HDF5_CHECK(type.reset(H5Aget_type(attr.get()), H5Tclose));
  if (H5Tget_class(type.get()) != H5T_STRING)
    throw RunError(std::string("attribute '") + name + "' is not a string");
  const size_t n = H5Tget_size(type.get());
  std::string out(n, '\0');
  HDF5_CHECK(mem.reset(H5Tcopy(H5T_C_S1), H5Tclose));
  HDF5_CHECK(H5Tset_size(mem.get(), n));
  HDF5_CHECK(H5Aread(attr.get(), mem.get(), &out[0]));
  const auto end = out.find('\0');
  if (end != std::string::npos) out.resize(end);
  return out;
}

std::vector<double> read_double_attribute(hid_t loc, const char* name) {
  need_attribute(loc, name);
  Handle attr, space;
  HDF5_CHECK(attr.reset(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose));
  HDF5_CHECK(space.reset(H5Aget_space(attr.get()), H5Sclose));
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  HDF5_CHECK(n);
  std::vector<double> out(static_cast<size_t>(n));
  if (n > 0) HDF5_CHECK(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, out.data()));
  return out;
}

long read_long_attribute(hid_t loc, const char* name) {
  need_attribute(loc, name);
  Handle attr;
  long v = 0;
  HDF5_CHECK(attr.reset(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose));
  HDF5_CHECK(H5Aread(attr.get(), H5T_NATIVE_LONG, &v));
  return v;
}

namespace {
// The owned block of a field along each axis d (x y z): first local index, count, and the
// global shape / offset in HDF5 (z y x) order. `all_nodes`: every owned node (reading back);
// otherwise shared face nodes go to the lower rank only (writing).
struct Block {
  int first[3], count[3];
  hsize_t gdims[3], start[3], block[3];
};
Block owned_block(const Mesh& mesh, Centering centering, bool all_nodes) {
  Block b{};
  const int extra = centering == Centering::Node ? 1 : 0;
  for (int d = 0; d < 3; ++d) {
    b.first[d] = Mesh::ng;
    const bool high_end = mesh.coords()[d] == mesh.dims()[d] - 1;
    b.count[d] = mesh.owned_cells(d) + (extra && (high_end || all_nodes) ? 1 : 0);
    b.gdims[2 - d] = static_cast<hsize_t>(mesh.global_cells(d) + extra);
    b.start[2 - d] = static_cast<hsize_t>(mesh.offset(d));
    b.block[2 - d] = static_cast<hsize_t>(b.count[d]);
  }
  return b;
}
}  // namespace

void write_block(hid_t file, hid_t dxpl, const Mesh& mesh, const std::string& name,
                 Centering centering, const Field3& view) {
  for (int d = 0; d < 3; ++d)
    if (static_cast<int>(view.extent(d)) != mesh.extent(centering, d))
      throw RunError("hdf5 output: field '" + name + "' does not match the mesh block");
  const Block b = owned_block(mesh, centering, false);
  // Owned block to host, (k, j, i) with i fastest.
  auto host = Kokkos::create_mirror_view(view);
  Kokkos::deep_copy(host, view);
  std::vector<Real> buf(static_cast<size_t>(b.count[0]) * b.count[1] * b.count[2]);
  size_t n = 0;
  for (int k = b.first[2]; k < b.first[2] + b.count[2]; ++k)
    for (int j = b.first[1]; j < b.first[1] + b.count[1]; ++j)
      for (int i = b.first[0]; i < b.first[0] + b.count[0]; ++i) buf[n++] = host(i, j, k);

  const hid_t type = native_real_type();
  Handle fspace, mspace, dset;
  HDF5_CHECK(fspace.reset(H5Screate_simple(3, b.gdims, nullptr), H5Sclose));
  HDF5_CHECK(dset.reset(
      H5Dcreate2(file, name.c_str(), type, fspace.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose));
  HDF5_CHECK(mspace.reset(H5Screate_simple(3, b.block, nullptr), H5Sclose));
  if (buf.empty()) {
    HDF5_CHECK(H5Sselect_none(fspace.get()));
    HDF5_CHECK(H5Sselect_none(mspace.get()));
  } else {
    HDF5_CHECK(
        H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, b.start, nullptr, b.block, nullptr));
  }
  HDF5_CHECK(H5Dwrite(dset.get(), type, mspace.get(), fspace.get(), dxpl, buf.data()));
  HDF5_CHECK(dset.close());
}

void read_block(hid_t file, hid_t dxpl, const Mesh& mesh, const std::string& name,
                Centering centering, const Field3& view) {
  const Block b = owned_block(mesh, centering, true);
  Handle dset, fspace, mspace, ftype;
  const htri_t there = H5Lexists(file, name.c_str(), H5P_DEFAULT);
  HDF5_CHECK(there);
  if (!there) throw RunError("dataset '" + name + "' is missing");
  HDF5_CHECK(dset.reset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose));
  HDF5_CHECK(ftype.reset(H5Dget_type(dset.get()), H5Tclose));
  if (H5Tget_class(ftype.get()) != H5T_FLOAT || H5Tget_size(ftype.get()) != sizeof(Real))
    throw RunError("dataset '" + name + "' is not stored in this build's Real (" +
                   std::to_string(sizeof(Real) * 8) + "-bit float)");
  HDF5_CHECK(fspace.reset(H5Dget_space(dset.get()), H5Sclose));
  hsize_t dims[3] = {0, 0, 0};
  if (H5Sget_simple_extent_ndims(fspace.get()) != 3)
    throw RunError("dataset '" + name + "' is not 3-D");
  HDF5_CHECK(H5Sget_simple_extent_dims(fspace.get(), dims, nullptr));
  for (int d = 0; d < 3; ++d)
    if (dims[d] != b.gdims[d])
      throw RunError("dataset '" + name + "' has the wrong shape for this mesh");
  HDF5_CHECK(mspace.reset(H5Screate_simple(3, b.block, nullptr), H5Sclose));
  HDF5_CHECK(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, b.start, nullptr, b.block, nullptr));
  std::vector<Real> buf(static_cast<size_t>(b.count[0]) * b.count[1] * b.count[2]);
  HDF5_CHECK(H5Dread(dset.get(), native_real_type(), mspace.get(), fspace.get(), dxpl, buf.data()));
  auto host = Kokkos::create_mirror_view(view);
  Kokkos::deep_copy(host, view);
  size_t n = 0;
  for (int k = b.first[2]; k < b.first[2] + b.count[2]; ++k)
    for (int j = b.first[1]; j < b.first[1] + b.count[1]; ++j)
      for (int i = b.first[0]; i < b.first[0] + b.count[0]; ++i) host(i, j, k) = buf[n++];
  Kokkos::deep_copy(view, host);
}

void rename_or_throw(const std::string& from, const std::string& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0)
    throw RunError("cannot rename " + from + " to " + to + ": " + std::strerror(errno));
}

}  // namespace mp::h5
