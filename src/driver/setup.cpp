// Setting up a scene's initial state: the regions painted onto the mesh (volume fractions,
// density, energy, node velocities), energy deposits, then the hydro's derived fields.
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "core/math.hpp"
#include "driver/modules.hpp"
#include "driver/simulation.hpp"
#include "driver/wave.hpp"
#include "materials/geometry.hpp"

namespace mp {

namespace {

// A region as the painting kernel sees it.
struct RegionDev {
  geom::Shape shape;
  bool all;
  double rho, e, vel[3], vcenter[3];
  int radial;
  double wave_amp, wave_lo[3], wave_len[3];
  int wave_axis, wave_shape;
  int mat;

  KOKKOS_INLINE_FUNCTION bool contains(double x, double y, double z) const {
    return shape.contains(x, y, z);
  }
  // Volume fraction of the cell with low corner lo and sizes h.
  KOKKOS_INLINE_FUNCTION double fraction(const double lo[3], const double h[3], int samples) const {
    return all ? 1.0 : geom::sampled_fraction(shape, lo, h, samples);
  }
  // Density and specific energy of the region in a cell: uniform, or a smooth entropy wave
  // (density times 1 + amplitude * P(s), P the wave's profile, driver/wave.hpp, averaged exactly
  // over the cell, at uniform pressure).
  KOKKOS_INLINE_FUNCTION void state(const double lo[3], const double h[3], double& r,
                                    double& en) const {
    double wf = 1;
    if (wave_amp > 0 && wave_shape == wave::kSine && wave_axis != wave::kDiagonal) {
      // (the sine along an axis in closed form)
      const int a = wave_axis;
      const double kw = 2 * M_PI / wave_len[a];
      const double x0 = lo[a] - wave_lo[a], x1 = x0 + h[a];
      wf = 1 +
           wave_amp * (MP_KOKKOS_MATH::cos(kw * x0) - MP_KOKKOS_MATH::cos(kw * x1)) / (kw * h[a]);
    } else if (wave_amp > 0) {
      // along an axis, or the diagonal (the scene reader requires the same cells per box length
      // along every axis there: s = x/Lx + y/Ly + z/Lz over a cube of width h/L)
      const bool diag = wave_axis == wave::kDiagonal;
      const int a = diag ? 0 : wave_axis;
      double s0 = 0;
      for (int d = 0; d < 3; ++d)
        if (diag || d == a) s0 += (lo[d] - wave_lo[d]) / wave_len[d];
      wf = 1 + wave_amp * wave::cell_mean(wave_shape, s0, h[a] / wave_len[a], diag ? 3 : 1);
    }
    r = rho * wf;
    en = wave_amp > 0 ? e / wf : e;
  }
};

// Paints one cell: at each of samples^3 sub-cell points the last region (in deck order) that
// contains the point decides the material, density and energy there, so regions that do not
// overlap keep exact volume fractions and a later region covers only what it contains.
// Accumulates per material the volume fraction, mass and internal energy per cell volume.
KOKKOS_INLINE_FUNCTION void paint_cell(const Kokkos::View<RegionDev*, MemSpace>& regs, int nreg,
                                       const double lo[3], const double h[3], int samples,
                                       double* vol, double* mass, double* ener) {
  const double w = 1.0 / (double(samples) * samples * samples), inv = 1.0 / samples;
  for (int k = 0; k < samples; ++k)
    for (int j = 0; j < samples; ++j)
      for (int i = 0; i < samples; ++i) {
        const double x = lo[0] + (i + 0.5) * inv * h[0], y = lo[1] + (j + 0.5) * inv * h[1],
                     z = lo[2] + (k + 0.5) * inv * h[2];
        for (int n = nreg - 1; n >= 0; --n) {
          const RegionDev& reg = regs(n);
          if (!(reg.all || reg.contains(x, y, z))) continue;
          double rr, ee;
          reg.state(lo, h, rr, ee);
          vol[reg.mat] += w;
          mass[reg.mat] += w * rr;
          ener[reg.mat] += w * rr * ee;
          break;
        }
      }
}

// Velocity at (x, y, z) of the last region (deck order) that contains the point: uniform, or
// radial about the region's centre.
KOKKOS_INLINE_FUNCTION void region_velocity(const RegionDev& r, double x, double y, double z,
                                            double vel[3]) {
  if (r.radial) {
    const double rx = x - r.vcenter[0], ry = y - r.vcenter[1], rz = z - r.vcenter[2];
    const double len = MP_KOKKOS_MATH::sqrt(rx * rx + ry * ry + rz * rz);
    const double f = len > 0 ? r.vel[0] / len : 0.0;
    vel[0] = f * rx;
    vel[1] = f * ry;
    vel[2] = f * rz;
  } else {
    for (int a = 0; a < 3; ++a) vel[a] = r.vel[a];
  }
}

KOKKOS_INLINE_FUNCTION void point_velocity(const Kokkos::View<RegionDev*, MemSpace>& regs, int nreg,
                                           double x, double y, double z, double vel[3]) {
  vel[0] = vel[1] = vel[2] = 0;
  for (int n = nreg - 1; n >= 0; --n)
    if (regs(n).all || regs(n).contains(x, y, z)) {
      region_velocity(regs(n), x, y, z, vel);
      return;
    }
}

// A node among cells that hold more than one material, or regions of different velocities:
// the velocity that carries the momentum its lumped mass (1/8 of each of its 8 cells' masses)
// holds in the regions, the mass-weighted mean of the regions' velocities (taken at the node)
// over the sub-cell points that paint those 8 cells (paint_cell's samples^3 points per cell), so
// the nodes start with exactly the momentum the painted masses carry. Without it a node just
// outside a dense body (a copper rod in air) started at the air's velocity though most of its
// mass is the body's: the R/8 Taylor rod started with 9 % less kinetic energy than rho V v^2 / 2;
// and the node on the 123 problem's velocity jump (-2 | +2, one material) started at -2, not
// at the painted 0, so the solution was not symmetric about the jump (1.5e-2 of the density at
// 400 cells). Returns false (the point rule applies) where those cells hold one material at one
// velocity (every node of a uniform or radial flow: the same bits as the point rule).
KOKKOS_INLINE_FUNCTION bool dual_cell_velocity(const Kokkos::View<RegionDev*, MemSpace>& regs,
                                               int nreg, double x, double y, double z,
                                               const Real dx[3], int samples, double vel[3]) {
  const double inv = 1.0 / samples;  // sub-cell spacing, in cells
  double m = 0, p[3] = {0, 0, 0};
  double v0[3] = {0, 0, 0};
  int first_mat = -1;
  bool mixed = false, same = true;
  for (int c = 0; c < 2 * samples; ++c)
    for (int b = 0; b < 2 * samples; ++b)
      for (int a = 0; a < 2 * samples; ++a) {
        const double sx = x + ((a + 0.5) * inv - 1) * dx[0];
        const double sy = y + ((b + 0.5) * inv - 1) * dx[1];
        const double sz = z + ((c + 0.5) * inv - 1) * dx[2];
        for (int n = nreg - 1; n >= 0; --n) {
          const RegionDev& r = regs(n);
          if (!(r.all || r.contains(sx, sy, sz))) continue;
          double rv[3];
          region_velocity(r, x, y, z, rv);
          if (first_mat < 0) {
            first_mat = r.mat;
            for (int d = 0; d < 3; ++d) v0[d] = rv[d];
          }
          if (r.mat != first_mat) mixed = true;
          if (rv[0] != v0[0] || rv[1] != v0[1] || rv[2] != v0[2]) same = false;
          m += r.rho;
          for (int d = 0; d < 3; ++d) p[d] += r.rho * rv[d];
          break;
        }
      }
  if ((!mixed && same) || !(m > 0)) return false;
  for (int d = 0; d < 3; ++d) vel[d] = same ? v0[d] : p[d] / m;  // one velocity: exactly it
  return true;
}

// Initial material content of the owned cells (paint_cell), materials below the smallest
// fraction handed to the largest one.
struct PaintSource {
  Kokkos::View<RegionDev*, MemSpace> regs;
  int nreg, nmat, samples;
  Geometry g;
  double min_fraction;
  int lo[3], hi[3];

