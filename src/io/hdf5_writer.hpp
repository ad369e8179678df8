// Parallel HDF5 dumps of cell and node fields, one file per dump, with an XDMF 3 sidecar that
// ParaView and VisIt open directly.
//
// Each dump <dir>/<basename>_<cycle, 6 digits>.h5 holds, on its root group:
//   one dataset per field, global shape (NZ, NY, NX) for cell fields and (NZ+1, NY+1, NX+1) for
//   node fields, x fastest, native type of Real;
//   attributes time (double), cycle (int), origin and spacing (double[3], x y z order: the low
//   corner of the box and the cell sizes) and cells (int[3], x y z order).
#pragma once
#include <hdf5.h>

#include <array>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "mesh/field.hpp"
#include "mesh/mesh.hpp"

namespace mp {

class Hdf5Writer {
 public:
  // dir must exist (the caller creates it). basename e.g. "sod".
  Hdf5Writer(const Mesh& mesh, std::string dir, std::string basename);

  // Collective over mesh.comm(). Writes the dump of `cycle` (each rank its owned block, one
  // collective MPI-IO transfer per field) under <final>.tmp, renames it once every rank has closed
  // it, and rewrites <dir>/<basename>.xmf (tmp + rename) listing every dump written so far by this
  // writer. Returns the final path of the .h5 file. Throws RunError on any HDF5, MPI or file error.
  std::string write(const std::vector<OutputField>& fields, double time, int cycle);
  // Lists a dump an earlier process wrote (a restart) in the XDMF series of later writes.
  void remember(const std::string& file, double time, int cycle,
                const std::vector<OutputField>& fields);

 private:
  struct Dump {
    std::string file;  // name relative to dir_
    double time;
    int cycle;
    std::vector<std::pair<std::string, Centering>> fields;
  };
  void write_xdmf() const;

  const Mesh& mesh_;
  std::string dir_, basename_;
  std::vector<Dump> dumps_;
};

// Serial helper for tests and tools: reads a whole global 3-D dataset into a host vector (x
// fastest, converted to double), and stores its dims (slowest first) in *dims when given.
std::vector<double> read_dataset(const std::string& file, const std::string& name,
                                 std::array<hsize_t, 3>* dims = nullptr);

}  // namespace mp
