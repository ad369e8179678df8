// The strength module's kernels (module.hpp says what each seam does and why).
#include "strength/module.hpp"

#include "hydro/per_mass.hpp"
#include "hydro/point.hpp"
#include "strength/stress_update.hpp"

namespace mp::strength {

namespace {

// The node-averaged velocity gradient of cell (i, j, k): L_ij = sum_nodes sgn_j u_i r_j, with
// r_j = 1 / (4 dx_j) and sgn_j = +1 on the cell's high side along j.
KOKKOS_INLINE_FUNCTION Mat3 cell_gradient(const Field3& u, const Field3& v, const Field3& w, int i,
                                          int j, int k, Real rx, Real ry, Real rz) {
  Mat3 L;
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        const Real sx = a ? Real(1) : Real(-1), sy = b ? Real(1) : Real(-1),
                   sz = c ? Real(1) : Real(-1);
        const Real vel[3] = {u(i + a, j + b, k + c), v(i + a, j + b, k + c),
                             w(i + a, j + b, k + c)};
        for (int q = 0; q < 3; ++q) {
          L(q, 0) += sx * vel[q];
          L(q, 1) += sy * vel[q];
          L(q, 2) += sz * vel[q];
        }
      }
  for (int q = 0; q < 3; ++q) {
    L(q, 0) *= rx;
    L(q, 1) *= ry;
    L(q, 2) *= rz;
  }
  return L;
}

// The six components of a deviator field at a cell.
struct SymField {
  Field3 xx, yy, zz, xy, yz, zx;
  explicit SymField(const std::array<Field3, 6>& s)
      : xx(s[0]), yy(s[1]), zz(s[2]), xy(s[3]), yz(s[4]), zx(s[5]) {}
  KOKKOS_INLINE_FUNCTION Sym get(int i, int j, int k) const {
    return {xx(i, j, k), yy(i, j, k), zz(i, j, k), xy(i, j, k), yz(i, j, k), zx(i, j, k)};
  }
  KOKKOS_INLINE_FUNCTION void set(int i, int j, int k, const Sym& s) const {
    xx(i, j, k) = s.xx;
    yy(i, j, k) = s.yy;
    zz(i, j, k) = s.zz;
    xy(i, j, k) = s.xy;
    yz(i, j, k) = s.yz;
    zx(i, j, k) = s.zx;
  }
};

// The flow-stress model's inputs at a cell.
KOKKOS_INLINE_FUNCTION PointState point_state(const FlowStress& f, Real rho0, Real rho, Real e,
                                              Real p, Real eps_p, Real eps_dot) {
  PointState x;
  x.eps_p = eps_p;
  x.eps_dot = eps_dot;
  x.p = p;
  x.eta = rho / rho0;
  x.T = f.temperature_of(e);
  return x;
}

}  // namespace

Strength::Strength(const Mesh& mesh, const FlowStress& model, Real rho0)
    : mesh_(mesh), model_(model), rho0_(rho0) {
  for (int& q : set_of_) q = -1;
  sets_.push_back(new_set(-1, ""));
  cell_half_ = sets_[0].s_half;
  allocate();
}