  KOKKOS_INLINE_FUNCTION bool changed(int i, int j, int k) const {
    return i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1] && k >= lo[2] && k < hi[2];
  }
  KOKKOS_INLINE_FUNCTION int content(int i, int j, int k, Real* a, Real* r, Real* en) const {
    const double clo[3] = {g.node_coord(0, i), g.node_coord(1, j), g.node_coord(2, k)};
    const double h[3] = {g.dx[0], g.dx[1], g.dx[2]};
    double vol[mat::kMaxMaterials], mass[mat::kMaxMaterials], ener[mat::kMaxMaterials];
    for (int m = 0; m < nmat; ++m) vol[m] = mass[m] = ener[m] = 0;
    paint_cell(regs, nreg, clo, h, samples, vol, mass, ener);
    int big = 0;
    for (int m = 1; m < nmat; ++m)
      if (vol[m] > vol[big]) big = m;
    double vsum = 0;
    for (int m = 0; m < nmat; ++m) {
      if (m != big && !(vol[m] > min_fraction)) {
        mass[big] += mass[m];
        ener[big] += ener[m];
        vol[m] = 0;
      }
      vsum += vol[m];
    }
    int n = 0;
    for (int m = 0; m < nmat; ++m) {
      if (!(vol[m] > 0)) continue;
      a[m] = Real(vol[m] / vsum);
      r[m] = Real(mass[m] / vol[m] * vsum);
      en[m] = Real(ener[m] / mass[m]);
      ++n;
    }
    return n;
  }
};

// Specific internal energy giving pressure p at density rho: every EOS here is affine in e at
// fixed density, p = p(rho, 0) + (p(rho, 1) - p(rho, 0)) e.
double energy_for_pressure(const eos::Eos& eos, double rho, double p) {
  const double p0 = double(eos.pressure(Real(rho), Real(0)));
  const double slope = double(eos.pressure(Real(rho), Real(1))) - p0;
  if (!(slope > 0))
    throw InputError("the EOS cannot set a pressure at density " + std::to_string(rho));
  return (p - p0) / slope;
}

// The multi-material init::deposit kernel (Simulation::initialize), a for_cells body (a functor
// at namespace scope, not a generic extended lambda, which nvcc rejects inside for_cells' own
// lambdas): region r's energy deposit, the same specific energy to every material of a cell.
struct MixedDeposit {
  Geometry g;
  RegionDev r;
  int samples;
  double per_volume_fraction;
  Field3 rho, e;
  double vol;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    const double lo[3] = {g.node_coord(0, i), g.node_coord(1, j), g.node_coord(2, k)};
    const double h[3] = {g.dx[0], g.dx[1], g.dx[2]};
    const double f = r.fraction(lo, h, samples);
    if (!(f > 0)) return;
    const Real de = Real(per_volume_fraction * f / (double(rho(i, j, k)) * vol));
    for (int q = 0; q < cell.count(); ++q) {
      const mat::MatRef mr = cell.get(q);
      if (mr.alpha > 0) *mr.e += de;
    }
    if (!cell.aliases()) e(i, j, k) += de;
  }
};

}  // namespace

