#include "driver/simulation.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/math.hpp"
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

eos::Eos material_eos(const MaterialSpec& m) {
  materials::MaterialData d;
  d.name = m.name;
  d.eos = m.eos;
  d.rho0 = Real(m.rho0);
  for (const auto& [k, v] : m.params) d.params[k] = Real(v);
  eos::Eos eos = materials::make_eos(d);
  if (m.has_p_min) eos.p_min = Real(m.p_min);
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
  f = strength::make_flow_stress(
      *data, st.model == "johnson_cook" ? strength::kJohnsonCook : strength::kSteinbergGuinan);
  if (st.shear_modulus > 0) {
    f.jc.G0 = Real(st.shear_modulus);
    f.sg.G0 = Real(st.shear_modulus);
  }
  return f;
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

}  // namespace

Simulation::Simulation(const Scene& scene, MPI_Comm comm, RunSettings settings)
    : scene_(scene), settings_(std::move(settings)) {
  mesh_ = std::make_unique<Mesh>(scene_.mesh, comm);
  halo_ = std::make_unique<Halo>(*mesh_);
  hydro::Options opt;
  opt.order = scene_.numerics.advection == "first" ? 1 : 2;
  opt.q_linear = Real(scene_.numerics.q_linear);
  opt.q_quadratic = Real(scene_.numerics.q_quadratic);
  opt.cfl = Real(scene_.time.cfl);
  opt.growth = Real(scene_.time.growth);
  opt.dt_max = Real(scene_.time.dt_max);
  opt.ke_fix = scene_.numerics.ke_fix;
  opt.unsplit = scene_.numerics.remap == "unsplit";
  opt.layout =
      scene_.numerics.layout == "dense" ? mat::LayoutKind::Dense : mat::LayoutKind::Compact;
  opt.interface = scene_.numerics.interface == "youngs" ? 0
                  : scene_.numerics.interface == "slic" ? 1
                                                        : 2;
  opt.min_fraction = Real(hydro::effective_min_fraction(scene_.numerics.min_fraction));
  opt.relax = scene_.numerics.closure == "relaxation";
  opt.relax_iterations = scene_.numerics.relaxation_iterations;
  if (scene_.materials.size() == 1) {
    opt.strength = material_strength(scene_.materials[0]);
    opt.strength_rho0 = Real(scene_.materials[0].rho0 > 0 ? scene_.materials[0].rho0 : 1.0);
    opt.burn = material_burn(scene_.materials[0]);
  }
  std::vector<eos::Eos> eos;
  for (const auto& m : scene_.materials) eos.push_back(material_eos(m));
  hydro_ = std::make_unique<hydro::Hydro>(*mesh_, *halo_, opt, eos);
}

Simulation::~Simulation() = default;

