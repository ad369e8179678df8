// Taylor anvil (issue #12): the OFHC copper cylinder of Johnson & Cook (1983) at 190 m/s onto a
// rigid wall (configs/taylor_anvil.yaml), recovered length and footprint diameter against the
// experiment (tests/exact/taylor_data.hpp). Verification: Zerilli-Armstrong, within the issue's
// 5 % at R/6 and R/8 cells with the footprint error falling. Pins (TaylorPin, label pin):
// Johnson-Cook and Steinberg-Guinan, which miss the 5 %, held near their present errors at R/6.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "exact/taylor_data.hpp"
#include "support.hpp"
#include "taylor_shape.hpp"

using namespace mp;
namespace tx = mp::exact::taylor;

namespace {

constexpr double kRadius = 0.5 * tx::kDiameter0;  // cm
// Cells across the radius of the two resolutions: R/8 runs 1637 cycles of 18x18x56 cells (25 s
// on one rank, one thread; 1670 under the combined step); an R/6 run (1238 cycles of 14x14x42;
// 1263) costs under half of that. One rank: the same digits as two (the code is rank-count
// bitwise, test_decomp), in 36 CPU s where two ranks took 51 (2026-12-07; the second rank's
// MPI waits poll) and held both cores of the CI host.
constexpr int kCoarse = 6, kFine = 8;

struct TaylorRun {
  bool ok = false;
  test::TaylorShape shape;
  double ke_left = NAN;  // kinetic energy at the end / at the start
  double cu_lost = NAN;  // copper mass change / initial copper mass (outflow, clamps)
  double wall_s = NAN;   // wall-clock seconds of the run
  long cycles = 0;
  long cells = 0;
};

// The deck with cubic cells of R/n: at least 2.25 R across (whole cells), 7 R high.
TaylorRun run_taylor(const std::string& model, int n) {
  const int nxy = static_cast<int>(std::ceil(2.25 * n)), nz = 7 * n;
  const double h = kRadius / n;
  const std::string cells = "mesh.cells=[" + std::to_string(nxy) + "," + std::to_string(nxy) + "," +
                            std::to_string(nz) + "]";
  char hi[160];
  std::snprintf(hi, sizeof hi, "mesh.hi=[%.9g,%.9g,%.9g]", nxy * h, nxy * h, nz * h);
  const Scene scene =
      test::load_scene("taylor_anvil.yaml", {cells, hi, "materials.0.strength.model=" + model});
  const auto t0 = std::chrono::steady_clock::now();
  auto r = test::run_scene(scene);
  const auto t1 = std::chrono::steady_clock::now();
  TaylorRun out;
  out.ok = r.result.ok;
  EXPECT_TRUE(r.result.ok) << model << " n " << n << ": " << r.result.health.what;
  if (!r.result.ok) return out;
  const Mesh& m = r.sim->mesh();
  const auto f = test::gather(m, r.sim->hydro().materials()->fraction(0), Centering::Cell);
  out.shape = test::measure_taylor(f, m.global_cells(0), m.global_cells(1), m.global_cells(2),
                                   m.dx(0), m.dx(1), m.dx(2));
  out.ke_left = r.result.end.kinetic / r.result.start.kinetic;
  out.cu_lost = 1 - r.result.end.material_mass.at(0) / r.result.start.material_mass.at(0);
  out.wall_s = std::chrono::duration<double>(t1 - t0).count();
  out.cycles = r.result.cycles;
  out.cells = long(nxy) * nxy * nz;
  return out;
}

double err(double x, double ref) {
  return x / ref - 1;
}

bool rank0() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank == 0;
}

void print(const char* model, int n, const TaylorRun& r) {
  if (!rank0()) return;
  const test::TaylorShape& s = r.shape;
  std::printf(
      "taylor %-16s R/%-2d %7ld cells %5ld cycles %6.1f s | L %.4f cm (%+.2f %%) [column "
      "%.4f, top cell %.4f] | D %.4f cm (%+.2f %%) [area-equivalent %.4f (%+.2f %%)] | KE "
      "left %.2e, Cu mass change %.1e\n",
      model, n, r.cells, r.cycles, r.wall_s, s.length, 100 * err(s.length, tx::kLengthFinal),
      s.length_column, s.length_any, s.footprint, 100 * err(s.footprint, tx::kFootprintDiameter),
      s.footprint_area, 100 * err(s.footprint_area, tx::kFootprintDiameter), r.ke_left, r.cu_lost);
}

// One model at R/n: the run printed and checked for what every model must do (the rod stopped,
// the copper's mass kept); returns the length and footprint errors against the experiment.
struct TaylorErrors {
  double length = NAN, footprint = NAN;
};

