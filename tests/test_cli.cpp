// End to end: the real minipagosa executable (MINIPAGOSA_EXE) run in a fresh temporary
// directory. Bad input exits 2 naming file:line and key, with nothing written; --help and
// --version exit 0; a good run writes its dumps and summary (also on 2 ranks); a run that goes
// non-physical exits 3, names the cell, and still writes the summary.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "paths.hpp"

namespace fs = std::filesystem;

namespace {

std::string env_or(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

std::string exe() {
  return mp::test::minipagosa_exe();
}
std::string source_dir() {
  return mp::test::source_dir();
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool holds(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A small valid deck; tests replace single lines (1-based numbering below).
const std::vector<std::string> kDeck = {
    "scene: cli",           // 1
    "mesh:",                // 2
    "  cells: [8, 2, 2]",   // 3
    "  lo: [0, 0, 0]",      // 4
    "  hi: [1, 0.1, 0.1]",  // 5
    "boundaries:",          // 6
    "  y: periodic",        // 7
    "  z: periodic",        // 8
    "time:",                // 9
    "  end: 0.01",          // 10
    "  cfl: 0.5",           // 11
    "numerics:",            // 12
    "  advection: second",  // 13
    "materials:",           // 14
    "  - name: gas",        // 15
    "    eos: ideal_gas",   // 16
    "    gamma: 1.4",       // 17
    "regions:",             // 18
    "  - material: gas",    // 19
    "    shape: all",       // 20
    "    density: 1.0",     // 21
    "    pressure: 1.0",    // 22
    "  - material: gas",    // 23
    "    shape: box",       // 24
    "    lo: [0, 0, 0]",    // 25
    "    hi: [0.5, 1, 1]",  // 26
    "    density: 2.0",     // 27
    "    pressure: 2.0",    // 28
};

std::string deck(const std::map<int, std::string>& edits = {}) {
  std::string text;
  for (std::size_t i = 0; i < kDeck.size(); ++i) {
    const auto it = edits.find(static_cast<int>(i) + 1);
    text += (it != edits.end() ? it->second : kDeck[i]) + "\n";
  }
  return text;
}

struct Result {
  int status = -1;  // exit status, or -1 if the child did not exit normally
  std::string out, err;
};

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string name = (fs::temp_directory_path() / "minipagosa_cli_XXXXXX").string();
    ASSERT_NE(mkdtemp(name.data()), nullptr);
    dir_ = name;
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure())
      fs::remove_all(dir_, ec);
    else
      std::fprintf(stderr, "kept %s for inspection\n", dir_.c_str());
  }

  // The child's OpenMP binding variables (a test clears them to run as a user who set none).
  std::string omp_bind_ = " OMP_PROC_BIND=false";

  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
  }

  // Runs `launcher exe args...` in the temporary directory, in a clean environment: the child
  // must not inherit the OMPI_*/PMIX_* variables that would make it part of this test's job.
  Result run(const std::vector<std::string>& args, const std::string& launcher = "") const {
    std::string cmd = "cd " + quote(dir_.string()) +
                      " && env -i PATH=" + quote(env_or("PATH", "/usr/bin:/bin")) +
                      " HOME=" + quote(env_or("HOME", "/tmp"));
    if (std::getenv("LD_LIBRARY_PATH"))
      cmd += " LD_LIBRARY_PATH=" + quote(env_or("LD_LIBRARY_PATH", ""));
    cmd +=
        " OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"
        " OMPI_MCA_rmaps_base_oversubscribe=1 OMP_NUM_THREADS=1" +
        omp_bind_ + " OMP_WAIT_POLICY=passive ";
    cmd += launcher + quote(exe());
    for (const auto& a : args) cmd += " " + quote(a);
    cmd += " > .stdout 2> .stderr < /dev/null";
    const int raw = std::system(cmd.c_str());
    Result r;
    if (raw != -1 && WIFEXITED(raw)) r.status = WEXITSTATUS(raw);
    r.out = read(dir_ / ".stdout");
    r.err = read(dir_ / ".stderr");
    fs::remove(dir_ / ".stdout");
    fs::remove(dir_ / ".stderr");
    return r;
  }

