#include "io/hdf5_writer.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <type_traits>
#include <utility>

#include "core/error.hpp"
#include "io/h5_util.hpp"

namespace mp {

namespace {

using h5::Handle;
using h5::on_root;
using h5::rename_or_throw;
using h5::write_attribute;

std::string dims_string(const std::array<int, 3>& zyx) {
  std::ostringstream os;
  os << zyx[0] << " " << zyx[1] << " " << zyx[2];
  return os.str();
}

// Field names go into XML attribute values.
std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

Hdf5Writer::Hdf5Writer(const Mesh& mesh, std::string dir, std::string basename)
    : mesh_(mesh), dir_(std::move(dir)), basename_(std::move(basename)) {
  // Failures become exceptions carrying the stack's detail; HDF5 must not also print them.
  HDF5_CHECK(H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr));
  if (dir_.empty()) dir_ = ".";
}

std::string Hdf5Writer::write(const std::vector<OutputField>& fields, double time, int cycle) {
  const MPI_Comm comm = mesh_.comm();
  char cycle_text[32];
  std::snprintf(cycle_text, sizeof cycle_text, "%06d", cycle);
  const std::string name = basename_ + "_" + cycle_text + ".h5";
  const std::string path = dir_ + "/" + name;
  const std::string tmp = path + ".tmp";

  for (const auto& f : fields) {
    if (f.name.empty() || f.name.find('/') != std::string::npos)
      throw RunError("hdf5 output: invalid field name '" + f.name + "'");
    for (int d = 0; d < 3; ++d)
      if (static_cast<int>(f.view.extent(d)) != mesh_.extent(f.centering, d))
        throw RunError("hdf5 output: field '" + f.name + "' does not match the mesh block");
  }

  try {
    h5::on_all(comm, [&] {
      Handle fapl, file, dxpl;
      HDF5_CHECK(fapl.reset(H5Pcreate(H5P_FILE_ACCESS), H5Pclose));
      HDF5_CHECK(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL));
      HDF5_CHECK(
          file.reset(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose));
      HDF5_CHECK(dxpl.reset(H5Pcreate(H5P_DATASET_XFER), H5Pclose));
      HDF5_CHECK(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE));

      // Root-group attributes: every rank passes the same values (metadata writes are collective).
      write_attribute(file.get(), "time", H5T_NATIVE_DOUBLE, 0, &time);
      write_attribute(file.get(), "cycle", H5T_NATIVE_INT, 0, &cycle);
      const MeshSpec& spec = mesh_.spec();
      double origin[3], spacing[3];
      int cells[3];
      for (int d = 0; d < 3; ++d) {
        origin[d] = spec.lo[d];
        spacing[d] = (spec.hi[d] - spec.lo[d]) / spec.cells[d];
        cells[d] = spec.cells[d];
      }
      write_attribute(file.get(), "origin", H5T_NATIVE_DOUBLE, 3, origin);
      write_attribute(file.get(), "spacing", H5T_NATIVE_DOUBLE, 3, spacing);
      write_attribute(file.get(), "cells", H5T_NATIVE_INT, 3, cells);

      for (const auto& f : fields)
        h5::write_block(file.get(), dxpl.get(), mesh_, f.name, f.centering, f.view);
      HDF5_CHECK(dxpl.close());
      HDF5_CHECK(file.close());
      HDF5_CHECK(fapl.close());
    });
    // Every rank has closed the file; only then does it get its final name.
    MPI_CHECK(MPI_Barrier(comm));
    on_root(comm, [&] { rename_or_throw(tmp, path); });
  } catch (const std::exception& e) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0) std::remove(tmp.c_str());
    throw CollectiveError("cannot write dump " + path + ": " + e.what() + disk_space_note(path) +
                          " (partial file removed; earlier dumps are intact)");
  }

  Dump dump{name, time, cycle, {}};
  for (const auto& f : fields) dump.fields.emplace_back(f.name, f.centering);
  bool replaced = false;
  for (auto& d : dumps_)
    if (d.file == name) {
      d = dump;
      replaced = true;
    }
  if (!replaced) dumps_.push_back(std::move(dump));
  on_root(comm, [&] { write_xdmf(); });
  return path;
}

void Hdf5Writer::remember(const std::string& file, double time, int cycle,
                          const std::vector<OutputField>& fields) {
  Dump dump{file, time, cycle, {}};
  for (const auto& f : fields) dump.fields.emplace_back(f.name, f.centering);
  dumps_.push_back(std::move(dump));
}

