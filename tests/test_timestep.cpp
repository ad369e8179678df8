// Time-step limits (Hydro::time_step, kernels/hydro/diagnostics.cpp; docs/numerics.md step 1):
// each limit is hit on purpose and must give its exact dt and its name — the per-axis CFL bound
// (with the viscous signal speed and the node speeds), the unsplit remap's Courant sum, growth,
// dt_max, the end time — and, through the executable's log, the first step held at
// time.dt_initial and the sequence initial -> growth -> max -> end.
//
// The expected CFL and Courant-sum steps are recomputed here on the host from the gathered
// fields with the definitions (in Real, the operations in the same order, so the bits agree):
//   c_eff = sqrt(c^2 + 2 q / rho), v_d = max over the cell's 8 nodes of |velocity_d|,
//   dt = cfl * min(min_d dx_d / (c_eff + v_d + 1e-30), [unsplit] 1 / (sum_d v_d / dx_d + 1e-30)).
// and the other two time.rule values (numerics.hpp StepRule) likewise: separate
//   dt = min_d min(cfl dx_d / (c_eff + 1e-30), cfl_u dx_d / (v_d + 1e-30)),
//   [unsplit] cfl_u / (sum_d v_d / dx_d + 1e-30) (either rule),
// and cloverleaf (CloverLeaf3D_ref's calc_dt_kernel), with f_d-, f_d+ the means of the velocity
// component d over the 4 nodes of the cell's low and high faces normal to d:
//   dt = min(cfl min_d dx_d / (c_eff + 1e-30), min_d cfl_u dx_d / (max|f_d+-| + 1e-30),
//            cfl_u / (|sum_d (f_d+ - f_d-) / dx_d| + 1e-30)).
#include <gtest/gtest.h>
#include <mpi.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/math.hpp"
#include "support.hpp"

namespace fs = std::filesystem;
using namespace mp;