  // A bad deck (or command line): exit 2, every one of `parts` on stderr, nothing written.
  void expect_rejected(const std::vector<std::string>& args,
                       const std::vector<std::string>& parts) {
    SCOPED_TRACE(::testing::PrintToString(args));
    std::vector<std::string> full = args;
    full.insert(full.end(), {"--output", "out"});
    const Result r = run(full);
    EXPECT_EQ(r.status, 2) << r.err;
    for (const auto& p : parts) EXPECT_TRUE(holds(r.err, p)) << "'" << p << "' missing: " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << "output written for bad input";
    EXPECT_FALSE(fs::exists(dir_ / "output")) << "deck's output.dir written for bad input";
  }

  fs::path dir_;
};

TEST_F(Cli, HelpAndVersion) {
  Result r = run({"--help"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(holds(r.out, "--set")) << r.out;
  EXPECT_TRUE(holds(r.out, "--output")) << r.out;
  r = run({"--version"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(holds(r.out, "minipagosa")) << r.out;
  // no deck at all is a usage error
  r = run({});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(holds(r.err, "scene")) << r.err;
}

TEST_F(Cli, BaseDeckChecksClean) {
  write("good.yaml", deck());
  const Result r = run({"good.yaml", "--check", "--output", "out"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(Cli, BadDecksExit2AndWriteNothing) {
  write("unknown.yaml", deck({{3, "  cels: [8, 2, 2]"}}));
  expect_rejected({"unknown.yaml"}, {"unknown.yaml:3:", "key 'mesh.cels'", "did you mean 'cells'"});
  write("type.yaml", deck({{11, "  cfl: fast"}}));
  expect_rejected({"type.yaml"}, {"type.yaml:11:", "key 'time.cfl'", "expected a number"});
  write("range.yaml", deck({{17, "    gamma: 0.5"}}));
  expect_rejected({"range.yaml"}, {"range.yaml:17:", "key 'materials.0.gamma'", "out of range"});
  write("enum.yaml", deck({{13, "  advection: thrid"}}));
  expect_rejected({"enum.yaml"}, {"enum.yaml:13:", "key 'numerics.advection'", "second, first"});
  write("mesh.yaml", deck({{5, "  hi: [1, 0, 0.1]"}}));
  expect_rejected({"mesh.yaml"}, {"mesh.yaml:5:", "key 'mesh.hi'", "along y"});
  write("box.yaml", deck({{25, "    lo: [2, 0, 0]"}, {26, "    hi: [3, 1, 1]"}}));
  expect_rejected({"box.yaml"}, {"box.yaml:25:", "key 'regions.1.lo'", "outside the mesh"});
  write("missing.yaml", deck({{10, ""}}));
  expect_rejected({"missing.yaml"}, {"missing.yaml:11:", "key 'time.end'", "missing required"});
  write("syntax.yaml", deck({{11, "  cfl: 0.5: 2"}}));
  expect_rejected({"syntax.yaml"}, {"syntax.yaml:11:", "YAML syntax error"});
}

TEST_F(Cli, MissingFileExit2) {
  expect_rejected({"nosuch.yaml"}, {"nosuch.yaml"});
}

TEST_F(Cli, BadOverridesExit2AndWriteNothing) {
  write("good.yaml", deck());
  expect_rejected({"good.yaml", "--set", "mesh.cells=[0,2,2]"},
                  {"--set mesh.cells=[0,2,2]", "key 'mesh.cells.0'", "out of range"});
  expect_rejected({"good.yaml", "--set", "mesh.cels=[8,2,2]"},
                  {"--set mesh.cels=[8,2,2]", "key 'mesh.cels'", "did you mean 'cells'"});
  expect_rejected({"good.yaml", "--set", "mesh.cells"}, {"--set mesh.cells", "key=value"});
}

TEST_F(Cli, BadRestartAllowExit2AndWriteNothing) {
  write("good.yaml", deck());
  expect_rejected({"good.yaml", "--restart", "latest", "--restart-allow", "mesh.zone"},
                  {"--restart-allow mesh.zone: only numerics.* and time.* keys"});
  expect_rejected({"good.yaml", "--restart-allow", "numerics.*"},
                  {"--restart-allow needs --restart"});
}

TEST_F(Cli, GoodRunWritesDumpsAndSummary) {
  const std::string sod = source_dir() + "/configs/sod_x.yaml";
  const Result r =
      run({sod, "--set", "mesh.cells=[40,2,2]", "--set", "time.end=0.02", "--output", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto summary = nlohmann::json::parse(read(dir_ / "run" / "summary.json"));
  EXPECT_EQ(summary["status"], "completed") << summary;
  EXPECT_EQ(summary["ended_by"], "end time reached") << summary;
  EXPECT_EQ(summary["cells"], (std::vector<int>{40, 2, 2})) << summary;
  const long cycles = summary["cycles"].get<long>();
  const double time = summary["time"].get<double>();
  std::printf("  summary: %ld cycles, t = %.17g (end time %.17g)\n", cycles, time,
              summary["end_time"].get<double>());
  EXPECT_GT(cycles, 0);
  // the last step is cut to land on the end time exactly (Simulation::run), and JSON keeps 17
  // significant digits, so the double round-trips
  EXPECT_EQ(time, 0.02);
  EXPECT_EQ(summary["end_time"].get<double>(), 0.02);
  EXPECT_TRUE(holds(r.out, "done (end time reached)")) << r.out;
  char last[64];
  std::snprintf(last, sizeof last, "sod_x_%06ld.h5", cycles);
  EXPECT_TRUE(fs::exists(dir_ / "run" / "sod_x_000000.h5"));
  EXPECT_TRUE(fs::exists(dir_ / "run" / last)) << last;
  EXPECT_TRUE(fs::exists(dir_ / "run" / "sod_x.xmf"));
  for (const auto& e : fs::directory_iterator(dir_ / "run"))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  EXPECT_FALSE(fs::exists(dir_ / "output")) << "--output ignored";
}

// A user who set no OpenMP binding (neither OMP_PROC_BIND nor OMP_PLACES) gets no Kokkos
// warning: minipagosa sets OMP_PROC_BIND=false, the runtime's own default, and says so in its
// kokkos line (src/core/mpi_env.hpp). One set by the user is left as it is and reported.
TEST_F(Cli, NoKokkosBindingWarningWhenTheUserSetNone) {
  const std::string sod = source_dir() + "/configs/sod_x.yaml";
  omp_bind_ = "";
  const Result r =
      run({sod, "--set", "mesh.cells=[20,2,2]", "--set", "time.end=0.01", "--output", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(holds(r.err, "OMP_PROC_BIND")) << r.err;
  EXPECT_FALSE(holds(r.out, "WARNING")) << r.out;
  EXPECT_TRUE(holds(r.out, "threads not bound (OMP_PROC_BIND unset: set to false")) << r.out;
  omp_bind_ = " OMP_PROC_BIND=spread OMP_PLACES=threads";
  const Result s =
      run({sod, "--set", "mesh.cells=[20,2,2]", "--set", "time.end=0.01", "--output", "run2"});
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_TRUE(holds(s.out, "OMP_PROC_BIND=spread OMP_PLACES=threads")) << s.out;
}

// An end time the run cannot reach: a warning naming time.max_cycles, and an ETA in words, not
// 25 digits of seconds.
TEST_F(Cli, UnreachableEndTimeWarnsAndTheEtaStaysShort) {
  const std::string sod = source_dir() + "/configs/sod_x.yaml";
  const Result r = run({sod, "--set", "mesh.cells=[20,2,2]", "--set", "time.end=1e300", "--set",
                        "time.max_cycles=120", "--set", "output.write=false", "--set",
                        "output.log_every=20", "--output", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(holds(r.err, "warning: time.end 1e+300 is out of reach")) << r.err;
  EXPECT_TRUE(holds(r.err, "time.max_cycles (120) stops the run first")) << r.err;
  EXPECT_TRUE(holds(r.out, "stopped (max_cycles reached)")) << r.out;
  std::stringstream ss(r.out);
  int cycle_lines = 0;
  for (std::string line; std::getline(ss, line);) {
    if (line.compare(0, 6, "cycle ") != 0) continue;
    ++cycle_lines;
    const auto at = line.find("ETA ");
    if (at == std::string::npos) continue;
    EXPECT_LE(line.size() - at, 16u) << line;  // "ETA 12 s", "ETA 3.2 h", "ETA > 1e6 h"
  }
  EXPECT_GE(cycle_lines, 5);
  // a reachable end time gives no warning
  const Result q =
      run({sod, "--set", "mesh.cells=[20,2,2]", "--set", "time.end=0.01", "--output", "run2"});
  ASSERT_EQ(q.status, 0) << q.err;
  EXPECT_FALSE(holds(q.err, "out of reach")) << q.err;
}

TEST_F(Cli, NonPhysicalRunExit3WithSummary) {
  // Converging flow at 100 times the sound speed, no artificial viscosity, a first step at the
  // full CFL limit: the light cell at the collision (x > 0.5, rho 0.125) is crushed at once.
  // The node on the collision starts with the painted momentum of its cells, (1 x 100 - 0.125 x
  // 100) / 1.125 = 77.8, so the light side's first cell, (20, 0, 0), is the one that fails.
  const std::string sod = source_dir() + "/configs/sod_x.yaml";
  const Result r =
      run({sod, "--set", "mesh.cells=[40,2,2]", "--set", "regions.0.velocity=[-100,0,0]", "--set",
           "regions.1.velocity=[100,0,0]", "--set", "numerics.viscosity.linear=0", "--set",
           "numerics.viscosity.quadratic=0", "--set", "time.cfl=1.0", "--set", "time.dt_initial=1",
           "--output", "bad"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(holds(r.err, "non-physical at cycle 1")) << r.err;
  EXPECT_TRUE(holds(r.err, "in cell (20, 0, 0)")) << r.err;
  EXPECT_TRUE(holds(r.err, "density = ")) << r.err;
  EXPECT_TRUE(holds(r.err, "energy = ")) << r.err;
  EXPECT_TRUE(holds(r.err, "pressure = ")) << r.err;
  const auto summary = nlohmann::json::parse(read(dir_ / "bad" / "summary.json"));
  EXPECT_EQ(summary["status"], "non-physical") << summary;
  EXPECT_EQ(summary["ended_by"], "non-physical state") << summary;
  EXPECT_EQ(summary["failure"]["cell"], (std::vector<int>{20, 0, 0})) << summary;
  EXPECT_TRUE(fs::exists(dir_ / "bad" / "sod_x_000001.h5"));
  for (const auto& e : fs::directory_iterator(dir_ / "bad"))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

// The same run on 2 ranks as on 1: the decomposition is bitwise (test_decomp), so the cycle
// count and end time are equal and the totals agree to the round-off of their sums, whose order
// follows the ranks: 160 cells x 2.2e-16 = 3.5e-14 relative if every rounding had one sign
// (bound 5e-14); sqrt(160) x 2.2e-16 = 2.8e-15 for roundings of mixed sign (observed 1.6e-15
// and 1.8e-15).
TEST_F(Cli, GoodRunOnTwoRanks) {
  const std::string sod = source_dir() + "/configs/sod_x.yaml";
  const std::vector<std::string> args = {sod,     "--set",         "mesh.cells=[40,2,2]",
                                         "--set", "time.end=0.02", "--output"};
  auto a1 = args, a2 = args;
  a1.push_back("run1");
  a2.push_back("run2");
  ASSERT_EQ(run(a1).status, 0);
  const Result r = run(a2, "mpiexec -np 2 --oversubscribe ");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto summary = nlohmann::json::parse(read(dir_ / "run2" / "summary.json"));
  const auto one = nlohmann::json::parse(read(dir_ / "run1" / "summary.json"));
  EXPECT_EQ(summary["status"], "completed") << summary;
  EXPECT_EQ(summary["ranks"], 2) << summary;
  EXPECT_EQ(one["ranks"], 1) << one;
  EXPECT_TRUE(fs::exists(dir_ / "run2" / "sod_x.xmf"));
  std::printf("  2 ranks: %ld cycles, t = %.17g; 1 rank: %ld cycles, t = %.17g\n",
              summary["cycles"].get<long>(), summary["time"].get<double>(),
              one["cycles"].get<long>(), one["time"].get<double>());
  EXPECT_EQ(summary["cycles"], one["cycles"]);
  EXPECT_EQ(summary["time"], one["time"]);
  for (const char* key : {"mass", "total_energy"}) {
    const double x = summary["end"][key].get<double>(), y = one["end"][key].get<double>();
    std::printf("  end %-12s 2 ranks %.17g, 1 rank %.17g, relative difference %.2g\n", key, x, y,
                std::abs(x / y - 1));
    EXPECT_LE(std::abs(x / y - 1), 5e-14) << key;
  }
}

}  // namespace
