// Smoke test of the headline scene, configs/perforator.yaml (issue #13), on a coarse mesh for a
// few microseconds: the charges detonate, the liners move, every material keeps its mass to
// round-off, nothing turns NaN, and the dense and compact layouts agree bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "support.hpp"

using namespace mp;

namespace {

// Coarse (zone 0.3 cm: 53 x 10 x 17 cells; the liner, 0.19 cm thick, is under one zone, so this
// is a smoke test, not a jet) to t = 1.2 us: the detonation reaches the liner apex, 0.125 cm
// from the detonator, at 0.16 us. Closed boundaries so that every material's mass is conserved
// to round-off (nothing reaches them by then anyway). RunsTo10UsWithTheCopperAboveTheBriefsSpeed
// below runs the same to 10 us.
const std::vector<std::string> kCoarse = {"mesh.zone=0.3", "time.end=1.2",
                                          "boundaries.x=reflective", "boundaries.y=reflective",
                                          "boundaries.z=reflective"};

struct PerfRun {
  test::Ran ran;
  std::vector<std::string> names;
  std::vector<std::vector<double>> fields;
};

PerfRun run_layout(const std::string& layout, const std::string& iface = "youngs",
                   const std::string& end = "time.end=1.2",
                   const std::string& zone = "mesh.zone=0.3") {
  auto o = kCoarse;
  o[0] = zone;
  o[1] = end;
  o.push_back("numerics.layout=" + layout);
  o.push_back("numerics.interface=" + iface);
  PerfRun r;
  r.ran = test::run_scene(test::load_scene("perforator.yaml", o));
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

const std::vector<double>& field(const PerfRun& r, const std::string& name) {
  for (std::size_t f = 0; f < r.names.size(); ++f)
    if (r.names[f] == name) return r.fields[f];
  ADD_FAILURE() << "no field " << name;
  static const std::vector<double> none;
  return none;
}

// The largest speed of a copper cell (fraction > 0.5; mean of its 8 node velocities).
double copper_speed(const PerfRun& c) {
  const Mesh& m = c.ran.sim->mesh();
  const int nx = m.global_cells(0), ny = m.global_cells(1), nz = m.global_cells(2);
  const auto& cu = field(c, "fraction_copper");
  const auto& ux = field(c, "velocity_x");
  const auto& uy = field(c, "velocity_y");
  const auto& uz = field(c, "velocity_z");
  const long nnx = nx + 1, nny = ny + 1;
  double vmax = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (cu[(long(k) * ny + j) * nx + i] <= 0.5) continue;
        double v[3] = {0, 0, 0};
        for (int c8 = 0; c8 < 8; ++c8) {
          const long n = (long(k + (c8 >> 2)) * nny + j + ((c8 >> 1) & 1)) * nnx + i + (c8 & 1);
          v[0] += ux[n] / 8;
          v[1] += uy[n] / 8;
          v[2] += uz[n] / 8;
        }
        vmax = std::max(vmax, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
      }
  return vmax;
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
