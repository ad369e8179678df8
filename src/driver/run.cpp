#include "driver/run.hpp"

#include <mpi.h>

#include <cstdio>
#include <sstream>

#include "config/scene.hpp"
#include "core/error.hpp"
#include "driver/simulation.hpp"
#include "io/log.hpp"

namespace mp {

int run(const CommandLine& cl) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  try {
    const Deck deck = Deck::load(cl.scene, cl.overrides);
    const Scene scene = read_scene(deck);
    RunSettings settings;
    settings.output_dir = cl.output.empty() ? scene.output.dir : cl.output;
    settings.quiet = cl.quiet;
    Simulation sim(scene, MPI_COMM_WORLD, settings);
    log_line("minipagosa " + std::string(MINIPAGOSA_VERSION) + ": scene '" + scene.name + "' (" +
             scene.file + ")");
    log_line("  mesh: " + sim.mesh().describe());
    log_line(std::string("  kokkos: ") + ExecSpace::name() + ", " +
             std::to_string(ExecSpace().concurrency()) +
             " threads per rank, Real = " + (sizeof(Real) == 8 ? "double" : "float"));
    for (const auto& m : sim.modules()) log_line("  module " + m);
    sim.initialize();
    if (cl.check_only) {
      log_line("deck and decomposition are valid; nothing run (--check)");
      return 0;
    }
    log_line("  output: " + settings.output_dir);
    const RunResult r = sim.run();
    std::ostringstream os;
    os.precision(6);
    const double cc = double(sim.mesh().global_cell_count()) * double(r.cycles);
    if (!r.ok) {
      const auto& h = r.health;
      os << "minipagosa: error: the run went non-physical at cycle " << r.cycles
         << " (t = " << r.time << "): " << h.what << " in cell (" << h.cell[0] << ", " << h.cell[1]
         << ", " << h.cell[2] << "): density = " << h.rho << ", energy = " << h.e
         << ", pressure = " << h.p << "; final dump and summary written to " << settings.output_dir;
      if (rank == 0) std::fprintf(stderr, "%s\n", os.str().c_str());
      return 3;
    }
    os << "done: " << r.cycles << " cycles to t = " << r.time << " in " << r.wall << " s ("
       << (r.wall > 0 ? cc / r.wall : 0) << " cell-cycles/s); mass change "
       << (r.end.mass - r.start.mass) / r.start.mass << " (relative), total energy change "
       << (r.end.total() - r.start.total()) / r.start.total() << " (relative)";
    log_line(os.str());
    if (!settings.output_dir.empty()) log_line("wrote " + settings.output_dir + "/summary.json");
    return 0;
  } catch (const InputError& e) {
    if (rank == 0) std::fprintf(stderr, "minipagosa: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "minipagosa: error (rank %d): %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 4);
    return 4;
  }
}

}  // namespace mp
