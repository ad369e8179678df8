// The Hydro object: its constructors (which fields and modules a scene has), the ghost
// exchanges, the set-up of the derived fields (prepare) and one full cycle (step).
#include "hydro/hydro.hpp"
#include "core/error.hpp"
#include "core/profiling.hpp"

namespace mp::hydro {

Hydro::Hydro(const Mesh& mesh, Halo& halo, const Options& opt, eos::Eos eos)
    : Hydro(mesh, halo, opt, std::vector<eos::Eos>{eos}) {}

Hydro::Hydro(const Mesh& mesh, Halo& halo, const Options& opt, const std::vector<eos::Eos>& eos)
    : mesh_(mesh), halo_(halo), opt_(opt), eos_(eos.at(0)) {
  const auto C = Centering::Cell, N = Centering::Node;
  s_.rho = mesh.new_field("density", C);
  s_.e = mesh.new_field("energy", C);
  s_.p = mesh.new_field("pressure", C);
  s_.c = mesh.new_field("sound_speed", C);
  s_.q = mesh.new_field("viscosity", C);
  for (int c = 0; c < 6; ++c)
    s_.qt[c] = mesh.new_field(std::string("viscosity_") + kSym6Names[c], C);
  s_.qcol = Kokkos::View<int**, MemSpace>("viscous_columns", mesh.extent(C, 0), mesh.extent(C, 1));
  s_.p_half = mesh.new_field("pressure_half", C);
  s_.converging = Kokkos::View<int, MemSpace>("converging_cells");
  s_.ke_unpaid = Kokkos::View<double, MemSpace>("ke_fix_unpaid");
  s_.ke_redo = Kokkos::View<int, MemSpace>("ke_fix_redo");
  if (eos.size() == 1 && opt.heat_flux > 0) s_.cjump = mesh.new_field("conduction_jump", C);
  // (a module with forces of its own turns it off: add_module)
  mid_geometry_ = eos.size() == 1 && opt.mid_geometry;
  if (mid_geometry_) {
    u0_ = mesh.new_field("velocity_x_start", N);
    v0_ = mesh.new_field("velocity_y_start", N);
    w0_ = mesh.new_field("velocity_z_start", N);
  }
  s_.pre_vol = mesh.new_field("pre_volume", C);
  s_.post_vol = mesh.new_field("post_volume", C);
  s_.u = mesh.new_field("velocity_x", N);
  s_.v = mesh.new_field("velocity_y", N);
  s_.w = mesh.new_field("velocity_z", N);
  s_.ub = mesh.new_field("velocity_x_mid", N);
  s_.vb = mesh.new_field("velocity_y_mid", N);
  s_.wb = mesh.new_field("velocity_z_mid", N);
  s_.node_mass = mesh.new_field("node_mass", N);
  s_.ke_loss = mesh.new_field("ke_loss", N);
  s_.dual_flux = mesh.new_field("dual_flux", N);
  s_.dual_u = mesh.new_field("dual_u", N);
  s_.dual_v = mesh.new_field("dual_v", N);
  s_.dual_w = mesh.new_field("dual_w", N);
  s_.dual_k = mesh.new_field("dual_ke", N);
  for (int d = 0; d < 3; ++d)
    s_.vol_flux[d] = mesh.new_field(std::string("volume_flux_") + "xyz"[d], N);
  for (int d = 0; d < 3; ++d) {
    // split sweeps use one pair of flux arrays in turn
    if (d == 0 || opt.unsplit) {
      s_.mass_flux[d] = mesh.new_field(std::string("mass_flux_") + "xyz"[d], N);
      s_.energy_flux[d] = mesh.new_field(std::string("energy_flux_") + "xyz"[d], N);
    } else {
      s_.mass_flux[d] = s_.mass_flux[0];
      s_.energy_flux[d] = s_.energy_flux[0];
    }
  }
  if (eos.size() == 1 && opt.ke_fix && opt.free_expansion > 0 &&
      eos[0].kind == eos::kIdealGas) {  // (and no module: add_module)
    expansion_gm1_ = Real(eos[0].params[0] - 1);
    s_.expansion_work = mesh.new_field("expansion_work", N);
    s_.expansion_work_axis[0] = s_.expansion_work;
    if (opt.unsplit)
      for (int d = 1; d < 3; ++d)
        s_.expansion_work_axis[d] = mesh.new_field(std::string("expansion_work_") + "xyz"[d], N);
    s_.expansion_any = Kokkos::View<int, MemSpace>("expansion_any");
  }
  if (eos.size() > 1) {
    s_.qw = mesh.new_field("viscous_work", C);
    mats_.n = static_cast<int>(eos.size());
    if (mats_.n > mat::kMaxMaterials)
      throw RunError("at most " + std::to_string(mat::kMaxMaterials) + " materials per scene");
    for (int m = 0; m < mats_.n; ++m) mats_.eos[m] = eos[m];
    mm_ = std::make_unique<mat::MaterialState>(mesh, opt.layout, mats_.n, s_.rho, s_.e, s_.p,
                                               s_.p_half);
    std::vector<Real> floors;  // what each EOS accepts below 0 (eos.hpp energy_floor)
    for (int m = 0; m < mats_.n; ++m) floors.push_back(mats_.eos[m].energy_floor());
    mm_->set_energy_floors(floors);
  }
}

void Hydro::add_module(std::unique_ptr<Module> m) {
  // the mid-step geometry's forces are the hydro's own: a module with forces keeps the fixed
  // faces (the strength module's deviator acts on the undeformed faces)
  if (m->adds_forces() && mid_geometry_) {
    mid_geometry_ = false;
    u0_ = v0_ = w0_ = Field3();
  }
  // the free-expansion rule acts in scenes without modules
  if (expansion_gm1_ > 0) {
    expansion_gm1_ = 0;
    s_.expansion_work = Field3();
    s_.expansion_work_axis = {};
    s_.expansion_any = Kokkos::View<int, MemSpace>();
  }
  if (const eos::Reactive* r = m->reactive()) {
    if (reactive_) throw RunError("a scene holds at most one explosive");
    if (mm_ && (r->material < 0 || r->material >= mats_.n))
      throw RunError("burn: the explosive's material id is not set");
    reactive_ = r;
  }
  const std::vector<unsigned> masks = m->carriers();
  first_carrier_.push_back(ncarrier_);
  carriers_.push_back(int(masks.size()));
  if (mm_)
    for (unsigned mask : masks) {
      if (ncarrier_ == kMaxCarriers) throw RunError("too many module carriers in one scene");
      const std::string id = std::to_string(ncarrier_);
      carrier_mask_[ncarrier_] = mask;
      carrier_flux_[ncarrier_] = mesh_.new_field("carrier_mass_flux_" + id, Centering::Node);
      carrier_rho_[ncarrier_] = mesh_.new_field("carrier_density_" + id, Centering::Cell);
      ++ncarrier_;
    }
  modules_.push_back(std::move(m));
}

void Hydro::exchange_cells() {
  // the material exchange also writes the ghosts' cell averages
  std::vector<HaloField> f;
  if (mm_) {
    mm_->exchange();
    for (Module* m : modules()) m->exchange_materials(halo_);
  } else
    f = {{s_.rho, Centering::Cell, {1, 1, 1}}, {s_.e, Centering::Cell, {1, 1, 1}}};
  for (const HaloField& h : halo_fields(module_fields(kHalo))) f.push_back(h);
  if (!f.empty()) halo_.exchange(f);
}

void Hydro::exchange_nodes(const Field3& u, const Field3& v, const Field3& w) {
  halo_.exchange({{u, Centering::Node, {-1, 1, 1}},
                  {v, Centering::Node, {1, -1, 1}},
                  {w, Centering::Node, {1, 1, -1}}});
}

void Hydro::prepare() {
  exchange_cells();
  exchange_nodes(s_.u, s_.v, s_.w);
  eos_viscosity();
}

Health Hydro::step(Real dt, long cycle) {
  Health h;
  if (opt_.heat_flux > 0) {
    ProfileRegion r("hydro::heat_flux");
    heat_flux(dt);
  }
  {
    ProfileRegion r("hydro::lagrange");
    h = lagrange(dt, cycle);
  }
  if (!h.ok) return h;
  {
    ProfileRegion r("hydro::remap");
    remap(cycle);
  }
  {
    ProfileRegion r("hydro::eos_viscosity");
    eos_viscosity();
  }
  ProfileRegion r("hydro::health");
  return check();
}

}  // namespace mp::hydro
