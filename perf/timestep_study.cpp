// Time-step rule study (issue #15): every verification scene run to its end time with the
// combined limit dt = cfl dx / (c_eff + |u|) and with separate limits
// dt = min(cfl dx / c_eff, cfl_transport dx / |u|), side by side. Reports per scene and rule:
// whether the run finished healthy, its cycles, the relative change of total energy, and the
// L1 difference of the final density between the two rules relative to the mean density.
//   timestep_study [--scenes sod_x.yaml,...] [--cfl 1.0] [--cfl-transport 0.5]
//                  [--set key=value ...]
// One rank. The 3-D scenes (noh, sedov) run at half their deck resolution to fit a shared VM.
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "config/scene.hpp"
#include "driver/simulation.hpp"
#include "paths.hpp"
#include "runtime.hpp"

using namespace mp;

namespace {

struct Outcome {
  bool ok = false;
  long cycles = 0;
  double time = 0, wall = 0, energy_change = 0;
  std::string what;
  std::vector<double> rho;  // owned cells, host copy
};

Outcome run(const std::string& deck, std::vector<std::string> ov, bool separate, double cfl_t) {
  Outcome o;
  try {
    const Scene scene = read_scene(Deck::load(deck, ov));
    RunSettings settings;
    settings.quiet = true;
    Simulation sim(scene, MPI_COMM_WORLD, settings);
    if (separate) sim.hydro().set_time_limits(true, Real(cfl_t < 0 ? scene.time.cfl : cfl_t));
    sim.initialize();
    const RunResult r = sim.run();
    o.ok = r.ok;
    o.cycles = r.cycles;
    o.time = r.time;
    o.wall = r.wall;
    o.what = r.health.what;
    o.energy_change = (r.end.total() - r.start.total()) / std::abs(r.start.total());
    const Mesh& m = sim.mesh();
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), sim.hydro().state().rho);
    const int ng = Mesh::ng;
    for (int k = ng; k < ng + m.owned_cells(2); ++k)
      for (int j = ng; j < ng + m.owned_cells(1); ++j)
        for (int i = ng; i < ng + m.owned_cells(0); ++i) o.rho.push_back(double(h(i, j, k)));
  } catch (const std::exception& e) {
    o.ok = false;
    o.what = e.what();
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const mp::perf::Runtime runtime(argc, argv);
  int rc = 0;
  {
    CLI::App app{"time-step rule study"};
    std::vector<std::string> scenes, sets;
    double cfl = -1, cfl_t = -1;
    app.add_option("--scenes", scenes, "decks under configs/ (default: all)")->delimiter(',');
    app.add_option("--cfl", cfl, "override time.cfl of every scene");
    app.add_option("--cfl-transport", cfl_t,
                   "safety factor of the transport limit (default: the scene's cfl)");
    app.add_option("--set", sets, "extra deck overrides");
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      rc = app.exit(e);
    }
    if (rc == 0) {
      const std::string dir = mp::test::source_dir() + "/configs/";
      if (scenes.empty())
        for (const auto& e : std::filesystem::directory_iterator(dir))
          if (e.path().extension() == ".yaml") scenes.push_back(e.path().filename().string());
      std::sort(scenes.begin(), scenes.end());
      std::printf(
          "| scene | cfl | cfl_transport | combined: ok, cycles, dE/E | separate: ok, cycles, "
          "dE/E | cycles separate/combined | L1(rho_sep - rho_comb)/mean rho |\n"
          "|---|---|---|---|---|---|---|\n");
      for (const std::string& s : scenes) {
        std::vector<std::string> ov = sets;
        if (s == "sedov.yaml") ov.push_back("mesh.cells=[24,24,24]");
        if (s == "noh.yaml") ov.push_back("mesh.cells=[32,32,32]");
        if (cfl > 0) ov.push_back("time.cfl=" + std::to_string(cfl));
        const Outcome a = run(dir + s, ov, false, cfl_t);
        const Outcome b = run(dir + s, ov, true, cfl_t);
        double l1 = 0, mean = 0;
        if (a.rho.size() == b.rho.size() && !a.rho.empty()) {
          for (std::size_t q = 0; q < a.rho.size(); ++q) {
            l1 += std::abs(b.rho[q] - a.rho[q]);
            mean += a.rho[q];
          }
          l1 /= mean;
        }
        const double scene_cfl = cfl > 0 ? cfl : read_scene(Deck::load(dir + s, sets)).time.cfl;
        std::printf("| %s | %g | %g | %s, %ld, %.2e | %s, %ld, %.2e | %.3f | %.2e |%s%s\n",
                    s.c_str(), scene_cfl, cfl_t < 0 ? scene_cfl : cfl_t, a.ok ? "ok" : "FAILED",
                    a.cycles, a.energy_change, b.ok ? "ok" : "FAILED", b.cycles, b.energy_change,
                    double(b.cycles) / double(a.cycles), l1,
                    a.ok ? "" : (" combined: " + a.what).c_str(),
                    b.ok ? "" : (" separate: " + b.what).c_str());
        std::fflush(stdout);
      }
    }
  }
  return rc;
}