TaylorErrors check_model(const char* model, int n) {
  if (rank0())
    std::printf(
        "taylor experiment (Johnson & Cook 1983): L0 %.3f cm, D0 %.3f cm, %.0f m/s -> "
        "L %.4f cm, footprint D %.4f cm\n",
        tx::kLength0, tx::kDiameter0, tx::kSpeed * 1e4, tx::kLengthFinal, tx::kFootprintDiameter);
  const TaylorRun run = run_taylor(model, n);
  if (!run.ok) return {};
  print(model, n, run);
  // The rod has stopped: at most 1e-3 of the impact's kinetic energy is left (observed
  // 2026-12-06: Johnson-Cook 2.08e-4 at R/6, Steinberg-Guinan 4.14e-4 at R/6, Zerilli-Armstrong
  // 9.9e-5 at R/6 and R/8, the elastic ringing of the recovered rod).
  EXPECT_LT(run.ke_left, 1e-3) << model << " R/" << n;
  // No copper left the mesh (the box is sized so the rod stays inside) and, at the default
  // min_fraction, none is handed to the air: the copper's mass is kept to round-off (observed
  // at most 1.1e-14 in double; bound 1e-12, a few thousand cycles of the flux sums' roundings).
  // With the deck's former min_fraction 1e-4, 7.3e-4 to 8.9e-4 went to the air.
  EXPECT_LT(std::abs(run.cu_lost), test::roundoff(1e-12)) << model << " R/" << n;
  const TaylorErrors e{err(run.shape.length, tx::kLengthFinal),
                       err(run.shape.footprint, tx::kFootprintDiameter)};
  if (rank0())
    std::printf("taylor %s R/%d: issue's 5 %% target %s (length %+.2f %%, footprint %+.2f %%)\n",
                model, n,
                std::abs(e.length) < 0.05 && std::abs(e.footprint) < 0.05 ? "met" : "NOT met",
                100 * e.length, 100 * e.footprint);
  return e;
}

}  // namespace

// Zerilli & Armstrong's (1987) copper, the model its authors checked against these cylinders:
// the target, length and footprint within 5 % of the experiment (the measurement's own
// rounding is 0.1-0.3 %, tests/exact/taylor_data.hpp), at R/6 and R/8, and the footprint error
// falling. Observed 2026-12-06 (2 ranks, double and float alike; 1 rank the same, 2026-12-07):
// R/6 L +2.97 %, D -4.91 %; R/8 L +3.08 %, D -2.25 %. Bounds: 5 % each (the target; R/6's footprint
// passes at 0.98 of it), and the R/8 footprint error below 0.8 of the R/6 one (observed 0.46). The
// length's error does not fall from R/6 to R/8 (+2.97 -> +3.08 %, within its 0.3-point measuring
// rounding; from R/6 to R/12 it settles near +3.5 %, docs/numerics.md "Taylor anvil"), so only its
// 5 % is asserted.
TEST(Taylor, ZerilliArmstrongCopperWithinFivePercentAtTwoResolutions) {
  const TaylorErrors c = check_model("zerilli_armstrong", kCoarse);
  const TaylorErrors f = check_model("zerilli_armstrong", kFine);
  for (const TaylorErrors* e : {&c, &f}) {
    const int n = e == &c ? kCoarse : kFine;
    EXPECT_LT(std::abs(e->length), 0.05) << "R/" << n;
    EXPECT_LT(std::abs(e->footprint), 0.05) << "R/" << n;
  }
  EXPECT_LT(std::abs(f.footprint), 0.8 * std::abs(c.footprint));
}

// Pins, not verification: Johnson-Cook and Steinberg-Guinan miss the 5 % target (what
// limits them: docs/numerics.md, "Taylor anvil"). Run at R/6 since 2026-12-06 (under half of
// R/8's cost; at R/8 they were asserted as "MatchesTheExperiment" at 6.5-7.5 %); the bounds hold
// the present errors plus about 1.5 points so that a change shows. Observed (2026-12-06, double,
// 2 ranks) at R/6 and, for comparison, R/8: Johnson-Cook L +6.38 % / +6.23 %, D +3.11 % /
// +5.04 % (the footprint's error grows with the zone); Steinberg-Guinan L +5.16 % / +4.96 %,
// D -7.00 % / -6.56 %.
TEST(TaylorPin, JohnsonCookCopperMissesTheFivePercentTarget) {
  const TaylorErrors e = check_model("johnson_cook", kCoarse);
  // observed L +6.38 % (bound 8 %), D +3.11 % (bound 4.5 %); the target 5 % each
  EXPECT_LT(std::abs(e.length), 0.08) << "pin; the issue's target is 5 %";
  EXPECT_LT(std::abs(e.footprint), 0.045) << "pin; the issue's target is 5 %";
}

TEST(TaylorPin, SteinbergGuinanCopperMissesTheFivePercentTarget) {
  const TaylorErrors e = check_model("steinberg_guinan", kCoarse);
  // observed L +5.16 % (bound 6.5 %), D -7.00 % (bound 8.5 %); the target 5 % each
  EXPECT_LT(std::abs(e.length), 0.065) << "pin; the issue's target is 5 %";
  EXPECT_LT(std::abs(e.footprint), 0.085) << "pin; the issue's target is 5 %";
}
