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
  allocate();
}

Strength::Strength(const Mesh& mesh, const MaterialModels& models,
                   const mat::MaterialState* materials)
    : mesh_(mesh), rho0_(1), models_(models), mm_(materials) {
  allocate();
}

void Strength::allocate() {
  const Mesh& mesh = mesh_;
  const char* names[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  for (int c = 0; c < 6; ++c) {
    s_[c] = mesh.new_field(std::string("stress_") + names[c], Centering::Cell);
    s_half_[c] = mesh.new_field(std::string("stress_half_") + names[c], Centering::Cell);
  }
  eps_p_ = mesh.new_field("plastic_strain", Centering::Cell);
  for (int d = 0; d < 3; ++d)
    force_[d] = mesh.new_field(std::string("stress_force_") + "xyz"[d], Centering::Node);
  scratch_ = mesh.new_field("strength_remap_scratch", Centering::Cell);
}

void Strength::stiffen_sound_speed(const Field3& rho, const Field3& e, const Field3& p,
                                   const Field3& c) const {
  if (mm_) return mm_stiffen_sound_speed(rho, c);
  const FlowStress f = model_;
  const Real rho0 = rho0_;
  auto ep = eps_p_;
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
  const SymField sh(s_half_);
  if (mm_) {
    mm_predictor(u, v, w, dt);
  } else {
    const Real rx = Real(0.25) / g.dx[0], ry = Real(0.25) / g.dx[1], rz = Real(0.25) / g.dx[2];
    const FlowStress f = model_;
    const Real rho0 = rho0_;
    const SymField s(s_);
    auto ep = eps_p_;
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
  const SymField s(s_), sh(s_half_);
  auto ep = eps_p_;
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

void Strength::remap(const std::array<bool, 3>& axes, const std::array<Field3, 3>& mass_flux,
                     const Field3& rho, const Field3& pre, int order) {
  hydro::remap_per_mass(mesh_, axes, mass_flux, rho, pre,
                        {s_[0], s_[1], s_[2], s_[3], s_[4], s_[5], eps_p_}, scratch_, order);
}

std::vector<HaloField> Strength::halo_fields() const {
  const auto C = Centering::Cell;
  return {{s_[0], C, {1, 1, 1}},   {s_[1], C, {1, 1, 1}},   {s_[2], C, {1, 1, 1}},
          {s_[3], C, {-1, -1, 1}}, {s_[4], C, {1, -1, -1}}, {s_[5], C, {-1, 1, -1}},
          {eps_p_, C, {1, 1, 1}}};
}

std::vector<OutputField> Strength::output_fields() const {
  const auto C = Centering::Cell;
  return {{"stress_xx", C, s_[0]},      {"stress_yy", C, s_[1]}, {"stress_zz", C, s_[2]},
          {"stress_xy", C, s_[3]},      {"stress_yz", C, s_[4]}, {"stress_zx", C, s_[5]},
          {"plastic_strain", C, eps_p_}};
}

// ------------------------------------------------------------------------------------------
// Multi-material scenes (module.hpp, "Multi-material scenes").

namespace {

// The shear modulus and flow stress of a cell: the volume-fraction weighted sums over its
// materials with strength, each at its own state; `solid` receives sum alpha_m rho_m over them.
template <class Cell>
KOKKOS_INLINE_FUNCTION void mixture_moduli(const MaterialModels& mm, const Cell& cell, Real eps_p,
                                           Real eps_dot, bool half, Real& G, Real& Y, Real& solid) {
  G = Y = solid = 0;
  for (int s = 0; s < cell.count(); ++s) {
    const mat::MatRef m = cell.get(s);
    const FlowStress& f = mm.f[m.m];
    if (!(m.alpha > 0) || f.kind == kNoStrength) continue;
    const PointState x =
        point_state(f, mm.rho0[m.m], *m.rho, *m.e, half ? *m.ph : *m.p, eps_p, eps_dot);
    G += m.alpha * f.shear_modulus(x);
    Y += m.alpha * f.yield_stress(x);
    solid += m.alpha * *m.rho;
  }
}

}  // namespace

void Strength::mm_stiffen_sound_speed(const Field3& rho, const Field3& c) const {
  const MaterialModels models = models_;
  auto ep = eps_p_;
  mm_->for_cells(
      "strength::sound_speed", {0, 0, 0},
      {mesh_.extent(Centering::Cell, 0), mesh_.extent(Centering::Cell, 1),
       mesh_.extent(Centering::Cell, 2)},
      KOKKOS_LAMBDA(int i, int j, int k, const auto& cell) {
        Real G, Y, solid;
        mixture_moduli(models, cell, ep(i, j, k), Real(0), false, G, Y, solid);
        if (!(solid > 0)) return;
        const Real c0 = c(i, j, k);
        c(i, j, k) = msqrt(c0 * c0 + Real(4) / Real(3) * G / rho(i, j, k));
      });
}

void Strength::mm_predictor(const Field3& u, const Field3& v, const Field3& w, Real dt) {
  const Geometry g = mesh_.geometry();
  const Real rx = Real(0.25) / g.dx[0], ry = Real(0.25) / g.dx[1], rz = Real(0.25) / g.dx[2];
  const MaterialModels models = models_;
  const SymField s(s_), sh(s_half_);
  auto ep = eps_p_;
  const Real h = Real(0.5) * dt;
  const int ng = Mesh::ng;
  const auto end = mesh_.owned_end();
  mm_->for_cells(
      "strength::predictor", {ng - 1, ng - 1, ng - 1}, {end[0] + 1, end[1] + 1, end[2] + 1},
      KOKKOS_LAMBDA(int i, int j, int k, const auto& cell) {
        const Mat3 L = cell_gradient(u, v, w, i, j, k, rx, ry, rz);
        Real G, Y, solid;
        mixture_moduli(models, cell, ep(i, j, k), equivalent_strain_rate(L), true, G, Y, solid);
        Sym t{};
        if (solid > 0) {
          t = elastic_trial_rotated(s.get(i, j, k), L, G, h);
          radial_return(t, Y, G);
        }
        sh.set(i, j, k, t);
      });
}

void Strength::mm_corrector(const Field3& ub, const Field3& vb, const Field3& wb, Real dt) {
  const Geometry g = mesh_.geometry();
  const Real rx = Real(0.25) / g.dx[0], ry = Real(0.25) / g.dx[1], rz = Real(0.25) / g.dx[2];
  const MaterialModels models = models_;
  const SymField s(s_), sh(s_half_);
  auto ep = eps_p_;
  const int ng = Mesh::ng;
  mm_->for_cells(
      "strength::corrector", {ng, ng, ng}, mesh_.owned_end(),
      KOKKOS_LAMBDA(int i, int j, int k, const auto& cell) {
        const Mat3 L = cell_gradient(ub, vb, wb, i, j, k, rx, ry, rz);
        Real G, Y, solid;
        mixture_moduli(models, cell, ep(i, j, k), equivalent_strain_rate(L), true, G, Y, solid);
        if (!(solid > 0)) {
          s.set(i, j, k, Sym{});
          return;
        }
        const Sym q = sh.get(i, j, k);
        const Real power = q.xx * L(0, 0) + q.yy * L(1, 1) + q.zz * L(2, 2) +
                           q.xy * (L(0, 1) + L(1, 0)) + q.yz * (L(1, 2) + L(2, 1)) +
                           q.zx * (L(2, 0) + L(0, 2));
        Sym t = elastic_trial_rotated(s.get(i, j, k), L, G, dt);
        const ReturnResult rr = radial_return(t, Y, G);
        s.set(i, j, k, t);
        ep(i, j, k) += rr.d_eps_p;
        // the work goes to the materials with strength, the same specific energy to each (the
        // hydro's corrector then rebuilds a mixed cell's average from its materials)
        const Real de = dt * power / solid;
        for (int n = 0; n < cell.count(); ++n) {
          const mat::MatRef m = cell.get(n);
          if (m.alpha > 0 && models.f[m.m].kind != kNoStrength) *m.e += de;
        }
      });
}

}  // namespace mp::strength