Strength::Strength(const Mesh& mesh, const MaterialModels& models,
                   const mat::MaterialState* materials, const std::vector<std::string>& names)
    : mesh_(mesh), rho0_(1), models_(models), mm_(materials), names_(names) {
  for (int& q : set_of_) q = -1;
  for (int m = 0; m < models.n; ++m) {
    if (models.f[m].kind == kNoStrength) continue;
    set_of_[m] = int(sets_.size());
    sets_.push_back(new_set(m, "_" + std::to_string(m)));
  }
  const char* comp[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  for (int c = 0; c < 6; ++c)
    cell_half_[c] = mesh.new_field(std::string("cell_stress_half_") + comp[c], Centering::Cell);
  allocate();
}

StressSet Strength::new_set(int material, const std::string& suffix) const {
  const char* comp[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  StressSet st;
  st.material = material;
  for (int c = 0; c < 6; ++c) {
    st.s[c] = mesh_.new_field(std::string("stress_") + comp[c] + suffix, Centering::Cell);
    st.s_half[c] = mesh_.new_field(std::string("stress_half_") + comp[c] + suffix, Centering::Cell);
  }
  st.eps_p = mesh_.new_field("plastic_strain" + suffix, Centering::Cell);
  return st;
}

void Strength::allocate() {
  const Mesh& mesh = mesh_;
  for (int d = 0; d < 3; ++d)
    force_[d] = mesh.new_field(std::string("stress_force_") + "xyz"[d], Centering::Node);
  scratch_ = mesh.new_field("strength_remap_scratch", Centering::Cell);
}

void Strength::stiffen_sound_speed(const Field3& rho, const Field3& e, const Field3& p,
                                   const Field3& c) const {
  if (mm_) return mm_stiffen_sound_speed(rho, c);
  const FlowStress f = model_;
  const Real rho0 = rho0_;
  auto ep = sets_[0].eps_p;
  Kokkos::parallel_for(
      "strength::sound_speed", mesh_.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
        const Real r = rho(i, j, k);
        const Real G =
            f.shear_modulus(point_state(f, rho0, r, e(i, j, k), p(i, j, k), ep(i, j, k), Real(0)));
        const Real c0 = c(i, j, k);
        c(i, j, k) = msqrt(c0 * c0 + Real(4) / Real(3) * G / r);
      });
}

void Strength::predictor(const Field3& u, const Field3& v, const Field3& w, const Field3& rho,
                         const Field3& e, const Field3& p_half, Real dt) {
  const Geometry g = mesh_.geometry();
  if (mm_) {
    mm_predictor(u, v, w, dt);
  } else {
    const Real rx = Real(0.25) / g.dx[0], ry = Real(0.25) / g.dx[1], rz = Real(0.25) / g.dx[2];
    const FlowStress f = model_;
    const Real rho0 = rho0_;
    const SymField s(sets_[0].s), sh(sets_[0].s_half);
    auto ep = sets_[0].eps_p;
    const Real h = Real(0.5) * dt;
    Kokkos::parallel_for(
        "strength::predictor", mesh_.cells_padded(1), KOKKOS_LAMBDA(int i, int j, int k) {
          const Mat3 L = cell_gradient(u, v, w, i, j, k, rx, ry, rz);
          const PointState x = point_state(f, rho0, rho(i, j, k), e(i, j, k), p_half(i, j, k),
                                           ep(i, j, k), equivalent_strain_rate(L));
          const Real G = f.shear_modulus(x);
          Sym t = elastic_trial_rotated(s.get(i, j, k), L, G, h);
          radial_return(t, f.yield_stress(x), G);
          sh.set(i, j, k, t);
        });
  }
  // F_i = -sum_j s_ij sgn_j A_j over the node's 8 cells; sgn_j = +1 where the node lies on the
  // cell's high side along j (the cell below the node along j).
  const Real ax = g.dx[1] * g.dx[2] * Real(0.25), ay = g.dx[0] * g.dx[2] * Real(0.25),
             az = g.dx[0] * g.dx[1] * Real(0.25);
  const SymField sh(cell_half_);
  auto fx = force_[0], fy = force_[1], fz = force_[2];
  Kokkos::parallel_for(
      "strength::forces", mesh_.nodes(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
        Real F[3] = {0, 0, 0};
        for (int c = 0; c < 2; ++c)
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) {
              const Sym q = sh.get(i - 1 + a, j - 1 + b, k - 1 + c);
              const Real tx = (a == 0 ? ax : -ax), ty = (b == 0 ? ay : -ay),
                         tz = (c == 0 ? az : -az);
              F[0] -= q.xx * tx + q.xy * ty + q.zx * tz;
              F[1] -= q.xy * tx + q.yy * ty + q.yz * tz;
              F[2] -= q.zx * tx + q.yz * ty + q.zz * tz;
            }
        fx(i, j, k) = F[0];
        fy(i, j, k) = F[1];
        fz(i, j, k) = F[2];
      });
}

