#include "driver/run.hpp"

#include <dirent.h>
#include <limits.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "config/options.hpp"
#include "config/scene.hpp"
#include "core/error.hpp"
#include "core/mpi_env.hpp"
#include "driver/memory.hpp"
#include "driver/signals.hpp"
#include "driver/simulation.hpp"
#include "io/checkpoint.hpp"
#include "io/log.hpp"
#include "mesh/halo.hpp"

namespace mp {

namespace {

// Rank 0 decides (it alone looks at the file system), every rank gets the same InputError.
template <class F>
void root_input_check(MPI_Comm comm, F&& check) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string msg;
  if (rank == 0) {
    try {
      check();
    } catch (const InputError& e) {
      msg = e.what();
    }
  }
  int len = static_cast<int>(msg.size());
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  if (len == 0) return;
  msg.resize(static_cast<size_t>(len));
  MPI_Bcast(&msg[0], len, MPI_CHAR, 0, comm);
  throw InputError(msg);
}

// mesh.ranks must describe the rank count the run has (0 entries are chosen by MPI).
void check_ranks(const Deck& deck, const Scene& scene, int nranks) {
  const auto& r = scene.mesh.ranks;
  long fixed = 1;
  bool all = true;
  for (int d = 0; d < 3; ++d) {
    if (r[d] > 0)
      fixed *= r[d];
    else
      all = false;
  }
  const bool bad = all ? fixed != nranks : nranks % fixed != 0;
  if (!bad) return;
  std::ostringstream os;
  os << "mesh.ranks [" << r[0] << ", " << r[1] << ", " << r[2] << "] "
     << (all ? "asks for " + std::to_string(fixed) + " ranks"
             : "needs a rank count divisible by " + std::to_string(fixed))
     << ", but the run has " << nranks << " (mpiexec -np " << nranks
     << "); change mesh.ranks or the rank count";
  deck.root().child("mesh").child("ranks").fail(os.str());
}

// The longest name the run writes into the output directory.
std::size_t longest_output_name(const Scene& s) {
  return s.output.basename.size() + std::string("_checkpoint_000000000.h5.tmp").size();
}

void check_output_path(const std::string& dir, const Scene& s) {
  if (dir.empty()) return;
  const std::size_t longest = longest_output_name(s);
  if (dir.size() + 1 + longest >= PATH_MAX)
    throw InputError("output directory '" + dir.substr(0, 60) + "...' is too long: " +
                     std::to_string(dir.size()) + " characters, and the files in it need " +
                     std::to_string(longest + 1) + " more; the system allows " +
                     std::to_string(PATH_MAX - 1) + " in all (choose a shorter --output)");
  std::stringstream ss(dir);
  for (std::string part; std::getline(ss, part, '/');)
    if (part.size() > NAME_MAX)
      throw InputError("output directory '" + dir.substr(0, 60) + "...' has a component of " +
                       std::to_string(part.size()) + " characters; the system allows " +
                       std::to_string(NAME_MAX) + " (choose a shorter --output)");
  if (longest > NAME_MAX)
    throw InputError("scene name '" + s.name.substr(0, 40) +
                     "...' is too long for the output file names (" + std::to_string(longest) +
                     " characters, the system allows " + std::to_string(NAME_MAX) + ")");
}

// Files of an earlier run in `dir`: its summary, XDMF series, dumps and checkpoints.
std::vector<std::string> earlier_outputs(const std::string& dir) {
  std::vector<std::string> out;
  DIR* dp = opendir(dir.c_str());
  if (!dp) return out;
  while (const dirent* e = readdir(dp)) {
    const std::string n = e->d_name;
    auto ends = [&](const std::string& t) {
      return n.size() >= t.size() && n.compare(n.size() - t.size(), t.size(), t) == 0;
    };
    if (n == "summary.json" || ends(".xmf") || ends(".h5")) out.push_back(n);
  }
  closedir(dp);
  std::sort(out.begin(), out.end());
  return out;
}

// Memory this node has free for the ranks on it (MemAvailable), bytes; < 0 if unknown.
double available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  return -1;
}

// The run's output directory: --output, else the deck's output.dir.
std::string output_dir(const CommandLine& cl, const Scene& scene) {
  return cl.output.empty() ? scene.output.dir : cl.output;
}

