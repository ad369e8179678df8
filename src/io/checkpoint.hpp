// Checkpoints: one parallel HDF5 file per checkpoint, <dir>/<basename>_checkpoint_<cycle>.h5,
// holding the owned blocks of every field the next cycle reads (global arrays, so a run may
// restart on any rank count) and a JSON metadata attribute (`meta`: build, deck, clock,
// counters). Written under <name>.tmp and renamed once complete, so a file with the final name
// is always whole; a restart never reads a .tmp.
#pragma once
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "io/hdf5_writer.hpp"
#include "mesh/mesh.hpp"

namespace mp {

// Collective over mesh.comm(). Throws RunError naming the file and the reason; the partial
// temporary file is removed. `before_rename` (if any) runs on every rank once the temporary
// file is complete (a test hook).
void write_checkpoint(const Mesh& mesh, const std::string& path,
                      const std::vector<OutputField>& fields, const std::string& meta_json,
                      const std::function<void()>& before_rename = {});

// Collective over comm: the metadata JSON text of a checkpoint. Throws RunError (file, reason).
std::string read_checkpoint_meta(const std::string& path, MPI_Comm comm);

// Collective over mesh.comm(): fills the owned block of every field from the checkpoint
// (ghosts are left to the caller's halo exchange).
void read_checkpoint_fields(const Mesh& mesh, const std::string& path,
                            const std::vector<OutputField>& fields);

// Collective over comm: which of `names` the checkpoint holds no dataset for (in order).
std::vector<std::string> checkpoint_missing(const std::string& path,
                                            const std::vector<std::string>& names, MPI_Comm comm);

// Complete checkpoints of `basename` in `dir`, oldest first, as (cycle, path).
std::vector<std::pair<long, std::string>> list_checkpoints(const std::string& dir,
                                                           const std::string& basename);
std::string checkpoint_path(const std::string& dir, const std::string& basename, long cycle);

}  // namespace mp
