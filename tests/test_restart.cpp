// Restart: a run checkpointed part way and continued from the checkpoint ends with every field
// bitwise equal to the straight run (maximum difference exactly 0: the restart reads back the
// exact bits and recomputes the derived fields with the same kernels, so round-off allows no
// difference), on the same rank count and from a checkpoint written by half the ranks (1 -> 2
// on 2 ranks, 2 -> 4 on 4), in the dense and the compact layout, on the three-material triple
// point. A checkpoint from another deck or another build is refused naming what differs.
#include <gtest/gtest.h>

#include <stdlib.h>
#include <functional>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/h5_util.hpp"
#include "support.hpp"

namespace fs = std::filesystem;

namespace {

using namespace mp;

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int world_size() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// A temporary directory every rank knows (made by rank 0), removed at the end.
struct SharedDir {
  std::string path;
  SharedDir() {
    char buf[256] = {0};
    if (world_rank() == 0) {
      std::string name = (fs::temp_directory_path() / "minipagosa_restart_XXXXXX").string();
      if (mkdtemp(name.data())) std::snprintf(buf, sizeof buf, "%s", name.c_str());
    }
    MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, MPI_COMM_WORLD);
    path = buf;
  }
  ~SharedDir() {
    MPI_Barrier(MPI_COMM_WORLD);
    std::error_code ec;
    if (world_rank() == 0) fs::remove_all(path, ec);
  }
};

// The triple point, small: 32 x 12 x 4 cells (at least 2 cells per rank per axis on 4 ranks),
// to t = 0.7 (the shock has crossed into both gases and mixed cells line both interfaces).
std::vector<std::string> deck(const std::string& layout) {
  return {"mesh.cells=[32,12,4]", "time.end=0.7", "numerics.layout=" + layout,
          "output.write=false"};
}

// A scene to restart: its deck, overrides and whether it must show mixed cells.
struct Case {
  std::string file;
  std::vector<std::string> set;
  bool mixed = true;
  long checkpoint_cycle = 17;  // where ModuleRestart stops and restarts
};

Case triple_point(const std::string& layout) {
  return {"triple_point.yaml", deck(layout), true};
}

using Snapshot = std::vector<std::pair<std::string, std::vector<double>>>;

// Every field a cycle reads or derives, gathered globally.
Snapshot snapshot(Simulation& sim) {
  Snapshot out;
  for (const auto& f : sim.checkpoint_fields())
    out.emplace_back(f.name, test::gather(sim.mesh(), f.view, f.centering));
  const auto& s = sim.hydro().state();
  for (const auto& [name, view] :
       {std::pair<const char*, Field3>{"p", s.p}, {"c", s.c}, {"q", s.q}})
    out.emplace_back(name, test::gather(sim.mesh(), view, Centering::Cell));
  return out;
}

Snapshot straight_run(const Case& c) {
  auto r = test::run_scene(test::load_scene(c.file, c.set));
  EXPECT_TRUE(r.result.ok);
  EXPECT_EQ(r.result.ending, Ending::EndTime);
  Snapshot s = snapshot(*r.sim);
  // the scene must exercise mixed cells, or the per-material restart goes untested
  long mixed = 0;
  for (const auto& [name, values] : s)
    if (name.rfind("alpha_", 0) == 0)
      for (double a : values) mixed += a > 0 && a < 1 ? 1 : 0;
  if (world_rank() == 0)
    std::printf("  %s: %ld partial volume fractions at the end, %zu fields\n", c.file.c_str(),
                mixed, s.size());
  if (c.mixed) {
    EXPECT_GT(mixed, 0);
  }
  return s;
}

