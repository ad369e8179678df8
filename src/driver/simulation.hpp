// One run of a scene: the mesh, the physics modules the scene needs, the time loop, output.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "config/scene.hpp"
#include "hydro/hydro.hpp"
#include "mesh/halo.hpp"
#include "mesh/mesh.hpp"

namespace mp {

struct RunSettings {
  std::string output_dir;  // where dumps and the summary go; empty: nothing is written
  bool quiet = false;      // no per-cycle log lines
};

struct RunResult {
  bool ok = true;
  long cycles = 0;
  double time = 0;
  double wall = 0;
  hydro::Totals start, end;
  hydro::Health health;
  std::vector<std::string> files;
};

class Simulation {
 public:
  Simulation(const Scene& scene, MPI_Comm comm, RunSettings settings);
  ~Simulation();

  // Paints the regions onto the mesh (cell centres decide; nodes take the velocity of the
  // region holding them) and derives pressure, sound speed and viscosity.
  void initialize();
  // Runs to the end time; writes dumps, the XDMF series and summary.json when asked to.
  RunResult run();

  const Mesh& mesh() const { return *mesh_; }
  hydro::Hydro& hydro() { return *hydro_; }
  const Scene& scene() const { return scene_; }
  std::vector<std::string> modules() const;

 private:
  std::string write_dump(double t, long cycle);
  void write_summary(const RunResult& r) const;

  Scene scene_;
  RunSettings settings_;
  std::unique_ptr<Mesh> mesh_;
  std::unique_ptr<Halo> halo_;
  std::unique_ptr<hydro::Hydro> hydro_;
  std::unique_ptr<Hdf5Writer> writer_;
};

}  // namespace mp
