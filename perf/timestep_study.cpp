// Time-step rule stability (issues #15, #54): every shipped scene run to its end time (or
// --max-cycles) with each time.rule, side by side. Reports per scene and rule whether the run
// finished healthy, its cycles and simulated time, the relative change of total energy, and
// the L1 difference of the final density from the first rule's relative to the mean density.
//   timestep_study [--scenes sod_x.yaml,...] [--rules combined,separate,cloverleaf]
//                  [--cfl 1.0] [--cfl-transport 0.5] [--max-cycles N] [--json FILE]
//                  [--set key=value ...]
// The accuracy half (error at equal wall time on the verification scenes) is
// perf/timestep_study.py over perf/tradeoff --rules.
// One rank. The 3-D scenes (noh, sedov) run at half their deck resolution to fit a shared VM.
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
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

Outcome run(const std::string& deck, std::vector<std::string> ov, const std::string& rule,
            double cfl_t) {
  Outcome o;
  try {
    ov.push_back("time.rule=" + rule);
    if (cfl_t > 0) ov.push_back("time.cfl_transport=" + std::to_string(cfl_t));
    ov.push_back("output.write=false");
    const Scene scene = read_scene(Deck::load(deck, ov));
    RunSettings settings;
    settings.quiet = true;
    Simulation sim(scene, MPI_COMM_WORLD, settings);
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
    std::vector<std::string> scenes, sets, rules = {"combined", "separate", "cloverleaf"};
    double cfl = -1, cfl_t = -1;
    long max_cycles = 0;
    std::string json_path;
    app.add_option("--scenes", scenes, "decks under configs/ (default: all)")->delimiter(',');
    app.add_option("--rules", rules, "time.rule values, the first the reference")->delimiter(',');
    app.add_option("--cfl", cfl, "override time.cfl of every scene");
    app.add_option("--cfl-transport", cfl_t,
                   "time.cfl_transport of every scene (default: the scene's own)");
    app.add_option("--max-cycles", max_cycles, "stop every run after this many cycles (0: none)");
    app.add_option("--json", json_path, "write the outcomes as JSON");
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
      std::string head = "| scene | cfl | cfl_transport |", rule = "|---|---|---|";
      for (std::size_t r = 0; r < rules.size(); ++r) {
        head += " " + rules[r] + ": ok, cycles, t, dE/E |";
        rule += "---|";
        if (r > 0) {
          head += " L1(rho - rho_" + rules[0] + ")/mean rho |";
          rule += "---|";
        }
      }
      std::printf("%s\n%s\n", head.c_str(), rule.c_str());
      nlohmann::ordered_json js = nlohmann::ordered_json::array();
      for (const std::string& s : scenes) {
        std::vector<std::string> ov = sets;
        if (s == "sedov.yaml") ov.push_back("mesh.cells=[24,24,24]");
        if (s == "noh.yaml") ov.push_back("mesh.cells=[32,32,32]");
        if (cfl > 0) ov.push_back("time.cfl=" + std::to_string(cfl));
        if (max_cycles > 0) ov.push_back("time.max_cycles=" + std::to_string(max_cycles));
        const Scene sc = read_scene(Deck::load(dir + s, ov));
        std::string line = "| " + s + " | ";
        char b[256];
        std::snprintf(b, sizeof b, "%g | %g |", sc.time.cfl,
                      cfl_t > 0 ? cfl_t : sc.time.cfl_transport);
        line += b;
        std::vector<Outcome> out;
        std::string why;
        for (const std::string& r : rules) {
          out.push_back(run(dir + s, ov, r, cfl_t));
          const Outcome& o = out.back();
          std::snprintf(b, sizeof b, " %s, %ld, %.4g, %.2e |", o.ok ? "ok" : "FAILED", o.cycles,
                        o.time, o.energy_change);
          line += b;
          if (!o.ok) why += " " + r + ": " + o.what + ";";
          double l1 = NAN;
          if (out.size() > 1) {
            const Outcome& a = out.front();
            if (a.rho.size() == o.rho.size() && !a.rho.empty()) {
              double mean = 0;
              l1 = 0;
              for (std::size_t q = 0; q < a.rho.size(); ++q) {
                l1 += std::abs(o.rho[q] - a.rho[q]);
                mean += a.rho[q];
              }
              l1 /= mean;
            }
            std::snprintf(b, sizeof b, " %.2e |", l1);
            line += b;
          }
          js.push_back({{"scene", s},
                        {"rule", r},
                        {"cfl", sc.time.cfl},
                        {"cfl_transport", cfl_t > 0 ? cfl_t : sc.time.cfl_transport},
                        {"ok", o.ok},
                        {"what", o.what},
                        {"cycles", o.cycles},
                        {"time", o.time},
                        {"end", sc.time.end},
                        {"wall_s", o.wall},
                        {"energy_change", o.energy_change},
                        {"l1_rho_vs_first", std::isfinite(l1) ? nlohmann::json(l1) : nullptr}});
        }
        std::printf("%s%s\n", line.c_str(), why.c_str());
        std::fflush(stdout);
        if (!json_path.empty()) std::ofstream(json_path) << js.dump(1) << "\n";
      }
    }
  }
  return rc;
}
