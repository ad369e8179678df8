// The layout study (DESIGN.md §3.1): the same multi-material scene run in the dense layout (the
// paper's: every cell holds every material) and the compact layout (pure cells in the cell
// arrays, mixed cells in a CSR list), sweeping the number of materials and the fraction of
// mixed cells. Reports time per cycle (and per phase), bytes of per-material state per cell,
// and the dense/compact ratio, beside the STREAM triad of the same process, as a markdown table
// and JSON (perf/plot_layouts.py draws the PNG).
//
// The scene: an nx x ny x nz box of stripes normal to x, each `width` cells wide, materials
// cycling through the stripes; each stripe boundary sits in the middle of a cell, so exactly
// 1/width of the cells are mixed (two materials each). Ideal gases of different gamma and
// density at one pressure, moving at a uniform speed along x: every cycle remaps material
// across the interfaces.
//   bench_layouts [--materials 2,4,8,16] [--widths 100,20,5,2] [--cells 200,16,16]
//                 [--cycles 10] [--json perf/results/layouts.json]
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <sstream>

#include "config/scene.hpp"
#include "core/mpi_env.hpp"
#include "cycle_timer.hpp"
#include "driver/simulation.hpp"
#include "report.hpp"

using namespace mp;

namespace {

std::string stripes_deck(int nmat, int width, const std::vector<int>& cells, const char* layout) {
  const double dx = 1.0 / cells[0];
  const double lx = 1.0, ly = double(cells[1]) * dx, lz = double(cells[2]) * dx;
  std::ostringstream d;
  d.precision(17);
  d << "scene: layouts\nmesh:\n  cells: [" << cells[0] << ", " << cells[1] << ", " << cells[2]
    << "]\n  lo: [0, 0, 0]\n  hi: [" << lx << ", " << ly << ", " << lz << "]\n"
    << "boundaries: {x: periodic, y: periodic, z: periodic}\n"
    << "time: {end: 1.0e9, cfl: 0.5, dt_initial: 1.0e-3}\n"
    << "numerics: {layout: " << layout << ", samples: 2}\nmaterials:\n";
  for (int m = 0; m < nmat; ++m)
    d << "  - {name: gas" << m << ", eos: ideal_gas, gamma: " << 1.3 + 0.02 * m << "}\n";
  d << "regions:\n  - {material: gas0, shape: all, density: 1.0, pressure: 1.0, velocity: [0.3, 0, "
       "0]}\n";
  const int stripes = cells[0] / width;
  for (int s = 1; s < stripes; ++s) {
    const double lo = (s * width + 0.5) * dx, hi = ((s + 1) * width + 0.5) * dx;
    d << "  - {material: gas" << s % nmat << ", shape: box, lo: [" << lo << ", -1, -1], hi: ["
      << (s + 1 == stripes ? 2.0 : hi) << ", 2, 2], density: " << 1.0 + 0.1 * (s % nmat)
      << ", pressure: 1.0, velocity: [0.3, 0, 0]}\n";
  }
  return d.str();
}

}  // namespace