void Strength::corrector(const Field3& ub, const Field3& vb, const Field3& wb, const Field3& rho,
                         const Field3& e, const Field3& p_half, Real dt) {
  if (mm_) return mm_corrector(ub, vb, wb, dt);
  const Geometry g = mesh_.geometry();
  const Real rx = Real(0.25) / g.dx[0], ry = Real(0.25) / g.dx[1], rz = Real(0.25) / g.dx[2];
  const FlowStress f = model_;
  const Real rho0 = rho0_;
  const SymField s(sets_[0].s), sh(sets_[0].s_half);
  auto ep = sets_[0].eps_p;
  Kokkos::parallel_for(
      "strength::corrector", mesh_.cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
        const Mat3 L = cell_gradient(ub, vb, wb, i, j, k, rx, ry, rz);
        // the work of the half-step deviator, the power its nodal forces took from the nodes
        const Sym q = sh.get(i, j, k);
        const Real power = q.xx * L(0, 0) + q.yy * L(1, 1) + q.zz * L(2, 2) +
                           q.xy * (L(0, 1) + L(1, 0)) + q.yz * (L(1, 2) + L(2, 1)) +
                           q.zx * (L(2, 0) + L(0, 2));
        const Real r = rho(i, j, k), en = e(i, j, k);
        const PointState x =
            point_state(f, rho0, r, en, p_half(i, j, k), ep(i, j, k), equivalent_strain_rate(L));
        const Real G = f.shear_modulus(x);
        Sym t = elastic_trial_rotated(s.get(i, j, k), L, G, dt);
        const ReturnResult rr = radial_return(t, f.yield_stress(x), G);
        s.set(i, j, k, t);
        ep(i, j, k) += rr.d_eps_p;
        e(i, j, k) = en + dt * power / r;
      });
}

void Strength::remap(int q, const std::array<bool, 3>& axes, const std::array<Field3, 3>& mass_flux,
                     const Field3& rho, const Field3& pre, int order) {
  const StressSet& st = sets_[q];
  hydro::remap_per_mass(mesh_, axes, mass_flux, rho, pre,
                        {st.s[0], st.s[1], st.s[2], st.s[3], st.s[4], st.s[5], st.eps_p}, scratch_,
                        order);
}

std::vector<HaloField> Strength::halo_fields() const {
  const auto C = Centering::Cell;
  std::vector<HaloField> h;
  for (const StressSet& st : sets_) {
    // the shear components change sign under the two reflections that flip them
    const std::vector<HaloField> one{{st.s[0], C, {1, 1, 1}},   {st.s[1], C, {1, 1, 1}},
                                     {st.s[2], C, {1, 1, 1}},   {st.s[3], C, {-1, -1, 1}},
                                     {st.s[4], C, {1, -1, -1}}, {st.s[5], C, {-1, 1, -1}},
                                     {st.eps_p, C, {1, 1, 1}}};
    h.insert(h.end(), one.begin(), one.end());
  }
  return h;
}

namespace {

std::vector<OutputField> set_fields(const StressSet& st, const std::string& suffix) {
  const auto C = Centering::Cell;
  return {{"stress_xx" + suffix, C, st.s[0]},      {"stress_yy" + suffix, C, st.s[1]},
          {"stress_zz" + suffix, C, st.s[2]},      {"stress_xy" + suffix, C, st.s[3]},
          {"stress_yz" + suffix, C, st.s[4]},      {"stress_zx" + suffix, C, st.s[5]},
          {"plastic_strain" + suffix, C, st.eps_p}};
}

}  // namespace

std::vector<OutputField> Strength::output_fields() const {
  std::vector<OutputField> f;
  for (const StressSet& st : sets_) {
    const std::string suffix = st.material < 0 ? ""
                               : st.material < int(names_.size())
                                   ? "_" + names_[st.material]
                                   : "_" + std::to_string(st.material);
    const auto one = set_fields(st, suffix);
    f.insert(f.end(), one.begin(), one.end());
  }
  return f;
}

