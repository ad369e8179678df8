// A named field of one rank's block as the run's output sees it: the dumps, the checkpoints and
// the XDMF series take lists of these (io/hdf5_writer.hpp), and the physics modules describe
// their fields with them, so the kernels need nothing from src/io.
#pragma once
#include <string>

#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace mp {

struct OutputField {
  std::string name;  // dataset name, also the XDMF attribute name; must not contain '/'
  Centering centering;
  Field3 view;  // indexed (i, j, k), ghosts included, as made by Mesh::new_field
};

}  // namespace mp