int main(int argc, char** argv) {
  mp::prepare_mpi_environment();
  MPI_Init(&argc, &argv);
  Kokkos::initialize(argc, argv);
  int rc = 0;
  {
    CLI::App app{"minipagosa dense vs compact material layout benchmark"};
    std::vector<int> materials{2, 4, 8, 16}, widths{100, 20, 5, 2}, cells{200, 16, 16};
    int cycles = 10, warmup = 2;
    std::string json;
    app.add_option("--materials", materials, "material counts")->delimiter(',');
    app.add_option("--widths", widths, "stripe widths in cells (mixed fraction 1/width)")
        ->delimiter(',');
    app.add_option("--cells", cells, "mesh cells nx,ny,nz (nx a multiple of every width)")
        ->delimiter(',')
        ->expected(3);
    app.add_option("--cycles", cycles, "timed cycles per run");
    app.add_option("--warmup", warmup, "untimed cycles first");
    app.add_option("--json", json, "write results as JSON here");
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      rc = app.exit(e);
    }
    int rank = 0, nranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    if (rc == 0) {
      const perf::Stream st = perf::stream_triad(1L << 24, 10);
      std::ostringstream rows, js;
      perf::json_machine(js, "material_layouts", st, nranks);
      js << ",\n  \"cells\": [" << cells[0] << ", " << cells[1] << ", " << cells[2]
         << "],\n  \"runs\": [";
      bool first = true;
      for (int nmat : materials)
        for (int width : widths) {
          double sec[2] = {0, 0}, bytes[2] = {0, 0}, mixed_frac = 0;
          double phase[2][perf::CycleTimes::kPhases] = {};
          const char* layouts[2] = {"dense", "compact"};
          for (int l = 0; l < 2; ++l) {
            const Scene scene = read_scene(
                Deck::parse(stripes_deck(nmat, width, cells, layouts[l]), "layouts.yaml"));
            RunSettings settings;
            settings.quiet = true;
            Simulation sim(scene, MPI_COMM_WORLD, settings);
            sim.initialize();
            const perf::CycleTimes ct = perf::time_cycles(sim.hydro(), warmup, cycles);
            sec[l] = ct.wall / cycles;
            for (int p = 0; p < perf::CycleTimes::kPhases; ++p) phase[l][p] = ct.phase[p] / cycles;
            const mat::MaterialState* mm = sim.hydro().materials();
            const Mesh& mesh = sim.mesh();
            double local[2] = {mm->bytes(), double(mm->mixed_cells())}, global[2];
            MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
            // per owned cell (the blocks' ghost layers included in the bytes)
            bytes[l] = global[0] / double(mesh.global_cell_count());
            if (l == 1) {
              // mixed cells of the owned region: count on the compact list less the ghosts is
              // not separated; report the design fraction 1/width beside the measured one
              mixed_frac = global[1] / double(mesh.global_cell_count());
            }
          }
          const double ratio = sec[0] / sec[1];
          rows << "| " << nmat << " | " << 100.0 / width << " | " << 100 * mixed_frac << " | "
               << sec[0] * 1e3 << " | " << sec[1] * 1e3 << " | " << ratio << " | " << bytes[0]
               << " | " << bytes[1] << " | " << bytes[0] / bytes[1] << " |\n";
          js << (first ? "" : ",") << "\n    {\"materials\": " << nmat
             << ", \"stripe_width\": " << width << ", \"mixed_fraction_design\": " << 1.0 / width
             << ", \"mixed_fraction_measured_with_ghosts\": " << mixed_frac
             << ", \"dense_seconds_per_cycle\": " << sec[0]
             << ", \"compact_seconds_per_cycle\": " << sec[1]
             << ", \"dense_over_compact_time\": " << ratio
             << ", \"dense_bytes_per_cell\": " << bytes[0]
             << ", \"compact_bytes_per_cell\": " << bytes[1] << ", \"phases\": {";
          for (int p = 0; p < perf::CycleTimes::kPhases; ++p)
            js << (p ? ", " : "") << "\"" << perf::CycleTimes::names[p]
               << "\": {\"dense\": " << phase[0][p] << ", \"compact\": " << phase[1][p] << "}";
          js << "}}";
          first = false;
          if (rank == 0) {
            std::fprintf(stderr, "  materials %d, mixed %.0f%%: dense %.2f ms, compact %.2f ms\n",
                         nmat, 100.0 / width, sec[0] * 1e3, sec[1] * 1e3);
          }
        }
      js << "\n  ]\n}\n";
      if (rank == 0) {
        std::printf(
            "STREAM triad (same process): %.2f GB/s; %s, %d threads/rank, %d ranks; "
            "mesh %dx%dx%d, %d timed cycles\n\n",
            st.triad_gbs, ExecSpace::name(), ExecSpace().concurrency(), nranks, cells[0], cells[1],
            cells[2], cycles);
        std::printf(
            "| materials | mixed %% (design) | mixed %% (measured, ghosts incl.) | dense ms/cycle "
            "| "
            "compact ms/cycle | dense/compact time | dense B/cell | compact B/cell | "
            "dense/compact memory |\n|---|---|---|---|---|---|---|---|---|\n%s",
            rows.str().c_str());
        perf::write_json(json, js.str());
      }
    }
  }
  Kokkos::finalize();
  MPI_Finalize();
  return rc;
}
