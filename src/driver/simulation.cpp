// One run of a scene: the time loop, its dumps and checkpoints, and the output directory.
#include "driver/simulation.hpp"

#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"
#include "core/math.hpp"
#include "core/profiling.hpp"
#include "driver/modules.hpp"
#include "driver/signals.hpp"
#include "io/checkpoint.hpp"
#include "io/h5_util.hpp"
#include "io/hdf5_writer.hpp"
#include "io/log.hpp"

namespace mp {

namespace {

void make_dirs(const std::string& dir) {
  std::string path;
  std::stringstream ss(dir);
  if (!dir.empty() && dir[0] == '/') path = "/";
  for (std::string part; std::getline(ss, part, '/');) {
    if (part.empty()) continue;
    path += part + "/";
    if (mkdir(path.c_str(), 0755) != 0 && errno != EEXIST)
      throw RunError("cannot create output directory '" + path + "': " + std::strerror(errno));
  }
}

}  // namespace

Simulation::Simulation(const Scene& scene, MPI_Comm comm, RunSettings settings)
    : scene_(scene), settings_(std::move(settings)) {
  auto t0 = std::chrono::steady_clock::now();
  mesh_ = std::make_unique<Mesh>(scene_.mesh, comm);
  halo_ = std::make_unique<Halo>(*mesh_);
  hydro_ =
      std::make_unique<hydro::Hydro>(*mesh_, *halo_, hydro_options(scene_), material_eoses(scene_));
  add_modules(scene_, *mesh_, *hydro_);  // (the modules the scene needs)
  hydro_->set_mass_ledger(scene_.output.mass_ledger);
  phase("allocation", t0);
}

void Simulation::phase(const std::string& name, std::chrono::steady_clock::time_point& since) {
  Kokkos::fence();
  const auto now = std::chrono::steady_clock::now();
  double s = std::chrono::duration<double>(now - since).count();
  MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_MAX, mesh_->comm()));
  setup_.emplace_back(name, s);
  since = std::chrono::steady_clock::now();
}

std::string Simulation::setup_text() const {
  double total = 0;
  std::string parts;
  char buf[96];
  for (const auto& [name, s] : setup_) {
    total += s;
    std::snprintf(buf, sizeof buf, "%s%s %.2g s", parts.empty() ? "" : ", ", name.c_str(), s);
    parts += buf;
  }
  std::snprintf(buf, sizeof buf, "%.3g s (", total);
  return buf + parts + ")";
}

Simulation::~Simulation() = default;

std::vector<OutputField> Simulation::dump_fields() const {
  auto fields = hydro_->output_fields();
  if (const mat::MaterialState* mm = hydro_->materials())
    for (int m = 0; m < mm->nmat(); ++m)
      fields.push_back({"fraction_" + scene_.materials[m].name, Centering::Cell, mm->fraction(m)});
  return fields;
}

std::string Simulation::write_dump(double t, long cycle) {
  ProfileRegion region("output::dump");
  if (!writer_) return "";
  const std::string path = writer_->write(dump_fields(), t, static_cast<int>(cycle));
  const std::string file = path.substr(path.rfind('/') + 1);
  bool known = false;
  for (auto& d : dumps_)
    if (d.file == file) {
      d = {file, t, cycle};
      known = true;
    }
  if (!known) dumps_.push_back({file, t, cycle});
  return path;
}

void Simulation::prepare_output_dir() {
  const std::string& dir = settings_.output_dir;
  h5::on_root(mesh_->comm(), [&] {
    make_dirs(dir);
    // Temporary files are renamed once complete; any left here were cut short by a crash or a
    // kill of an earlier run and hold nothing a later run may read.
    DIR* dp = opendir(dir.c_str());
    if (!dp) throw RunError("cannot read output directory '" + dir + "': " + std::strerror(errno));
    std::vector<std::string> stale;
    while (const dirent* e = readdir(dp)) {
      const std::string name = e->d_name;
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) stale.push_back(name);
    }
    closedir(dp);
    std::sort(stale.begin(), stale.end());
    for (const auto& name : stale) {
      const std::string p = dir + "/" + name;
      if (std::remove(p.c_str()) != 0)
        throw RunError("cannot remove stale temporary file " + p + ": " + std::strerror(errno));
      log_line("  removed stale temporary file " + p + " (left by an earlier run cut short)");
    }
  });
}