namespace {

int world_size() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

struct HostStep {
  Real dt = FLT_MAX;
  std::string limit;                         // "cfl" or "courant_sum"
  std::vector<std::array<int, 3>> limiting;  // every cell attaining dt (ties)
};

HostStep host_step(Simulation& sim) {
  const Mesh& m = sim.mesh();
  const auto& s = sim.hydro().state();
  const auto& opt = sim.hydro().options();
  const auto C = Centering::Cell, N = Centering::Node;
  const auto c = test::gather(m, s.c, C), q = test::gather(m, s.q, C),
             rho = test::gather(m, s.rho, C);
  const std::vector<double> vel[3] = {test::gather(m, s.u, N), test::gather(m, s.v, N),
                                      test::gather(m, s.w, N)};
  const long nx = m.global_cells(0), ny = m.global_cells(1), nz = m.global_cells(2);
  const Real* dx = m.geometry().dx;
  HostStep h;
  for (long k = 0; k < nz; ++k)
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        const long cell = i + nx * (j + ny * k);
        const Real cc = Real(c[cell]), qq = Real(q[cell]), rr = Real(rho[cell]);
        const Real ceff = msqrt(cc * cc + 2 * qq / rr);
        Real vmax[3] = {0, 0, 0};
        for (int d = 0; d < 3; ++d)
          for (int z = 0; z < 2; ++z)
            for (int y = 0; y < 2; ++y)
              for (int x = 0; x < 2; ++x) {
                const long node = (i + x) + (nx + 1) * ((j + y) + (ny + 1) * (k + z));
                vmax[d] = mmax(vmax[d], mabs(Real(vel[d][node])));
              }
        Real dt = FLT_MAX;
        if (opt.rule != hydro::StepRule::Combined) {
          const Real cu = opt.cfl_transport;
          if (opt.rule == hydro::StepRule::Separate) {
            for (int d = 0; d < 3; ++d)
              dt = mmin(dt, mmin(opt.cfl * dx[d] / (ceff + Real(1e-30)),
                                 cu * dx[d] / (vmax[d] + Real(1e-30))));
          } else {
            // the face means, summed in the kernel's order of the 4 nodes
            const auto v = [&](int d, long a, long b, long cc2) {
              return Real(vel[d][a + (nx + 1) * (b + (ny + 1) * cc2)]);
            };
            Real lo[3], hi[3];
            for (int side = 0; side < 2; ++side) {
              Real* f = side == 0 ? lo : hi;
              f[0] = Real(0.25) * (v(0, i + side, j, k) + v(0, i + side, j + 1, k) +
                                   v(0, i + side, j, k + 1) + v(0, i + side, j + 1, k + 1));
              f[1] = Real(0.25) * (v(1, i, j + side, k) + v(1, i + 1, j + side, k) +
                                   v(1, i, j + side, k + 1) + v(1, i + 1, j + side, k + 1));
              f[2] = Real(0.25) * (v(2, i, j, k + side) + v(2, i + 1, j, k + side) +
                                   v(2, i, j + 1, k + side) + v(2, i + 1, j + 1, k + side));
            }
            dt = opt.cfl * mmin(dx[0], mmin(dx[1], dx[2])) / (ceff + Real(1e-30));
            for (int d = 0; d < 3; ++d)
              dt = mmin(dt, cu * dx[d] / (mmax(mabs(lo[d]), mabs(hi[d])) + Real(1e-30)));
            const Real div =
                (hi[0] - lo[0]) / dx[0] + (hi[1] - lo[1]) / dx[1] + (hi[2] - lo[2]) / dx[2];
            dt = mmin(dt, cu / (mabs(div) + Real(1e-30)));
          }
          bool sum = false;
          if (opt.unsplit) {
            const Real dt_sum =
                cu / (vmax[0] / dx[0] + vmax[1] / dx[1] + vmax[2] / dx[2] + Real(1e-30));
            if (dt_sum < dt) {
              dt = dt_sum;
              sum = true;
            }
          }
          if (dt < h.dt) {
            h.dt = dt;
            h.limit = sum ? "courant_sum" : "cfl";
            h.limiting.clear();
          }
          if (dt == h.dt) h.limiting.push_back({int(i), int(j), int(k)});
          continue;
        }
        for (int d = 0; d < 3; ++d) dt = mmin(dt, dx[d] / (ceff + vmax[d] + Real(1e-30)));
        bool sum = false;
        if (opt.unsplit) {
          const Real dt_sum =
              1 / (vmax[0] / dx[0] + vmax[1] / dx[1] + vmax[2] / dx[2] + Real(1e-30));
          if (dt_sum < dt) {
            dt = dt_sum;
            sum = true;
          }
        }
        dt *= opt.cfl;
        // the combined acoustic-viscous bound where the viscosity acts (b = c_L c)
        const Real b = qq > 0 ? opt.q_linear * cc : Real(0);
        const Real cv = b + msqrt(b * b + ceff * ceff);
        for (int d = 0; d < 3; ++d) dt = mmin(dt, dx[d] / (cv + vmax[d] + Real(1e-30)));
        if (dt < h.dt) {
          h.dt = dt;
          h.limit = sum ? "courant_sum" : "cfl";
          h.limiting.clear();
        }
        if (dt == h.dt) h.limiting.push_back({int(i), int(j), int(k)});
      }
  return h;
}

std::unique_ptr<Simulation> make(const std::string& deck, const std::vector<std::string>& ov) {
  RunSettings settings;
  settings.quiet = true;
  auto sim = std::make_unique<Simulation>(test::load_scene(deck, ov), MPI_COMM_WORLD, settings);
  sim->initialize();
  return sim;
}

std::string cell_text(const std::array<int, 3>& c) {
  return std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]);
}

// The step of the code against the host's: same bits, same name, a limiting cell.
void expect_host_step(const hydro::TimeStep& ts, const HostStep& h, const std::string& label) {
  bool listed = false;
  for (const auto& c : h.limiting) listed = listed || c == ts.cell;
  std::printf("%s: dt %.17g (%s at %s), host %.17g (%s, %zu cell%s)\n", label.c_str(),
              double(ts.dt), mp::hydro::dt_limit_name(ts.limit), cell_text(ts.cell).c_str(),
              double(h.dt), h.limit.c_str(), h.limiting.size(),
              h.limiting.size() == 1 ? "" : "s tied");
  EXPECT_EQ(ts.dt, h.dt) << label;
  EXPECT_EQ(mp::hydro::dt_limit_name(ts.limit), h.limit) << label;
  EXPECT_TRUE(listed) << label << ": cell " << cell_text(ts.cell) << " does not attain the minimum";
}

