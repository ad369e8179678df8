// Helpers shared by the integration tests: run a scene from configs/, gather fields globally.
#pragma once
#include <mpi.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "burn/module.hpp"
#include "config/scene.hpp"
#include "core/error.hpp"
#include "driver/simulation.hpp"
#include "mpi_rest.hpp"
#include "paths.hpp"
#include "precision.hpp"
#include "strength/module.hpp"

namespace mp::test {

inline Scene load_scene(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return read_scene(Deck::load(source_dir() + "/configs/" + name, overrides));
}

// The InputError message of loading a deck from configs/ with `overrides`, or "" if it loads.
inline std::string input_error(const std::string& name, const std::vector<std::string>& overrides) {
  try {
    load_scene(name, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A quiet, initialised simulation of a deck from configs/ on `cells` per axis (time.end far
// away), with `overrides` after those two, for tests that drive Hydro::step themselves.
inline std::unique_ptr<Simulation> started(const std::string& deck, int cells,
                                           const std::vector<std::string>& overrides = {}) {
  const std::string n = std::to_string(cells);
  std::vector<std::string> ov = {"mesh.cells=[" + n + "," + n + "," + n + "]", "time.end=1e9"};
  ov.insert(ov.end(), overrides.begin(), overrides.end());
  RunSettings settings;
  settings.quiet = true;
  auto sim = std::make_unique<Simulation>(load_scene(deck, ov), MPI_COMM_WORLD, settings);
  sim->initialize();
  return sim;
}

// Steps a simulation's hydro from t = 0 toward t_end by the run's own time-step rule, calling
// after(t, dt) once each step is taken; stops at t_end, at a step that goes bad or when after
// returns false. Returns the time reached, the cycles taken and the last step's health.
struct Stepped {
  double t = 0;
  long cycles = 0;
  hydro::Health health;
};
template <class After>
Stepped step_until(Simulation& sim, double t_end, After after) {
  auto& h = sim.hydro();
  Stepped s;
  Real dt_old = 0;
  while (s.t < t_end) {
    const auto ts = h.time_step(dt_old, s.t, t_end);
    s.health = h.step(ts.dt, s.cycles++);
    if (!s.health.ok) break;
    s.t += ts.dt;
    dt_old = ts.dt;
    if (!after(s.t, double(ts.dt))) break;
  }
  return s;
}

struct Ran {
  std::unique_ptr<Simulation> sim;
  RunResult result;
};

// Runs a scene quietly, writing nothing, on `comm`.
inline Ran run_scene(const Scene& scene, MPI_Comm comm = MPI_COMM_WORLD) {
  Ran r;
  RunSettings settings;
  settings.quiet = true;
  r.sim = std::make_unique<Simulation>(scene, comm, settings);
  r.sim->initialize();
  r.result = r.sim->run();
  return r;
}

// The whole global array of a field on every rank of the mesh's communicator, x fastest.
// Each global entry is written by exactly one rank, so the sum-reduction is exact.
inline std::vector<double> gather(const Mesh& mesh, const Field3& f, Centering c) {
  const int extra = c == Centering::Node ? 1 : 0;
  const long nx = mesh.global_cells(0) + extra, ny = mesh.global_cells(1) + extra,
             nz = mesh.global_cells(2) + extra;
  std::vector<double> out(nx * ny * nz, 0.0);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f);
  int hi[3];
  for (int d = 0; d < 3; ++d) {
    const bool last = mesh.offset(d) + mesh.owned_cells(d) == mesh.global_cells(d);
    hi[d] = Mesh::ng + mesh.owned_cells(d) + (extra && last ? 1 : 0);
  }
  for (int k = Mesh::ng; k < hi[2]; ++k)
    for (int j = Mesh::ng; j < hi[1]; ++j)
      for (int i = Mesh::ng; i < hi[0]; ++i) {
        const long gi = mesh.offset(0) + i - Mesh::ng, gj = mesh.offset(1) + j - Mesh::ng,
                   gk = mesh.offset(2) + k - Mesh::ng;
        out[gi + nx * (gj + ny * gk)] = h(i, j, k);
      }
  MPI_Allreduce(MPI_IN_PLACE, out.data(), static_cast<int>(out.size()), MPI_DOUBLE, MPI_SUM,
                mesh.comm());
  return out;
}

// How many values of two runs' gathered fields differ (the fields in the same order, each the
// same size; a bitwise comparison, so 0 is the claim).
inline long values_differ(const std::vector<std::vector<double>>& a,
                          const std::vector<std::vector<double>>& b) {
  long differ = 0;
  for (std::size_t f = 0; f < a.size() && f < b.size(); ++f)
    for (std::size_t i = 0; i < a[f].size() && i < b[f].size(); ++i)
      differ += a[f][i] != b[f][i] ? 1 : 0;
  return differ;
}

}  // namespace mp::test