std::vector<std::string> Simulation::modules() const {
  std::vector<std::string> m;
  m.push_back("hydro: staggered Lagrange (predictor-corrector) + split remap, " +
              std::string(scene_.numerics.advection == "first" ? "first-order donor cell"
                                                               : "second-order van Leer") +
              " advection, " + scene_.numerics.remap + " remap");
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
      os << "; Jaumann rate, radial return; fields stress_xx..zx, plastic_strain)";
      m.push_back(os.str());
    }
    if (mat.burn.on) {
      std::ostringstream os;
      os << "burn: " << (mat.burn.programmed ? "programmed" : "")
         << (mat.burn.programmed && mat.burn.volume_burn ? " + " : "")
         << (mat.burn.volume_burn ? "CJ volume" : "") << " (" << mat.name
         << ", D=" << mat.burn.detonation_speed << " cm/us, p_cj=" << mat.burn.cj_pressure
         << " Mbar, " << mat.burn.detonators.size() << " detonator(s), ramp " << mat.burn.ramp_cells
         << " cells; p = F P_products; Huygens lighting times; fields burn_fraction, "
            "lighting_time)";
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
  for (const auto& m : scene_.materials) eos.push_back(material_eos(m));
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
  Kokkos::parallel_for(
      "init::nodes", mesh_->nodes(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
        const double x = g.node_coord(0, i), y = g.node_coord(1, j), z = g.node_coord(2, k);
        for (int n = 0; n < nreg; ++n)
          if (dregs(n).contains(x, y, z)) {
            const RegionDev& r = dregs(n);
            if (r.radial) {
              const double rx = x - r.vcenter[0], ry = y - r.vcenter[1], rz = z - r.vcenter[2];
              const double len = MP_KOKKOS_MATH::sqrt(rx * rx + ry * ry + rz * rz);
              const double f = len > 0 ? r.vel[0] / len : 0.0;
              u(i, j, k) = Real(f * rx);
              v(i, j, k) = Real(f * ry);
              w(i, j, k) = Real(f * rz);
            } else {
              u(i, j, k) = Real(r.vel[0]);
              v(i, j, k) = Real(r.vel[1]);
              w(i, j, k) = Real(r.vel[2]);
            }
          }
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
      mm->for_cells(
          "init::deposit", {ng, ng, ng}, mesh_->owned_end(),
          KOKKOS_LAMBDA(int i, int j, int k, const auto& cell) {
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
          });
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

std::string Simulation::write_dump(double t, long cycle) {
  if (!writer_) return "";
  auto fields = hydro_->output_fields();
  if (const mat::MaterialState* mm = hydro_->materials())
    for (int m = 0; m < mm->nmat(); ++m)
      fields.push_back({"fraction_" + scene_.materials[m].name, Centering::Cell, mm->fraction(m)});
  return writer_->write(fields, t, static_cast<int>(cycle));
}

RunResult Simulation::run() {
  const bool root = mesh_->rank() == 0;
  const bool write = !settings_.output_dir.empty();
  if (write) {
    if (root) make_dirs(settings_.output_dir);
    MPI_Barrier(mesh_->comm());
    if (scene_.output.write)
      writer_ = std::make_unique<Hdf5Writer>(*mesh_, settings_.output_dir, scene_.output.basename);
  }
  RunResult r;
  r.start = hydro_->totals();
  const auto t0 = std::chrono::steady_clock::now();
  auto wall = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };

  const double t_end = scene_.time.end;
  double t = 0, next_dump = scene_.output.interval > 0 ? scene_.output.interval : t_end;
  Real dt_old = 0;
  long cycle = 0;
  if (write && writer_) r.files.push_back(write_dump(t, cycle));
  hydro::Health h;
  while (t < t_end * (1 - 1e-12) && cycle < scene_.time.max_cycles) {
    hydro::TimeStep ts = hydro_->time_step(dt_old, t, t_end);
    if (cycle == 0 && ts.dt > Real(scene_.time.dt_initial)) {
      ts.dt = Real(scene_.time.dt_initial);
      ts.limit = "initial";
    }
    h = hydro_->step(ts.dt, cycle);
    // the last step lands on the end time exactly (Real(t_end - t) is rounded in float builds)
    t = ts.limit == "end" ? t_end : t + double(ts.dt);
    ++cycle;
    dt_old = ts.dt;
    if (!h.ok) break;
    if (!settings_.quiet && root &&
        (cycle % scene_.output.log_every == 0 || t >= t_end * (1 - 1e-12)))
      log_cycle(cycle, t, double(ts.dt), ts.limit, ts.cell, wall(), t / t_end);
    if (write && writer_ && scene_.output.interval > 0 && t >= next_dump * (1 - 1e-12) &&
        t < t_end * (1 - 1e-12)) {
      r.files.push_back(write_dump(t, cycle));
      next_dump += scene_.output.interval;
    }
  }
  r.cycles = cycle;
  r.time = t;
  r.wall = wall();
  r.end = hydro_->totals();
  r.health = h;
  r.ok = h.ok;
  if (write && writer_) r.files.push_back(write_dump(t, cycle));
  if (write) write_summary(r);
  return r;
}

void Simulation::write_summary(const RunResult& r) const {
  if (mesh_->rank() != 0) return;
  const double cc = double(mesh_->global_cell_count()) * double(r.cycles);
  // JSON has no NaN or infinity: a run that went non-physical writes them as null
  const auto N = [](double x) { return json_number(x); };
  std::ostringstream js;
  js.precision(17);
  auto totals = [&](const hydro::Totals& t) {
    std::ostringstream o;
    o.precision(17);
    o << "{\"mass\": " << N(t.mass) << ", \"momentum\": [" << N(t.momentum[0]) << ", "
      << N(t.momentum[1]) << ", " << N(t.momentum[2]) << "], \"internal_energy\": " << N(t.internal)
      << ", \"kinetic_energy\": " << N(t.kinetic) << ", \"total_energy\": " << N(t.total());
    if (!t.material_mass.empty()) {
      o << ", \"material_mass\": {";
      for (std::size_t m = 0; m < t.material_mass.size(); ++m)
        o << (m ? ", " : "") << "\"" << json_escape(scene_.materials[m].name)
          << "\": " << N(t.material_mass[m]);
      o << "}";
    }
    o << "}";
    return o.str();
  };
  js << "{\n  \"scene\": \"" << scene_.name << "\",\n  \"deck\": \"" << json_escape(scene_.file)
     << "\",\n  \"version\": \"" << MINIPAGOSA_VERSION << "\",\n  \"status\": \""
     << (r.ok ? "completed" : "stopped: " + json_escape(r.health.what)) << "\",\n"
     << "  \"ranks\": " << mesh_->nranks() << ",\n  \"decomposition\": [" << mesh_->dims()[0]
     << ", " << mesh_->dims()[1] << ", " << mesh_->dims()[2] << "],\n"
     << "  \"kokkos_execution_space\": \"" << ExecSpace::name() << "\",\n"
     << "  \"threads_per_rank\": " << ExecSpace().concurrency() << ",\n"
     << "  \"real\": \"" << (sizeof(Real) == 8 ? "double" : "float") << "\",\n"
     << "  \"cells\": [" << mesh_->global_cells(0) << ", " << mesh_->global_cells(1) << ", "
     << mesh_->global_cells(2) << "],\n  \"cycles\": " << r.cycles << ",\n  \"time\": " << N(r.time)
     << ",\n  \"wall_seconds\": " << N(r.wall)
     << ",\n  \"cell_cycles_per_second\": " << N(r.wall > 0 ? cc / r.wall : 0)
     << ",\n  \"modules\": [";
  const auto mods = modules();
  for (std::size_t i = 0; i < mods.size(); ++i)
    js << (i ? ", " : "") << "\"" << json_escape(mods[i]) << "\"";
  const double dm = r.end.mass - r.start.mass;
  const double de = r.end.total() - r.start.total();
  js << "],\n  \"start\": " << totals(r.start) << ",\n  \"end\": " << totals(r.end)
     << ",\n  \"mass_change_relative\": " << N(r.start.mass != 0 ? dm / r.start.mass : 0)
     << ",\n  \"total_energy_change_relative\": "
     << N(r.start.total() != 0 ? de / r.start.total() : 0) << ",\n  \"files\": [";
  for (std::size_t i = 0; i < r.files.size(); ++i)
    js << (i ? ", " : "") << "\"" << json_escape(r.files[i]) << "\"";
  js << "]";
  if (!r.ok)
    js << ",\n  \"failure\": {\"what\": \"" << json_escape(r.health.what) << "\", \"cell\": ["
       << r.health.cell[0] << ", " << r.health.cell[1] << ", " << r.health.cell[2]
       << "], \"cycle\": " << r.cycles << ", \"density\": " << N(r.health.rho)
       << ", \"energy\": " << N(r.health.e) << ", \"pressure\": " << N(r.health.p) << "}";
  js << "\n}\n";
  const std::string path = settings_.output_dir + "/summary.json";
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << js.str();
    if (!out) throw RunError("cannot write " + tmp);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw RunError("cannot rename " + tmp);
}

}  // namespace mp