TEST(TimeStep, SoundSpeedLimitNamesTheHotCell) {
  // Sedov on 8^3 (dx = 0.15) with the deposit sphere grown to r = 0.15: cell (0,0,0) holds the
  // largest share of it, the one hottest cell; at rest, q = 0.
  auto sim = make("sedov.yaml", {"mesh.cells=[8,8,8]", "regions.1.radius=0.15"});
  const hydro::TimeStep ts = sim->hydro().time_step(0, 0, 1e30);
  const HostStep h = host_step(*sim);
  expect_host_step(ts, h, "sound speed");
  EXPECT_EQ(h.limiting.size(), 1u);
  EXPECT_EQ(ts.cell, (std::array<int, 3>{0, 0, 0}));
  EXPECT_STREQ(mp::hydro::dt_limit_name(ts.limit), "cfl");
}

TEST(TimeStep, ViscosityAndNodeSpeedEnterTheLimit) {
  // A Sod tube after 10 cycles (cubic cells, dx = 0.02): moving nodes and a viscous shock. The
  // host recomputation with the definitions must agree bit for bit, and the viscous and node
  // speed terms must matter: the sound speed alone would allow a longer step.
  auto sim =
      make("sod_x.yaml", {"mesh.cells=[50,2,2]", "mesh.hi=[1,0.04,0.04]", "time.max_cycles=10"});
  sim->run();
  const hydro::TimeStep ts = sim->hydro().time_step(0, 0, 1e30);
  const HostStep h = host_step(*sim);
  expect_host_step(ts, h, "after 10 cycles");
  // the same cells with the sound speed alone
  const Mesh& m = sim->mesh();
  const auto c = test::gather(m, sim->hydro().state().c, Centering::Cell);
  double cmax = 0;
  for (double x : c) cmax = std::max(cmax, x);
  const double dt_sound = sim->hydro().options().cfl * m.dx(0) / cmax;
  std::printf("  sound speed alone would allow %.6e; the limit is %.4f of it\n", dt_sound,
              double(ts.dt) / dt_sound);
  EXPECT_LT(double(ts.dt), 0.99 * dt_sound);
}

// The three time.rule values on one state (a Sod tube after 10 cycles under the default rule,
// cloverleaf: moving nodes, a viscous shock): each step equals its host recomputation bit for
// bit; the
// combined rule's is the shortest (it adds |u| to c_eff), and the separate and CloverLeaf rules
// allow more (each cell's separate limits both exceed cfl dx / (c_eff + |u|); CloverLeaf's face
// means are at most the corner maxima; observed ratios in the printout).
TEST(TimeStep, EachRuleMatchesItsDefinition) {
  auto sim =
      make("sod_x.yaml", {"mesh.cells=[50,2,2]", "mesh.hi=[1,0.04,0.04]", "time.max_cycles=10"});
  sim->run();
  const Real cu = sim->hydro().options().cfl_transport;
  sim->hydro().set_time_rule(hydro::StepRule::Combined, cu);
  const hydro::TimeStep comb = sim->hydro().time_step(0, 0, 1e30);
  expect_host_step(comb, host_step(*sim), "combined");
  for (const auto rule : {hydro::StepRule::Separate, hydro::StepRule::CloverLeaf}) {
    sim->hydro().set_time_rule(rule, cu);
    const hydro::TimeStep ts = sim->hydro().time_step(0, 0, 1e30);
    const char* name = rule == hydro::StepRule::Separate ? "separate" : "cloverleaf";
    expect_host_step(ts, host_step(*sim), name);
    std::printf("  %s / combined: %.4f\n", name, double(ts.dt / comb.dt));
    EXPECT_GT(ts.dt, comb.dt) << name;
  }
  sim->hydro().set_time_rule(hydro::StepRule::CloverLeaf, cu);
}

