// minipagosa SCENE.yaml [--set key=value]... [--output DIR]; minipagosa --list-keys
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <Kokkos_Core.hpp>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "config/catalogue.hpp"
#include "config/scene.hpp"
#include "core/error.hpp"
#include "core/mpi_env.hpp"
#include "driver/run.hpp"

namespace {

// This process's rank as its launcher numbers it, before MPI starts (Open MPI's mpiexec, PMIx,
// MPICH's Hydra and Slurm's srun each set one of these); 0 for a process started alone. The
// process that prints a message every process would.
int launcher_rank() {
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"})
    if (const char* s = std::getenv(v)) return std::atoi(s);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // minipagosa --list-keys: every deck key the reader accepts (docs/options.md), nothing else.
  if (argc == 2 && std::string(argv[1]) == "--list-keys") {
    try {
      std::fputs(mp::options_markdown().c_str(), stdout);
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "minipagosa: error: --list-keys: %s\n", e.what());
      return 4;
    }
  }
  // Bad input fails before MPI and Kokkos start (a singleton Open MPI start-up alone takes about
  // 0.4 s): the command line and the deck are checked on every process, and the launcher's first
  // process prints what is wrong. mp::run checks them again, with the ones that need the ranks.
  const bool first = launcher_rank() == 0;
  // Kokkos sees only its own --kokkos-* options (it would also answer a plain --help); the
  // command line parser sees the rest.
  std::vector<char*> kargs{argv[0]}, args{argv[0]};
  for (int i = 1; i < argc; ++i)
    (std::string(argv[i]).rfind("--kokkos", 0) == 0 ? kargs : args).push_back(argv[i]);
  // Kokkos aborts (or silently ignores) a bad thread count; say what is wrong instead.
  for (std::size_t i = 1; i < kargs.size(); ++i) {
    const std::string a = kargs[i];
    for (const char* name : {"--kokkos-threads", "--kokkos-num-threads"}) {
      const std::string key = name;
      if (a.compare(0, key.size(), key) != 0) continue;
      if (a.size() > key.size() && a[key.size()] != '=') continue;  // another option
      const std::string v = a.size() > key.size() ? a.substr(key.size() + 1) : "";
      bool ok =
          !v.empty() && v.size() <= 6 && v.find_first_not_of("0123456789") == std::string::npos;
      if (ok) ok = std::stol(v) >= 1 && std::stol(v) <= 65536;
      if (!ok) {
        if (first)
          std::fprintf(stderr,
                       "minipagosa: error: %s: expected %s=N with N a whole number from 1 to "
                       "65536, got '%s'\n",
                       a.c_str(), name, v.c_str());
        return 2;
      }
    }
  }
  CLI::App app{
      "minipagosa: a Kokkos/MPI mini-app of PAGOSA, the LANL 3-D multi-material "
      "Eulerian hydrocode. Kokkos options (--kokkos-threads=N, --kokkos-help, ...) "
      "are passed through to Kokkos. 'minipagosa --list-keys' prints every deck key with its "
      "type, range and default (docs/options.md).",
      "minipagosa"};
  mp::CommandLine cl;
  app.add_option("scene", cl.scene, "YAML scene deck")->required()->check(CLI::ExistingFile);
  app.add_option("--set", cl.overrides,
                 "override a deck value, e.g. --set mesh.cells=[64,64,64] (repeatable)")
      ->allow_extra_args(false)
      ->take_all();
  app.add_option("-o,--output", cl.output, "output directory (default: the deck's output.dir)");
  app.add_flag("-q,--quiet", cl.quiet, "no per-cycle log lines");
  app.add_flag("--check", cl.check_only,
               "dry run: validate the deck, print the decomposition and the memory estimate, "
               "allocate and write nothing");
  app.add_option("--restart", cl.restart,
                 "continue from a checkpoint: a path, or 'latest' (the newest in the output "
                 "directory)");
  app.add_option("--restart-allow", cl.restart_allow,
                 "with --restart: a numerics.* or time.* deck key (or a prefix ending in "
                 "'.*') that may differ from the checkpoint's deck; each change is logged and "
                 "kept in summary.json (repeatable)");
  app.add_flag("--overwrite", cl.overwrite,
               "replace an earlier run's files (summary.json, *.xmf, *.h5) in the output "
               "directory instead of refusing to mix runs");
  app.set_version_flag("-V,--version", std::string("minipagosa ") + MINIPAGOSA_VERSION +
                                           " (Kokkos " + std::to_string(KOKKOS_VERSION) + ")");
  try {
    app.parse(static_cast<int>(args.size()), args.data());
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; any other command-line error is bad input (exit code 2).
    const int code = first ? app.exit(e) : e.get_exit_code();
    return code == 0 ? 0 : 2;
  }
  try {
    mp::check_input(cl);
  } catch (const mp::InputError& e) {
    if (first) std::fprintf(stderr, "minipagosa: error: %s\n", e.what());
    return 2;
  } catch (const std::exception&) {
    // anything else: mp::run meets it again and reports it as a run-time failure
  }
  mp::prepare_mpi_environment();
  mp::openmp_binding() = mp::prepare_openmp_environment();
  MPI_Init(&argc, &argv);
  int kargc = static_cast<int>(kargs.size());
  Kokkos::initialize(kargc, kargs.data());
  const int rc = mp::run(cl);
  Kokkos::finalize();
  MPI_Finalize();
  return rc;
}
