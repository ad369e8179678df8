#include "driver/simulation.hpp"

#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"
#include "core/math.hpp"
#include "core/profiling.hpp"
#include "driver/signals.hpp"
#include "io/checkpoint.hpp"
#include "io/h5_util.hpp"
#include "io/hdf5_writer.hpp"
#include "io/log.hpp"
#include "materials/geometry.hpp"
#include "materials/library.hpp"
#include "strength/library.hpp"

namespace mp {

namespace {

// A region as the painting kernel sees it.
struct RegionDev {
  geom::Shape shape;
  bool all;
  double rho, e, vel[3], vcenter[3];
  int radial;
  double wave_amp, wave_lo, wave_len;
  int wave_axis;
  int mat;

  KOKKOS_INLINE_FUNCTION bool contains(double x, double y, double z) const {
    return shape.contains(x, y, z);
  }
  // Volume fraction of the cell with low corner lo and sizes h.
  KOKKOS_INLINE_FUNCTION double fraction(const double lo[3], const double h[3], int samples) const {
    return all ? 1.0 : geom::sampled_fraction(shape, lo, h, samples);
  }
  // Density and specific energy of the region in a cell: uniform, or a smooth entropy wave
  // (density times 1 + amplitude * sin(2 pi (x - lo) / L), averaged exactly over the cell, at
  // uniform pressure).
  KOKKOS_INLINE_FUNCTION void state(const double lo[3], const double h[3], double& r,
                                    double& en) const {
    double wf = 1;
    if (wave_amp > 0) {
      const int a = wave_axis;
      const double kw = 2 * M_PI / wave_len;
      const double x0 = lo[a] - wave_lo, x1 = x0 + h[a];
      wf = 1 +
           wave_amp * (MP_KOKKOS_MATH::cos(kw * x0) - MP_KOKKOS_MATH::cos(kw * x1)) / (kw * h[a]);
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

void make_dirs(const std::string& dir) {
  std::string path;
  std::stringstream ss(dir);
  if (!dir.empty() && dir[0] == '/') path = "/";
  for (std::string part; std::getline(ss, part, '/');) {
    if (part.empty()) continue;
    path += part + "/";
    if (mkdir(path.c_str(), 0755) != 0 && errno != EEXIST)
      throw RunError("cannot create output directory '" + path + "': " + std::strerror(errno));
  }
}

eos::Eos material_eos(const MaterialSpec& m, double void_density) {
  materials::MaterialData d;
  d.name = m.name;
  d.eos = m.eos;
  d.rho0 = Real(m.rho0);
  for (const auto& [k, v] : m.params) d.params[k] = Real(v);
  eos::Eos eos = materials::make_eos(d);
  if (m.has_p_min) eos.p_min = Real(m.p_min);
  eos.rho_void = Real(void_density);
  return eos;
}

// Specific internal energy giving pressure p at density rho: every EOS here is affine in e at
// fixed density, p = p(rho, 0) + (p(rho, 1) - p(rho, 0)) e.
// The flow-stress model of a material's strength block (kNoStrength when it has none).
strength::FlowStress material_strength(const MaterialSpec& m) {
  const StrengthSpec& st = m.strength;
  strength::FlowStress f;
  if (st.model.empty()) return f;
  const strength::StrengthData* data =
      st.library.empty() ? nullptr : strength::find_strength(st.library);
  if (st.model == "elastic_plastic") {
    f.kind = strength::kConstantYield;
    f.constant = {Real(st.shear_modulus > 0 ? st.shear_modulus : double(data->G0)), Real(st.yield)};
    return f;
  }
  // a deck's shear modulus replaces the library's (and stands in where it cites none)
  strength::StrengthData d = *data;
  if (st.shear_modulus > 0) d.G0 = d.jc.G0 = d.sg.G0 = d.za.G0 = Real(st.shear_modulus);
  return strength::make_flow_stress(d, st.model == "johnson_cook" ? strength::kJohnsonCook
                                       : st.model == "zerilli_armstrong"
                                           ? strength::kZerilliArmstrong
                                           : strength::kSteinbergGuinan);
}

// The burn module's set-up of a material's burn block (burn.on false when it has none).
burn::BurnSetup material_burn(const MaterialSpec& m) {
  burn::BurnSetup b;
  const BurnSpec& bs = m.burn;
  if (!bs.on) return b;
  b.on = true;
  b.d_cj = Real(bs.detonation_speed);
  b.p_cj = Real(bs.cj_pressure);
  b.rho0 = Real(m.rho0);
  b.ramp_cells = Real(bs.ramp_cells);
  b.programmed = bs.programmed;
  b.volume_burn = bs.volume_burn;
  if (!bs.unreacted.empty()) {
    // the deck reader checked the entry (a mie_gruneisen library material)
    b.mixed = true;
    b.unreacted = materials::make_eos(*materials::find_material(bs.unreacted));
    b.e0 = Real(bs.unreacted_e0);
  }
  for (const DetonatorSpec& d : bs.detonators) {
    burn::Detonator det;
    det.kind = d.type == "point"  ? burn::Detonator::Kind::Point
               : d.type == "line" ? burn::Detonator::Kind::Line
                                  : burn::Detonator::Kind::Plane;
    det.a = d.a;
    det.b = d.b;
    det.t0 = d.time;
    b.detonators.push_back(det);
  }
  return b;
}

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

Simulation::Simulation(const Scene& scene, MPI_Comm comm, RunSettings settings)
    : scene_(scene), settings_(std::move(settings)) {
  mesh_ = std::make_unique<Mesh>(scene_.mesh, comm);
  halo_ = std::make_unique<Halo>(*mesh_);
  hydro::Options opt;
  opt.order = scene_.numerics.advection == "first" ? 1 : 2;
  opt.q_linear = Real(scene_.numerics.q_linear);
  opt.q_quadratic = Real(scene_.numerics.q_quadratic);
  opt.q_isotropic = Real(scene_.numerics.q_isotropic);
  opt.heat_flux = Real(scene_.numerics.heat_flux);
  opt.free_expansion = Real(scene_.numerics.free_expansion);
  opt.mid_geometry = scene_.numerics.geometry == "midstep";
  opt.cfl = Real(scene_.time.cfl);
  opt.growth = Real(scene_.time.growth);
  opt.dt_max = Real(scene_.time.dt_max);
  opt.ke_fix = scene_.numerics.ke_fix;
  opt.ke_fix_by_mass = scene_.numerics.ke_fix_share == "mass";
  opt.ke_fix_redo = scene_.numerics.ke_fix_redo;
  opt.unsplit = scene_.numerics.remap == "unsplit";
  opt.layout =
      scene_.numerics.layout == "dense" ? mat::LayoutKind::Dense : mat::LayoutKind::Compact;
  opt.interface = scene_.numerics.interface == "youngs" ? 0
                  : scene_.numerics.interface == "slic" ? 1
                                                        : 2;
  opt.min_fraction = Real(hydro::effective_min_fraction(scene_.numerics.min_fraction));
  opt.relax = scene_.numerics.closure == "relaxation";
  opt.relax_iterations = scene_.numerics.relaxation_iterations;
  opt.solid_floor = Real(scene_.numerics.solid_floor);
  if (scene_.materials.size() == 1) {
    opt.strength = material_strength(scene_.materials[0]);
    opt.strength_rho0 = Real(scene_.materials[0].rho0 > 0 ? scene_.materials[0].rho0 : 1.0);
    opt.burn = material_burn(scene_.materials[0]);
  } else {
    // per material; the scene reader allows one explosive
    opt.material_strength.n = int(scene_.materials.size());
    for (std::size_t m = 0; m < scene_.materials.size(); ++m) {
      const MaterialSpec& ms = scene_.materials[m];
      opt.material_names.push_back(ms.name);
      opt.material_strength.f[m] = material_strength(ms);
      opt.material_strength.rho0[m] = Real(ms.rho0 > 0 ? ms.rho0 : 1.0);
      if (ms.burn.on) {
        opt.burn = material_burn(ms);
        opt.burn.material = int(m);
      }
    }
  }
  std::vector<eos::Eos> eos;
  for (const auto& m : scene_.materials)
    eos.push_back(material_eos(m, scene_.numerics.void_density));
  hydro_ = std::make_unique<hydro::Hydro>(*mesh_, *halo_, opt, eos);
}

Simulation::~Simulation() = default;

std::vector<std::string> Simulation::modules() const {
  std::vector<std::string> m;
  m.push_back("hydro: staggered Lagrange (predictor-corrector) + remap, " +
              std::string(scene_.numerics.advection == "first" ? "first-order donor cell"
                                                               : "second-order van Leer") +
              " advection, " + scene_.numerics.remap + " remap, KE fix " +
              (!scene_.numerics.ke_fix ? std::string("off")
               : scene_.materials.size() < 2
                   ? std::string(scene_.numerics.ke_fix_redo
                                     ? "on"
                                     : "on (no donor-value redo, numerics.ke_fix_redo: false)")
               : scene_.numerics.ke_fix_share == "mass"
                   ? std::string("on (a node's loss shared by its cells' mass)")
                   : std::string("on (a node's loss in eighths, numerics.ke_fix_share: equal)")) +
              // Noh's heat flux (kernels/hydro/conduction.cpp): single-material scenes
              (scene_.numerics.heat_flux > 0 && scene_.materials.size() < 2
                   ? ", heat flux h = " +
                         [&] {
                           std::ostringstream os;
                           os << scene_.numerics.heat_flux;
                           return os.str();
                         }() +
                         " in converging shocks"
                   : std::string()) +
              // the Lagrangian step's geometry, as the hydro decided it (single material, no
              // strength)
              (hydro_->mid_geometry() ? ", mid-step geometry" : ", fixed geometry") +
              // the free-expansion rule, where the hydro allocated it
              (hydro_->free_expansion_acts() ? [&] {
                std::ostringstream os;
                os << ", free expansion to the nodes below density ratio "
                   << scene_.numerics.free_expansion;
                return os.str();
              }()
                                             : std::string()));
  if (scene_.numerics.void_density > 0) {
    std::ostringstream os;
    os << "void: a material below " << scene_.numerics.void_density
       << " g/cm3 has no pressure and no sound speed (numerics.void_density)";
    m.push_back(os.str());
  }
  for (const MaterialSpec& mat : scene_.materials) {
    std::string eos = "eos: " + mat.eos + " (" + mat.name;
    if (!mat.library.empty()) eos += ", library '" + mat.library + "'";
    for (const auto& [k, v] : mat.params) {
      std::ostringstream os;
      os << ", " << k << "=" << v;
      eos += os.str();
    }
    if (mat.has_p_min) {
      std::ostringstream os;
      os << "; tension cutoff p_min=" << mat.p_min;
      eos += os.str();
    }
    m.push_back(eos + ")");
    if (!mat.strength.model.empty()) {
      std::ostringstream os;
      os << "strength: " << mat.strength.model << " (" << mat.name;
      if (!mat.strength.library.empty() && mat.strength.model != "elastic_plastic")
        os << ", library '" << mat.strength.library << "'";
      const strength::FlowStress f = material_strength(mat);
      if (f.kind == strength::kConstantYield)
        os << ", G=" << f.constant.G0 << " Mbar, Y=" << f.constant.Y0 << " Mbar";
      os << "; Jaumann rate, radial return; fields ";
      if (scene_.materials.size() == 1)
        os << "stress_xx..zx, plastic_strain)";
      else  // its own stress set (kernels/strength/module.hpp, "Multi-material scenes")
        os << "stress_xx_" << mat.name << "..zx_" << mat.name << ", plastic_strain_" << mat.name
           << ")";
      m.push_back(os.str());
    }
    if (mat.burn.on) {
      std::ostringstream os;
      os << "burn: " << (mat.burn.programmed ? "programmed" : "")
         << (mat.burn.programmed && mat.burn.volume_burn ? " + " : "")
         << (mat.burn.volume_burn ? "CJ volume" : "") << " (" << mat.name
         << ", D=" << mat.burn.detonation_speed << " cm/us, p_cj=" << mat.burn.cj_pressure
         << " Mbar, " << mat.burn.detonators.size() << " detonator(s), ramp " << mat.burn.ramp_cells
         << " cells; "
         << (mat.burn.unreacted.empty()
                 ? std::string("p = F P_products")
                 : "p = (1-F) P_unreacted(rho, e-e0) + F P_products, unreacted '" +
                       mat.burn.unreacted + "'")
         << "; Huygens lighting times; fields burn_fraction, lighting_time)";
      m.push_back(os.str());
    }
  }
  if (scene_.materials.size() == 1) {
    m.push_back("materials: single material (no mixed cells, no interface reconstruction)");
  } else {
    const double asked = scene_.numerics.min_fraction;
    const double used = hydro::effective_min_fraction(asked);
    std::ostringstream os;
    os << "materials: " << scene_.materials.size() << " materials, " << scene_.numerics.layout
       << " layout, "
       << (scene_.numerics.closure == "relaxation"
               ? "equal-strain + pressure-relaxation (at most " +
                     std::to_string(scene_.numerics.relaxation_iterations) +
                     " iterations/cycle) mixed cells"
               : std::string("equal-strain mixed cells"))
       << ", interface reconstruction "
       << (scene_.numerics.interface == "youngs" ? "Youngs PLIC (onion skin)"
                                                 : scene_.numerics.interface)
       << ", min fraction " << used;
    if (used > asked)
      os << " (the deck's " << asked << " raised to 4 ulps of 1 in this build's "
         << (sizeof(Real) == 4 ? "float" : "double") << " fields)";
    m.push_back(os.str());
  }
  return m;
}

void Simulation::initialize() {
  std::vector<RegionDev> regs;
  std::vector<eos::Eos> eos;
  for (const auto& m : scene_.materials)
    eos.push_back(material_eos(m, scene_.numerics.void_density));
  for (const auto& r : scene_.regions) {
    RegionDev d{};
    d.shape = r.shape.shape;
    d.all = r.shape.kind == "all";
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
    d.wave_lo = scene_.mesh.lo[r.wave_axis];
    d.wave_len = scene_.mesh.hi[r.wave_axis] - scene_.mesh.lo[r.wave_axis];
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
    if (burn::Burn* b = hydro_->burn()) b->light();  // through the explosive just painted
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
  const int node_samples = scene_.numerics.samples;
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
}

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

std::string Simulation::write_dump(double t, long cycle) {
  ProfileRegion region("output::dump");
  if (!writer_) return "";
  auto fields = hydro_->output_fields();
  if (const mat::MaterialState* mm = hydro_->materials())
    for (int m = 0; m < mm->nmat(); ++m)
      fields.push_back({"fraction_" + scene_.materials[m].name, Centering::Cell, mm->fraction(m)});
  const std::string path = writer_->write(fields, t, static_cast<int>(cycle));
  const std::string file = path.substr(path.rfind('/') + 1);
  bool known = false;
  for (auto& d : dumps_)
    if (d.file == file) {
      d = {file, t, cycle};
      known = true;
    }
  if (!known) dumps_.push_back({file, t, cycle});
  return path;
}

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
  for (const OutputField& o : module_state()) f.push_back(o);
  return f;
}

// What the strength and burn modules carry from cycle to cycle: the stress deviator and plastic
// strain, the burn fraction (their other fields are derived, or static like lighting times).
std::vector<OutputField> Simulation::module_state() const {
  std::vector<OutputField> f;
  if (const strength::Strength* st = hydro_->strength())
    for (const OutputField& o : st->state_fields()) f.push_back(o);
  if (const burn::Burn* b = hydro_->burn())
    f.push_back({"burn_fraction", Centering::Cell, b->fraction()});
  return f;
}

namespace {

const char* real_name() {
  return sizeof(Real) == 8 ? "double" : "float";
}

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
  return j.dump();
}

std::string Simulation::write_checkpoint_now() {
  ProfileRegion region("output::checkpoint");
  const std::string path = checkpoint_path(settings_.output_dir, scene_.output.basename, cycle_);
  write_checkpoint(*mesh_, path, checkpoint_fields(), checkpoint_meta());
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
  const std::vector<OutputField> state = module_state();
  for (const OutputField& o : state) fields.push_back(o);
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
    // stress sets kept in the compact pool take their values once the pool holds the materials
    if (strength::Strength* st = hydro_->strength()) st->restore_state(state);
    if (burn::Burn* b = hydro_->burn()) b->light();
    auto rho = s.rho, e = s.e;
    Kokkos::parallel_for(
        "restart::cells", mesh_->cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
          rho(i, j, k) = crho(i, j, k);
          e(i, j, k) = ce(i, j, k);
        });
  }
  hydro_->prepare();

  try {
    t_ = meta.at("time").get<double>();
    if (burn::Burn* b = hydro_->burn()) b->set_time(t_);
    cycle_ = meta.at("cycle").get<long>();
    dt_old_ = Real(meta.at("dt_old").get<double>());
    next_dump_ = meta.at("next_dump").get<double>();
    start_ = totals_from(meta.at("start"));
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

void Simulation::prepare_output_dir() {
  const std::string& dir = settings_.output_dir;
  h5::on_root(mesh_->comm(), [&] {
    make_dirs(dir);
    // Temporary files are renamed once complete; any left here were cut short by a crash or a
    // kill of an earlier run and hold nothing a later run may read.
    DIR* dp = opendir(dir.c_str());
    if (!dp) throw RunError("cannot read output directory '" + dir + "': " + std::strerror(errno));
    std::vector<std::string> stale;
    while (const dirent* e = readdir(dp)) {
      const std::string name = e->d_name;
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) stale.push_back(name);
    }
    closedir(dp);
    std::sort(stale.begin(), stale.end());
    for (const auto& name : stale) {
      const std::string p = dir + "/" + name;
      if (std::remove(p.c_str()) != 0)
        throw RunError("cannot remove stale temporary file " + p + ": " + std::strerror(errno));
      log_line("  removed stale temporary file " + p + " (left by an earlier run cut short)");
    }
  });
}

RunResult Simulation::run() {
  const bool root = mesh_->rank() == 0;
  const bool write = !settings_.output_dir.empty();
  if (write) {
    prepare_output_dir();
    if (scene_.output.write) {
      writer_ = std::make_unique<Hdf5Writer>(*mesh_, settings_.output_dir, scene_.output.basename);
      if (restarted_) {
        std::vector<OutputField> fields = hydro_->output_fields();
        if (const mat::MaterialState* mm = hydro_->materials())
          for (int m = 0; m < mm->nmat(); ++m)
            fields.push_back({"fraction_" + scene_.materials[m].name, Centering::Cell, Field3()});
        for (const auto& d : dumps_)
          if (d.cycle <= cycle_) writer_->remember(d.file, d.time, int(d.cycle), fields);
      }
    }
  }
  const double t_end = scene_.time.end;
  RunResult r;
  r.first_cycle = cycle_;
  r.restarted_from = restarted_from_;
  r.restart_changes = restart_changes_;
  r.restart_history = restart_history_;
  if (!restarted_) {
    start_ = hydro_->totals();
    t_ = 0;
    cycle_ = 0;
    dt_old_ = 0;
    next_dump_ = scene_.output.interval > 0 ? scene_.output.interval : t_end;
    if (write && writer_) files_.push_back(write_dump(t_, cycle_));
  } else {
    log_line("  restarted from " + restarted_from_ + " at cycle " + std::to_string(cycle_));
  }
  r.start = start_;
  const auto t0 = std::chrono::steady_clock::now();
  auto wall = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  const double t_begin = t_;
  double last_checkpoint = 0;
  long checkpoint_cycle = -1;
  const bool checkpoints =
      write && (scene_.output.checkpoint_cycles > 0 || scene_.output.checkpoint_seconds > 0);

  hydro::Health h;
  bool interrupted = false;
  try {
    while (t_ < t_end * (1 - 1e-12) && cycle_ < scene_.time.max_cycles) {
      hydro::TimeStep ts = hydro_->time_step(dt_old_, t_, t_end);
      if (cycle_ == 0 && ts.dt > Real(scene_.time.dt_initial)) {
        ts.dt = Real(scene_.time.dt_initial);
        ts.limit = "initial";
      }
      h = hydro_->step(ts.dt, cycle_);
      // the last step lands on the end time exactly (Real(t_end - t) is rounded in float builds)
      t_ = ts.limit == "end" ? t_end : t_ + double(ts.dt);
      ++cycle_;
      dt_old_ = ts.dt;
      if (!h.ok) break;
      const bool at_end = t_ >= t_end * (1 - 1e-12);
      if (!settings_.quiet && root && (cycle_ % scene_.output.log_every == 0 || at_end)) {
        const double w = wall(), done = (t_ - t_begin) / (t_end - t_begin);
        log_cycle(cycle_, t_, double(ts.dt), ts.limit, ts.cell, w, t_ / t_end,
                  done > 0 ? w * (1 - done) / done : -1);
      }
      if (write && writer_ && scene_.output.interval > 0 && t_ >= next_dump_ * (1 - 1e-12) &&
          !at_end) {
        files_.push_back(write_dump(t_, cycle_));
        next_dump_ += scene_.output.interval;
      }
      // Every rank learns whether any rank saw a stop signal or reached the checkpoint wall
      // time, so all stop or checkpoint after the same cycle.
      int flags = 0;
      if (settings_.watch_signals && signals::requested()) flags |= 1;
      if (checkpoints && scene_.output.checkpoint_seconds > 0 &&
          wall() - last_checkpoint >= scene_.output.checkpoint_seconds)
        flags |= 2;
      MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, &flags, 1, MPI_INT, MPI_BOR, mesh_->comm()));
      if (flags & 1) {
        interrupted = !at_end;
        break;
      }
      if (checkpoints && !at_end &&
          ((scene_.output.checkpoint_cycles > 0 && cycle_ % scene_.output.checkpoint_cycles == 0) ||
           (flags & 2))) {
        r.checkpoints.push_back(write_checkpoint_now());
        checkpoint_cycle = cycle_;
        last_checkpoint = wall();
        if (!settings_.quiet) log_line("  checkpoint " + r.checkpoints.back());
      }
    }
  } catch (const CollectiveError& e) {
    output_failed(r, e.what());
  }
  r.cycles = cycle_;
  r.time = t_;
  r.end = hydro_->totals();
  r.ke_redone = hydro_->ke_redone();
  r.health = h;
  const double tot[] = {r.end.mass,        r.end.internal,    r.end.kinetic,
                        r.end.momentum[0], r.end.momentum[1], r.end.momentum[2]};
  bool finite = true;
  for (double v : tot) finite = finite && std::isfinite(v);
  if (h.ok && !finite) {
    r.health.ok = false;
    r.health.what = "non-finite totals (mass, energy or momentum)";
    r.health.cell = {-1, -1, -1};
  }
  r.ok = r.health.ok;
  r.ending = !r.ok                       ? Ending::NonPhysical
             : interrupted               ? Ending::Interrupted
             : t_ >= t_end * (1 - 1e-12) ? Ending::EndTime
                                         : Ending::MaxCycles;
  // A run that stops before its end time leaves a checkpoint to continue from.
  try {
    if (write && r.ok && (r.checkpoints.empty() || checkpoint_cycle != cycle_) &&
        (r.ending == Ending::Interrupted || (r.ending == Ending::MaxCycles && checkpoints)))
      r.checkpoints.push_back(write_checkpoint_now());
    if (write && writer_) files_.push_back(write_dump(t_, cycle_));
  } catch (const CollectiveError& e) {
    output_failed(r, e.what());
  }
  r.files = files_;
  r.wall = wall();
  if (write) write_summary(r);
  return r;
}

void Simulation::output_failed(RunResult& r, const std::string& what) {
  r.cycles = cycle_;
  r.time = t_;
  r.end = hydro_->totals();
  r.ke_redone = hydro_->ke_redone();
  r.files = files_;
  r.output_error = what;
  std::string note = "; nothing else was written";
  try {
    write_summary(r);
    note = "; summary.json records the failure";
  } catch (const std::exception&) {
  }
  throw CollectiveError(what + note);
}

void Simulation::write_summary(const RunResult& r) const {
  const std::string path = settings_.output_dir + "/summary.json";
  const std::string text = summary_json(r);
  h5::on_root(mesh_->comm(), [&] { write_text_atomically(path, text); });
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
