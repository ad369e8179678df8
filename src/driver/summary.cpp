// How a run ended, and summary.json: the run's totals, its ending, its files, as JSON.
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "driver/modules.hpp"
#include "driver/simulation.hpp"
#include "io/h5_util.hpp"

namespace mp {

const char* status_name(Ending e) {
  switch (e) {
    case Ending::EndTime:
      return "completed";
    case Ending::MaxCycles:
      return "max_cycles";
    case Ending::Interrupted:
      return "interrupted";
    case Ending::NonPhysical:
      return "non-physical";
  }
  return "?";
}

const char* ending_text(Ending e) {
  switch (e) {
    case Ending::EndTime:
      return "end time reached";
    case Ending::MaxCycles:
      return "max_cycles reached";
    case Ending::Interrupted:
      return "interrupted by a signal";
    case Ending::NonPhysical:
      return "non-physical state";
  }
  return "?";
}

void Simulation::write_summary(const RunResult& r) const {
  const std::string path = settings_.output_dir + "/summary.json";
  const std::string text = summary_json(r);
  h5::on_root(mesh_->comm(), [&] { write_text_atomically(path, text); });
}

std::vector<LedgerEntry> ledger_entries(const Scene& scene, const RunResult& r) {
  std::vector<LedgerEntry> out;
  const std::size_t n = r.mass_ledger.size() / 6;
  for (std::size_t m = 0; m < n; ++m) {
    LedgerEntry e;
    e.name = n > 1 || scene.materials.size() == 1 ? scene.materials[m].name : "mass";
    for (int f = 0; f < 6; ++f) {
      e.faces[f] = r.mass_ledger[6 * m + f];
      e.out += e.faces[f];
    }
    e.start = n > 1 ? r.start.material_mass[m] : r.start.mass;
    out.push_back(e);
  }
  return out;
}

std::string ledger_line(const std::vector<LedgerEntry>& entries) {
  static const char* face[] = {"x lo", "x hi", "y lo", "y hi", "z lo", "z hi"};
  std::ostringstream os;
  os << "mass out through the boundaries (share of the start's):";
  for (const auto& e : entries) {
    int big = 0;
    for (int f = 1; f < 6; ++f)
      if (std::abs(e.faces[f]) > std::abs(e.faces[big])) big = f;
    os << " " << e.name << " " << std::setprecision(3)
       << (e.start != 0 ? 100 * e.out / e.start : 0.0) << " %";
    if (e.out != 0) os << " (most at " << face[big] << ")";
    os << ";";
  }
  std::string s = os.str();
  s.back() = '.';
  return s;
}

std::string Simulation::summary_json(const RunResult& r) const {
  // Non-finite numbers are not JSON: each becomes null and its key is listed in "non_finite".
  std::vector<std::string> non_finite;
  auto num = [&](double v, const std::string& key) -> nlohmann::ordered_json {
    if (std::isfinite(v)) return v;
    non_finite.push_back(key);
    return nullptr;
  };
  auto totals = [&](const hydro::Totals& t, const std::string& at) {
    nlohmann::ordered_json o;
    o["mass"] = num(t.mass, at + ".mass");
    o["momentum"] = {num(t.momentum[0], at + ".momentum.0"), num(t.momentum[1], at + ".momentum.1"),
                     num(t.momentum[2], at + ".momentum.2")};
    o["internal_energy"] = num(t.internal, at + ".internal_energy");
    o["kinetic_energy"] = num(t.kinetic, at + ".kinetic_energy");
    o["total_energy"] = num(t.total(), at + ".total_energy");
    if (!t.material_mass.empty()) {
      nlohmann::ordered_json mm = nlohmann::ordered_json::object();
      for (std::size_t m = 0; m < t.material_mass.size(); ++m)
        mm[scene_.materials[m].name] =
            num(t.material_mass[m], at + ".material_mass." + scene_.materials[m].name);
      o["material_mass"] = mm;
    }
    return o;
  };
  const double cc = double(mesh_->global_cell_count()) * double(r.cycles - r.first_cycle);
  nlohmann::ordered_json js;
  js["scene"] = scene_.name;
  js["deck"] = scene_.file;
  js["version"] = MINIPAGOSA_VERSION;
  js["status"] = r.output_error.empty() ? status_name(r.ending) : "output-failed";
  js["ended_by"] = r.output_error.empty() ? ending_text(r.ending) : "output failed";
  if (!r.output_error.empty()) js["output_error"] = r.output_error;
  js["ranks"] = mesh_->nranks();
  js["decomposition"] = mesh_->dims();
  js["kokkos_execution_space"] = ExecSpace::name();
  js["threads_per_rank"] = ExecSpace().concurrency();
  js["real"] = real_name();
  js["cells"] = {mesh_->global_cells(0), mesh_->global_cells(1), mesh_->global_cells(2)};
  js["cycles"] = r.cycles;
  js["time"] = num(r.time, "time");
  js["end_time"] = scene_.time.end;
  js["wall_seconds"] = r.wall;
  {
    nlohmann::ordered_json setup = nlohmann::ordered_json::object();
    for (const auto& [name, sec] : setup_) setup[name] = sec;
    js["setup_seconds"] = setup;
  }
  js["cell_cycles_per_second"] = r.wall > 0 ? cc / r.wall : 0.0;
  js["modules"] = modules();
  js["start"] = totals(r.start, "start");
  js["end"] = totals(r.end, "end");
  const double dm = r.end.mass - r.start.mass;
  const double de = r.end.total() - r.start.total();
  js["mass_change_relative"] =
      num(r.start.mass != 0 ? dm / r.start.mass : 0, "mass_change_relative");
  js["total_energy_change_relative"] =
      num(r.start.total() != 0 ? de / r.start.total() : 0, "total_energy_change_relative");
  // the part of that change the KE fix's floor left unpaid (Totals::ke_fix_unpaid)
  const double du = r.end.ke_fix_unpaid - r.start.ke_fix_unpaid;
  js["ke_fix_redone_sweeps"] = r.ke_redone;
  js["ke_fix_unpaid_relative"] =
      num(r.start.total() != 0 ? du / r.start.total() : 0, "ke_fix_unpaid_relative");
  if (!r.mass_ledger.empty()) {
    // output.mass_ledger: per material, the mass out through each face (negative: in)
    static const char* face[] = {"x_lo", "x_hi", "y_lo", "y_hi", "z_lo", "z_hi"};
    nlohmann::ordered_json led = nlohmann::ordered_json::object();
    for (const auto& e : ledger_entries(scene_, r)) {
      nlohmann::ordered_json o;
      for (int f = 0; f < 6; ++f) o[face[f]] = num(e.faces[f], "mass_ledger." + e.name);
      o["out"] = num(e.out, "mass_ledger." + e.name + ".out");
      o["out_relative"] = num(e.start != 0 ? e.out / e.start : 0, "mass_ledger." + e.name);
      led[e.name] = o;
    }
    js["mass_ledger"] = {{"from_cycle", r.mass_ledger_from}, {"materials", led}};
  }
  js["files"] = r.files;
  js["checkpoints"] = r.checkpoints;
  if (!r.restarted_from.empty()) {
    js["restarted_from"] = r.restarted_from;
    js["restart_cycle"] = r.first_cycle;
    js["restart_changes"] = r.restart_changes;
    js["restart_history"] = r.restart_history;
  }
  if (!r.ok) {
    const auto& h = r.health;
    js["failure"] = {{"what", h.what},
                     {"cell", h.cell},
                     {"cycle", r.cycles},
                     {"density", num(h.rho, "failure.density")},
                     {"energy", num(h.e, "failure.energy")},
                     {"pressure", num(h.p, "failure.pressure")}};
    if (h.material >= 0)
      js["failure"]["material"] = {{"id", h.material},
                                   {"fraction", num(h.m_fraction, "failure.material.fraction")},
                                   {"density", num(h.m_rho, "failure.material.density")},
                                   {"energy", num(h.m_e, "failure.material.energy")}};
  }
  js["non_finite"] = non_finite;
  return js.dump(2) + "\n";
}

}  // namespace mp