// A uniform stream (c = 0.0374, u = 10 along x, periodic): the transport limit binds. Separate:
// cfl_u dx / |u|; CloverLeaf: the same from the face means (all equal to u), and its divergence
// limit is idle (div u = 0); the combined rule cfl dx / (c + |u|).
TEST(TimeStep, TransportLimitOfEachRule) {
  const std::vector<std::string> flow = {
      "mesh.cells=[20,2,2]",         "mesh.hi=[0.1,0.01,0.01]",     "boundaries.x=periodic",
      "regions.0.velocity=[10,0,0]", "regions.1.velocity=[10,0,0]", "regions.0.pressure=1e-3",
      "regions.1.pressure=1e-3",     "time.cfl_transport=0.5"};
  for (const char* rule : {"combined", "separate", "cloverleaf"}) {
    auto ov = flow;
    ov.push_back(std::string("time.rule=") + rule);
    auto sim = make("sod_x.yaml", ov);
    const hydro::TimeStep ts = sim->hydro().time_step(0, 0, 1e30);
    expect_host_step(ts, host_step(*sim), rule);
    const Real dx = sim->mesh().dx(0), cfl = sim->hydro().options().cfl;
    if (std::string(rule) == "combined") {
      EXPECT_LT(ts.dt, cfl * dx / Real(10));
    } else {
      EXPECT_EQ(ts.dt, Real(0.5) * dx / (Real(10) + Real(1e-30))) << rule;
    }
  }
}

// The defaults (numerics.hpp StepControl; docs/numerics.md "Time step"): the cloverleaf rule,
// and the transport factor the deck's cfl unless the deck gives its own; the same through
// Options built without a deck (StepControl's cfl_transport 0 stands for the cfl).
TEST(TimeStep, DefaultRuleAndTransportFactor) {
  auto a = make("sod_x.yaml", {"mesh.cells=[20,2,2]", "time.cfl=0.3"});
  EXPECT_TRUE(a->hydro().options().rule == hydro::StepRule::CloverLeaf);
  EXPECT_EQ(a->hydro().options().cfl_transport, Real(0.3));
  auto b = make("sod_x.yaml", {"mesh.cells=[20,2,2]", "time.cfl=0.3", "time.cfl_transport=0.5"});
  EXPECT_EQ(b->hydro().options().cfl_transport, Real(0.5));
  hydro::StepControl sc;
  sc.cfl = 0.7;
  EXPECT_EQ(hydro::Options(hydro::Numerics{}, sc).cfl_transport, Real(0.7));
  sc.cfl_transport = 0.25;
  EXPECT_EQ(hydro::Options(hydro::Numerics{}, sc).cfl_transport, Real(0.25));
}

// CloverLeaf's divergence limit: the 123 problem at its start (u = -2 | +2 about x = 0.5,
// c = 0.75) with cfl_transport 0.1, so the flow limits bind rather than the sound. The separate
// rule takes 0.1 dx / max|u| = 0.05 dx in every cell (all 160 tie). CloverLeaf's transport limit
// is the same in every cell, but its divergence limit 0.1 / |div u| acts only in the two cells
// beside the split, whose faces move apart at 2 / dx (the node at 0.5 at rest): there it is
// 0.05 dx too, 1 ulp below the transport limit's rounding (observed 0.00125 against
// 0.0012500000000000002), so the limiting cells are those 8 (2 x 2 x 2). Both steps match their
// host recomputations bit for bit (the limiting cells are asserted in double builds).
TEST(TimeStep, DivergenceLimitOfCloverLeafRule) {
  const Real dx = Real(1) / 40;
  for (const char* rule : {"separate", "cloverleaf"}) {
    auto sim = make("test123.yaml", {"mesh.cells=[40,2,2]", "mesh.hi=[1,0.05,0.05]",
                                     "time.cfl_transport=0.1", std::string("time.rule=") + rule});
    const hydro::TimeStep ts = sim->hydro().time_step(0, 0, 1e30);
    const HostStep h = host_step(*sim);
    expect_host_step(ts, h, rule);
    EXPECT_NEAR(double(ts.dt), 0.05 * double(dx), 1e-6 * double(dx)) << rule;
    // (the 1-ulp parting is double's; a float build may round the two limits alike)
    if (sizeof(Real) != 8) continue;
    if (std::string(rule) == "separate") {
      EXPECT_EQ(h.limiting.size(), 160u);
    } else {
      EXPECT_EQ(h.limiting.size(), 8u);
      for (const auto& c : h.limiting) EXPECT_TRUE(c[0] == 19 || c[0] == 20) << cell_text(c);
    }
  }
}