// The strength and burn modules' state at the checkpoint is not trivial, or its restart would
// compare zeros: some plastic strain (in one material at least: a multi-material scene has one
// plastic_strain_<material id> per material with strength, and charge_3d's steel inclusion has
// not yielded yet), and a burn front part way through the explosive (cells burnt and cells not
// yet lit). Collective over the simulation's ranks; prints from rank 0.
void expect_module_state_in_use(Simulation& sim, const std::string& file) {
  long strained = 0, strain_fields = 0;
  for (const auto& f : sim.checkpoint_fields()) {
    const bool strain = f.name.rfind("plastic_strain", 0) == 0;
    if (!strain && f.name != "burn_fraction") continue;
    const auto v = test::gather(sim.mesh(), f.view, f.centering);
    long positive = 0, below_one = 0;
    double largest = 0;
    for (double x : v) {
      positive += x > 0 ? 1 : 0;
      below_one += x < 1 ? 1 : 0;
      largest = std::max(largest, x);
    }
    if (world_rank() == 0)
      std::printf(
          "  %s at the checkpoint (cycle %ld): %s > 0 in %ld of %zu cells (largest %.3e), "
          "< 1 in %ld\n",
          file.c_str(), sim.cycle(), f.name.c_str(), positive, v.size(), largest, below_one);
    if (strain) {
      ++strain_fields;
      strained += positive;
    } else {
      EXPECT_GT(positive, 0) << f.name;
      EXPECT_GT(below_one, 0) << "the burn has finished before the checkpoint";
    }
  }
  if (strain_fields > 0) {
    EXPECT_GT(strained, 0) << "no material has yielded by the checkpoint";
  }
}

// Runs the first `cycles` cycles on `comm` (the ranks not in it wait), writing a checkpoint in
// `dir`; returns its path on every rank of the world.
std::string run_to_checkpoint(const Case& c, long cycles, MPI_Comm comm, const std::string& dir) {
  std::string path;
  if (comm != MPI_COMM_NULL) {
    auto d = c.set;
    d.push_back("time.max_cycles=" + std::to_string(cycles));
    d.push_back("output.checkpoint_every={cycles: " + std::to_string(cycles) + "}");
    RunSettings settings;
    settings.quiet = true;
    settings.output_dir = dir;
    Simulation sim(test::load_scene(c.file, d), comm, settings);
    sim.initialize();
    const RunResult r = sim.run();
    EXPECT_EQ(r.ending, Ending::MaxCycles);
    EXPECT_EQ(r.cycles, cycles);
    EXPECT_EQ(r.checkpoints.size(), 1u) << "one checkpoint at the stop, not two";
    if (!r.checkpoints.empty()) path = r.checkpoints.back();
    expect_module_state_in_use(sim, c.file);
  }
  test::rest_until_all();  // the ranks not in comm wait asleep (tests/mpi_rest.hpp)
  char buf[512] = {0};
  std::snprintf(buf, sizeof buf, "%s", path.c_str());
  MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, MPI_COMM_WORLD);
  return buf;
}

// Continues `checkpoint` to the end on `comm` (MPI_COMM_NULL on the ranks not in it, which
// return an empty snapshot); the snapshot is whole on comm's first rank.
Snapshot restarted_run(const Case& c, const std::string& checkpoint, long from,
                       MPI_Comm comm = MPI_COMM_WORLD) {
  if (comm == MPI_COMM_NULL) return {};
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(test::load_scene(c.file, c.set), comm, settings);
  sim.restart(checkpoint);
  EXPECT_EQ(sim.cycle(), from);
  const RunResult r = sim.run();
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.ending, Ending::EndTime);
  EXPECT_EQ(r.first_cycle, from);
  if (world_rank() == 0)
    std::printf("  restarted at cycle %ld on %d rank(s), ended at cycle %ld, t = %.17g\n", from,
                sim.mesh().nranks(), r.cycles, r.time);
  return snapshot(sim);
}

void expect_identical(const Snapshot& a, const Snapshot& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t n = 0; n < a.size(); ++n) {
    ASSERT_EQ(a[n].first, b[n].first);
    ASSERT_EQ(a[n].second.size(), b[n].second.size());
    double maxdiff = 0;
    long differ = 0;
    for (std::size_t i = 0; i < a[n].second.size(); ++i) {
      const double d = std::abs(a[n].second[i] - b[n].second[i]);
      // bit equality (NaN never equals itself, so a NaN counts as a difference)
      if (!(a[n].second[i] == b[n].second[i])) ++differ;
      maxdiff = std::max(maxdiff, d);
    }
    if (world_rank() == 0)
      std::printf("  %s %-8s %6zu values  max |difference| %.3g  differing %ld\n", what.c_str(),
                  a[n].first.c_str(), a[n].second.size(), maxdiff, differ);
    EXPECT_EQ(differ, 0) << what << ": field " << a[n].first;
    EXPECT_EQ(maxdiff, 0.0) << what << ": field " << a[n].first;
  }
}

