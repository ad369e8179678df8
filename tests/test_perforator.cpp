// Smoke test of the headline scene, configs/perforator.yaml (issue #13), on a coarse mesh for a
// few microseconds: the charges detonate, the liners move, every material keeps its mass to
// round-off, nothing turns NaN, and the dense and compact layouts agree bit for bit.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "support.hpp"

using namespace mp;

namespace {

// Coarse (zone 0.3 cm: 53 x 10 x 17 cells; the liner, 0.19 cm thick, is under one zone, so this
// is a smoke test, not a jet) to t = 1.2 us: the detonation reaches the liner apex, 0.125 cm
// from the detonator, at 0.16 us. The box cut to 1 cm of rock beyond the casing on either side
// (x in [-8, 8]; the deck's 11 and 5 cm are for the jets' penetration, which no run here
// reaches). Closed boundaries so that every material's mass is conserved to round-off (nothing
// reaches them by then anyway). RunsTo10UsWithTheCopperAboveTheBriefsSpeed below runs the same
// to 10 us.
const std::vector<std::string> kCoarse = {"mesh.zone=0.3",           "time.end=1.2",
                                          "mesh.lo=[-8,0,-2.5]",     "mesh.hi=[8,3,2.5]",
                                          "boundaries.x=reflective", "boundaries.y=reflective",
                                          "boundaries.z=reflective"};

struct PerfRun {
  test::Ran ran;
  std::vector<std::string> names;
  std::vector<std::vector<double>> fields;
};

// The run's output fields and every material's volume fraction, gathered whole on every rank.
PerfRun gathered(test::Ran ran) {
  PerfRun r;
  r.ran = std::move(ran);
  const Mesh& m = r.ran.sim->mesh();
  const auto& h = r.ran.sim->hydro();
  for (const auto& f : h.output_fields()) {
    r.names.push_back(f.name);
    r.fields.push_back(test::gather(m, f.view, f.centering));
  }
  const mat::MaterialState* mm = h.materials();
  for (int q = 0; q < mm->nmat(); ++q) {
    r.names.push_back("fraction_" + r.ran.sim->scene().materials[q].name);
    r.fields.push_back(test::gather(m, mm->fraction(q), Centering::Cell));
  }
  return r;
}

PerfRun run_layout(const std::string& layout, const std::string& iface = "youngs",
                   const std::string& end = "time.end=1.2",
                   const std::string& zone = "mesh.zone=0.3") {
  auto o = kCoarse;
  o[0] = zone;
  o[1] = end;
  o.push_back("numerics.layout=" + layout);
  o.push_back("numerics.interface=" + iface);
  return gathered(test::run_scene(test::load_scene("perforator.yaml", o)));
}

const std::vector<double>& field(const PerfRun& r, const std::string& name) {
  for (std::size_t f = 0; f < r.names.size(); ++f)
    if (r.names[f] == name) return r.fields[f];
  ADD_FAILURE() << "no field " << name;
  static const std::vector<double> none;
  return none;
}

// The mean of the 8 node values of cell (i, j, k) of a gathered node field on nx x ny cells.
double cell_mean(const std::vector<double>& u, int nx, int ny, int i, int j, int k) {
  const long nnx = nx + 1, nny = ny + 1;
  double sum = 0;
  for (int c8 = 0; c8 < 8; ++c8)
    sum += u[(long(k + (c8 >> 2)) * nny + j + ((c8 >> 1) & 1)) * nnx + i + (c8 & 1)];
  return sum / 8;
}

// The largest speed of a copper cell (fraction > 0.5; mean of its 8 node velocities).
double copper_speed(const PerfRun& c) {
  const Mesh& m = c.ran.sim->mesh();
  const int nx = m.global_cells(0), ny = m.global_cells(1), nz = m.global_cells(2);
  const auto& cu = field(c, "fraction_copper");
  const auto& ux = field(c, "velocity_x");
  const auto& uy = field(c, "velocity_y");
  const auto& uz = field(c, "velocity_z");
  double vmax = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (cu[(long(k) * ny + j) * nx + i] <= 0.5) continue;
        const double v[3] = {cell_mean(ux, nx, ny, i, j, k), cell_mean(uy, nx, ny, i, j, k),
                             cell_mean(uz, nx, ny, i, j, k)};
        vmax = std::max(vmax, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
      }
  return vmax;
}

// The jet guard's scene (PerforatorJetPin below): configs/perforator.yaml cut to the box of its
// top charge and the carrier wall in front of it, perf/studies/perforator_top_charge.yaml's box:
// x in [-5.45, -1.85] (the charge case's back at -5.3564 to beyond the carrier's outer surface at
// -2.2225), y in [0, 1.3] (reflective y = 0; the case's radius 0.9886 inside), z in [0.15, 2.45]
// (the case spans 0.2814..2.2586), the deck's outflow elsewhere. At zone 0.1 (36 x 13 x 23
// cells) to 7 us: the jet leaves the liner at 4-5 us and at 7 us flies free, 0.3 cm short of the
// carrier's inner surface (x = -2.6670), which it reaches at 8 us.
const std::array<double, 3> kTopLo = {-5.45, 0.0, 0.15}, kTopHi = {-1.85, 1.3, 2.45};

// Whether the box spanned by the deck's points p and q, widened by `pad` on every side, lies
// wholly outside the guard's box.
bool outside_box(const YAML::Node& p, const YAML::Node& q, double pad) {
  for (int d = 0; d < 3; ++d) {
    const double a = std::min(p[d].as<double>(), q[d].as<double>()) - pad;
    const double b = std::max(p[d].as<double>(), q[d].as<double>()) + pad;
    if (b < kTopLo[d] || a > kTopHi[d]) return true;
  }
  return false;
}

// configs/perforator.yaml cut to the guard's box: the regions (cylinders and cones, bounded by
// base, top and radius) and point detonators wholly outside it dropped, which here is the bottom
// charge (the deck reader refuses a region outside the mesh); every other value the deck's, so
// that the guard watches the deck itself. `overrides` apply after the cut, as --set's.
Scene top_charge_scene(const std::vector<std::string>& overrides) {
  YAML::Node deck = YAML::LoadFile(test::source_dir() + "/configs/perforator.yaml");
  YAML::Node regions(YAML::NodeType::Sequence);
  for (const YAML::Node& r : deck["regions"])
    if (!r["base"] || !outside_box(r["base"], r["top"], r["radius"].as<double>()))
      regions.push_back(r);
  deck["regions"] = regions;
  for (YAML::Node m : deck["materials"]) {
    if (!m["burn"]) continue;
    YAML::Node kept(YAML::NodeType::Sequence);
    for (const YAML::Node& d : m["burn"]["detonators"])
      if (d["type"].as<std::string>() != "point" || !outside_box(d["at"], d["at"], 0))
        kept.push_back(d);
    m["burn"]["detonators"] = kept;
  }
  deck["mesh"]["lo"] = std::vector<double>(kTopLo.begin(), kTopLo.end());
  deck["mesh"]["hi"] = std::vector<double>(kTopHi.begin(), kTopHi.end());
  YAML::Emitter text;
  text << deck;
  std::vector<std::string> o = {"mesh.zone=0.1", "time.end=7.0"};
  o.insert(o.end(), overrides.begin(), overrides.end());
  return read_scene(Deck::parse(text.c_str(), "configs/perforator.yaml (top charge)", o));
}

// The top jet at the end of a run of the guard's scene, measured as tools/jet_profile.py does
// from a dump, on the axis row (the cells nearest y = 0, z = 1.27; the row's centres lie at
// z = 1.30):
// - tip_x: where the copper fraction along the row last falls through 0.5, linear between the
//   centres of the last cell above 0.5 and the next (the tools take the cell's centre; the
//   interpolation keeps a change under one zone visible);
// - tip_u: the x velocity of that last cell above 0.5 (the mean of its 8 nodes);
// - fast_mass: the copper mass (fraction x copper density x cell volume, the half charge of the
//   y >= 0 mesh) in every cell whose x velocity exceeds 0.2 cm/us, about 60 % of the jet's
//   speed: the jet and not the slug (0.02-0.05 cm/us) or the liner's skirt.
struct Jet {
  double tip_x = 0, tip_u = 0, fast_mass = 0;
};

Jet measure_jet(const PerfRun& r) {
  const Mesh& m = r.ran.sim->mesh();
  const int nx = m.global_cells(0), ny = m.global_cells(1), nz = m.global_cells(2);
  const double h = m.dx(0), vol = double(m.dx(0)) * m.dx(1) * m.dx(2);
  const auto& cu = field(r, "fraction_copper");
  const auto& ux = field(r, "velocity_x");
  const mat::MaterialState* mm = r.ran.sim->hydro().materials();
  const auto& names = r.ran.sim->scene().materials;
  int q = 0;
  while (names[q].name != "copper") ++q;
  const auto rho = test::gather(m, mm->material_field(q, 1), Centering::Cell);
  Jet jet;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const long c = (long(k) * ny + j) * nx + i;
        if (cell_mean(ux, nx, ny, i, j, k) > 0.2) jet.fast_mass += cu[c] * rho[c] * vol;
      }
  const int k = static_cast<int>(std::lround((1.27 - kTopLo[2]) / m.dx(2) - 0.5)), j = 0;
  const long row = (long(k) * ny + j) * nx;
  int i = nx - 1;
  while (i >= 0 && cu[row + i] <= 0.5) --i;
  if (i < 0) {
    ADD_FAILURE() << "no copper cell (fraction > 0.5) on the top charge's axis";
    return jet;
  }
  const double next = i + 1 < nx ? cu[row + i + 1] : 0.0;
  jet.tip_x = kTopLo[0] + (i + 0.5) * h + h * (cu[row + i] - 0.5) / (cu[row + i] - next);
  jet.tip_u = cell_mean(ux, nx, ny, i, j, k);
  return jet;
}

}  // namespace