std::vector<OutputField> Strength::state_fields() const {
  std::vector<OutputField> f;
  for (const StressSet& st : sets_) {
    const auto one = set_fields(st, st.material < 0 ? "" : "_" + std::to_string(st.material));
    f.insert(f.end(), one.begin(), one.end());
  }
  return f;
}

// ------------------------------------------------------------------------------------------
// Multi-material scenes (module.hpp, "Multi-material scenes"): one pass per stress set, in
// material-id order, over the cells that hold its material.

namespace {

// The slot of material m in a cell (-1 where the cell does not hold it).
template <class Cell>
KOKKOS_INLINE_FUNCTION int find_material(const Cell& cell, int m) {
  for (int s = 0; s < cell.count(); ++s) {
    const mat::MatRef r = cell.get(s);
    if (r.m == m) return r.alpha > 0 ? s : -1;
  }
  return -1;
}

// The plastic strain field of each material with strength, indexed by material id.
struct StrainOf {
  Field3 f[mat::kMaxMaterials];
};

KOKKOS_INLINE_FUNCTION Real stress_power(const Sym& q, const Mat3& L) {
  return q.xx * L(0, 0) + q.yy * L(1, 1) + q.zz * L(2, 2) + q.xy * (L(0, 1) + L(1, 0)) +
         q.yz * (L(1, 2) + L(2, 1)) + q.zx * (L(2, 0) + L(0, 2));
}

}  // namespace

void Strength::mm_stiffen_sound_speed(const Field3& rho, const Field3& c) const {
  const MaterialModels models = models_;
  StrainOf eps;
  for (const StressSet& st : sets_) eps.f[st.material] = st.eps_p;
  mm_->for_cells(
      "strength::sound_speed", {0, 0, 0},
      {mesh_.extent(Centering::Cell, 0), mesh_.extent(Centering::Cell, 1),
       mesh_.extent(Centering::Cell, 2)},
      KOKKOS_LAMBDA(int i, int j, int k, const auto& cell) {
        // the cell's shear stiffness: sum alpha_m G_m over its materials with strength, each at
        // its own state and plastic strain
        Real G = 0;
        bool any = false;
        for (int s = 0; s < cell.count(); ++s) {
          const mat::MatRef m = cell.get(s);
          const FlowStress& f = models.f[m.m];
          if (!(m.alpha > 0) || f.kind == kNoStrength) continue;
          const PointState x =
              point_state(f, models.rho0[m.m], *m.rho, *m.e, *m.p, eps.f[m.m](i, j, k), Real(0));
          G += m.alpha * f.shear_modulus(x);
          any = true;
        }
        if (!any) return;
        const Real c0 = c(i, j, k);
        c(i, j, k) = msqrt(c0 * c0 + Real(4) / Real(3) * G / rho(i, j, k));
      });
}

void Strength::mm_predictor(const Field3& u, const Field3& v, const Field3& w, Real dt) {
  const Geometry g = mesh_.geometry();
  const Real rx = Real(0.25) / g.dx[0], ry = Real(0.25) / g.dx[1], rz = Real(0.25) / g.dx[2];
  const MaterialModels models = models_;
  const SymField cs(cell_half_);
  const Real h = Real(0.5) * dt;
  const int ng = Mesh::ng;
  const auto end = mesh_.owned_end();
  for (std::size_t q = 0; q < sets_.size(); ++q) {
    const StressSet& st = sets_[q];
    const int mid = st.material;
    const bool first = q == 0;
    const SymField s(st.s), sh(st.s_half);
    auto ep = st.eps_p;
    mm_->for_cells(
        "strength::predictor", {ng - 1, ng - 1, ng - 1}, {end[0] + 1, end[1] + 1, end[2] + 1},
        KOKKOS_LAMBDA(int i, int j, int k, const auto& cell) {
          const int slot = find_material(cell, mid);
          if (slot < 0) {
            sh.set(i, j, k, Sym{});
            if (first) cs.set(i, j, k, Sym{});
            return;
          }
          const mat::MatRef m = cell.get(slot);
          const FlowStress& f = models.f[mid];
          const Mat3 L = cell_gradient(u, v, w, i, j, k, rx, ry, rz);
          const PointState x = point_state(f, models.rho0[mid], *m.rho, *m.e, *m.ph, ep(i, j, k),
                                           equivalent_strain_rate(L));
          const Real G = f.shear_modulus(x);
          Sym t = elastic_trial_rotated(s.get(i, j, k), L, G, h);
          radial_return(t, f.yield_stress(x), G);
          sh.set(i, j, k, t);
          // the cell's stress on its nodes: each material's deviator over its share of the
          // cell, summed in material-id order
          const Real a = m.alpha;
          Sym c = first ? Sym{} : cs.get(i, j, k);
          c = Sym{c.xx + a * t.xx, c.yy + a * t.yy, c.zz + a * t.zz,
                  c.xy + a * t.xy, c.yz + a * t.yz, c.zx + a * t.zx};
          cs.set(i, j, k, c);
        });
  }
}

