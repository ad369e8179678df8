// Single-material hydro throughput: cell-cycles per second of the full cycle (Lagrange, remap,
// halos, EOS, time step) on the 3-D Sedov scene at several sizes, beside the STREAM triad
// bandwidth of the same process. Writes JSON (machine-readable) and prints a markdown table,
// then a per-kernel breakdown from a separate block of cycles with a Kokkos::fence before and
// after every kernel (perf/kernel_timer.hpp; the plain timing has no extra fences).
// --deck runs any single-material deck instead: on its own mesh (unless --sizes is given: cubes
// of those cells over the deck's box), from its initial state; with --warmup 0 and --cycles at
// the deck's time.max_cycles it times the same cycles as `minipagosa deck` (perf/cloverleaf/
// bm_short.yaml: docs/perf.md, "Any deck").
// Bandwidths come from the counted traffic model of perf/bytes_model.hpp (per kernel: fields
// read and written over its range); kernel launches per cycle are counted through the Kokkos
// Tools callbacks of the breakdown block (perf/kernel_timer.hpp).
//   bench_hydro [--sizes 32,64] [--cycles 40] [--warmup 5] [--deck D] [--no-breakdown]
//               [--json perf/results/hydro.json]
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <vector>

#include "bytes_model.hpp"
#include "config/scene.hpp"
#include "cycle_timer.hpp"
#include "driver/simulation.hpp"
#include "kernel_timer.hpp"
#include "paths.hpp"
#include "report.hpp"
#include "runtime.hpp"

using namespace mp;