TEST(Perforator, CoarseSmokeRun) {
  const PerfRun c = run_layout("compact");
  ASSERT_TRUE(c.ran.result.ok) << c.ran.result.health.what;
  const Scene& scene = c.ran.sim->scene();
  const Mesh& m = c.ran.sim->mesh();
  const int nx = m.global_cells(0), ny = m.global_cells(1), nz = m.global_cells(2);
  std::printf("perforator at zone 0.3: %d x %d x %d cells, %ld cycles to t = %.3f us\n", nx, ny, nz,
              c.ran.result.cycles, c.ran.result.time);
  EXPECT_NEAR(c.ran.result.time, 1.2, 1e-12);  // the end step lands on t_end (Simulation::run)

  // No NaN or infinity in any field.
  for (std::size_t f = 0; f < c.fields.size(); ++f) {
    long bad = 0;
    for (double v : c.fields[f]) bad += std::isfinite(v) ? 0 : 1;
    EXPECT_EQ(bad, 0) << c.names[f];
  }

  // Detonation: some explosive has burnt (burn fraction > 0), and the cells the front passed
  // first are fully burnt (the ramp is 2 zones, 0.6 cm, crossed in 0.75 us at D = 0.798).
  const auto burn =
      test::gather(m, c.ran.sim->hydro().module<burn::Burn>()->fraction(), Centering::Cell);
  long burnt = 0;
  double fmax = 0;
  for (double f : burn) {
    burnt += f > 0 ? 1 : 0;
    fmax = std::max(fmax, f);
  }
  std::printf("burn fraction > 0 in %ld cells, largest %.4f\n", burnt, fmax);
  EXPECT_GT(burnt, 0);
  EXPECT_EQ(fmax, 1.0);

  // The liners move: the largest speed of a copper cell (fraction > 0.5; mean of its 8 node
  // velocities). At rest it is 0. The brief asked for 0.05 cm/us; at this zone and time the
  // coarse burn ramp has only begun to drive the liner (0.0154 cm/us at 1.05 us at zone 0.25,
  // 0.0235 at 1.40 us at zone 0.3), so the bound is 0.01 cm/us: motion, not a collapse speed.
  const double vmax = copper_speed(c);
  std::printf("largest copper cell speed %.4f cm/us\n", vmax);
  EXPECT_GT(vmax, 0.01);

  // Total mass to round-off in the closed box (observed 1.1e-14; the per-cycle roundings of the
  // remap's flux sums, as test_multimat's 1e-13). Each material's own mass: see
  // EveryMaterialsMass* below (with Youngs, mass moves between materials).
  const double m0 = c.ran.result.start.mass, m1 = c.ran.result.end.mass;
  std::printf("total mass %.6e, relative change %.3e\n", m0, m1 / m0 - 1);
  EXPECT_NEAR(m1 / m0, 1.0, test::roundoff(1e-13));
  const auto& a = c.ran.result.start.material_mass;
  const auto& b = c.ran.result.end.material_mass;
  ASSERT_EQ(a.size(), scene.materials.size());
  for (std::size_t q = 0; q < a.size(); ++q)
    std::printf("  %-7s mass %.6e -> change %.3e g (relative %.3e)\n",
                scene.materials[q].name.c_str(), a[q], b[q] - a[q], b[q] / a[q] - 1);

  // Dense and compact layouts: the same point functions on the same values, bit for bit.
  const PerfRun d = run_layout("dense");
  ASSERT_TRUE(d.ran.result.ok) << d.ran.result.health.what;
  EXPECT_EQ(c.ran.result.cycles, d.ran.result.cycles);
  ASSERT_EQ(c.names, d.names);
  for (std::size_t f = 0; f < c.fields.size(); ++f) {
    double diff = 0;
    for (std::size_t i = 0; i < c.fields[f].size(); ++i)
      diff = std::max(diff, std::abs(c.fields[f][i] - d.fields[f][i]));
    EXPECT_EQ(diff, 0.0) << c.names[f];
  }
  std::printf("dense vs compact: %zu fields equal bit for bit over %ld cycles\n", c.fields.size(),
              c.ran.result.cycles);
}