void Simulation::initialize() {
  auto t0 = std::chrono::steady_clock::now();
  std::vector<RegionDev> regs;
  const std::vector<eos::Eos> eos = material_eoses(scene_);
  for (const auto& r : scene_.regions) {
    RegionDev d{};
    d.shape = r.shape.shape;
    d.all = r.shape.shape.primary.kind == geom::kAll;
    for (int a = 0; a < 3; ++a) {
      d.vel[a] = r.velocity[a];
      d.vcenter[a] = r.velocity_center[a];
    }
    d.rho = r.density;
    d.e = r.has_pressure ? energy_for_pressure(eos[r.material_index], r.density, r.pressure)
                         : r.energy;
    d.radial = r.radial_velocity ? 1 : 0;
    d.wave_amp = r.wave_amplitude;
    d.wave_axis = r.wave_axis;
    d.wave_shape = r.wave_shape;
    for (int a = 0; a < 3; ++a) {
      d.wave_lo[a] = scene_.mesh.lo[a];
      d.wave_len[a] = scene_.mesh.hi[a] - scene_.mesh.lo[a];
    }
    d.mat = r.material_index;
    regs.push_back(d);
  }
  Kokkos::View<RegionDev*, MemSpace> dregs("regions", regs.size());
  auto hregs = Kokkos::create_mirror_view(dregs);
  for (std::size_t n = 0; n < regs.size(); ++n) hregs(n) = regs[n];
  Kokkos::deep_copy(dregs, hregs);
  const int nreg = static_cast<int>(regs.size());

  auto& s = hydro_->state();
  auto rho = s.rho, e = s.e, u = s.u, v = s.v, w = s.w;
  const Geometry g = mesh_->geometry();
  // Regions paint in order; a later region takes the volume fraction of the cell it covers
  // (sub-cell sampled), mixing mass and internal energy with what was there.
  const int samples = scene_.numerics.samples;
  mat::MaterialState* mm = hydro_->materials();
  if (mm) {
    const int ng = Mesh::ng;
    PaintSource src{
        dregs,
        nreg,
        mm->nmat(),
        samples,
        g,
        hydro::effective_min_fraction(scene_.numerics.min_fraction),
        {ng, ng, ng},
        {ng + mesh_->owned_cells(0), ng + mesh_->owned_cells(1), ng + mesh_->owned_cells(2)}};
    mm->assign("init::materials", src);
    phase("painting", t0);
    for (hydro::Module* m : hydro_->modules()) {
      m->materials_placed();  // (lighting times)
      phase(std::string(m->name()) + " set-up", t0);
    }
  }
  if (!mm)
    Kokkos::parallel_for(
        "init::cells", mesh_->cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
          const double lo[3] = {g.node_coord(0, i), g.node_coord(1, j), g.node_coord(2, k)};
          const double h[3] = {g.dx[0], g.dx[1], g.dx[2]};
          // one material: every region's material index is 0
          double vol = 0, mass = 0, ener = 0;
          paint_cell(dregs, nreg, lo, h, samples, &vol, &mass, &ener);
          const double rho_c = mass, e_c = ener / mass;
          rho(i, j, k) = Real(rho_c);
          e(i, j, k) = Real(e_c);
        });
  if (!mm) phase("painting", t0);
  // Every region at rest (no velocity, not radial): every node's velocity is +0 under both
  // rules below, so the sampling (8 samples^3 points per node, most of a large scene's set-up)
  // is skipped; the fields are zero from their allocation.
  bool at_rest = true;
  for (const RegionDev& r : regs)
    for (int a = 0; a < 3; ++a)
      at_rest = at_rest && !r.radial && r.vel[a] == 0 && !std::signbit(r.vel[a]);
  const int node_samples = scene_.numerics.samples;
  if (!at_rest)
    Kokkos::parallel_for(
        "init::nodes", mesh_->nodes(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
          const double x = g.node_coord(0, i), y = g.node_coord(1, j), z = g.node_coord(2, k);
          double vel[3];
          if (!dual_cell_velocity(dregs, nreg, x, y, z, g.dx, node_samples, vel))
            point_velocity(dregs, nreg, x, y, z, vel);
          u(i, j, k) = Real(vel[0]);
          v(i, j, k) = Real(vel[1]);
          w(i, j, k) = Real(vel[2]);
        });
  phase(at_rest ? "node velocities (all regions at rest)" : "node velocities", t0);

  // Energy deposits (point blasts): the total is split evenly over the region's cells.
  for (int n = 0; n < nreg; ++n) {
    const double deposit = scene_.regions[n].deposit;
    if (deposit <= 0) continue;
    const RegionDev r = regs[n];
    double weight = 0;  // cells' volume fractions summed
    Kokkos::parallel_reduce(
        "init::deposit_weight", mesh_->cells(Region::Owned),
        KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
          const double lo[3] = {g.node_coord(0, i), g.node_coord(1, j), g.node_coord(2, k)};
          const double h[3] = {g.dx[0], g.dx[1], g.dx[2]};
          acc += r.fraction(lo, h, samples);
        },
        weight);
    double total = 0;
    MPI_Allreduce(&weight, &total, 1, MPI_DOUBLE, MPI_SUM, mesh_->comm());
    if (!(total > 0))
      throw InputError(scene_.file + ": region " + std::to_string(n) +
                       " deposits energy but covers no cell; enlarge it");
    const double per_volume_fraction = deposit / total;
    const double vol = g.cell_volume();
    if (mm) {
      const int ng = Mesh::ng;
      mm->for_cells("init::deposit", {ng, ng, ng}, mesh_->owned_end(),
                    MixedDeposit{g, r, samples, per_volume_fraction, rho, e, vol});
      continue;
    }
    Kokkos::parallel_for(
        "init::deposit", mesh_->cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
          const double lo[3] = {g.node_coord(0, i), g.node_coord(1, j), g.node_coord(2, k)};
          const double h[3] = {g.dx[0], g.dx[1], g.dx[2]};
          const double f = r.fraction(lo, h, samples);
          if (f > 0) e(i, j, k) += Real(per_volume_fraction * f / (double(rho(i, j, k)) * vol));
        });
  }
  hydro_->prepare();
  phase("equation of state", t0);
}

}  // namespace mp
