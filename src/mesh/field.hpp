// Fields of one rank's block as the run sees them. OutputField: a named field for the dumps,
// the checkpoints and the XDMF series (io/hdf5_writer.hpp). FieldSpec: the registry's one
// description of a field (its names, centring, what the run does with it, its halo parity,
// its units), from which the physics modules' dumps, checkpoints and halo are all taken
// (kernels/hydro/module.hpp), so the kernels need nothing from src/io and the driver names
// no module's field.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "mesh/halo.hpp"
#include "mesh/mesh.hpp"

namespace mp {

struct OutputField {
  std::string name;  // dataset name, also the XDMF attribute name; must not contain '/'
  Centering centering;
  Field3 view;  // indexed (i, j, k), ghosts included, as made by Mesh::new_field
};

// What the run does with a registered field (bits of FieldSpec::use).
enum FieldUse : unsigned {
  kDump = 1u << 0,        // written in every dump, as `name`
  kCheckpoint = 1u << 1,  // state a restart cannot rebuild: checkpointed, as `key`
  kHalo = 1u << 2,        // ghosts filled by the cell exchange, with `parity`
};

struct FieldSpec {
  std::string name;  // the dumps' dataset name
  Centering centering;
  Field3 view;
  unsigned use = kDump;
  std::string key;                       // the checkpoints' dataset name
  std::array<int, 3> parity{{1, 1, 1}};  // sign under reflection in a plane normal to x, y, z
  const char* units = "";                // (cm, us, g units: "Mbar", "us", "" for a number)
};

// The fields of `all` that `use` selects: as the dumps take them (name), as the checkpoints
// take them (key), as the cell halo takes them (parity).
inline std::vector<OutputField> dump_fields(const std::vector<FieldSpec>& all) {
  std::vector<OutputField> out;
  for (const FieldSpec& f : all)
    if (f.use & kDump) out.push_back({f.name, f.centering, f.view});
  return out;
}
inline std::vector<OutputField> checkpoint_fields(const std::vector<FieldSpec>& all) {
  std::vector<OutputField> out;
  for (const FieldSpec& f : all)
    if (f.use & kCheckpoint) out.push_back({f.key, f.centering, f.view});
  return out;
}
inline std::vector<HaloField> halo_fields(const std::vector<FieldSpec>& all) {
  std::vector<HaloField> out;
  for (const FieldSpec& f : all)
    if (f.use & kHalo) out.push_back({f.view, f.centering, f.parity});
  return out;
}

}  // namespace mp
