// The speed/accuracy trade (issue #17): one command sweeps option axes over verification scenes
// and measures, for every combination, the error against the exact solution (the measures the
// tests use: tests/exact/norms.hpp), the wall time of the run, cycles and cell-cycles/s.
//   tradeoff [--quick] [--json FILE] [--md FILE] [--scenes sod,sod2,mader,sedov]
// Axes: resolution; advection second | first; remap split | unsplit (single-material scenes);
// interface youngs | slic, closure equal_strain | relaxation, layout compact | dense (sod2).
// Precision is the build's (run the float build's harness too and give both JSON files to
// perf/plot_tradeoff.py, which draws the error-vs-time Pareto fronts per scene). --quick is the
// CI-sized sweep (under 3 minutes on 2 cores); the full sweep adds the finer meshes.
// One rank. Times are wall times of the run only (set-up excluded) on a shared machine: compare
// within one run of this program, not across machines.
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "config/scene.hpp"
#include "driver/simulation.hpp"
#include "exact/norms.hpp"
#include "runtime.hpp"

using namespace mp;

namespace {

struct Point {
  std::string scene, options, measure;
  int cells = 0;
  double error = NAN, wall = 0, cell_cycles_per_s = 0;
  long cycles = 0;
  bool ok = false;
};

std::vector<double> gather_line(const Simulation& sim, const Field3& f) {
  // one rank: the owned row j = k = 0
  const Mesh& m = sim.mesh();
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f);
  std::vector<double> out;
  for (int i = Mesh::ng; i < Mesh::ng + m.owned_cells(0); ++i)
    out.push_back(double(h(i, Mesh::ng, Mesh::ng)));
  return out;
}

std::vector<double> gather_all(const Simulation& sim, const Field3& f) {
  const Mesh& m = sim.mesh();
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f);
  std::vector<double> out;
  const int ng = Mesh::ng;
  for (int k = ng; k < ng + m.owned_cells(2); ++k)
    for (int j = ng; j < ng + m.owned_cells(1); ++j)
      for (int i = ng; i < ng + m.owned_cells(0); ++i) out.push_back(double(h(i, j, k)));
  return out;
}