// The linear viscosity's own stability bound of the combined rule (diagnostics.cpp, CflCells;
// the other rules do not apply it, so the runs set time.rule=combined): an undamped acoustic
// wave (configs/elastic_wave.yaml, a 1e-4 cm/us bar on a wall, aluminium with and without
// strength) at the deck's largest cfl. With the step from c_eff alone its total energy grew
// 9.1x at cfl 1.0 with strength and 22.6x / 83.6x at cfl 0.95 / 1.0 without (a node-to-node
// sawtooth at the wave front, inside the solid's energy floor, so the health check never
// fired). With the bound every run keeps the 1.5e-4 that the deck's boundary inflow brings at
// cfl 0.5 (observed 1.4801e-4 in each). At cfl <= 0.8 the bound never binds (b = 0.2 c:
// 1 / (0.2 + sqrt(1.04)) = 0.82), so the decks' steps are unchanged bit for bit (the host
// recomputation above includes it; the other TimeStep tests agree with it to the bit).
TEST(TimeStep, LinearViscosityBoundKeepsAnUndampedWaveStable) {
  for (const auto& ov :
       std::vector<std::vector<std::string>>{{"time.cfl=1.0"},
                                             {"time.cfl=0.95", "materials.0.strength=null"},
                                             {"time.cfl=1.0", "materials.0.strength=null"}}) {
    auto with_rule = ov;
    with_rule.push_back("time.rule=combined");
    auto r = test::run_scene(test::load_scene("elastic_wave.yaml", with_rule));
    ASSERT_TRUE(r.result.ok) << r.result.health.what;
    const double e0 = r.result.start.total(), e1 = r.result.end.total();
    const double change = (e1 - e0) / std::abs(e0);
    std::printf("elastic wave %s%s: %ld cycles, total energy change %.4e\n", ov[0].c_str(),
                ov.size() > 1 ? " (no strength)" : "", r.result.cycles, change);
    EXPECT_LT(std::abs(change), 1e-3);
  }
}

TEST(TimeStep, UnsplitCourantSum) {
  // A cold gas (c = 0.0374) streaming diagonally at 10 cm/us on equal cells, under the default
  // rule (cloverleaf, cfl_transport = cfl = 0.5): each axis alone allows cfl dx / 10, the sum of
  // the three Courant numbers only cfl dx / 30 (observed unsplit / split 1/3).
  const std::vector<std::string> flow = {
      "mesh.cells=[20,2,2]",           "mesh.hi=[0.1,0.01,0.01]",       "boundaries.x=periodic",
      "regions.0.velocity=[10,10,10]", "regions.1.velocity=[10,10,10]", "regions.0.pressure=1e-3",
      "regions.1.pressure=1e-3"};
  auto ov = flow;
  ov.push_back("numerics.remap=unsplit");
  auto sim = make("sod_x.yaml", ov);
  const hydro::TimeStep ts = sim->hydro().time_step(0, 0, 1e30);
  expect_host_step(ts, host_step(*sim), "unsplit, diagonal flow");
  EXPECT_STREQ(mp::hydro::dt_limit_name(ts.limit), "courant_sum");
  const Real dx = sim->mesh().dx(0);
  const Real want = sim->hydro().options().cfl *
                    (1 / (Real(10) / dx + Real(10) / dx + Real(10) / dx + Real(1e-30)));
  EXPECT_EQ(ts.dt, want);
  // the split remap on the same flow is limited per axis
  auto split = make("sod_x.yaml", flow);
  const hydro::TimeStep ts_split = split->hydro().time_step(0, 0, 1e30);
  expect_host_step(ts_split, host_step(*split), "split, diagonal flow");
  EXPECT_STREQ(mp::hydro::dt_limit_name(ts_split.limit), "cfl");
  std::printf("  unsplit / split step: %.6f\n", double(ts.dt / ts_split.dt));
  EXPECT_LT(ts.dt, ts_split.dt);
}