RunResult Simulation::run() {
  const bool root = mesh_->rank() == 0;
  const bool write = !settings_.output_dir.empty();
  if (write) {
    prepare_output_dir();
    if (scene_.output.write) {
      writer_ = std::make_unique<Hdf5Writer>(*mesh_, settings_.output_dir, scene_.output.basename);
      if (restarted_) {
        std::vector<OutputField> fields = hydro_->output_fields();
        if (const mat::MaterialState* mm = hydro_->materials())
          for (int m = 0; m < mm->nmat(); ++m)
            fields.push_back({"fraction_" + scene_.materials[m].name, Centering::Cell, Field3()});
        for (const auto& d : dumps_)
          if (d.cycle <= cycle_) writer_->remember(d.file, d.time, int(d.cycle), fields);
      }
    }
  }
  const double t_end = scene_.time.end;
  RunResult r;
  r.first_cycle = cycle_;
  r.restarted_from = restarted_from_;
  r.restart_changes = restart_changes_;
  r.restart_history = restart_history_;
  if (!restarted_) {
    start_ = hydro_->totals();
    t_ = 0;
    cycle_ = 0;
    dt_old_ = 0;
    next_dump_ = scene_.output.interval > 0 ? scene_.output.interval : t_end;
    if (write && writer_) files_.push_back(write_dump(t_, cycle_));
  } else {
    log_line("  restarted from " + restarted_from_ + " at cycle " + std::to_string(cycle_));
  }
  r.start = start_;
  const auto t0 = std::chrono::steady_clock::now();
  auto wall = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  const double t_begin = t_;
  const long cycle_begin = cycle_;
  bool end_warned = false;
  double last_checkpoint = 0;
  long checkpoint_cycle = -1;
  const bool checkpoints =
      write && (scene_.output.checkpoint_cycles > 0 || scene_.output.checkpoint_seconds > 0);

  hydro::Health h;
  bool interrupted = false;
  try {
    while (t_ < t_end * (1 - 1e-12) && cycle_ < scene_.time.max_cycles) {
      hydro::TimeStep ts = hydro_->time_step(dt_old_, t_, t_end);
      if (cycle_ == 0 && ts.dt > Real(scene_.time.dt_initial)) {
        ts.dt = Real(scene_.time.dt_initial);
        ts.limit = hydro::DtLimit::Initial;
      }
      h = hydro_->step(ts.dt, cycle_);
      // the last step lands on the end time exactly (Real(t_end - t) is rounded in float builds)
      t_ = ts.limit == hydro::DtLimit::End ? t_end : t_ + double(ts.dt);
      ++cycle_;
      dt_old_ = ts.dt;
      if (!h.ok) break;
      const bool at_end = t_ >= t_end * (1 - 1e-12);
      // An end time the run cannot reach: once the step is set by the flow (not by its start or
      // growth limits), the cycles the rest would take at this step, against time.max_cycles.
      if (!end_warned && root && !at_end &&
          (ts.limit == hydro::DtLimit::Cfl || ts.limit == hydro::DtLimit::CourantSum ||
           ts.limit == hydro::DtLimit::Max || cycle_ >= 100)) {
        end_warned = true;
        const double more = (t_end - t_) / double(ts.dt);
        if (!(more <= double(scene_.time.max_cycles - cycle_))) {
          char b[320];
          std::snprintf(b, sizeof b,
                        "minipagosa: warning: time.end %.6g is out of reach: at the step of "
                        "cycle %ld (dt %.3e) it needs about %.2e more cycles, and time.max_cycles "
                        "(%ld) stops the run first, near t = %.3e\n",
                        t_end, cycle_, double(ts.dt), more, scene_.time.max_cycles,
                        t_ + double(ts.dt) * double(scene_.time.max_cycles - cycle_));
          std::fputs(b, stderr);
          std::fflush(stderr);
        }
      }
      if (!settings_.quiet && root && (cycle_ % scene_.output.log_every == 0 || at_end)) {
        const double w = wall(), done = (t_ - t_begin) / (t_end - t_begin);
        // the wall time left to the end time, or to time.max_cycles where that comes first
        double eta = done > 0 ? w * (1 - done) / done : -1;
        const long cycles_done = cycle_ - cycle_begin;
        if (cycles_done > 0) {
          const double by_cycles =
              w / double(cycles_done) * double(scene_.time.max_cycles - cycle_);
          if (eta < 0 || by_cycles < eta) eta = by_cycles;
        }
        log_cycle(cycle_, t_, double(ts.dt), hydro::dt_limit_name(ts.limit), ts.cell, w, t_ / t_end,
                  eta);
      }
      if (write && writer_ && scene_.output.interval > 0 && t_ >= next_dump_ * (1 - 1e-12) &&
          !at_end) {
        files_.push_back(write_dump(t_, cycle_));
        next_dump_ += scene_.output.interval;
      }
      // Every rank learns whether any rank saw a stop signal or reached the checkpoint wall
      // time, so all stop or checkpoint after the same cycle.
      int flags = 0;
      if (settings_.watch_signals && signals::requested()) flags |= 1;
      if (checkpoints && scene_.output.checkpoint_seconds > 0 &&
          wall() - last_checkpoint >= scene_.output.checkpoint_seconds)
        flags |= 2;
      MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, &flags, 1, MPI_INT, MPI_BOR, mesh_->comm()));
      if (flags & 1) {
        interrupted = !at_end;
        break;
      }
      if (checkpoints && !at_end &&
          ((scene_.output.checkpoint_cycles > 0 && cycle_ % scene_.output.checkpoint_cycles == 0) ||
           (flags & 2))) {
        r.checkpoints.push_back(write_checkpoint_now());
        checkpoint_cycle = cycle_;
        last_checkpoint = wall();
        if (!settings_.quiet) log_line("  checkpoint " + r.checkpoints.back());
      }
      signals::kill_point("cycle", cycle_);
    }
  } catch (const CollectiveError& e) {
    output_failed(r, e.what());
  }
  r.cycles = cycle_;
  r.time = t_;
  r.end = hydro_->totals();
  r.ke_redone = hydro_->ke_redone();
  r.mass_ledger = hydro_->mass_ledger();
  r.mass_ledger_from = mass_ledger_from_;
  r.health = h;
  const double tot[] = {r.end.mass,        r.end.internal,    r.end.kinetic,
                        r.end.momentum[0], r.end.momentum[1], r.end.momentum[2]};
  bool finite = true;
  for (double v : tot) finite = finite && std::isfinite(v);
  if (h.ok && !finite) {
    r.health.ok = false;
    r.health.what = "non-finite totals (mass, energy or momentum)";
    r.health.cell = {-1, -1, -1};
  }
  r.ok = r.health.ok;
  r.ending = !r.ok                       ? Ending::NonPhysical
             : interrupted               ? Ending::Interrupted
             : t_ >= t_end * (1 - 1e-12) ? Ending::EndTime
                                         : Ending::MaxCycles;
  // A run that stops before its end time leaves a checkpoint to continue from.
  try {
    if (write && r.ok && (r.checkpoints.empty() || checkpoint_cycle != cycle_) &&
        (r.ending == Ending::Interrupted || (r.ending == Ending::MaxCycles && checkpoints)))
      r.checkpoints.push_back(write_checkpoint_now());
    if (write && writer_) files_.push_back(write_dump(t_, cycle_));
  } catch (const CollectiveError& e) {
    output_failed(r, e.what());
  }
  r.files = files_;
  r.wall = wall();
  if (write) write_summary(r);
  return r;
}

void Simulation::output_failed(RunResult& r, const std::string& what) {
  r.cycles = cycle_;
  r.time = t_;
  r.end = hydro_->totals();
  r.ke_redone = hydro_->ke_redone();
  r.mass_ledger = hydro_->mass_ledger();
  r.mass_ledger_from = mass_ledger_from_;
  r.files = files_;
  r.output_error = what;
  std::string note = "; nothing else was written";
  try {
    write_summary(r);
    note = "; summary.json records the failure";
  } catch (const std::exception&) {
  }
  throw CollectiveError(what + note);
}

}  // namespace mp