class Restart : public ::testing::TestWithParam<std::string> {};

TEST_P(Restart, SameRankCountIsBitwiseEqual) {
  const std::string layout = GetParam();
  const Case c = triple_point(layout);
  const Snapshot straight = straight_run(c);
  SharedDir dir;
  const long at = 25;
  const std::string ckpt = run_to_checkpoint(c, at, MPI_COMM_WORLD, dir.path);
  ASSERT_FALSE(ckpt.empty());
  expect_identical(
      straight, restarted_run(c, ckpt, at),
      layout + " " + std::to_string(world_size()) + "->" + std::to_string(world_size()));
}

TEST_P(Restart, FromHalfTheRanksIsBitwiseEqual) {
  const std::string layout = GetParam();
  const int n = world_size();
  if (n < 2) GTEST_SKIP() << "needs 2 or more ranks";
  const Case c = triple_point(layout);
  const Snapshot straight = straight_run(c);
  SharedDir dir;
  MPI_Comm half;
  MPI_Comm_split(MPI_COMM_WORLD, world_rank() < n / 2 ? 0 : MPI_UNDEFINED, world_rank(), &half);
  const long at = 31;
  const std::string ckpt = run_to_checkpoint(c, at, half, dir.path);
  if (half != MPI_COMM_NULL) MPI_Comm_free(&half);
  ASSERT_FALSE(ckpt.empty());
  expect_identical(straight, restarted_run(c, ckpt, at),
                   layout + " " + std::to_string(n / 2) + "->" + std::to_string(n));
}

INSTANTIATE_TEST_SUITE_P(Layouts, Restart, ::testing::Values("dense", "compact"));

// The strength and burn modules' state (deviator, plastic strain, burn fraction, the burn clock)
// survives a restart bit for bit, from half the ranks (also with Forest Fire, fragment_3d): an
// aluminium sphere driven obliquely through a block (3-D shear, plasticity), and a point-detonated
// block of gamma-law explosive stopped with its front part way across (at cycle 40 of 73: at cycle
// 17, where it stopped before, no cell had started to burn, so the burn fraction restored was all
// zeros). The sphere stops at cycle 25 of 44: since its surface nodes start with the painted
// momentum of their cells (2026-12-02, docs/numerics.md "Initial node velocities") no cell has
// yielded by cycle 17, and 1147 of 1920 have by 25.
TEST(ModuleRestart, StrengthAndBurnFromHalfTheRanksAreBitwiseEqual) {
  const int n = world_size();
  const std::vector<Case> cases = {
      {"elastic_wave.yaml",
       {"mesh.cells=[24,10,8]", "mesh.hi=[2,1,0.8]", "boundaries.x=reflective",
        "materials.0.strength.model=elastic_plastic", "materials.0.strength.yield=0.0029",
        "materials.0.strength.shear_modulus=0.276",
        "regions=[{material: al, shape: all, density: 2.703, energy: 1.0e-5}, {material: al, "
        "shape: sphere, center: [1, 0.5, 0.4], radius: 0.3, density: 2.703, energy: 1.0e-5, "
        "velocity: [0.02, 0.01, -0.005]}]",
        "time.end=0.6", "output.write=false"},
       false,
       25},
      {"mader.yaml",
       {"mesh.cells=[24,10,8]", "mesh.hi=[1,0.4,0.32]",
        "materials.0.burn.detonators=[{type: point, at: [0.1, 0.2, 0.16]}]", "time.end=0.5",
        "output.write=false"},
       false,
       40},
      // both modules in a multi-material scene (lighting times rebuilt from the restored
      // fractions), stopped at cycle 70 of 89 (t = 0.56 us) with the front part way across
      {"charge_3d.yaml", {"time.end=1.0", "output.write=false"}, true, 70},
      // Forest Fire (nothing lit: a copper fragment shock-initiates PBX 9404), stopped at cycle
      // 65 of 74, the detonation under way (F > 0 in 1716 of 3360 cells, largest 1; at cycle 50
      // the largest was still 4e-4)
      {"fragment_3d.yaml", {"time.end=1.0", "output.write=false"}, true, 65}};
  for (const Case& c : cases) {
    const Snapshot straight = straight_run(c);
    SharedDir dir;
    MPI_Comm half;
    MPI_Comm_split(MPI_COMM_WORLD, world_rank() < (n + 1) / 2 ? 0 : MPI_UNDEFINED, world_rank(),
                   &half);
    const long at = c.checkpoint_cycle;
    const std::string ckpt = run_to_checkpoint(c, at, half, dir.path);
    if (half != MPI_COMM_NULL) MPI_Comm_free(&half);
    ASSERT_FALSE(ckpt.empty());
    expect_identical(straight, restarted_run(c, ckpt, at),
                     c.file + " " + std::to_string((n + 1) / 2) + "->" + std::to_string(n));
  }
}