TEST(TimeStep, GrowthMaxAndEnd) {
  auto sim = make("sod_x.yaml", {"mesh.cells=[50,2,2]", "mesh.hi=[1,0.04,0.04]", "time.dt_max=1e-3",
                                 "time.growth=1.5"});
  auto& hy = sim->hydro();
  const HostStep h = host_step(*sim);
  // growth: the previous step was far shorter than the CFL one
  const Real dt_old = Real(1e-6);
  hydro::TimeStep ts = hy.time_step(dt_old, 0, 1e30);
  std::printf("growth: dt %.17g (%s), 1.5 x %.17g\n", double(ts.dt),
              mp::hydro::dt_limit_name(ts.limit), double(dt_old));
  EXPECT_STREQ(mp::hydro::dt_limit_name(ts.limit), "growth");
  EXPECT_EQ(ts.dt, Real(1.5) * dt_old);
  // max: no previous step, the CFL step (0.0085) above dt_max
  ts = hy.time_step(0, 0, 1e30);
  std::printf("max: dt %.17g (%s), CFL step %.17g\n", double(ts.dt),
              mp::hydro::dt_limit_name(ts.limit), double(h.dt));
  EXPECT_GT(h.dt, Real(1e-3));
  EXPECT_STREQ(mp::hydro::dt_limit_name(ts.limit), "max");
  EXPECT_EQ(ts.dt, Real(1e-3));
  // growth beyond dt_max: max wins (applied after growth)
  ts = hy.time_step(Real(9e-4), 0, 1e30);
  EXPECT_STREQ(mp::hydro::dt_limit_name(ts.limit), "max");
  EXPECT_EQ(ts.dt, Real(1e-3));
  // end: less than one step left
  ts = hy.time_step(0, 0.2 - 3e-4, 0.2);
  std::printf("end: dt %.17g (%s), left %.17g\n", double(ts.dt), mp::hydro::dt_limit_name(ts.limit),
              0.2 - (0.2 - 3e-4));
  EXPECT_STREQ(mp::hydro::dt_limit_name(ts.limit), "end");
  EXPECT_EQ(ts.dt, Real(0.2 - (0.2 - 3e-4)));
  // a step that fits is not cut
  ts = hy.time_step(0, 0.1, 0.2);
  EXPECT_STREQ(mp::hydro::dt_limit_name(ts.limit), "max");
}

// ------------------------------------------------------------------------------------------
// Through the executable's log: every cycle line names its limit.