void Hdf5Writer::write_xdmf() const {
  const std::string path = dir_ + "/" + basename_ + ".xmf";
  const MeshSpec& spec = mesh_.spec();
  const std::array<int, 3> nodes{{spec.cells[2] + 1, spec.cells[1] + 1, spec.cells[0] + 1}};
  const std::array<int, 3> cells{{spec.cells[2], spec.cells[1], spec.cells[0]}};
  const bool dbl = std::is_same<Real, double>::value;
  const char* precision = dbl ? "8" : "4";

  std::ostringstream os;
  os << std::setprecision(17);
  os << "<?xml version=\"1.0\" ?>\n"
     << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
     << "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n"
     << "  <Domain>\n"
     << "    <Grid Name=\"" << xml_escape(basename_)
     << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& d : dumps_) {
    os << "      <Grid Name=\"cycle_" << d.cycle << "\" GridType=\"Uniform\">\n"
       << "        <Time Value=\"" << d.time << "\"/>\n"
       << "        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << dims_string(nodes)
       << "\"/>\n"
       << "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
       << "          <DataItem Name=\"Origin\" Dimensions=\"3\" NumberType=\"Float\" "
          "Precision=\"8\" Format=\"XML\">"
       << spec.lo[2] << " " << spec.lo[1] << " " << spec.lo[0] << "</DataItem>\n"
       << "          <DataItem Name=\"Spacing\" Dimensions=\"3\" NumberType=\"Float\" "
          "Precision=\"8\" Format=\"XML\">";
    for (int a = 2; a >= 0; --a)
      os << (spec.hi[a] - spec.lo[a]) / spec.cells[a] << (a > 0 ? " " : "");
    os << "</DataItem>\n"
       << "        </Geometry>\n";
    for (const auto& f : d.fields) {
      const bool cell = f.second == Centering::Cell;
      os << "        <Attribute Name=\"" << xml_escape(f.first)
         << "\" AttributeType=\"Scalar\" Center=\"" << (cell ? "Cell" : "Node") << "\">\n"
         << "          <DataItem Dimensions=\"" << dims_string(cell ? cells : nodes)
         << "\" NumberType=\"Float\" Precision=\"" << precision << "\" Format=\"HDF\">"
         << xml_escape(d.file) << ":/" << xml_escape(f.first) << "</DataItem>\n"
         << "        </Attribute>\n";
    }
    // The node velocity also as one vector (ParaView / VisIt glyphs and stream lines), joined
    // from the three component datasets by an XDMF function: no data written twice.
    const auto has = [&](const std::string& n) {
      for (const auto& f : d.fields)
        if (f.first == n && f.second == Centering::Node) return true;
      return false;
    };
    if (has("velocity_x") && has("velocity_y") && has("velocity_z")) {
      os << "        <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n"
         << "          <DataItem ItemType=\"Function\" Function=\"JOIN($0, $1, $2)\" "
            "Dimensions=\""
         << dims_string(nodes) << " 3\">\n";
      for (const char* c : {"velocity_x", "velocity_y", "velocity_z"})
        os << "            <DataItem Dimensions=\"" << dims_string(nodes)
           << "\" NumberType=\"Float\" Precision=\"" << precision << "\" Format=\"HDF\">"
           << xml_escape(d.file) << ":/" << c << "</DataItem>\n";
      os << "          </DataItem>\n"
         << "        </Attribute>\n";
    }
    os << "      </Grid>\n";
  }
  os << "    </Grid>\n"
     << "  </Domain>\n"
     << "</Xdmf>\n";

  write_text_atomically(path, os.str());
}

std::vector<double> read_dataset(const std::string& file, const std::string& name,
                                 std::array<hsize_t, 3>* dims) {
  HDF5_CHECK(H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr));
  Handle f, dset, space;
  HDF5_CHECK(f.reset(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose));
  HDF5_CHECK(dset.reset(H5Dopen2(f.get(), name.c_str(), H5P_DEFAULT), H5Dclose));
  HDF5_CHECK(space.reset(H5Dget_space(dset.get()), H5Sclose));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  HDF5_CHECK(rank);
  if (rank != 3)
    throw RunError("read_dataset: " + file + ":/" + name + " has rank " + std::to_string(rank) +
                   ", expected 3");
  std::array<hsize_t, 3> d{};
  HDF5_CHECK(H5Sget_simple_extent_dims(space.get(), d.data(), nullptr));
  std::vector<double> data(static_cast<size_t>(d[0] * d[1] * d[2]));
  if (!data.empty())
    HDF5_CHECK(H5Dread(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()));
  HDF5_CHECK(space.close());
  HDF5_CHECK(dset.close());
  HDF5_CHECK(f.close());
  if (dims) *dims = d;
  return data;
}

}  // namespace mp
