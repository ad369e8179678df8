// The strength module's stress update: the sound speed, the predictor's half-step stress and its
// nodal forces, the corrector's full-step stress and its work (single set and multi-material).
#include "strength/module.hpp"

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
  SymField() = default;
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

const std::array<Field3, 3>* Strength::predictor(const Field3& u, const Field3& v, const Field3& w,
                                                 const Field3& rho, const Field3& e,
                                                 const Field3& p_half, Real dt) {
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
  return &force_;
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

// Where one stress set's values are (module.hpp, "Storage"): the dense layout's cell fields of
// the set, or the compact layout's pure-cell arrays and per-slot extras (0-5 deviator, 6
// plastic strain, 7-12 half-step deviator). Accessed through the cell accessor of the layout.
struct SetStore {
  int mid = -1;
  SymField s, sh;  // dense
  Field3 ep;
  SymField ps;  // compact: pure cells
  Field3 pep;
  Buffer sx[13];  // compact: slots

  KOKKOS_INLINE_FUNCTION Sym get_s(const mat::DenseCell&, int, int i, int j, int k) const {
    return s.get(i, j, k);
  }
  KOKKOS_INLINE_FUNCTION Sym get_s(const mat::PureCell&, int, int i, int j, int k) const {
    return ps.get(i, j, k);
  }
  KOKKOS_INLINE_FUNCTION Sym get_s(const mat::MixedCell& c, int slot, int, int, int) const {
    return take(c.first + slot, 0);
  }
  KOKKOS_INLINE_FUNCTION void set_s(const mat::DenseCell&, int, int i, int j, int k,
                                    const Sym& t) const {
    s.set(i, j, k, t);
  }
  KOKKOS_INLINE_FUNCTION void set_s(const mat::PureCell&, int, int i, int j, int k,
                                    const Sym& t) const {
    ps.set(i, j, k, t);
  }
  KOKKOS_INLINE_FUNCTION void set_s(const mat::MixedCell& c, int slot, int, int, int,
                                    const Sym& t) const {
    put(c.first + slot, 0, t);
  }
  KOKKOS_INLINE_FUNCTION Real& eps(const mat::DenseCell&, int, int i, int j, int k) const {
    return ep(i, j, k);
  }
  KOKKOS_INLINE_FUNCTION Real& eps(const mat::PureCell&, int, int i, int j, int k) const {
    return pep(i, j, k);
  }
  KOKKOS_INLINE_FUNCTION Real& eps(const mat::MixedCell& c, int slot, int, int, int) const {
    return sx[6](c.first + slot);
  }
  // The half-step deviator of a material that shares its cell (a material alone in its cell
  // has the cell's: the callers read cell_half_ there, and a pure compact cell stores none).
  KOKKOS_INLINE_FUNCTION Sym get_sh(const mat::DenseCell&, int, int i, int j, int k) const {
    return sh.get(i, j, k);
  }
  KOKKOS_INLINE_FUNCTION Sym get_sh(const mat::PureCell&, int, int, int, int) const {
    return Sym{};  // (never called: a pure cell's material is alone)
  }
  KOKKOS_INLINE_FUNCTION Sym get_sh(const mat::MixedCell& c, int slot, int, int, int) const {
    return take(c.first + slot, 7);
  }
  KOKKOS_INLINE_FUNCTION void set_sh(const mat::DenseCell&, int, int i, int j, int k,
                                     const Sym& t) const {
    sh.set(i, j, k, t);
  }
  KOKKOS_INLINE_FUNCTION void set_sh(const mat::PureCell&, int, int, int, int, const Sym&) const {}
  KOKKOS_INLINE_FUNCTION void set_sh(const mat::MixedCell& c, int slot, int, int, int,
                                     const Sym& t) const {
    put(c.first + slot, 7, t);
  }
  KOKKOS_INLINE_FUNCTION Sym take(int q, int x0) const {
    return {sx[x0](q), sx[x0 + 1](q), sx[x0 + 2](q), sx[x0 + 3](q), sx[x0 + 4](q), sx[x0 + 5](q)};
  }
  KOKKOS_INLINE_FUNCTION void put(int q, int x0, const Sym& t) const {
    sx[x0](q) = t.xx;
    sx[x0 + 1](q) = t.yy;
    sx[x0 + 2](q) = t.zz;
    sx[x0 + 3](q) = t.xy;
    sx[x0 + 4](q) = t.yz;
    sx[x0 + 5](q) = t.zx;
  }
};

// The plastic strain of each material with strength, indexed by material id (dense: its set's
// field; compact: the pure-cell array and the slot extra, shared by all).
struct StrainOf {
  Field3 f[mat::kMaxMaterials];
  Field3 pure;
  Buffer slot;
  KOKKOS_INLINE_FUNCTION Real get(const mat::DenseCell&, int, int m, int i, int j, int k) const {
    return f[m](i, j, k);
  }
  KOKKOS_INLINE_FUNCTION Real get(const mat::PureCell&, int, int, int i, int j, int k) const {
    return pure(i, j, k);
  }
  KOKKOS_INLINE_FUNCTION Real get(const mat::MixedCell& c, int s, int, int, int, int) const {
    return slot(c.first + s);
  }
};

KOKKOS_INLINE_FUNCTION Real stress_power(const Sym& q, const Mat3& L) {
  return q.xx * L(0, 0) + q.yy * L(1, 1) + q.zz * L(2, 2) + q.xy * (L(0, 1) + L(1, 0)) +
         q.yz * (L(1, 2) + L(2, 1)) + q.zx * (L(2, 0) + L(0, 2));
}

// Set `set`'s store as the kernels launched now see it: its cell fields (dense), or the
// pure-cell arrays, the current pool buffer set's slot extras and the half-step slot buffers.
SetStore set_store(const StressSet& set, const mat::MaterialState* mm,
                   const std::array<Field3, 7>& pure, const Buffer (&half)[6]) {
  SetStore st;
  st.mid = set.material;
  if (mm->kind() == mat::LayoutKind::Compact) {
    st.ps = SymField({pure[0], pure[1], pure[2], pure[3], pure[4], pure[5]});
    st.pep = pure[6];
    const mat::CompactDev& cd = mm->compact();
    for (int x = 0; x < 7; ++x) st.sx[x] = cd.sx[x];
    for (int x = 7; x < 13; ++x) st.sx[x] = half[x - 7];
  } else {
    st.s = SymField(set.s);
    st.sh = SymField(set.s_half);
    st.ep = set.eps_p;
  }
  return st;
}

// The for_cells bodies of the multi-material kernels below (functors at namespace scope, not
// generic extended lambdas, which nvcc rejects inside for_cells' own lambdas).

// strength::sound_speed (Strength::mm_stiffen_sound_speed)
struct StiffenSoundSpeed {
  MaterialModels models;
  StrainOf eps;
  Field3 rho, c;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    // the cell's shear stiffness: sum alpha_m G_m over its materials with strength, each at
    // its own state and plastic strain
    Real G = 0;
    bool any = false;
    for (int s = 0; s < cell.count(); ++s) {
      const mat::MatRef m = cell.get(s);
      const FlowStress& f = models.f[m.m];
      if (!(m.alpha > 0) || f.kind == kNoStrength) continue;
      const PointState x = point_state(f, models.rho0[m.m], *m.rho, *m.e, *m.p,
                                       eps.get(cell, s, m.m, i, j, k), Real(0));
      G += m.alpha * f.shear_modulus(x);
      any = true;
    }
    if (!any) return;
    const Real c0 = c(i, j, k);
    c(i, j, k) = msqrt(c0 * c0 + Real(4) / Real(3) * G / rho(i, j, k));
  }
};