// The compact layout keeps a material's stress set only where the material is (pure-cell
// arrays and pool slots), the dense one as cell fields; both write the same checkpoint fields
// (stress_*_<id>, plastic_strain_<id>: 0 where the material is absent). So a checkpoint of
// either continues in the other, bit for bit: charge_3d (copper and steel with strength, a
// burning explosive) stopped at cycle 70 of 89, from half the ranks.
TEST(ModuleRestart, StressSetsCrossLayoutsBitwise) {
  const int n = world_size();
  for (const char* from : {"compact", "dense"}) {
    const std::string to = std::string(from) == "compact" ? "dense" : "compact";
    const Case a{"charge_3d.yaml",
                 {"time.end=1.0", "output.write=false", std::string("numerics.layout=") + from},
                 true,
                 70};
    const Case b{"charge_3d.yaml",
                 {"time.end=1.0", "output.write=false", "numerics.layout=" + to},
                 true,
                 70};
    const Snapshot straight = straight_run(a);
    SharedDir dir;
    MPI_Comm half;
    MPI_Comm_split(MPI_COMM_WORLD, world_rank() < (n + 1) / 2 ? 0 : MPI_UNDEFINED, world_rank(),
                   &half);
    const std::string ckpt = run_to_checkpoint(a, a.checkpoint_cycle, half, dir.path);
    if (half != MPI_COMM_NULL) MPI_Comm_free(&half);
    ASSERT_FALSE(ckpt.empty());
    RunSettings settings;
    settings.quiet = true;
    settings.restart_allow = {"numerics.layout"};
    Simulation sim(test::load_scene(b.file, b.set), MPI_COMM_WORLD, settings);
    sim.restart(ckpt);
    const RunResult r = sim.run();
    EXPECT_TRUE(r.ok);
    EXPECT_EQ(r.ending, Ending::EndTime);
    expect_identical(straight, snapshot(sim), std::string(from) + " -> " + to);
  }
}