int main(int argc, char** argv) {
  const mp::perf::Runtime runtime(argc, argv);
  int rc = 0;
  {
    CLI::App app{"minipagosa single-material hydro benchmark"};
    std::vector<int> sizes;
    int cycles = 40, warmup = 5;
    const std::string sedov = mp::test::source_dir() + "/configs/sedov.yaml";
    std::string deck = sedov;
    std::string json;
    bool no_breakdown = false;
    app.add_flag("--no-breakdown", no_breakdown, "skip the fenced per-kernel breakdown block");
    app.add_option("--sizes", sizes,
                   "cells per axis of each run (default 32,64; a --deck: its mesh)")
        ->delimiter(',');
    app.add_option("--cycles", cycles, "timed cycles per size");
    app.add_option("--warmup", warmup, "untimed cycles first");
    app.add_option("--deck", deck, "a single-material scene deck (default: configs/sedov.yaml)");
    app.add_option("--json", json, "write results as JSON here");
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      rc = app.exit(e);
    }
    int rank = 0, nranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    const bool own_mesh = sizes.empty() && deck != sedov;  // the deck's mesh, as it is
    if (sizes.empty()) sizes = {own_mesh ? 0 : 32, 64};
    if (own_mesh) sizes.resize(1);
    if (rc == 0) {
      const perf::Stream st = perf::stream_triad(1L << 24, 10);
      std::ostringstream rows, js, krows;
      perf::json_machine(js, "hydro_single_material", st, nranks);
      js << ",\n  \"deck\": \"" << deck << "\",\n  \"runs\": [";
      for (std::size_t n = 0; n < sizes.size(); ++n) {
        const std::string c = std::to_string(sizes[n]);
        std::vector<std::string> set{"time.end=1e9",
                                     "time.max_cycles=" + std::to_string(warmup + cycles)};
        if (!own_mesh) set.push_back("mesh.cells=[" + c + "," + c + "," + c + "]");
        if (deck == sedov) set.push_back("regions.1.radius=0.15");
        Scene scene = read_scene(Deck::load(deck, set));
        RunSettings settings;
        settings.quiet = true;
        Simulation sim(scene, MPI_COMM_WORLD, settings);
        sim.initialize();
        const perf::CycleTimes ct = perf::time_cycles(sim.hydro(), warmup, cycles);
        const double wall = ct.wall;
        const double* phase = ct.phase;
        const char* const* phase_names = perf::CycleTimes::names;
        const int s =
            sim.mesh().global_cells(0);  // labels: the x cells (cubes but for a deck's own)
        const double cells = double(sim.mesh().global_cell_count());
        const double rate = cells * cycles / wall;
        // the counted model, summed over the ranks' blocks
        const std::map<std::string, double> model =
            perf::cycle_bytes(sim.mesh(), sim.hydro().mid_geometry());
        double cycle_bytes = 0;
        for (const auto& kv : model) cycle_bytes += kv.second;
        MPI_Allreduce(MPI_IN_PLACE, &cycle_bytes, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
        const double gbs = cycle_bytes * cycles / wall / 1e9;
        rows << "| " << s << "^3 | " << cycles << " | " << wall / cycles * 1e3 << " | "
             << rate / 1e6 << " | " << cycle_bytes / cells << " | " << gbs << " | "
             << 100 * gbs / st.triad_gbs << " |";
        for (int ph = 0; ph < 5; ++ph) rows << " " << 100 * phase[ph] / wall << " |";
        rows << "\n";
        js << (n ? "," : "") << "\n    {\"cells_per_axis\": " << s << ", \"cells\": " << cells
           << ", \"geometry\": \"" << (sim.hydro().mid_geometry() ? "midstep" : "fixed") << "\""
           << ", \"cycles\": " << cycles << ", \"seconds_per_cycle\": " << wall / cycles
           << ", \"cell_cycles_per_second\": " << rate
           << ", \"model_bytes_per_cell\": " << cycle_bytes / cells << ", \"model_GBs\": " << gbs
           << ", \"percent_of_stream\": " << 100 * gbs / st.triad_gbs
           << ", \"phase_seconds_per_cycle\": {";
        for (int ph = 0; ph < 5; ++ph)
          js << (ph ? ", " : "") << "\"" << phase_names[ph] << "\": " << phase[ph] / cycles;
        js << "}";
        if (!no_breakdown) {
          // A separate fenced block: every kernel charged its own time (rank 0's view).
          perf::RunClock clock;
          {
            perf::KernelTimer warm;  // the timer's first fences; not counted
          }
          Kokkos::fence();
          MPI_Barrier(MPI_COMM_WORLD);
          const auto t0 = std::chrono::steady_clock::now();
          std::vector<std::pair<std::string, perf::KernelStat>> ks;
          {
            perf::KernelTimer kt;
            perf::run_cycles(sim.hydro(), clock, 0, cycles);
            ks.assign(kt.kernels().begin(), kt.kernels().end());
          }
          const double fenced =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          std::sort(ks.begin(), ks.end(), [](const auto& a, const auto& b) {
            return a.second.seconds > b.second.seconds;
          });
          double in_kernels = 0, launches = 0, halo_launches = 0, modelled = 0, in_model = 0;
          js << ", \"breakdown\": {\"fenced_seconds_per_cycle\": " << fenced / cycles
             << ", \"kernels\": {";
          for (std::size_t q = 0; q < ks.size(); ++q) {
            const std::string& name = ks[q].first;
            const double sec = ks[q].second.seconds / cycles;
            const double calls = double(ks[q].second.calls) / cycles;
            in_kernels += ks[q].second.seconds;
            launches += calls;
            if (name.rfind("halo::", 0) == 0) halo_launches += calls;
            const auto m = model.find(name);
            const double bytes = m == model.end() ? 0 : m->second;  // this rank's block
            const double kgbs = bytes / sec / 1e9;
            if (bytes > 0) {
              modelled += bytes;
              in_model += sec;
            }
            js << (q ? ", " : "") << "\"" << name << "\": {\"seconds_per_cycle\": " << sec
               << ", \"calls_per_cycle\": " << calls << ", \"model_bytes_per_cycle\": " << bytes
               << ", \"model_GBs\": " << kgbs << "}";
            char line[256];
            std::snprintf(line, sizeof line,
                          "| %d^3 | %s | %.3f | %g | %.1f | %.3g | %.1f | %.0f |\n", s,
                          name.c_str(), sec * 1e3, calls, 100 * sec * cycles / fenced,
                          bytes / cells * nranks, kgbs, 100 * kgbs / st.triad_gbs);
            krows << (bytes > 0 ? line : "");
            if (bytes == 0 && ks[q].second.seconds > 0.02 * fenced)
              krows << "| " << s << "^3 | " << name << " | " << sec * 1e3 << " | " << calls << " | "
                    << 100 * sec * cycles / fenced << " | (not modelled) | | |\n";
          }
          js << "}, \"launches_per_cycle\": " << launches
             << ", \"halo_launches_per_cycle\": " << halo_launches
             << ", \"model_GBs_in_modelled_kernels\": " << modelled / in_model / 1e9 << "}";
          char line[320];
          std::snprintf(
              line, sizeof line,
              "| %d^3 | (outside kernels: MPI, host) | %.3f | | %.1f | | | |\n"
              "| %d^3 | **modelled kernels, fenced** | %.3f | | %.1f | %.0f | %.1f | %.0f |\n"
              "| %d^3 | **fenced cycle: %g launches (%g halo)** | %.3f | %g | 100 | | | |\n",
              s, (fenced - in_kernels) / cycles * 1e3, 100 * (fenced - in_kernels) / fenced, s,
              in_model * 1e3, 100 * in_model * cycles / fenced, modelled / cells * nranks,
              modelled / in_model / 1e9, 100 * modelled / in_model / 1e9 / st.triad_gbs, s,
              launches, halo_launches, fenced / cycles * 1e3, launches);
          krows << line;
          if (rank == 0)
            std::printf(
                "%d^3: %g kernel launches per cycle, %g of them halo (Kokkos Tools count); %s "
                "geometry\n",
                s, launches, halo_launches, sim.hydro().mid_geometry() ? "mid-step" : "fixed");
        }
        js << "}";
      }
      js << "\n  ]\n}\n";
      if (rank == 0) {
        std::printf("STREAM triad (same process): %.2f GB/s; %s, %d threads/rank, %d ranks\n\n",
                    st.triad_gbs, ExecSpace::name(), ExecSpace().concurrency(), nranks);
        std::printf(
            "| size | cycles | ms/cycle | Mcell-cycles/s | model B/cell | model GB/s | %% of "
            "STREAM "
            "| %% time step | %% lagrange | %% remap | %% eos+q | %% check |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|\n%s",
            rows.str().c_str());
        if (!no_breakdown)
          std::printf(
              "\nPer-kernel breakdown (separate block, Kokkos::fence before and after every "
              "kernel), with the counted traffic model of perf/bytes_model.hpp (B/cell per cycle, "
              "GB/s and %% of the STREAM triad above; unmodelled kernels shown above 2 %%):\n\n"
              "| size | kernel | ms/cycle | calls/cycle | %% of fenced cycle | model B/cell | GB/s "
              "| %% of STREAM |\n"
              "|---|---|---|---|---|---|---|---|\n%s",
              krows.str().c_str());
        perf::write_json(json, js.str());
      }
    }
  }
  return rc;
}