// strength::predictor (Strength::mm_predictor), for stress set st of material mid
struct MixedPredictor {
  SetStore st;
  int mid;
  bool first;
  SymField cs;
  MaterialModels models;
  Field3 u, v, w;
  Real rx, ry, rz, h;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    const int slot = find_material(cell, mid);
    if (slot < 0) {
      if constexpr (std::is_same_v<Cell, mat::DenseCell>) st.set_sh(cell, 0, i, j, k, Sym{});
      if (first) cs.set(i, j, k, Sym{});
      return;
    }
    const mat::MatRef m = cell.get(slot);
    const FlowStress& f = models.f[mid];
    const Mat3 L = cell_gradient(u, v, w, i, j, k, rx, ry, rz);
    const PointState x = point_state(f, models.rho0[mid], *m.rho, *m.e, *m.ph,
                                     st.eps(cell, slot, i, j, k), equivalent_strain_rate(L));
    const Real G = f.shear_modulus(x);
    Sym t = elastic_trial_rotated(st.get_s(cell, slot, i, j, k), L, G, h);
    radial_return(t, f.yield_stress(x), G);
    st.set_sh(cell, slot, i, j, k, t);
    // the cell's stress on its nodes: each material's deviator over its share of the
    // cell, summed in material-id order
    const Real a = m.alpha;
    Sym c = first ? Sym{} : cs.get(i, j, k);
    c = Sym{c.xx + a * t.xx, c.yy + a * t.yy, c.zz + a * t.zz,
            c.xy + a * t.xy, c.yz + a * t.yz, c.zx + a * t.zx};
    cs.set(i, j, k, c);
  }
};