// A restart where cells' material sets changed between the start and the checkpoint: charge_3d at
// 48 x 24 x 24 cells, where some cells near the charge's edge cross the "at least half
// explosive" line before cycle 2. The lighting times are built from the materials as painted;
// before 2026-12-06 a restart rebuilt them from the restarted materials, and lighting_time
// differed in ~1,400 of 27,648 cells (up to 0.061 us), every other field following. Checkpoints
// at cycles 2, 10 and 40 written on all the ranks, continued on 3, 2 and 1 ranks (the longest
// leg on the most ranks: 24.1 s where 1, 2, 3 took 26.2), in both layouts, to t = 0.5 us
// (cycle 69): every field (lighting_time among them, a checkpointed field now) equal to the
// straight run's, bit for bit. The end is where the rebuilt lighting times show in the flow: with
// the rebuild put back (2026-12-07), rho and burn_fraction differ in ~7,900 and ~6,100 cells at
// every leg at t = 0.5; at t = 0.12 (cycle 51) only lighting_time itself differed. (t = 1.2, cycle
// 99, took 27.6 s on 4 oversubscribed ranks of the 2-core VM; 0.5 takes 20.7 s.)
TEST(ModuleRestart, MaterialSetChangedBeforeTheCheckpointIsBitwiseEqual) {
  const int n = world_size();
  if (n < 3) GTEST_SKIP() << "needs 3 or more ranks (the np4 instance runs it)";
  for (const char* layout : {"dense", "compact"}) {
    const Case c{"charge_3d.yaml",
                 {"mesh.cells=[48,24,24]", "time.end=0.5", "output.write=false",
                  std::string("numerics.layout=") + layout},
                 true,
                 40};
    const Snapshot straight = straight_run(c);
    SharedDir dir;
    {
      auto d = c.set;
      d.push_back("time.max_cycles=40");
      d.push_back("output.checkpoint_every={cycles: 2}");
      d.push_back("output.checkpoint_keep=20");
      RunSettings settings;
      settings.quiet = true;
      settings.output_dir = dir.path;
      Simulation sim(test::load_scene(c.file, d), MPI_COMM_WORLD, settings);
      sim.initialize();
      // the explosive's (material 1's) volume fraction as painted and at cycle 40: the cells
      // that crossed the "at least half explosive" line that the lighting times are built on
      auto explosive = [&] {
        for (const auto& f : sim.checkpoint_fields())
          if (f.name == "alpha_1") return test::gather(sim.mesh(), f.view, f.centering);
        return std::vector<double>();
      };
      const std::vector<double> before = explosive();
      ASSERT_EQ(sim.run().ending, Ending::MaxCycles);
      const std::vector<double> after = explosive();
      if (world_rank() == 0) {
        ASSERT_EQ(before.size(), after.size());
        long crossed = 0;
        for (std::size_t q = 0; q < before.size(); ++q)
          crossed += (before[q] >= 0.5) != (after[q] >= 0.5) ? 1 : 0;
        std::printf("  %s: %ld cells crossed the half-explosive line by cycle 40\n", layout,
                    crossed);
        EXPECT_GT(crossed, 0) << "the material sets did not change: the test tests nothing";
      }
    }
    const std::vector<std::pair<long, int>> legs = {{2, 3}, {10, 2}, {40, 1}};
    for (const auto& [at, ranks] : legs) {
      MPI_Comm part;
      MPI_Comm_split(MPI_COMM_WORLD, world_rank() < ranks ? 0 : MPI_UNDEFINED, world_rank(), &part);
      const Snapshot restarted =
          restarted_run(c, checkpoint_path(dir.path, "charge_3d", at), at, part);
      if (part != MPI_COMM_NULL) MPI_Comm_free(&part);
      if (world_rank() == 0)
        expect_identical(straight, restarted,
                         std::string(layout) + " cycle " + std::to_string(at) + " " +
                             std::to_string(n) + "->" + std::to_string(ranks));
      test::rest_until_all();
    }
  }
}