// Each material's mass in the closed box, to round-off: every change at most 1e-13 of the
// scene's mass (the roundings of the per-material flux sums scale with the cell masses that
// cross mixed faces, not with the material's own mass; air is 3e-5 of the total). With SLIC
// interfaces: observed changes of at most 1.3e-15 of the total (steel), air 8.6e-17 of it
// (3.1e-12 of its own mass).
void expect_each_mass_conserved(const std::string& iface) {
  const PerfRun r = run_layout("compact", iface);
  ASSERT_TRUE(r.ran.result.ok) << r.ran.result.health.what;
  const auto& a = r.ran.result.start.material_mass;
  const auto& b = r.ran.result.end.material_mass;
  const double total = r.ran.result.start.mass;
  for (std::size_t q = 0; q < a.size(); ++q) {
    const std::string& name = r.ran.sim->scene().materials[q].name;
    std::printf("%s: %-7s mass change %.3e g = %.3e of the total\n", iface.c_str(), name.c_str(),
                b[q] - a[q], (b[q] - a[q]) / total);
    EXPECT_LE(std::abs(b[q] - a[q]), test::roundoff(1e-13) * total) << iface << " " << name;
  }
}

TEST(Perforator, EveryMaterialsMassWithSlic) {
  expect_each_mass_conserved("slic");
}