// strength::corrector (Strength::mm_corrector), for stress set st of material mid
struct MixedCorrector {
  SetStore st;
  int mid;
  SymField cs;
  MaterialModels models;
  Field3 ub, vb, wb;
  Real rx, ry, rz, dt;

  template <class Cell>
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, const Cell& cell) const {
    const int slot = find_material(cell, mid);
    if (slot < 0) {
      if constexpr (std::is_same_v<Cell, mat::DenseCell>) st.set_s(cell, 0, i, j, k, Sym{});
      return;
    }
    const mat::MatRef m = cell.get(slot);
    const FlowStress& f = models.f[mid];
    const Mat3 L = cell_gradient(ub, vb, wb, i, j, k, rx, ry, rz);
    // the work of the material's half-step deviator, alpha_m s_m : L V dt (its part of
    // the power the cell's nodal forces took), per unit mass of the material; a material
    // alone in its cell has the cell's half-step stress
    const Sym half = mat::holds_several(cell) ? st.get_sh(cell, slot, i, j, k) : cs.get(i, j, k);
    const Real power = stress_power(half, L);
    const Real r = *m.rho, en = *m.e;
    Real& ep = st.eps(cell, slot, i, j, k);
    const PointState x =
        point_state(f, models.rho0[mid], r, en, *m.ph, ep, equivalent_strain_rate(L));
    const Real G = f.shear_modulus(x);
    Sym t = elastic_trial_rotated(st.get_s(cell, slot, i, j, k), L, G, dt);
    const ReturnResult rr = radial_return(t, f.yield_stress(x), G);
    st.set_s(cell, slot, i, j, k, t);
    ep += rr.d_eps_p;
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
  }
};

}  // namespace

void Strength::mm_stiffen_sound_speed(const Field3& rho, const Field3& c) const {
  const MaterialModels models = models_;
  StrainOf eps;
  if (pooled_) {
    eps.pure = pure_[6];
    eps.slot = mm_->compact().sx[6];
  } else {
    for (const StressSet& st : sets_) eps.f[st.material] = st.eps_p;
  }
  mm_->for_cells("strength::sound_speed", {0, 0, 0},
                 {mesh_.extent(Centering::Cell, 0), mesh_.extent(Centering::Cell, 1),
                  mesh_.extent(Centering::Cell, 2)},
                 StiffenSoundSpeed{models, eps, rho, c});
}

void Strength::mm_predictor(const Field3& u, const Field3& v, const Field3& w, Real dt) {
  const Geometry g = mesh_.geometry();
  const Real rx = Real(0.25) / g.dx[0], ry = Real(0.25) / g.dx[1], rz = Real(0.25) / g.dx[2];
  const MaterialModels models = models_;
  const SymField cs(cell_half_);
  const Real h = Real(0.5) * dt;
  const int ng = Mesh::ng;
  const auto end = mesh_.owned_end();
  if (pooled_) {
    const std::size_t cap = mm_->compact().smat.extent(0);
    for (Buffer& b : half_)
      if (b.extent(0) < cap)
        b = Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "slot_stress_half"), cap);
  }
  for (int q = 0; q < sets(); ++q) {
    const SetStore st = set_store(sets_[q], mm_, pure_, half_);
    const int mid = st.mid;
    const bool first = q == 0;
    mm_->for_cells("strength::predictor", {ng - 1, ng - 1, ng - 1},
                   {end[0] + 1, end[1] + 1, end[2] + 1},
                   MixedPredictor{st, mid, first, cs, models, u, v, w, rx, ry, rz, h});
  }
}

void Strength::mm_corrector(const Field3& ub, const Field3& vb, const Field3& wb, Real dt) {
  const Geometry g = mesh_.geometry();
  const Real rx = Real(0.25) / g.dx[0], ry = Real(0.25) / g.dx[1], rz = Real(0.25) / g.dx[2];
  const MaterialModels models = models_;
  const SymField cs(cell_half_);
  const int ng = Mesh::ng;
  for (int q = 0; q < sets(); ++q) {
    const SetStore st = set_store(sets_[q], mm_, pure_, half_);
    const int mid = st.mid;
    mm_->for_cells("strength::corrector", {ng, ng, ng}, mesh_.owned_end(),
                   MixedCorrector{st, mid, cs, models, ub, vb, wb, rx, ry, rz, dt});
  }
}

}  // namespace mp::strength