// The deck and the options that do not depend on the ranks (check_input, run).
void check_options(const CommandLine& cl, const Scene& scene) {
  if (!cl.restart_allow.empty() && cl.restart.empty())
    throw InputError("--restart-allow needs --restart");
  for (const std::string& p : cl.restart_allow) {
    const std::string why = restart_allow_error(p);
    if (!why.empty()) throw InputError(why);
  }
  check_output_path(output_dir(cl, scene), scene);
}

}  // namespace

void check_input(const CommandLine& cl) {
  const Deck deck = Deck::load(cl.scene, cl.overrides);
  check_options(cl, read_scene(deck));
}

int run(const CommandLine& cl) {
  int rank = 0, nranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  try {
    const Deck deck = Deck::load(cl.scene, cl.overrides);
    const Scene scene = read_scene(deck);
    check_ranks(deck, scene, nranks);
    check_options(cl, scene);
    RunSettings settings;
    settings.output_dir = output_dir(cl, scene);
    settings.quiet = cl.quiet;
    settings.watch_signals = true;
    settings.restart_allow = cl.restart_allow;

    // Memory up front: estimate, compare with what the node has, before allocating.
    MemoryEstimate estimate;
    double per_rank = 0, node_total = 0, node_avail = -1;
    {
      const Mesh block(scene.mesh, MPI_COMM_WORLD);
      estimate = estimate_memory(scene, block);
      per_rank = estimate.total();
      MPI_Comm node;
      MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node);
      MPI_Allreduce(&per_rank, &node_total, 1, MPI_DOUBLE, MPI_SUM, node);
      MPI_Comm_free(&node);
      node_avail = available_memory();
      double worst = node_total - node_avail;  // > 0 where some node lacks room
      if (node_avail < 0) worst = -1;
      MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
      double max_rank = per_rank;
      MPI_Allreduce(MPI_IN_PLACE, &max_rank, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
      if (cl.check_only) {
        log_line("minipagosa " + std::string(MINIPAGOSA_VERSION) + ": scene '" + scene.name +
                 "' (" + scene.file + ")");
        log_line("  mesh: " + block.describe());
        log_line("  memory estimate: " + estimate.text() + " per rank; " + mib(max_rank) +
                 " on the largest block, " + mib(node_total) + " on this node" +
                 (node_avail >= 0 ? ", " + mib(node_avail) + " available" : std::string()));
      }
      if (worst > 0)
        throw InputError(scene.file + ": the run needs about " + mib(node_total) +
                         " of memory on this node (" + mib(per_rank) + " per rank), " +
                         mib(node_avail) + " available; use a coarser mesh.cells or more nodes");
    }
    if (cl.check_only) {
      log_line(
          "deck, decomposition and memory are valid; the run's arrays not allocated, nothing run "
          "(--check)");
      return 0;
    }

    // The output directory: a restart continues in it; otherwise it must not hold another
    // run's files, unless --overwrite (which removes them first).
    std::string restart_path;
    root_input_check(MPI_COMM_WORLD, [&] {
      const std::string& dir = settings.output_dir;
      if (!cl.restart.empty()) {
        if (dir.empty()) throw InputError("--restart needs an output directory");
        if (restart_from_newest(cl.restart)) {
          const auto all = list_checkpoints(dir, scene.output.basename);
          if (all.empty())
            throw InputError("--restart latest: no checkpoint " + scene.output.basename +
                             "_checkpoint_*.h5 in " + dir);
          restart_path = all.back().second;
        } else {
          restart_path = cl.restart;
          std::ifstream probe(restart_path);
          if (!probe) throw InputError("--restart " + restart_path + ": " + std::strerror(errno));
        }
        return;
      }
      const auto old = earlier_outputs(dir);
      if (old.empty()) return;
      if (!cl.overwrite)
        throw InputError(
            "output directory " + dir + " holds another run's files (" + old[0] +
            (old.size() > 1 ? " and " + std::to_string(old.size() - 1) + " more" : std::string()) +
            "); pass --overwrite to replace them, --restart latest to continue "
            "that run, or choose another --output");
      for (const auto& n : old) {
        const std::string p = dir + "/" + n;
        if (std::remove(p.c_str()) != 0)
          throw InputError("--overwrite: cannot remove " + p + ": " + std::strerror(errno));
      }
      log_line("  --overwrite: removed " + std::to_string(old.size()) +
               " files of an earlier run from " + dir);
    });
    {  // every rank needs the path
      int len = static_cast<int>(restart_path.size());
      MPI_Bcast(&len, 1, MPI_INT, 0, MPI_COMM_WORLD);
      restart_path.resize(static_cast<size_t>(len));
      if (len > 0) MPI_Bcast(&restart_path[0], len, MPI_CHAR, 0, MPI_COMM_WORLD);
    }

    signals::check_kill_hook();
    Simulation sim(scene, MPI_COMM_WORLD, settings);
    log_line("minipagosa " + std::string(MINIPAGOSA_VERSION) + ": scene '" + scene.name + "' (" +
             scene.file + ")");
    log_line("  mesh: " + sim.mesh().describe());
    log_line(std::string("  kokkos: ") + ExecSpace::name() + ", " +
             std::to_string(ExecSpace().concurrency()) +
             " threads per rank, Real = " + (sizeof(Real) == 8 ? "double" : "float") +
             (openmp_binding().empty() ? std::string() : "; " + openmp_binding()));
    if (nranks > 1) log_line("  mpi messages: " + message_path());
    log_line("  memory estimate: " + estimate.text() + " per rank");
    for (const auto& m : sim.modules()) log_line("  module " + m);
    if (restart_path.empty())
      sim.initialize();
    else
      sim.restart(restart_path);
    log_line("  set-up: " + sim.setup_text());
    log_line("  output: " + settings.output_dir +
             (scene.output.mass_ledger ? " (with the boundary mass ledger)" : ""));
    signals::install();
    const RunResult r = sim.run();
    std::ostringstream os;
    os.precision(6);
    const double cc = double(sim.mesh().global_cell_count()) * double(r.cycles - r.first_cycle);
    if (!r.ok) {
      const auto& h = r.health;
      os << "minipagosa: error: the run went non-physical at cycle " << r.cycles
         << " (t = " << r.time << "): " << h.what;
      if (h.cell[0] >= 0)
        os << " in cell (" << h.cell[0] << ", " << h.cell[1] << ", " << h.cell[2]
           << "): density = " << h.rho << ", energy = " << h.e << ", pressure = " << h.p;
      if (h.material >= 0 && h.material < int(scene.materials.size()))
        os << "; material " << h.material << " (" << scene.materials[h.material].name
           << ") there: fraction = " << h.m_fraction << ", density = " << h.m_rho
           << ", energy = " << h.m_e;
      os << "; final dump and summary written to " << settings.output_dir;
      if (rank == 0) std::fprintf(stderr, "%s\n", os.str().c_str());
      return 3;
    }
    const char* head = r.ending == Ending::EndTime ? "done" : "stopped";
    os << head << " (" << ending_text(r.ending) << "): " << r.cycles << " cycles to t = " << r.time
       << " of " << scene.time.end << " in " << r.wall << " s (" << (r.wall > 0 ? cc / r.wall : 0)
       << " cell-cycles/s); mass change " << (r.end.mass - r.start.mass) / r.start.mass
       << " (relative), total energy change " << (r.end.total() - r.start.total()) / r.start.total()
       << " (relative)";
    // the KE fix's redone faces and its floor (docs/numerics.md, "One cycle", item 6): said
    // only where they acted
    if (r.ke_redone > 0)
      os << "; the KE fix redid the momentum remap with donor values in " << r.ke_redone
         << " sweeps (gas too cold to pay the kinetic energy the remap made)";
    const double unpaid = r.end.ke_fix_unpaid - r.start.ke_fix_unpaid;
    if (unpaid > 0)
      os << ", of which " << unpaid / r.start.total()
         << " the KE fix could not charge (its cells too cold to pay the kinetic energy the remap "
            "made)";
    log_line(os.str());
    if (!r.mass_ledger.empty()) log_line(ledger_line(ledger_entries(scene, r)));
    if (!r.checkpoints.empty() && r.ending != Ending::EndTime)
      log_line("checkpoint " + r.checkpoints.back() + "; continue with --restart latest");
    if (!settings.output_dir.empty()) log_line("wrote " + settings.output_dir + "/summary.json");
    return r.ending == Ending::Interrupted ? signals::kExitInterrupted : 0;
  } catch (const InputError& e) {
    if (rank == 0) std::fprintf(stderr, "minipagosa: error: %s\n", e.what());
    return 2;
  } catch (const CollectiveError& e) {
    // every rank threw it: end cleanly, one message
    if (rank == 0) std::fprintf(stderr, "minipagosa: error: %s\n", e.what());
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "minipagosa: error (rank %d): %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 4);
    return 4;
  }
}

}  // namespace mp
