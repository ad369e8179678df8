// One run of a scene: the mesh, the physics modules the scene needs, the time loop, output.
#pragma once
#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "config/scene.hpp"
#include "hydro/hydro.hpp"
#include "io/hdf5_writer.hpp"
#include "mesh/halo.hpp"
#include "mesh/mesh.hpp"

namespace mp {

struct RunSettings {
  std::string output_dir;  // where dumps and the summary go; empty: nothing is written
  bool quiet = false;      // no per-cycle log lines
  // Stop after the current cycle when a SIGTERM/SIGINT arrived (signals.hpp); all ranks agree.
  bool watch_signals = false;
  // Deck keys a restart may change besides output.*, time.end, time.max_cycles, mesh.ranks and
  // description: exact keys, or prefixes ending in ".*" ("numerics.*"); only numerics.* and
  // time.* keys are accepted (restart_allow_error). Each change is logged and kept in
  // summary.json ("restart_changes").
  std::vector<std::string> restart_allow;
};

// Why a --restart-allow pattern is refused (a key outside numerics.* and time.*, which shape
// what the checkpoint's state means), or "" when it is accepted.
std::string restart_allow_error(const std::string& pattern);

// What ended a run.
enum class Ending { EndTime, MaxCycles, Interrupted, NonPhysical };
// "completed", "max_cycles", "interrupted", "non-physical" (summary.json "status")
const char* status_name(Ending e);
// "end time reached", ... (closing line, summary.json "ended_by")
const char* ending_text(Ending e);

struct RunResult {
  Ending ending = Ending::EndTime;
  bool ok = true;  // false: non-physical (a cell, or non-finite totals)
  long cycles = 0;
  double time = 0;
  double wall = 0;
  hydro::Totals start, end;
  // sweeps in which the KE fix redid dual faces with donor values (hydro::ke_redo): cold gas
  // draining towards vacuum, where the remap would make kinetic energy its cells cannot pay
  long ke_redone = 0;
  // output.mass_ledger: hydro::Hydro::mass_ledger() at the end (empty when off), and the
  // cycle it counts from (0, or a restart's cycle where the checkpoint had none)
  std::vector<double> mass_ledger;
  long mass_ledger_from = 0;
  hydro::Health health;
  std::vector<std::string> files;
  std::vector<std::string> checkpoints;  // written by this run
  std::string restarted_from;            // checkpoint path, or empty
  // deck keys this restart changed (--restart-allow): "key: 'old' in the checkpoint, 'new' here"
  std::vector<std::string> restart_changes;
  // every restart's changes of the run so far, "cycle N: <change>" (kept in the checkpoints)
  std::vector<std::string> restart_history;
  long first_cycle = 0;      // cycle this process started at (restart: > 0)
  std::string output_error;  // a dump or checkpoint that could not be written
};

// The boundary mass ledger of a run (RunResult::mass_ledger), one entry per material (the
// scene's material names; one entry, the scene's mass, in a single-material scene): the mass
// out through each face of the mesh and in all, and that against the material's mass at the
// start. ledger_line(): the run log's line, each material's share lost and its largest face.
struct LedgerEntry {
  std::string name;
  std::array<double, 6> faces{};  // x lo, x hi, y lo, y hi, z lo, z hi
  double out = 0, start = 0;
};
std::vector<LedgerEntry> ledger_entries(const Scene& scene, const RunResult& r);
std::string ledger_line(const std::vector<LedgerEntry>& entries);

class Simulation {
 public:
  Simulation(const Scene& scene, MPI_Comm comm, RunSettings settings);
  ~Simulation();

  // Paints the regions onto the mesh (cell centres decide; nodes take the velocity of the
  // region holding them) and derives pressure, sound speed and viscosity.
  void initialize();
  // Instead of initialize(): continues from a checkpoint (io/checkpoint.hpp). Throws
  // InputError when the checkpoint was written by another build or another deck (naming what
  // differs), RunError when it cannot be read.
  void restart(const std::string& path);
  // Runs to the end time, max_cycles, a non-physical state or a stop signal; writes dumps,
  // the XDMF series, checkpoints and summary.json when asked to.
  RunResult run();
  // Writes a checkpoint of the current state now (collective); returns its path.
  std::string write_checkpoint_now();
  // The fields a dump holds (the hydro's and its modules' kDump fields, each material's volume
  // fraction); derived ones are computed into new arrays.
  std::vector<OutputField> dump_fields() const;
  // The fields a checkpoint holds (cell rho, e; node u, v, w; per material alpha, rho, e; the
  // modules' registered state).
  std::vector<OutputField> checkpoint_fields() const;
  // The text of summary.json for a result (always valid JSON: a non-finite number is null and
  // its key is listed under "non_finite").
  std::string summary_json(const RunResult& r) const;
  double time() const { return t_; }
  long cycle() const { return cycle_; }

  const Mesh& mesh() const { return *mesh_; }
  hydro::Hydro& hydro() { return *hydro_; }
  const Scene& scene() const { return scene_; }
  std::vector<std::string> modules() const;
  // Where the set-up went, in order (phase, wall seconds; the slowest rank's): the allocation
  // (construction), then initialize()'s or restart()'s phases. Printed in the run log and kept
  // in summary.json (setup_seconds).
  const std::vector<std::pair<std::string, double>>& setup_times() const { return setup_; }
  // "35.1 s (allocation 0.4 s, painting 2.2 s, ...)".
  std::string setup_text() const;

 private:
  // Ends the set-up phase `name` begun at `since` (a steady_clock reading; all ranks call it)
  // and restarts the clock.
  void phase(const std::string& name, std::chrono::steady_clock::time_point& since);
  std::string write_dump(double t, long cycle);
  void write_summary(const RunResult& r) const;
  std::string checkpoint_meta() const;
  // A dump or checkpoint failed on every rank: record it in summary.json (if that can still be
  // written) and throw CollectiveError with the reason.
  [[noreturn]] void output_failed(RunResult& r, const std::string& what);
  void prepare_output_dir();

  Scene scene_;
  RunSettings settings_;
  std::unique_ptr<Mesh> mesh_;
  std::unique_ptr<Halo> halo_;
  std::unique_ptr<hydro::Hydro> hydro_;
  std::unique_ptr<Hdf5Writer> writer_;
  // The run's clock and counters: what a checkpoint saves beside the fields.
  double t_ = 0, next_dump_ = 0, wall_before_ = 0;
  long cycle_ = 0;
  Real dt_old_ = 0;
  hydro::Totals start_;
  long mass_ledger_from_ = 0;  // RunResult::mass_ledger_from
  std::vector<std::pair<std::string, double>> setup_;
  std::vector<std::string> restart_changes_, restart_history_;
  bool restarted_ = false;
  std::string restarted_from_;
  std::vector<std::string> files_;
  struct DumpRecord {
    std::string file;
    double time;
    long cycle;
  };
  std::vector<DumpRecord> dumps_;
};

}  // namespace mp