// With Youngs (the deck's default). Until 2026-12-01 the remap moved mass from steel to the
// explosive here (steel -3.1e-7 g, comp_b +3.1e-7 g: 5.6e-10 of the scene's mass): a steel
// sliver below 1e-6 of a cell whose energy went negative by cancellation left the cell and its
// mass went to the largest material. Such a sliver now stays at zero energy, the largest
// material paying the deficit (kernels/hydro/mixed_remap_cells.cpp, RemapSource).
TEST(Perforator, EveryMaterialsMassWithYoungs) {
  expect_each_mass_conserved("youngs");
}

// The coarse scene runs past the liner collapse (until 2026-12-01 it stopped non-physical at
// 1.40 us at zone 0.3, and at 0.87 / 2.55 us at the deck's 0.2 on the way to the fixes: the
// mixed-cell viscous work by mass, the compression switch, the health check's floor for cold
// Mie-Grueneisen solids; docs/numerics.md). By 10 us the liners are driven beyond the brief's
// 0.05 cm/us (the liner is under one zone thick and no jet forms, so this is motion, not a jet
// speed). Run at zone 0.25 since 2026-12-05: at 0.3 the largest speed was two cells' (0.0631
// and 0.0611 with the scalar viscosity, the next 0.041; 0.0419 with the tensor viscosity, whose
// bulk is the same), so it measured those two cells; at 0.25 the two viscosities give 0.0750 and
// 0.0752, at 0.2 0.0994 and 0.1016. Named for what it checks (issue #55; was
// RunsPastTheLinerCollapse, which no assert shows): the run reaches 10 us healthy and the
// fastest copper cell is above 0.05 cm/us (observed 0.0750; bound 0.67x of it).
TEST(Perforator, RunsTo10UsWithTheCopperAboveTheBriefsSpeed) {
  const PerfRun c = run_layout("compact", "youngs", "time.end=10.0", "mesh.zone=0.25");
  ASSERT_TRUE(c.ran.result.ok) << c.ran.result.health.what;
  EXPECT_NEAR(c.ran.result.time, 10.0, 1e-12);
  const double vmax = copper_speed(c);
  std::printf("zone 0.25 to t = %.3f us in %ld cycles: largest copper cell speed %.4f cm/us\n",
              c.ran.result.time, c.ran.result.cycles, vmax);
  EXPECT_GT(vmax, 0.05);
}