Point run(const std::string& scene_name, const std::string& deck, int cells,
          const std::vector<std::string>& options) {
  Point pt;
  pt.scene = scene_name;
  pt.cells = cells;
  for (const auto& o : options) pt.options += (pt.options.empty() ? "" : " ") + o;
  std::vector<std::string> ov = options;
  const std::string n = std::to_string(cells);
  if (scene_name == "sedov")
    ov.push_back("mesh.cells=[" + n + "," + n + "," + n + "]");
  else if (scene_name == "mader")  // cubic cells: the burn ramp is 2 of the largest edge
    ov.insert(ov.end(),
              {"mesh.cells=[" + n + ",2,2]", "mesh.hi=[1," + std::to_string(2.0 / cells) + "," +
                                                 std::to_string(2.0 / cells) + "]"});
  else
    ov.push_back("mesh.cells=[" + n + ",2,2]");
  ov.push_back("output.write=false");
  const Scene scene =
      read_scene(Deck::load(std::string(MINIPAGOSA_SOURCE_DIR) + "/configs/" + deck, ov));
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(scene, MPI_COMM_WORLD, settings);
  sim.initialize();
  const RunResult r = sim.run();
  pt.ok = r.ok;
  pt.cycles = r.cycles;
  pt.wall = r.wall;
  pt.cell_cycles_per_s =
      r.wall > 0 ? double(sim.mesh().global_cell_count()) * r.cycles / r.wall : 0;
  if (!r.ok) return pt;
  const Mesh& m = sim.mesh();
  const double dx = m.dx(0);
  std::vector<double> x;
  for (int i = 0; i < m.global_cells(0); ++i) x.push_back(m.spec().lo[0] + (i + 0.5) * dx);
  const auto& st = sim.hydro().state();
  if (scene_name == "sod") {
    pt.measure = "L1(rho)";
    const exact::Riemann rs({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 1.4);
    pt.error = exact::l1_density(x, gather_line(sim, st.rho), dx, rs, 0.5, r.time);
  } else if (scene_name == "sod2") {
    pt.measure = "L1(rho)";
    const exact::Riemann rs({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 1.667);
    pt.error = exact::l1_density(x, gather_line(sim, st.rho), dx, rs, 0.5, r.time);
  } else if (scene_name == "mader") {
    pt.measure = "L1(p)";
    const exact::Mader md(0.25, 1.0, 3.0);
    pt.error = exact::l1_pressure(x, gather_line(sim, st.p), dx, md, r.time);
  } else if (scene_name == "sedov") {
    // R = t^(2/5) for E = alpha (configs/sedov.yaml); the outermost crossing of density 2 (the
    // test's 3.5, halfway to the jump 6, is not reached by the smeared shock of a 24^3 mesh)
    pt.measure = "|R/R_exact - 1|";
    const double radius = exact::octant_shock_radius(gather_all(sim, st.rho), cells, dx, 2.0);
    pt.error = std::abs(radius / std::pow(r.time, 0.4) - 1);
  }
  return pt;
}

}  // namespace

namespace {

int sweep_main(int argc, char** argv) {
  CLI::App app{"minipagosa speed/accuracy trade-off sweep"};
  bool quick = false;
  std::string json_path, md_path;
  std::vector<std::string> scenes = {"sod", "sod2", "mader", "sedov"};
  app.add_flag("--quick", quick, "CI-sized sweep (under 3 minutes on 2 cores)");
  app.add_option("--json", json_path, "write the points as JSON");
  app.add_option("--md", md_path, "write the Markdown tables");
  app.add_option("--scenes", scenes, "scenes: sod, sod2, mader, sedov")->delimiter(',');
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  int size = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size != 1) {
    std::fprintf(stderr, "tradeoff: runs on one rank\n");
    return 2;
  }

  std::vector<Point> pts;
  auto sweep = [&](const std::string& name, const std::string& deck, std::vector<int> sizes,
                   const std::vector<std::vector<std::string>>& variants) {
    for (int n : sizes)
      for (const auto& v : variants) {
        pts.push_back(run(name, deck, n, v));
        const Point& p = pts.back();
        std::fprintf(stderr, "%-6s %4d cells  %-60s error %.4e  %.3f s\n", name.c_str(), n,
                     p.options.c_str(), p.error, p.wall);
      }
  };
  const std::vector<std::vector<std::string>> single = {
      {"numerics.advection=second", "numerics.remap=split"},
      {"numerics.advection=second", "numerics.remap=unsplit"},
      {"numerics.advection=first", "numerics.remap=split"}};
  for (const auto& s : scenes) {
    if (s == "sod")
      sweep("sod", "sod_x.yaml",
            quick ? std::vector<int>{100, 200} : std::vector<int>{100, 200, 400, 800}, single);
    else if (s == "mader")
      sweep("mader", "mader.yaml",
            quick ? std::vector<int>{100, 200} : std::vector<int>{100, 200, 400, 800}, single);
    else if (s == "sedov")
      sweep("sedov", "sedov.yaml", quick ? std::vector<int>{24, 32} : std::vector<int>{24, 32, 48},
            single);
    else if (s == "sod2")
      sweep(
          "sod2", "sod2.yaml", quick ? std::vector<int>{100, 200} : std::vector<int>{100, 200, 400},
          {{"numerics.interface=youngs", "numerics.closure=equal_strain",
            "numerics.layout=compact"},
           {"numerics.interface=youngs", "numerics.closure=equal_strain", "numerics.layout=dense"},
           {"numerics.interface=slic", "numerics.closure=equal_strain", "numerics.layout=compact"},
           {"numerics.interface=youngs", "numerics.closure=relaxation", "numerics.layout=compact"},
           {"numerics.interface=youngs", "numerics.advection=first", "numerics.layout=compact"}});
    else {
      std::fprintf(stderr, "tradeoff: unknown scene '%s' (sod, sod2, mader, sedov)\n", s.c_str());
      return 2;
    }
  }

  // Pareto front per scene: no other point of the scene is both faster and more accurate.
  std::vector<bool> front(pts.size(), false);
  for (std::size_t a = 0; a < pts.size(); ++a) {
    if (!pts[a].ok || !std::isfinite(pts[a].error)) continue;
    bool dominated = false;
    for (std::size_t b = 0; b < pts.size() && !dominated; ++b)
      dominated = b != a && pts[b].scene == pts[a].scene && pts[b].ok &&
                  pts[b].wall <= pts[a].wall && pts[b].error <= pts[a].error &&
                  (pts[b].wall < pts[a].wall || pts[b].error < pts[a].error);
    front[a] = !dominated;
  }
  const char* real = sizeof(Real) == 8 ? "double" : "float";
  std::ostringstream md;
  md << "# Speed/accuracy sweep (" << real << ", " << (quick ? "quick" : "full")
     << "; wall times of one run each on this machine)\n\n";
  std::string last;
  for (std::size_t a = 0; a < pts.size(); ++a) {
    const Point& p = pts[a];
    if (p.scene != last) {
      md << "\n## " << p.scene << " (error: " << p.measure << ")\n\n"
         << "| cells | options | error | wall s | cycles | Mcell-cycles/s | Pareto |\n"
         << "|---|---|---|---|---|---|---|\n";
      last = p.scene;
    }
    char row[512];
    std::snprintf(row, sizeof row, "| %d | %s | %.4e | %.3f | %ld | %.3f | %s |\n", p.cells,
                  p.options.c_str(), p.error, p.wall, p.cycles, p.cell_cycles_per_s / 1e6,
                  front[a] ? "yes" : "");
    md << row;
  }
  std::printf("%s", md.str().c_str());
  if (!md_path.empty()) std::ofstream(md_path) << md.str();
  if (!json_path.empty()) {
    nlohmann::ordered_json js;
    js["real"] = real;
    js["mode"] = quick ? "quick" : "full";
    js["points"] = nlohmann::ordered_json::array();
    for (std::size_t a = 0; a < pts.size(); ++a) {
      const Point& p = pts[a];
      js["points"].push_back({{"scene", p.scene},
                              {"cells", p.cells},
                              {"options", p.options},
                              {"measure", p.measure},
                              {"error", std::isfinite(p.error) ? nlohmann::json(p.error) : nullptr},
                              {"wall_s", p.wall},
                              {"cycles", p.cycles},
                              {"cell_cycles_per_s", p.cell_cycles_per_s},
                              {"ok", p.ok},
                              {"pareto", bool(front[a])}});
    }
    std::ofstream(json_path) << js.dump(1) << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const mp::perf::Runtime runtime(argc, argv);
  const int rc = sweep_main(argc, argv);
  return rc;
}
