// The layout study (DESIGN.md §3.1): the same multi-material scene run in the dense layout (the
// paper's: every cell holds every material) and the compact layout (pure cells in the cell
// arrays, mixed cells in a CSR list), sweeping the number of materials and the fraction of
// mixed cells. Reports time per cycle (and per phase), a per-kernel breakdown, bytes per cell
// from the allocations themselves (live Kokkos View allocations after set-up and warm-up, seen
// through the Kokkos Tools callbacks, src/core/memory.hpp: the material state, labels "dense::",
// "compact::", and the whole run), and the dense/compact ratio, beside the STREAM triad
// of the same process, as two markdown tables and JSON (perf/plot_layouts.py draws the PNG).
//
// The scene: an nx x ny x nz box of stripes normal to x, each `width` cells wide, materials
// cycling through the stripes; each stripe boundary sits in the middle of a cell, so exactly
// 1/width of the cells are mixed (two materials each). Ideal gases of different gamma and
// density at one pressure, moving at a uniform speed along x: every cycle remaps material
// across the interfaces.
//
// Timing protocol (the machine may be shared and noisy): both layouts of a configuration, and a
// single-material reference (the same mesh and flow with one material: what the issue's
// "compact at most 1.5x the single-material cycle" compares against), are set up side by side
// and run `warmup` untimed cycles each; then `repeats` blocks of `cycles` timed cycles rotate
// between the three (each first in turn), and each reports the median over its blocks, with the
// spread (max / min). The share of the CPUs that other processes took meanwhile is measured from
// /proc/stat and reported. A separate block afterwards times every Kokkos kernel with a fence on
// each side (the breakdown; its fences are never part of the plain timing).
//   bench_layouts [--materials 2,4,8,16] [--widths 100,20,5,2] [--cells 200,16,16]
//                 [--cycles 4] [--repeats 5] [--warmup 3] [--strength 0]
//                 [--json perf/results/layouts.json]
#include <mpi.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include "config/scene.hpp"
#include "cycle_timer.hpp"
#include "driver/simulation.hpp"
#include "kernel_timer.hpp"
#include "core/memory.hpp"
#include "protocol.hpp"
#include "report.hpp"
#include "runtime.hpp"

using namespace mp;
using perf::cpu_sample;
using perf::CpuSample;
using perf::median;
using perf::others_share;
using perf::stripes_deck;