void Strength::mm_corrector(const Field3& ub, const Field3& vb, const Field3& wb, Real dt) {
  const Geometry g = mesh_.geometry();
  const Real rx = Real(0.25) / g.dx[0], ry = Real(0.25) / g.dx[1], rz = Real(0.25) / g.dx[2];
  const MaterialModels models = models_;
  const int ng = Mesh::ng;
  for (const StressSet& st : sets_) {
    const int mid = st.material;
    const SymField s(st.s), sh(st.s_half);
    auto ep = st.eps_p;
    mm_->for_cells(
        "strength::corrector", {ng, ng, ng}, mesh_.owned_end(),
        KOKKOS_LAMBDA(int i, int j, int k, const auto& cell) {
          const int slot = find_material(cell, mid);
          if (slot < 0) {
            s.set(i, j, k, Sym{});
            return;
          }
          const mat::MatRef m = cell.get(slot);
          const FlowStress& f = models.f[mid];
          const Mat3 L = cell_gradient(ub, vb, wb, i, j, k, rx, ry, rz);
          // the work of the material's half-step deviator, alpha_m s_m : L V dt (its part of
          // the power the cell's nodal forces took), per unit mass of the material
          const Real power = stress_power(sh.get(i, j, k), L);
          const Real r = *m.rho, en = *m.e;
          const PointState x = point_state(f, models.rho0[mid], r, en, *m.ph, ep(i, j, k),
                                           equivalent_strain_rate(L));
          const Real G = f.shear_modulus(x);
          Sym t = elastic_trial_rotated(s.get(i, j, k), L, G, dt);
          const ReturnResult rr = radial_return(t, f.yield_stress(x), G);
          s.set(i, j, k, t);
          ep(i, j, k) += rr.d_eps_p;
          // Where the work is negative (elastic unloading) in a cell that also holds materials
          // without strength, the material gives at most half of its specific energy and the
          // rest comes from those others by mass: the deviator a mixed cell holds came by remap
          // without the elastic energy that built it, so its unloading under a gas's strain can
          // take more than the solid has (cold copper, e ~ 5e-8, went negative in the
          // perforator). Total energy stays exact unless the others cannot pay either.
          Real de = dt * power / r, de_other = 0;
          const Real floor = -Real(0.5) * mmax(en, Real(0));
          if (de < floor) {
            Real other = 0, emin_other = Real(1e30);
            for (int n = 0; n < cell.count(); ++n) {
              const mat::MatRef o = cell.get(n);
              if (!(o.alpha > 0) || models.f[o.m].kind != kNoStrength) continue;
              other += o.alpha * *o.rho;
              emin_other = mmin(emin_other, *o.e);
            }
            if (other > 0) {
              const Real rest = (de - floor) * m.alpha * r / other;  // per unit mass of the others
              if (rest >= -Real(0.5) * mmax(emin_other, Real(0))) {
                de = floor;
                de_other = rest;
              }
            }
          }
          *m.e = en + de;
          if (de_other != 0)
            for (int n = 0; n < cell.count(); ++n) {
              const mat::MatRef o = cell.get(n);
              if (o.alpha > 0 && models.f[o.m].kind == kNoStrength) *o.e += de_other;
            }
        });
  }
}

}  // namespace mp::strength
