// Checkpoints and restart: what a checkpoint holds, its metadata (the build, the deck's resolved
// keys, the run's clock), and continuing a run from one on any number of ranks.
#include <array>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/profiling.hpp"
#include "driver/modules.hpp"
#include "driver/signals.hpp"
#include "driver/simulation.hpp"
#include "io/checkpoint.hpp"
#include "io/h5_util.hpp"
#include "io/log.hpp"

namespace mp {

std::vector<OutputField> Simulation::checkpoint_fields() const {
  const auto& s = hydro_->state();
  std::vector<OutputField> f = {{"rho", Centering::Cell, s.rho},
                                {"e", Centering::Cell, s.e},
                                {"u", Centering::Node, s.u},
                                {"v", Centering::Node, s.v},
                                {"w", Centering::Node, s.w}};
  if (const mat::MaterialState* mm = hydro_->materials())
    for (int m = 0; m < mm->nmat(); ++m) {
      const std::string n = std::to_string(m);
      f.push_back({"alpha_" + n, Centering::Cell, mm->material_field(m, 0)});
      f.push_back({"rho_" + n, Centering::Cell, mm->material_field(m, 1)});
      f.push_back({"e_" + n, Centering::Cell, mm->material_field(m, 2)});
    }
  // what the modules carry from cycle to cycle (their registered kCheckpoint fields)
  for (const OutputField& o : mp::checkpoint_fields(hydro_->module_fields(kCheckpoint)))
    f.push_back(o);
  return f;
}

namespace {

// Is a --restart-allow pattern a prefix ("numerics.*") rather than an exact key?
bool prefix_pattern(const std::string& p) {
  return p.size() >= 2 && p.compare(p.size() - 2, 2, ".*") == 0;
}

// Does `key` match one of the --restart-allow patterns (an exact key, or "prefix.*")?
bool allowed_by(const std::vector<std::string>& patterns, const std::string& key) {
  for (const std::string& p : patterns) {
    if (prefix_pattern(p) ? key.compare(0, p.size() - 1, p, 0, p.size() - 1) == 0 : key == p)
      return true;
  }
  return false;
}

// Deck keys a restart may change: where and how often output goes, how far the run goes, how
// the ranks split the mesh, the free text.
bool restart_may_change(const std::string& key) {
  return key.rfind("output.", 0) == 0 || key == "output" || key == "time.end" ||
         key == "time.max_cycles" || key.rfind("mesh.ranks", 0) == 0 || key == "description";
}

nlohmann::json totals_json(const hydro::Totals& t) {
  return {{"mass", t.mass},
          {"internal", t.internal},
          {"kinetic", t.kinetic},
          {"momentum", t.momentum},
          {"material_mass", t.material_mass}};
}

hydro::Totals totals_from(const nlohmann::json& j) {
  hydro::Totals t;
  t.mass = j.at("mass").get<double>();
  t.internal = j.at("internal").get<double>();
  t.kinetic = j.at("kinetic").get<double>();
  t.momentum = j.at("momentum").get<std::array<double, 3>>();
  t.material_mass = j.at("material_mass").get<std::vector<double>>();
  return t;
}

// Restores the per-material content of the owned cells from per-material arrays
// (nmat, cell index) read from a checkpoint.
struct RestoreSource {
  Kokkos::View<Real****, Kokkos::LayoutRight, MemSpace> a, r, e;
  int nmat;
  int lo[3], hi[3];
  KOKKOS_INLINE_FUNCTION bool changed(int i, int j, int k) const {
    return i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1] && k >= lo[2] && k < hi[2];
  }
  KOKKOS_INLINE_FUNCTION int content(int i, int j, int k, Real* al, Real* rh, Real* en) const {
    int n = 0;
    for (int m = 0; m < nmat; ++m) {
      if (!(a(m, i, j, k) > 0)) continue;
      al[m] = a(m, i, j, k);
      rh[m] = r(m, i, j, k);
      en[m] = e(m, i, j, k);
      ++n;
    }
    return n;
  }
};

}  // namespace