// The jet guard (issue #52): a regression pin on the top charge's jet in top_charge_scene's cut
// box at zone 0.1 to 7 us (203 cycles, about 13 s on one core). Nothing else in the suite sees a
// jet: the runs above have the liner under one zone. The bounds are the values measured on
// 2026-12-07 with the margin each comment states (double: the same bit for bit on 1 and 2 ranks
// and on 2 threads; float within 1e-4 of each). They say what this code and deck gave, not what
// is right: the jet is not converged at zone 0.1 (docs/perforator.md). A value out of its
// bounds is a change of the perforator's account (the scheme, a material, the deck's charge):
// find why, then re-measure the pin.
// Proven to fail: with the liner 1.5x thicker (the inner cone's and the cavity's apex moved to
// x = -4.2893, radius 0.54985, the outer cone against the explosive kept: --set
// regions.7.minus.0.top=[-4.2893,0,1.27] regions.7.minus.0.radius=0.54985 and the same for
// regions.8) the three lower bounds fail: tip x -3.0714 cm (bound -3.0029), tip u 0.2377 cm/us
// (bound 0.305), fast copper 0.01073 g (bound 0.0252), in 188 cycles.
TEST(PerforatorJetPin, TopJetAt7UsOnZone01) {
  const PerfRun r = gathered(test::run_scene(top_charge_scene({})));
  ASSERT_TRUE(r.ran.result.ok) << r.ran.result.health.what;
  EXPECT_NEAR(r.ran.result.time, 7.0, 1e-12);
  const Jet jet = measure_jet(r);
  std::printf(
      "top charge, zone 0.1, t = %.3f us, %ld cycles: tip x %.4f cm, tip u %.4f cm/us, "
      "copper faster than 0.2 cm/us %.5f g\n",
      r.ran.result.time, r.ran.result.cycles, jet.tip_x, jet.tip_u, jet.fast_mass);
  // Tip: observed -2.9525 cm with air in the well (-2.9529 with water; float -2.9528); bounds
  // +-0.05 cm, half a zone: within them the last cell above 0.5 is the same cell (centre -3.0),
  // whose speed tip_u reads.
  EXPECT_GE(jet.tip_x, -3.0029) << "pin: the jet's tip is behind where it was (-2.9529 cm)";
  EXPECT_LE(jet.tip_x, -2.9029) << "pin: the jet's tip is ahead of where it was (-2.9529 cm)";
  // Tip speed: observed 0.3392 cm/us (0.3391 with water; float 0.3391); bounds +-10 %,
  // 0.305..0.373: a tenth of the jet's speed; the cell behind the tip moves 18 % slower (0.279), so
  // a tip one cell back fails here as well as above.
  EXPECT_GE(jet.tip_u, 0.305) << "pin: the jet's tip is slower than it was (0.3391 cm/us)";
  EXPECT_LE(jet.tip_u, 0.373) << "pin: the jet's tip is faster than it was (0.3391 cm/us)";
  // Fast copper: observed 0.03146 g (0.03144 with water; float 0.03144); bounds +-20 %,
  // 0.0252..0.0377: the mass above a speed cut moves about twice as much as the speeds (the copper
  // volume faster than 0.15 and 0.25 cm/us is 7.3 and 3.2 mm^3 against 4.2 above 0.2), so this is
  // the speed's 10 % again, and about one zone of copper (1 mm^3, 0.0075 g at the fast cells'
  // density).
  EXPECT_GE(jet.fast_mass, 0.0252) << "pin: less copper in the jet than there was (0.03144 g)";
  EXPECT_LE(jet.fast_mass, 0.0377) << "pin: more copper in the jet than there was (0.03144 g)";
}

