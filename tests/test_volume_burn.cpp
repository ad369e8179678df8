// CJ volume burn in the cycle (kernels/burn/burn.hpp volume_burn_fraction, `burn.volume_burn`):
// a confined charge compressed past the CJ volume burns where the shock compresses it, long
// before programmed burn would have lit it; alone and with programmed burn (the combination
// production codes use: F = max(F_programmed, F_volume)).
//
// The scene: configs/shock_initiation.yaml (PBX 9404 with its unreacted solid's EOS, 1-D along
// z, 100 cells of 0.01 cm) with the explosive at the products' rho0 = 1.84 g/cm^3 (F_vol = 0 at
// rest) moving at -0.18 cm/us onto the wall at z = 0: the unreacted Hugoniot puts the shocked
// explosive at v / v0 = 1 - up / Us = 0.69, past v_cj / v0 = 1 - p_cj / (rho0 D^2) = 0.740, so
// it burns as the shock reaches it. The programmed burn's plane detonator is at the far end
// z = 1 (t_light(z) = (1 - z) / D), so that a cell near the wall is lit late.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "materials/library.hpp"
#include "support.hpp"

using namespace mp;

namespace {

constexpr int kCells = 100;
constexpr double kDz = 0.01, kTEnd = 0.6;

struct Burnt {
  std::vector<double> t_half;  // the time F first reached 1/2 per cell (-1: never), us
  std::vector<double> f_end;   // F at kTEnd
  double dt_max = 0;           // the largest step, us
};

// The run with `burn` as the explosive's burn block, stepped by hand to record when each cell
// burns.
Burnt run(const std::string& burn) {
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(
      test::load_scene("shock_initiation.yaml",
                       {"mesh.cells=[2,2," + std::to_string(kCells) + "]", "mesh.hi=[0.02,0.02,1]",
                        "materials.0.burn=" + burn, "regions.0.density=1.84",
                        "regions.0.velocity=[0,0,-0.18]", "time.end=1e9", "output.write=false"}),
      MPI_COMM_WORLD, settings);
  sim.initialize();
  const auto* b = sim.hydro().module<burn::Burn>();
  Burnt out;
  out.t_half.assign(kCells, -1);
  std::vector<double> f;
  const test::Stepped run = test::step_until(sim, kTEnd, [&](double t, double dt) {
    out.dt_max = std::max(out.dt_max, dt);
    f = test::gather(sim.mesh(), b->fraction(), Centering::Cell);
    for (int k = 0; k < kCells; ++k)
      if (out.t_half[k] < 0 && f[4 * k] >= 0.5) out.t_half[k] = t;
    return true;
  });
  EXPECT_TRUE(run.health.ok) << run.health.what;
  for (int k = 0; k < kCells; ++k) out.f_end.push_back(f[4 * k]);
  return out;
}

const char* kUnreacted = "unreacted: pbx9404_unreacted";
const char* kDetonator = "detonators: [{type: plane, at: [0, 0, 1], normal: [0, 0, 1]}]";

}  // namespace

TEST(VolumeBurn, CompressedChargeBurnsBeforeItsLightingTime) {
  const double d = materials::find_material("pbx9404_products")->param("D");
  auto t_light = [&](int k) { return (1 - (k + 0.5) * kDz) / d; };
  const Burnt vol = run(std::string("{programmed: false, volume_burn: true, ") + kUnreacted + "}");
  const Burnt prog = run(std::string("{") + kUnreacted + ", " + kDetonator + "}");
  const Burnt both =
      run(std::string("{volume_burn: true, ") + kUnreacted + ", " + kDetonator + "}");
  // the volume-burn front's speed: a least-squares line through (z, t_half) over 0.05..0.39 cm
  // (the front reaches the next cell, z = 0.395, at t = 0.600 under the combined step and at
  // 0.601, after the end, under the default cloverleaf step; a later end lets the programmed
  // front's remapped tail of F reach the cells near the wall: 6.6e-18 at z = 0.395 by 0.62 us)
  double s0 = 0, sz = 0, st = 0, szz = 0, szt = 0;
  for (int k = 5; k < 39; ++k) {
    const double z = (k + 0.5) * kDz, t = vol.t_half[k];
    ASSERT_GT(t, 0) << "cell " << k << " never burnt under volume burn";
    s0 += 1, sz += z, st += t, szz += z * z, szt += z * t;
  }
  const double slowness = (s0 * szt - sz * st) / (s0 * szz - sz * sz);
  // in the frame of the explosive ahead of it (moving at -0.18 cm/us)
  const double front = 1 / slowness + 0.18;
  std::printf(
      "volume-burn front from the wall: %.5f cm/us in the explosive's frame (D %.3f, %+.2f %%); "
      "largest step %.5f us\n",
      front, d, 100 * (front / d - 1), vol.dt_max);
  // a detonation-like front: within 6 % of D (observed -4.5 % under the default cloverleaf
  // step, -4.2 % under the combined one over 0.05..0.4 cm: the volume burn has no reaction zone
  // of its own, F follows the smeared shock's compression)
  EXPECT_NEAR(front / d, 1.0, 0.06);
  for (int k : {5, 10, 20, 30, 38})
    std::printf(
        "z %.3f cm: t_light %.4f us; F = 1/2 at %.4f (volume), %.4f (programmed), %.4f (both)\n",
        (k + 0.5) * kDz, t_light(k), vol.t_half[k], prog.t_half[k], both.t_half[k]);
  for (int k = 5; k < 40; ++k) {
    // volume burn alone, z up to 0.295 cm: burnt at least 0.3 us before the programmed burn
    // would have lit the cell (observed margins 0.98 us at z = 0.055, 0.34 us at z = 0.295)
    if (k < 30) {
      EXPECT_LT(vol.t_half[k], t_light(k) - 0.3) << k;
    }
    // programmed alone: nothing near the wall has burnt by t = 0.6 us (t_light > 0.68 there;
    // the remap's tail of F from the burnt end is below 1e-40 here)
    EXPECT_LT(prog.f_end[k], 1e-20) << k;
    EXPECT_LT(prog.t_half[k], 0.0) << k;
    // both: the volume burn's times, to within two steps (the programmed front changes the
    // time step, so the step sequence is not the same)
    EXPECT_NEAR(both.t_half[k], vol.t_half[k], 2 * vol.dt_max) << k;
  }
  // the programmed front from the far end: F = 1/2 one cell after the lighting time (F ramps
  // over 2 cells at D), to within a step, alone and with volume burn
  for (int k = 90; k < 99; ++k) {
    EXPECT_NEAR(prog.t_half[k], t_light(k) + kDz / d, prog.dt_max) << k;
    EXPECT_NEAR(both.t_half[k], t_light(k) + kDz / d, both.dt_max) << k;
  }
}