std::string restart_allow_error(const std::string& pattern) {
  const bool wildcard = prefix_pattern(pattern);
  const std::string stem = wildcard ? pattern.substr(0, pattern.size() - 2) : pattern;
  // a bare "numerics" or "time" names no deck key (keys are leaves): only "numerics.*", "time.*"
  const bool scoped = ((stem == "numerics" || stem == "time") && wildcard) ||
                      stem.rfind("numerics.", 0) == 0 || stem.rfind("time.", 0) == 0;
  if (scoped && stem.find('*') == std::string::npos && stem.back() != '.') return "";
  return "--restart-allow " + pattern +
         ": only numerics.* and time.* keys (an exact key, or a prefix ending in '.*') may "
         "change on a restart; the mesh, materials and regions define what the checkpoint's "
         "state means";
}

std::string Simulation::checkpoint_meta() const {
  nlohmann::json deck = nlohmann::json::object();
  for (const auto& [k, v] : scene_.deck_values)
    if (!restart_may_change(k)) deck[k] = v;
  nlohmann::json dumps = nlohmann::json::array();
  for (const auto& d : dumps_) dumps.push_back({d.file, d.time, d.cycle});
  nlohmann::json j = {{"format", 1},
                      {"version", MINIPAGOSA_VERSION},
                      {"real", real_name()},
                      {"scene", scene_.name},
                      {"deck", deck},
                      {"resolved", resolved_numerics(scene_)},
                      {"time", t_},
                      {"cycle", cycle_},
                      {"dt_old", double(dt_old_)},
                      {"next_dump", next_dump_},
                      {"start", totals_json(start_)},
                      {"dumps", dumps},
                      {"files", files_},
                      {"restart_history", restart_history_}};
  if (hydro_->mass_ledger_on()) {
    j["mass_ledger"] = hydro_->mass_ledger();
    j["mass_ledger_from"] = mass_ledger_from_;
  }
  return j.dump();
}

std::string Simulation::write_checkpoint_now() {
  ProfileRegion region("output::checkpoint");
  const std::string path = checkpoint_path(settings_.output_dir, scene_.output.basename, cycle_);
  write_checkpoint(*mesh_, path, checkpoint_fields(), checkpoint_meta(),
                   [&] { signals::kill_point("checkpoint", cycle_); });
  // Keep the newest checkpoint_keep complete checkpoints.
  if (mesh_->rank() == 0) {
    auto all = list_checkpoints(settings_.output_dir, scene_.output.basename);
    const int keep = scene_.output.checkpoint_keep;
    for (int n = 0; n + keep < static_cast<int>(all.size()); ++n)
      std::remove(all[n].second.c_str());
  }
  return path;
}