// The charges' lighting times at zone 0.1 (300 x 30 x 50 cells) from the per-rank kernels (the
// default) against the host reference construction (burn.lighting: host): the same cells lit
// (observed 4608, bound > 4000: the two charges' cells at least half explosive and their thin
// neighbours), and the times within 0.25 h/D (h = 0.1 cm; tests/test_lighting_device.cpp's
// shadow bound): observed 4535 cells the same bits, the other 73 within 0.118 h/D (0.0147 us).
TEST(Perforator, LightingTimesOnTheDeviceMatchTheHostAtZone01) {
  std::vector<double> t[2];
  double d_cj = 0;
  for (int host = 0; host < 2; ++host) {
    Scene scene = test::load_scene("perforator.yaml", {"mesh.zone=0.1", "output.write=false"});
    for (auto& mat : scene.materials)
      if (mat.burn.on) mat.burn.host_lighting = host == 1;
    RunSettings quiet;
    quiet.quiet = true;
    Simulation sim(scene, MPI_COMM_WORLD, quiet);
    sim.initialize();
    const auto* b = sim.hydro().module<burn::Burn>();
    ASSERT_NE(b, nullptr);
    d_cj = double(b->params().d_cj);
    t[host] = test::gather(sim.mesh(), b->lighting_time(), Centering::Cell);
  }
  const double never = double(Real(burn::kNeverLit)), h = 0.1;
  long lit = 0, same = 0, unlit_differ = 0;
  double worst = 0;
  for (std::size_t c = 0; c < t[0].size(); ++c) {
    const bool a = t[0][c] < never, b = t[1][c] < never;
    if (a != b) ++unlit_differ;
    if (!a || !b) continue;
    ++lit;
    same += t[0][c] == t[1][c];
    worst = std::max(worst, std::fabs(t[0][c] - t[1][c]));
  }
  std::printf(
      "perforator zone 0.1: %zu cells, %ld lit, %ld the same bits, max |device - host| = "
      "%.3e us = %.4f h/D; %ld lit by one only\n",
      t[0].size(), lit, same, worst, worst / (h / d_cj), unlit_differ);
  EXPECT_GT(lit, 4000);
  EXPECT_EQ(unlit_differ, 0);
  EXPECT_LE(worst, 0.25 * h / d_cj);
}