namespace {

constexpr int kPhases = perf::CycleTimes::kPhases;

// Owned cells holding two or more materials: a cell is pure when some material fills it.
long owned_mixed_cells(const Mesh& mesh, const mat::MaterialState& mm) {
  const int ng = Mesh::ng;
  const auto hi = mesh.owned_end();
  const Policy3 owned({ng, ng, ng}, {hi[0], hi[1], hi[2]});
  IntField3 pure("pure", mesh.extent(Centering::Cell, 0), mesh.extent(Centering::Cell, 1),
                 mesh.extent(Centering::Cell, 2));
  for (int m = 0; m < mm.nmat(); ++m) {
    const Field3 f = mm.fraction(m);
    Kokkos::parallel_for(
        "bench::pure", owned, KOKKOS_LAMBDA(int i, int j, int k) {
          if (f(i, j, k) == Real(1)) pure(i, j, k) = 1;
        });
  }
  long n = 0;
  Kokkos::parallel_reduce(
      "bench::count_mixed", owned,
      KOKKOS_LAMBDA(int i, int j, int k, long& acc) { acc += pure(i, j, k) ? 0 : 1; }, n);
  long global = 0;
  MPI_Allreduce(&n, &global, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return global;
}

// One layout of one configuration: the run, its timed blocks and its kernel breakdown.
struct LayoutRun {
  std::unique_ptr<Simulation> sim;
  perf::RunClock clock;
  std::vector<double> block;                        // seconds per cycle of each timed block
  std::vector<std::array<double, kPhases>> phase;   // seconds per cycle of each phase, per block
  long faults = 0;                                  // page faults in the timed blocks
  std::map<std::string, perf::KernelStat> kernels;  // breakdown block (rank 0)
  std::map<std::string, perf::KernelStat> regions;  // breakdown block (rank 0)
  double breakdown_wall = 0;                        // seconds of the breakdown block
  long allocations = 0;                             // Kokkos allocations in the breakdown block
  double bytes = 0;                                 // per-material state per owned cell (model)
  double alloc_state = 0;  // per owned cell: live Kokkos allocations of the material state
  double alloc_all = 0;    // per owned cell: every live Kokkos allocation of the run
  double alloc_halo = 0;   // per owned cell: the material halo's message buffers

  void time_block(int cycles) {
    const perf::CycleTimes ct = perf::run_cycles(sim->hydro(), clock, 0, cycles);
    block.push_back(ct.wall / cycles);
    std::array<double, kPhases> p{};
    for (int q = 0; q < kPhases; ++q) p[q] = ct.phase[q] / cycles;
    phase.push_back(p);
    faults += ct.minor_faults;
  }
  double seconds() const { return median(block); }
  double spread() const {
    return *std::max_element(block.begin(), block.end()) /
           *std::min_element(block.begin(), block.end());
  }
  double phase_median(int q) const {
    std::vector<double> v;
    for (const auto& p : phase) v.push_back(p[q]);
    return median(v);
  }
};

// The columns of the breakdown table: kernel labels grouped by what they do. The compact layout
// runs a kernel as "name[pure]" and "name[mixed]", and rebuilds its slot pool in three passes
// "name::count", "name::scan", "name::fill" (the dense layout runs "name" once).
struct Column {
  const char* title;
  const char* prefix;  // kernels whose label starts with this (nullptr: computed)
};
const Column kColumns[] = {
    {"eos::pressure_sound_speed", "eos::pressure_sound_speed"},
    {"lagrange::predictor", "lagrange::predictor"},
    {"lagrange::corrector", "lagrange::corrector"},
    {"remap::material_flux", "remap::material_flux"},
    {"remap::material_update", "remap::material_update"},
    {"material halo (pack, MPI, ghost update)", nullptr},
    {"compact pool rebuilds (all ::count/::scan/::fill)", nullptr},
    {"other kernels", nullptr},
    {"outside kernels (MPI, host)", nullptr},
};
constexpr int kColumns_n = sizeof(kColumns) / sizeof(kColumns[0]);

bool starts_with(const std::string& s, const char* p) {
  return s.rfind(p, 0) == 0;
}
bool rebuild_pass(const std::string& s) {
  for (const char* p : {"::count", "::scan", "::fill"}) {
    const std::string q(p);
    if (s.size() > q.size() && s.compare(s.size() - q.size(), q.size(), q) == 0) return true;
  }
  return false;
}

// Seconds per cycle of each breakdown column.
std::array<double, kColumns_n> columns(const LayoutRun& r, int cycles) {
  std::array<double, kColumns_n> c{};
  double all = 0, named = 0;
  for (const auto& [name, st] : r.kernels) {
    all += st.seconds;
    for (int q = 0; q < kColumns_n; ++q)
      if (kColumns[q].prefix && starts_with(name, kColumns[q].prefix)) {
        c[q] += st.seconds;
        named += st.seconds;
      }
    if (rebuild_pass(name)) c[6] += st.seconds;
  }
  const auto halo = r.regions.find("matter::exchange");
  c[5] = halo == r.regions.end() ? 0.0 : halo->second.seconds;
  double in_halo = 0;  // kernels inside the material halo region
  for (const auto& [name, st] : r.kernels)
    if (starts_with(name, "matter::pack") || starts_with(name, "matter::halo"))
      in_halo += st.seconds;
  c[7] = all - named - in_halo;
  c[8] = r.breakdown_wall - all - (c[5] - in_halo);
  for (double& x : c) x /= cycles;
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const mp::perf::Runtime runtime(argc, argv);
  int rc = 0;
  {
    CLI::App app{"minipagosa dense vs compact material layout benchmark"};
    std::vector<int> materials{2, 4, 8, 16}, widths{100, 20, 5, 2}, cells{200, 16, 16};
    std::vector<double> velocity{0.3, 0, 0};
    int cycles = 4, repeats = 5, warmup = 3, strength = 0;
    bool no_breakdown = false;
    std::string json, note;
    app.add_option("--materials", materials, "material counts")->delimiter(',');
    app.add_option("--widths", widths, "stripe widths in cells (mixed fraction 1/width)")
        ->delimiter(',');
    app.add_option("--cells", cells, "mesh cells nx,ny,nz (nx a multiple of every width)")
        ->delimiter(',')
        ->expected(3);
    app.add_option("--cycles", cycles, "timed cycles per block (and in the breakdown block)");
    app.add_option("--repeats", repeats, "timed blocks per layout (median reported)");
    app.add_option("--warmup", warmup, "untimed cycles per layout first");
    app.add_option("--strength", strength,
                   "the first N materials have elastic-plastic strength (the strength module "
                   "in mixed cells; 0: none)");
    app.add_option("--velocity", velocity,
                   "the flow's velocity u,v,w (default 0.3,0,0: along x, across the stripes; "
                   "a transverse part makes the y and z sweeps move material too)")
        ->delimiter(',')
        ->expected(3);
    app.add_flag("--no-breakdown", no_breakdown, "skip the fenced per-kernel breakdown block");
    app.add_option("--json", json, "write results as JSON here");
    app.add_option("--note", note, "a line about the run conditions, printed and kept in the JSON");
    try {
      app.parse(argc, argv);
      if (cycles < 1 || repeats < 1 || warmup < 0 || strength < 0)
        throw CLI::ValidationError("counts", "< 1");
    } catch (const CLI::ParseError& e) {
      rc = app.exit(e);
    }
    const bool breakdown = !no_breakdown;
    int rank = 0, nranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    if (rc == 0) {
      const perf::Stream st = perf::stream_triad(1L << 24, 10);
      std::ostringstream rows, krows, js;
      perf::json_machine(js, "material_layouts", st, nranks);
      js << ",\n  \"cells\": [" << cells[0] << ", " << cells[1] << ", " << cells[2]
         << "],\n  \"protocol\": {\"warmup_cycles\": " << warmup
         << ", \"cycles_per_block\": " << cycles << ", \"blocks\": " << repeats
         << ", \"statistic\": \"median over blocks\", \"order\": \"dense, compact, single material "
            "rotate "
            "block by block\", \"breakdown\": \""
         << (breakdown ? "separate block, Kokkos::fence before and after every kernel" : "off")
         << "\"},\n  \"materials_with_strength\": " << strength << ",\n  \"velocity\": ["
         << velocity[0] << ", " << velocity[1] << ", " << velocity[2] << "],\n  \"note\": \""
         << note << "\",\n  \"runs\": [";
      bool first = true;
      const char* layouts[3] = {"dense", "compact", "single_material"};
      for (int nmat : materials)
        for (int width : widths) {
          // dense, compact, and the single-material reference: the same mesh, flow and step
          // count with one material (every stripe gas0; the single-material cycle, no material
          // state), so "compact / single" is what the materials cost
          LayoutRun run[3];
          for (int l = 0; l < 3; ++l) {
            // the allocations this layout's run makes and keeps through set-up and warm-up
            AllocationTracker mem;
            const Scene scene = read_scene(
                Deck::parse(l < 2 ? stripes_deck(nmat, width, cells, layouts[l],
                                                 std::min(strength, nmat), velocity)
                                  : stripes_deck(1, width, cells, "compact", 0, velocity),
                            "layouts.yaml"));
            RunSettings settings;
            settings.quiet = true;
            run[l].sim = std::make_unique<Simulation>(scene, MPI_COMM_WORLD, settings);
            run[l].sim->initialize();
            perf::run_cycles(run[l].sim->hydro(), run[l].clock, warmup, 0);
            // material state: the layouts' arrays ("dense::", "compact::"); the material
            // halo's message buffers ("matter::") apart
            double b[3] = {mem.live_bytes_with("dense::", "compact::"), mem.live_bytes(),
                           mem.live_bytes_with("matter::")};
            MPI_Allreduce(MPI_IN_PLACE, b, 3, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
            const double ncells = double(run[l].sim->mesh().global_cell_count());
            run[l].alloc_state = b[0] / ncells;
            run[l].alloc_all = b[1] / ncells;
            run[l].alloc_halo = b[2] / ncells;
          }
          const CpuSample c0 = cpu_sample();
          for (int b = 0; b < repeats; ++b)  // the order rotates block by block
            for (int o = 0; o < 3; ++o) run[(b + o) % 3].time_block(cycles);
          const CpuSample c1 = cpu_sample();
          double others = others_share(c0, c1);
          MPI_Allreduce(MPI_IN_PLACE, &others, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
          if (breakdown)  // (the single-material reference too: what the materials add, kernel
                          // by kernel, in the JSON)
            for (int l = 0; l < 3; ++l) {
              LayoutRun& r = run[l];
              Kokkos::fence();
              MPI_Barrier(MPI_COMM_WORLD);
              const auto t0 = std::chrono::steady_clock::now();
              perf::KernelTimer kt;
              perf::run_cycles(r.sim->hydro(), r.clock, 0, cycles);
              r.breakdown_wall =
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
              r.kernels = kt.kernels();
              r.regions = kt.regions();
              r.allocations = kt.allocations();
            }
          long mixed = 0;
          for (int l = 0; l < 2; ++l) {
            LayoutRun& r = run[l];
            const mat::MaterialState* mm = r.sim->hydro().materials();
            const Mesh& mesh = r.sim->mesh();
            double b = mm->bytes();
            MPI_Allreduce(MPI_IN_PLACE, &b, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
            // per owned cell (the blocks' ghost layers included in the bytes)
            r.bytes = b / double(mesh.global_cell_count());
            mixed = owned_mixed_cells(mesh, *mm);
          }
          const double ncell = double(run[1].sim->mesh().global_cell_count());
          const double mixed_frac = double(mixed) / ncell;
          const double ratio = run[0].seconds() / run[1].seconds();
          const double over_single = run[1].seconds() / run[2].seconds();
          char line[512];
          std::snprintf(line, sizeof line,
                        "| %d | %g | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f, %.2f | %.0f "
                        "| %.1f | %.1f | %.0f, %.0f | %.0f |\n",
                        nmat, 100.0 / width, 100 * mixed_frac, run[0].seconds() * 1e3,
                        run[1].seconds() * 1e3, ratio, run[2].seconds() * 1e3, over_single,
                        run[0].spread(), run[1].spread(), run[0].alloc_state, run[1].alloc_state,
                        run[0].alloc_state / run[1].alloc_state, run[0].alloc_all, run[1].alloc_all,
                        100 * others);
          rows << line;
          js << (first ? "" : ",") << "\n    {\"materials\": " << nmat
             << ", \"stripe_width\": " << width << ", \"mixed_fraction_design\": " << 1.0 / width
             << ", \"mixed_fraction_measured\": " << mixed_frac
             << ", \"dense_seconds_per_cycle\": " << run[0].seconds()
             << ", \"compact_seconds_per_cycle\": " << run[1].seconds()
             << ", \"dense_over_compact_time\": " << ratio
             << ", \"single_material_seconds_per_cycle\": " << run[2].seconds()
             << ", \"compact_over_single_material_time\": " << over_single
             << ", \"dense_bytes_per_cell\": " << run[0].bytes
             << ", \"compact_bytes_per_cell\": " << run[1].bytes
             << ", \"dense_allocated_state_bytes_per_cell\": " << run[0].alloc_state
             << ", \"compact_allocated_state_bytes_per_cell\": " << run[1].alloc_state
             << ", \"dense_allocated_material_halo_bytes_per_cell\": " << run[0].alloc_halo
             << ", \"compact_allocated_material_halo_bytes_per_cell\": " << run[1].alloc_halo
             << ", \"dense_allocated_bytes_per_cell\": " << run[0].alloc_all
             << ", \"compact_allocated_bytes_per_cell\": " << run[1].alloc_all
             << ", \"others_cpu_share\": " << others;
          for (int l = 0; l < 3; ++l) {
            const LayoutRun& r = run[l];
            js << ",\n     \"" << layouts[l] << "\": {\"blocks_seconds_per_cycle\": [";
            for (std::size_t b = 0; b < r.block.size(); ++b) js << (b ? ", " : "") << r.block[b];
            js << "], \"page_faults_per_timed_cycle\": "
               << double(r.faults) / (double(repeats) * cycles) << ", \"phases_median\": {";
            for (int q = 0; q < kPhases; ++q)
              js << (q ? ", " : "") << "\"" << perf::CycleTimes::names[q]
                 << "\": " << r.phase_median(q);
            js << "}";
            if (breakdown) {
              js << ",\n      \"breakdown\": {\"cycles\": " << cycles
                 << ", \"seconds_per_cycle_fenced\": " << r.breakdown_wall / cycles
                 << ", \"kokkos_allocations\": " << r.allocations << ", \"kernels\": {";
              bool fk = true;
              for (const auto& [name, ks] : r.kernels) {
                js << (fk ? "" : ", ") << "\n        \"" << name
                   << "\": {\"seconds_per_cycle\": " << ks.seconds / cycles
                   << ", \"calls_per_cycle\": " << double(ks.calls) / cycles << "}";
                fk = false;
              }
              js << "},\n       \"regions\": {";
              fk = true;
              for (const auto& [name, ks] : r.regions) {
                js << (fk ? "" : ", ") << "\"" << name
                   << "\": {\"seconds_per_cycle\": " << ks.seconds / cycles
                   << ", \"calls_per_cycle\": " << double(ks.calls) / cycles << "}";
                fk = false;
              }
              js << "}}";
            }
            js << "}";
          }
          js << "}";
          first = false;
          if (breakdown) {
            const auto cd = columns(run[0], cycles), cc = columns(run[1], cycles);
            krows << "| " << nmat << " | " << 100.0 / width << " |";
            for (int q = 0; q < kColumns_n; ++q) {
              if (q == 6)  // the dense layout has no pool to rebuild
                std::snprintf(line, sizeof line, " - / %.2f |", cc[q] * 1e3);
              else
                std::snprintf(line, sizeof line, " %.2f / %.2f |", cd[q] * 1e3, cc[q] * 1e3);
              krows << line;
            }
            std::snprintf(line, sizeof line, " %.1f / %.1f | %ld / %ld |\n",
                          run[0].breakdown_wall / cycles * 1e3,
                          run[1].breakdown_wall / cycles * 1e3, run[0].allocations,
                          run[1].allocations);
            krows << line;
          }
          if (rank == 0) {
            std::fprintf(stderr,
                         "  materials %d, mixed %g%%: dense %.2f ms, compact %.2f ms (others "
                         "used %.0f%% of the CPUs)\n",
                         nmat, 100.0 / width, run[0].seconds() * 1e3, run[1].seconds() * 1e3,
                         100 * others);
          }
        }
      js << "\n  ]\n}\n";
      if (rank == 0) {
        std::printf(
            "STREAM triad (same process): %.2f GB/s; %s, %d threads/rank, %d ranks; "
            "mesh %dx%dx%d; %d warm-up cycles, then %d blocks of %d cycles per layout, dense, "
            "compact and the single-material reference (the same flow, one material) in "
            "rotating order; median over blocks\n",
            st.triad_gbs, ExecSpace::name(), ExecSpace().concurrency(), nranks, cells[0], cells[1],
            cells[2], warmup, repeats, cycles);
        if (!note.empty()) std::printf("%s\n", note.c_str());
        std::printf("flow velocity (%g, %g, %g)\n", velocity[0], velocity[1], velocity[2]);
        if (strength > 0)
          std::printf("materials with strength (elastic-plastic): the first %d of each scene\n",
                      strength);
        std::printf(
            "B/cell: live Kokkos allocations per owned cell after set-up and warm-up (Kokkos "
            "Tools allocate/deallocate callbacks): the material state (dense::, compact:: labels: "
            "cell and slot arrays, face fluxes) and the whole run (every field, the field and "
            "material halo buffers, the material state).\n");
        std::printf(
            "\n| materials | mixed %% (design) | mixed %% (owned cells) | dense ms/cycle "
            "| compact ms/cycle | dense/compact time | single-material ms/cycle | compact/single "
            "time | max/min over blocks (dense, compact) "
            "| dense B/cell | compact B/cell | dense/compact memory | whole run B/cell (dense, "
            "compact) | CPU taken by others %% |\n|---|---|---|---|---|---|---|---|---|---|---|---|"
            "---|---|"
            "\n%s",
            rows.str().c_str());
        if (breakdown) {
          std::printf(
              "\nPer-kernel breakdown, ms/cycle, dense / compact: one separate block of %d "
              "cycles per layout with Kokkos::fence() before and after every kernel (Kokkos "
              "tools callbacks; rank 0). The halo column is the whole MaterialState::exchange "
              "(pack, MPI, ghost update with its pool rebuilds); the columns but the rebuild "
              "one add up to the fenced cycle; the rebuild column (part of the update and halo "
              "columns) counts every compact ::count/::scan/::fill pass.\n\n"
              "| materials | mixed %% |",
              cycles);
          for (const Column& c : kColumns) std::printf(" %s |", c.title);
          std::printf(" cycle, fenced | Kokkos allocations |\n|---|---|");
          for (int q = 0; q < kColumns_n + 2; ++q) std::printf("---|");
          std::printf("\n%s", krows.str().c_str());
        }
        perf::write_json(json, js.str());
      }
    }
  }
  return rc;
}