void Simulation::restart(const std::string& path) {
  auto t0 = std::chrono::steady_clock::now();
  nlohmann::json meta;
  const std::string text = read_checkpoint_meta(path, mesh_->comm());
  try {
    meta = nlohmann::json::parse(text);
  } catch (const std::exception& e) {
    throw RunError("checkpoint " + path + ": unreadable metadata: " + e.what());
  }
  const auto str = [&](const char* key) {
    return meta.contains(key) && meta[key].is_string() ? meta[key].get<std::string>()
                                                       : std::string("?");
  };
  if (str("version") != MINIPAGOSA_VERSION || str("real") != real_name())
    throw InputError("checkpoint " + path + " was written by minipagosa " + str("version") +
                     " with Real = " + str("real") + "; this build is minipagosa " +
                     MINIPAGOSA_VERSION + " with Real = " + real_name() +
                     ": restart it with the build that wrote it");
  // The deck: every key that shapes the solution must match.
  std::map<std::string, std::string> here, there;
  for (const auto& [k, v] : scene_.deck_values)
    if (!restart_may_change(k)) here[k] = v;
  if (meta.contains("deck") && meta["deck"].is_object())
    for (auto it = meta["deck"].begin(); it != meta["deck"].end(); ++it)
      there[it.key()] = it.value().is_string() ? it.value().get<std::string>() : it.value().dump();
  std::string diff;
  int ndiff = 0;
  restart_changes_.clear();
  auto note = [&](const std::string& k, const std::string& a, const std::string& b) {
    const std::string line = k + ": " + a + " in the checkpoint, " + b + " here";
    if (allowed_by(settings_.restart_allow, k)) {
      restart_changes_.push_back(line);
      return;
    }
    if (++ndiff <= 6) diff += "\n  " + line;
  };
  // With the checkpoint's resolved numerics (defaults included; written since 2026-12-03) the
  // numerics.* and time.cfl/growth/dt_max keys are compared as resolved: a key the deck leaves
  // to the default still differs if the checkpoint's build had another default, and a key set
  // to its default equals it left out. Older checkpoints: the deck's own keys only (logged).
  const bool resolved = meta.contains("resolved") && meta["resolved"].is_object();
  std::map<std::string, std::string> now, then;
  if (resolved) {
    now = resolved_numerics(scene_);
    for (auto it = meta["resolved"].begin(); it != meta["resolved"].end(); ++it)
      then[it.key()] = it.value().is_string() ? it.value().get<std::string>() : it.value().dump();
    for (const auto& [k, v] : now) here.erase(k), there.erase(k);
    for (const auto& [k, v] : then) here.erase(k), there.erase(k);
  }
  for (const auto& [k, v] : there) {
    const auto it = here.find(k);
    if (it == here.end())
      note(k, "'" + v + "'", "not set");
    else if (it->second != v)
      note(k, "'" + v + "'", "'" + it->second + "'");
  }
  for (const auto& [k, v] : here)
    if (!there.count(k)) note(k, "not set", "'" + v + "'");
  for (const auto& [k, v] : then) {
    const auto h = now.find(k);
    if (h == now.end())
      note(k, "'" + v + "'", "unknown to this build");
    else if (h->second != v)
      note(k, "'" + v + "'",
           "'" + h->second + "'" + (scene_.deck_values.count(k) ? "" : " (this build's default)"));
  }
  for (const auto& [k, v] : now)
    if (!then.count(k)) note(k, "not recorded", "'" + v + "'");
  if (ndiff > 0)
    throw InputError("checkpoint " + path + " was written for another deck (" +
                     std::to_string(ndiff) + " difference" + (ndiff > 1 ? "s" : "") +
                     "; only output.*, time.end, time.max_cycles, mesh.ranks and description "
                     "may change on a restart, and numerics.* or time.* keys named by "
                     "--restart-allow):" +
                     diff);
  for (const std::string& c : restart_changes_) log_line("  restart changes " + c);
  if (!resolved)
    log_line("  restart: " + path +
             " records only the deck's own keys (written before 2026-12-03): numerics the deck "
             "leaves to their defaults take this build's defaults");

  // Fields: cell and node state straight into the hydro's arrays; per-material state through
  // the layout's own rebuild, then the cell averages as they were (a mixed cell's average is
  // whatever the remap left, not necessarily the re-averaged materials).
  auto& s = hydro_->state();
  mat::MaterialState* mm = hydro_->materials();
  Field3 crho = s.rho, ce = s.e;
  if (mm) {
    crho = mesh_->new_field("restart_rho", Centering::Cell);
    ce = mesh_->new_field("restart_e", Centering::Cell);
  }
  std::vector<OutputField> fields = {{"rho", Centering::Cell, crho},
                                     {"e", Centering::Cell, ce},
                                     {"u", Centering::Node, s.u},
                                     {"v", Centering::Node, s.v},
                                     {"w", Centering::Node, s.w}};
  const int nmat = mm ? mm->nmat() : 0;
  std::vector<Field3> per;
  for (int m = 0; m < nmat; ++m)
    for (const char* q : {"alpha_", "rho_", "e_"}) {
      per.push_back(mesh_->new_field(std::string("restart_") + q, Centering::Cell));
      fields.push_back({q + std::to_string(m), Centering::Cell, per.back()});
    }
  // each module's checkpointed fields (the views the file is read into, handed back to it)
  std::vector<std::vector<FieldSpec>> state;
  for (const hydro::Module* m : hydro_->modules()) {
    state.emplace_back();
    for (const FieldSpec& f : m->fields(kCheckpoint))
      if (f.use & kCheckpoint) state.back().push_back(f);
    for (const OutputField& o : mp::checkpoint_fields(state.back())) fields.push_back(o);
  }
  // A field this build checkpoints and the file lacks (a checkpoint from before lighting times
  // were checkpointed, 2026-12-06) cannot be restored exactly: refuse, naming it.
  std::vector<std::string> names;
  for (const OutputField& o : fields) names.push_back(o.name);
  const std::vector<std::string> missing = checkpoint_missing(path, names, mesh_->comm());
  if (!missing.empty()) {
    std::string list;
    for (const std::string& m : missing) list += (list.empty() ? "'" : ", '") + m + "'";
    throw InputError("checkpoint " + path + " holds no " + list +
                     ", which this build checkpoints and cannot rebuild exactly from the "
                     "checkpoint's state (a checkpoint written by an older build): restart it "
                     "with the build that wrote it, or run the deck from the start");
  }
  read_checkpoint_fields(*mesh_, path, fields);
  if (mm) {
    const int ex = mesh_->extent(Centering::Cell, 0), ey = mesh_->extent(Centering::Cell, 1),
              ez = mesh_->extent(Centering::Cell, 2);
    const int ng = Mesh::ng;
    const auto end = mesh_->owned_end();
    using Field4 = Kokkos::View<Real****, Kokkos::LayoutRight, MemSpace>;
    RestoreSource src{Field4("restart_alpha", nmat, ex, ey, ez),
                      Field4("restart_rho_m", nmat, ex, ey, ez),
                      Field4("restart_e_m", nmat, ex, ey, ez),
                      nmat,
                      {ng, ng, ng},
                      {end[0], end[1], end[2]}};
    for (int m = 0; m < nmat; ++m) {
      auto a = src.a, r = src.r, e = src.e;
      auto pa = per[3 * m], pr = per[3 * m + 1], pe = per[3 * m + 2];
      Kokkos::parallel_for(
          "restart::materials", mesh_->cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
            a(m, i, j, k) = pa(i, j, k);
            r(m, i, j, k) = pr(i, j, k);
            e(m, i, j, k) = pe(i, j, k);
          });
    }
    mm->assign("restart::assign", src);
    auto rho = s.rho, e = s.e;
    Kokkos::parallel_for(
        "restart::cells", mesh_->cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
          rho(i, j, k) = crho(i, j, k);
          e(i, j, k) = ce(i, j, k);
        });
  }
  // the modules' restored state (stress sets kept in the compact pool take their values now
  // that the pool holds the materials); nothing is rebuilt from the restarted materials
  for (std::size_t n = 0; n < state.size(); ++n) hydro_->modules()[n]->restore(state[n]);
  hydro_->prepare();
  phase("checkpoint read", t0);

  try {
    t_ = meta.at("time").get<double>();
    for (hydro::Module* m : hydro_->modules()) m->set_time(t_);
    cycle_ = meta.at("cycle").get<long>();
    dt_old_ = Real(meta.at("dt_old").get<double>());
    next_dump_ = meta.at("next_dump").get<double>();
    start_ = totals_from(meta.at("start"));
    // the ledger so far (a checkpoint written without it: this run's ledger counts from here)
    if (hydro_->mass_ledger_on()) {
      if (meta.contains("mass_ledger")) {
        hydro_->restore_mass_ledger(meta.at("mass_ledger").get<std::vector<double>>());
        mass_ledger_from_ = meta.value("mass_ledger_from", 0L);
      } else {
        mass_ledger_from_ = cycle_;
      }
    }
    files_ = meta.at("files").get<std::vector<std::string>>();
    dumps_.clear();
    for (const auto& d : meta.at("dumps"))
      dumps_.push_back({d.at(0).get<std::string>(), d.at(1).get<double>(), d.at(2).get<long>()});
    // every --restart-allow change of the run's earlier restarts, then this one's
    restart_history_.clear();
    if (meta.contains("restart_history"))
      restart_history_ = meta.at("restart_history").get<std::vector<std::string>>();
    for (const std::string& c : restart_changes_)
      restart_history_.push_back("cycle " + std::to_string(cycle_) + ": " + c);
  } catch (const std::exception& e) {
    throw RunError("checkpoint " + path + ": incomplete metadata: " + e.what());
  }
  restarted_ = true;
  restarted_from_ = path;
}

}  // namespace mp