// A checkpoint without a field this build checkpoints (one written before lighting times were
// checkpointed) is refused, naming the field, since a restart cannot rebuild it exactly.
TEST(RestartRefusal, CheckpointWithoutLightingTimesIsRefusedNamingThem) {
  const Case c{"charge_3d.yaml", {"output.write=false"}, true, 10};
  SharedDir dir;
  std::string ckpt;
  {
    auto d = c.set;
    d.push_back("time.max_cycles=10");
    d.push_back("output.checkpoint_every={cycles: 10}");
    RunSettings settings;
    settings.quiet = true;
    settings.output_dir = dir.path;
    Simulation sim(test::load_scene(c.file, d), MPI_COMM_WORLD, settings);
    sim.initialize();
    const RunResult r = sim.run();
    ASSERT_EQ(r.checkpoints.size(), 1u);
    ckpt = r.checkpoints.back();
  }
  if (world_rank() == 0) {
    const hid_t f = H5Fopen(ckpt.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    EXPECT_GE(H5Ldelete(f, "lighting_time", H5P_DEFAULT), 0);
    H5Fclose(f);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(test::load_scene(c.file, c.set), MPI_COMM_WORLD, settings);
  std::string what;
  try {
    sim.restart(ckpt);
  } catch (const InputError& e) {
    what = e.what();
  }
  if (world_rank() == 0) std::printf("  refused: %s\n", what.c_str());
  EXPECT_NE(what.find("holds no 'lighting_time'"), std::string::npos) << what;
}

// The message of the InputError with which sim.restart(ckpt) refuses the checkpoint (printed
// from rank 0); a failure, and "", when it accepts it.
std::string refusal(Simulation& sim, const std::string& ckpt) {
  try {
    sim.restart(ckpt);
  } catch (const InputError& e) {
    if (world_rank() == 0) std::printf("  refused: %s\n", e.what());
    return e.what();
  }
  ADD_FAILURE() << "the checkpoint was accepted";
  return "";
}

TEST(RestartRefusal, AnotherDeckIsRefusedNamingTheKey) {
  SharedDir dir;
  const std::string ckpt = run_to_checkpoint(triple_point("compact"), 5, MPI_COMM_WORLD, dir.path);
  auto d = deck("compact");
  d.push_back("time.cfl=0.4");
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(test::load_scene("triple_point.yaml", d), MPI_COMM_WORLD, settings);
  const std::string msg = refusal(sim, ckpt);
  EXPECT_NE(msg.find("time.cfl: '0.5' in the checkpoint, '0.4' here"), std::string::npos) << msg;
}

// --restart-allow: a numerics.* or time.* key may differ when named, and the change is kept in
// the run's result; one not named is still refused. Changing the layout from compact to dense
// continues the same solution, bit for bit (the layouts agree bitwise).
TEST(RestartRefusal, AllowedKeysAreKeptAndTheRunGoesOn) {
  SharedDir dir;
  const Case c = triple_point("compact");
  const std::string ckpt = run_to_checkpoint(c, 5, MPI_COMM_WORLD, dir.path);
  const std::string layout_line = "numerics.layout: 'compact' in the checkpoint, 'dense' here";
  {
    auto d = deck("dense");
    d.push_back("time.cfl=0.4");
    RunSettings settings;
    settings.quiet = true;
    settings.restart_allow = {"time.*"};
    Simulation sim(test::load_scene("triple_point.yaml", d), MPI_COMM_WORLD, settings);
    const std::string msg = refusal(sim, ckpt);
    EXPECT_NE(msg.find(layout_line), std::string::npos) << msg;
    EXPECT_EQ(msg.find("time.cfl"), std::string::npos) << "an allowed key refused: " << msg;
    EXPECT_NE(msg.find("1 difference;"), std::string::npos) << msg;
  }
  const Snapshot straight = straight_run(c);
  RunSettings settings;
  settings.quiet = true;
  settings.restart_allow = {"numerics.layout"};  // an exact key (the refusal above: a prefix)
  settings.output_dir = dir.path;                // (for the checkpoint written below)
  Simulation sim(test::load_scene("triple_point.yaml", deck("dense")), MPI_COMM_WORLD, settings);
  sim.restart(ckpt);
  const RunResult r = sim.run();
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.ending, Ending::EndTime);
  ASSERT_EQ(r.restart_changes.size(), 1u);
  EXPECT_EQ(r.restart_changes[0], layout_line);
  expect_identical(straight, snapshot(sim), "compact -> dense restart");
  // A checkpoint written after the change carries it: a restart from there (no change now)
  // reports the run's history.
  const std::string later = sim.write_checkpoint_now();
  RunSettings plain;
  plain.quiet = true;
  Simulation again(test::load_scene("triple_point.yaml", deck("dense")), MPI_COMM_WORLD, plain);
  again.restart(later);
  const RunResult r2 = again.run();
  EXPECT_TRUE(r2.restart_changes.empty());
  ASSERT_EQ(r2.restart_history.size(), 1u);
  EXPECT_EQ(r2.restart_history[0], "cycle 5: " + layout_line);
}

TEST(RestartRefusal, AllowPatternsOnlyForNumericsAndTime) {
  for (const char* ok : {"numerics.*", "numerics.ke_fix", "time.*", "time.cfl"})
    EXPECT_EQ(restart_allow_error(ok), "") << ok;
  for (const char* bad : {"mesh.zone", "materials.*", "regions.0.density", "numerics*", "*",
                          "numerics.", "time.c*", "numerics", "time", ""}) {
    const std::string why = restart_allow_error(bad);
    EXPECT_NE(why.find("--restart-allow " + std::string(bad) + ": only numerics.* and time.*"),
              std::string::npos)
        << "'" << bad << "': " << why;
  }
}

// Rewrites a checkpoint's metadata on rank 0 (as another build would have written it).
void edit_meta(const std::string& ckpt, const std::function<void(nlohmann::json&)>& edit) {
  if (world_rank() == 0) {
    h5::Handle file;
    HDF5_CHECK(file.reset(H5Fopen(ckpt.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose));
    auto meta = nlohmann::json::parse(h5::read_string_attribute(file.get(), "meta"));
    edit(meta);
    HDF5_CHECK(H5Adelete(file.get(), "meta"));
    h5::write_string_attribute(file.get(), "meta", meta.dump());
    HDF5_CHECK(file.close());
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

TEST(RestartRefusal, AnotherBuildIsRefusedNamingIt) {
  SharedDir dir;
  const std::string ckpt = run_to_checkpoint(triple_point("compact"), 5, MPI_COMM_WORLD, dir.path);
  // Rewrite the metadata as a build of the other precision would have written it.
  const std::string other = sizeof(Real) == 8 ? "float" : "double";
  edit_meta(ckpt, [&](nlohmann::json& m) { m["real"] = other; });
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(test::load_scene("triple_point.yaml", deck("compact")), MPI_COMM_WORLD, settings);
  try {
    sim.restart(ckpt);
    ADD_FAILURE() << "a checkpoint of another build was accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    if (world_rank() == 0) std::printf("  refused: %s\n", msg.c_str());
    EXPECT_NE(msg.find("with Real = " + other), std::string::npos) << msg;
  }
}

// A checkpoint records the numerics as resolved, defaults included: a build whose default
// differs (here the KE fix's shares, whose default became `mass` on 2026-12-03) is refused
// although neither deck names the key; --restart-allow takes the change. Setting a key to the
// value the checkpoint resolved is no difference. (Until 2026-12-03 only the deck's own keys
// were compared, and such a restart changed the numerics silently.)
TEST(RestartRefusal, ChangedDefaultIsRefusedNamingTheKey) {
  SharedDir dir;
  const std::string ckpt = run_to_checkpoint(triple_point("compact"), 5, MPI_COMM_WORLD, dir.path);
  RunSettings settings;
  settings.quiet = true;
  {  // the key set to the default it resolved to: accepted, no change reported
    auto d = deck("compact");
    d.push_back("numerics.ke_fix_share=mass");
    Simulation sim(test::load_scene("triple_point.yaml", d), MPI_COMM_WORLD, settings);
    sim.restart(ckpt);
    const RunResult r = sim.run();
    EXPECT_TRUE(r.ok);
    EXPECT_TRUE(r.restart_changes.empty());
  }
  edit_meta(ckpt, [](nlohmann::json& m) {
    ASSERT_TRUE(m.contains("resolved"));
    ASSERT_EQ(m["resolved"]["numerics.ke_fix_share"], "mass");
    m["resolved"]["numerics.ke_fix_share"] = "equal";
  });
  const std::string line =
      "numerics.ke_fix_share: 'equal' in the checkpoint, 'mass' (this build's default) here";
  {
    Simulation sim(test::load_scene("triple_point.yaml", deck("compact")), MPI_COMM_WORLD,
                   settings);
    const std::string msg = refusal(sim, ckpt);
    EXPECT_NE(msg.find(line), std::string::npos) << msg;
    EXPECT_NE(msg.find("1 difference;"), std::string::npos) << msg;
  }
  settings.restart_allow = {"numerics.ke_fix_share"};
  Simulation sim(test::load_scene("triple_point.yaml", deck("compact")), MPI_COMM_WORLD, settings);
  sim.restart(ckpt);
  const RunResult r = sim.run();
  EXPECT_TRUE(r.ok);
  ASSERT_EQ(r.restart_changes.size(), 1u);
  EXPECT_EQ(r.restart_changes[0], line);
}

// A checkpoint written before the resolved numerics were recorded restarts (its deck's own
// keys are still compared) and continues the same solution bit for bit.
TEST(RestartRefusal, CheckpointWithoutResolvedNumericsStillRestarts) {
  SharedDir dir;
  const Case c = triple_point("compact");
  const std::string ckpt = run_to_checkpoint(c, 5, MPI_COMM_WORLD, dir.path);
  edit_meta(ckpt, [](nlohmann::json& m) { m.erase("resolved"); });
  RunSettings settings;
  settings.quiet = true;
  {
    auto d = deck("compact");
    d.push_back("time.cfl=0.4");
    Simulation sim(test::load_scene("triple_point.yaml", d), MPI_COMM_WORLD, settings);
    const std::string msg = refusal(sim, ckpt);
    EXPECT_NE(msg.find("time.cfl: '0.5' in the checkpoint, '0.4' here"), std::string::npos) << msg;
  }
  Simulation sim(test::load_scene("triple_point.yaml", deck("compact")), MPI_COMM_WORLD, settings);
  sim.restart(ckpt);
  const RunResult r = sim.run();
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(r.restart_changes.empty());
  expect_identical(straight_run(c), snapshot(sim), "restart without resolved numerics");
}

TEST(Checkpoints, KeepsTheNewest) {
  SharedDir dir;
  auto d = deck("compact");
  d.push_back("time.max_cycles=20");
  d.push_back("output.checkpoint_every={cycles: 4}");
  d.push_back("output.checkpoint_keep=2");
  RunSettings settings;
  settings.quiet = true;
  settings.output_dir = dir.path;
  Simulation sim(test::load_scene("triple_point.yaml", d), MPI_COMM_WORLD, settings);
  sim.initialize();
  const RunResult r = sim.run();
  const auto left = list_checkpoints(dir.path, "triple_point");
  std::vector<long> cycles;
  for (const auto& c : left) cycles.push_back(c.first);
  if (world_rank() == 0)
    std::printf("  wrote %zu checkpoints, kept cycles %s\n", r.checkpoints.size(),
                ::testing::PrintToString(cycles).c_str());
  EXPECT_EQ(r.checkpoints.size(), 5u);  // cycles 4, 8, 12, 16 and 20 (the stop)
  EXPECT_EQ(cycles, (std::vector<long>{16, 20}));
}

TEST(Checkpoints, WallClockIntervalWritesEveryDueCycleOnEveryRank) {
  // checkpoint_every.seconds: with 1 ns every cycle is due on every rank, and a checkpoint is
  // written at each of the 6 cycles (was named WallClockFollowsTheSlowestRank, which this
  // cannot show: no rank's clock lags another's here; issue #55).
  SharedDir dir;
  auto d = deck("dense");
  d.push_back("time.max_cycles=6");
  d.push_back("output.checkpoint_every={seconds: 1.0e-9}");
  d.push_back("output.checkpoint_keep=10");
  RunSettings settings;
  settings.quiet = true;
  settings.output_dir = dir.path;
  Simulation sim(test::load_scene("triple_point.yaml", d), MPI_COMM_WORLD, settings);
  sim.initialize();
  const RunResult r = sim.run();
  std::vector<long> cycles;
  for (const auto& c : list_checkpoints(dir.path, "triple_point")) cycles.push_back(c.first);
  if (world_rank() == 0)
    std::printf("  checkpoints by wall clock at cycles %s\n",
                ::testing::PrintToString(cycles).c_str());
  EXPECT_EQ(cycles, (std::vector<long>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(r.checkpoints.size(), 6u);
}

}  // namespace
