#include "io/checkpoint.hpp"

#include <dirent.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "core/error.hpp"
#include "io/h5_util.hpp"

namespace mp {

std::string checkpoint_path(const std::string& dir, const std::string& basename, long cycle) {
  char text[32];
  std::snprintf(text, sizeof text, "%06ld", cycle);
  return (dir.empty() ? std::string(".") : dir) + "/" + basename + "_checkpoint_" + text + ".h5";
}

void write_checkpoint(const Mesh& mesh, const std::string& path,
                      const std::vector<OutputField>& fields, const std::string& meta_json,
                      const std::function<void()>& before_rename) {
  const MPI_Comm comm = mesh.comm();
  const std::string tmp = path + ".tmp";
  HDF5_CHECK(H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr));
  try {
    h5::on_all(comm, [&] {
      h5::Handle fapl, file, dxpl;
      HDF5_CHECK(fapl.reset(H5Pcreate(H5P_FILE_ACCESS), H5Pclose));
      HDF5_CHECK(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL));
      HDF5_CHECK(
          file.reset(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose));
      HDF5_CHECK(dxpl.reset(H5Pcreate(H5P_DATASET_XFER), H5Pclose));
      HDF5_CHECK(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE));
      h5::write_string_attribute(file.get(), "meta", meta_json);
      for (const auto& f : fields)
        h5::write_block(file.get(), dxpl.get(), mesh, f.name, f.centering, f.view);
      HDF5_CHECK(dxpl.close());
      HDF5_CHECK(file.close());
      HDF5_CHECK(fapl.close());
    });
    MPI_CHECK(MPI_Barrier(comm));
    if (before_rename) before_rename();
    h5::on_root(comm, [&] { h5::rename_or_throw(tmp, path); });
  } catch (const std::exception& e) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0) std::remove(tmp.c_str());
    throw CollectiveError("cannot write checkpoint " + path + ": " + e.what() +
                          disk_space_note(path) +
                          " (partial file removed; earlier checkpoints are intact)");
  }
}

std::string read_checkpoint_meta(const std::string& path, MPI_Comm comm) {
  HDF5_CHECK(H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr));
  std::string meta;
  try {
    h5::on_all(comm, [&] {
      h5::Handle file;
      HDF5_CHECK(file.reset(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose));
      meta = h5::read_string_attribute(file.get(), "meta");
      HDF5_CHECK(file.close());
    });
  } catch (const std::exception& e) {
    throw CollectiveError("cannot read checkpoint " + path + ": " + e.what());
  }
  return meta;
}

void read_checkpoint_fields(const Mesh& mesh, const std::string& path,
                            const std::vector<OutputField>& fields) {
  const MPI_Comm comm = mesh.comm();
  try {
    h5::on_all(comm, [&] {
      h5::Handle fapl, file, dxpl;
      HDF5_CHECK(fapl.reset(H5Pcreate(H5P_FILE_ACCESS), H5Pclose));
      HDF5_CHECK(H5Pset_fapl_mpio(fapl.get(), comm, MPI_INFO_NULL));
      HDF5_CHECK(file.reset(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose));
      HDF5_CHECK(dxpl.reset(H5Pcreate(H5P_DATASET_XFER), H5Pclose));
      HDF5_CHECK(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE));
      for (const auto& f : fields)
        h5::read_block(file.get(), dxpl.get(), mesh, f.name, f.centering, f.view);
      HDF5_CHECK(file.close());
    });
  } catch (const std::exception& e) {
    throw CollectiveError("cannot read checkpoint " + path + ": " + e.what());
  }
}

std::vector<std::string> checkpoint_missing(const std::string& path,
                                            const std::vector<std::string>& names, MPI_Comm comm) {
  HDF5_CHECK(H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr));
  std::string joined;  // the missing names, each followed by '\n'
  try {
    h5::on_root(comm, [&] {
      h5::Handle file;
      HDF5_CHECK(file.reset(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose));
      for (const std::string& n : names) {
        const htri_t there = H5Lexists(file.get(), n.c_str(), H5P_DEFAULT);
        HDF5_CHECK(there);
        if (there == 0) joined += n + '\n';
      }
      HDF5_CHECK(file.close());
    });
  } catch (const std::exception& e) {
    throw CollectiveError("cannot read checkpoint " + path + ": " + e.what());
  }
  int len = static_cast<int>(joined.size());
  MPI_CHECK(MPI_Bcast(&len, 1, MPI_INT, 0, comm));
  joined.resize(static_cast<size_t>(len));
  if (len > 0) MPI_CHECK(MPI_Bcast(&joined[0], len, MPI_CHAR, 0, comm));
  std::vector<std::string> out;
  for (std::size_t a = 0, b; (b = joined.find('\n', a)) != std::string::npos; a = b + 1)
    out.push_back(joined.substr(a, b - a));
  return out;
}

std::vector<std::pair<long, std::string>> list_checkpoints(const std::string& dir,
                                                           const std::string& basename) {
  std::vector<std::pair<long, std::string>> out;
  const std::string d = dir.empty() ? "." : dir;
  DIR* dp = opendir(d.c_str());
  if (!dp) return out;
  const std::string prefix = basename + "_checkpoint_";
  while (const dirent* e = readdir(dp)) {
    const std::string name = e->d_name;
    if (name.size() < prefix.size() + 9 || name.compare(0, prefix.size(), prefix) != 0 ||
        name.compare(name.size() - 3, 3, ".h5") != 0)
      continue;
    const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - 3);
    if (!std::all_of(digits.begin(), digits.end(), ::isdigit)) continue;
    out.emplace_back(std::strtol(digits.c_str(), nullptr, 10), d + "/" + name);
  }
  closedir(dp);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace mp