std::string env_or(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct LogLine {
  long cycle;
  double t, dt;
  std::string limit;
};

// Runs the executable on a deck with overrides; returns its exit status and cycle lines.
int run_logged(const std::vector<std::string>& ov, std::vector<LogLine>& lines) {
  std::string name = (fs::temp_directory_path() / "minipagosa_dt_XXXXXX").string();
  if (!mkdtemp(name.data())) return -1;
  const fs::path dir = name;
  std::string cmd = "cd " + quote(dir.string()) +
                    " && env -i PATH=" + quote(env_or("PATH", "/usr/bin:/bin")) +
                    " HOME=" + quote(env_or("HOME", "/tmp"));
  if (std::getenv("LD_LIBRARY_PATH"))
    cmd += " LD_LIBRARY_PATH=" + quote(env_or("LD_LIBRARY_PATH", ""));
  cmd += " OMP_NUM_THREADS=1 OMP_PROC_BIND=false OMP_WAIT_POLICY=passive " +
         quote(test::minipagosa_exe()) + " " + quote(test::source_dir() + "/configs/sod_x.yaml") +
         " --set output.log_every=1";
  for (const auto& o : ov) cmd += " --set " + quote(o);
  cmd += " --output out > log.txt 2>&1 < /dev/null";
  const int raw = std::system(cmd.c_str());
  std::ifstream in(dir / "log.txt");
  std::string line;
  while (std::getline(in, line)) {
    LogLine l{};
    char limit[32] = {0};
    if (std::sscanf(line.c_str(), "cycle %ld t %le dt %le (%31[a-z_] at", &l.cycle, &l.t, &l.dt,
                    limit) == 4) {
      l.limit = limit;
      lines.push_back(l);
    }
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  return raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

TEST(TimeStep, LogNamesEveryLimit) {
  if (world_size() != 1) GTEST_SKIP() << "runs the executable, from a 1-rank test";
  // dt_initial 1e-5, growth x2 per cycle up to dt_max 1e-3 (below the CFL step, 0.0021 on
  // 50 x 2 x 2 cells of the deck's 1 x 0.01 x 0.01 tube), then dt_max until the end at 0.01 cuts
  // the last step: 1e-5 .. 6.4e-4 (7 steps, t = 1.27e-3), 8 steps of 1e-3 (t = 9.27e-3),
  // then 7.3e-4 to the end.
  std::vector<LogLine> lines;
  const int status = run_logged({"mesh.cells=[50,2,2]", "time.dt_initial=1e-5", "time.growth=2",
                                 "time.dt_max=1e-3", "time.end=0.01"},
                                lines);
  ASSERT_EQ(status, 0);
  std::string seq;
  for (const auto& l : lines) {
    std::printf("  cycle %ld dt %.4e %s\n", l.cycle, l.dt, l.limit.c_str());
    seq += l.limit + " ";
  }
  ASSERT_EQ(lines.size(), 16u) << seq;
  EXPECT_EQ(lines[0].limit, "initial");
  EXPECT_NEAR(lines[0].dt, 1e-5, 1e-9);  // the log prints 5 significant digits
  for (int c = 1; c <= 6; ++c) {
    EXPECT_EQ(lines[c].limit, "growth") << c;
    EXPECT_NEAR(lines[c].dt / lines[c - 1].dt, 2.0, 1e-3) << c;
  }
  for (int c = 7; c <= 14; ++c) {
    EXPECT_EQ(lines[c].limit, "max") << c;
    EXPECT_NEAR(lines[c].dt, 1e-3, 1e-7) << c;
  }
  EXPECT_EQ(lines[15].limit, "end");
  EXPECT_NEAR(lines[15].t, 0.01, 1e-9);

  // No dt_max: after the first step the growth reaches the CFL step and stays there.
  lines.clear();
  ASSERT_EQ(run_logged({"mesh.cells=[50,2,2]", "time.dt_initial=1e-3", "time.end=0.05"}, lines), 0);
  ASSERT_GE(lines.size(), 4u);
  EXPECT_EQ(lines[0].limit, "initial");
  EXPECT_EQ(lines[1].limit, "growth");
  std::string tail;
  for (std::size_t c = 2; c + 1 < lines.size(); ++c) tail += lines[c].limit + " ";
  std::printf("  CFL run: %zu cycles, limits after the first two: %s\n", lines.size(),
              tail.c_str());
  EXPECT_NE(tail.find("cfl"), std::string::npos) << tail;

  // The unsplit remap on a diagonal cold flow: the Courant sum limits every step.
  lines.clear();
  ASSERT_EQ(run_logged({"mesh.cells=[20,2,2]", "mesh.hi=[0.1,0.01,0.01]", "boundaries.x=periodic",
                        "regions.0.velocity=[10,10,10]", "regions.1.velocity=[10,10,10]",
                        "regions.0.pressure=1e-3", "regions.1.pressure=1e-3",
                        "numerics.remap=unsplit", "time.dt_initial=1", "time.end=1e-3"},
                       lines),
            0);
  ASSERT_GE(lines.size(), 2u);
  for (std::size_t c = 0; c + 1 < lines.size(); ++c)
    EXPECT_EQ(lines[c].limit, "courant_sum") << "cycle " << lines[c].cycle;
  std::printf("  unsplit run: %zu cycles, first %s dt %.4e\n", lines.size(), lines[0].limit.c_str(),
              lines[0].dt);
}

}  // namespace
