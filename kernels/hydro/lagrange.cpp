// The Lagrangian phase's predictor–corrector step on the staggered mesh (Hydro::lagrange). The
// volume change of a cell and the force on a node use the same face areas, so the work done on
// the nodes equals the p dV work taken from the cells.
#include "core/columns.hpp"
#include "hydro/hydro.hpp"
#include "hydro/point.hpp"

namespace mp::hydro {

namespace {

// The single-material predictor over every cell of `mesh`'s block: each cell's half-step density
// and energy from the start-of-step volume fluxes of its six faces (computed here from the node
// velocities, `a*` the half step times a quarter of the face areas: no stored face fluxes and no
// launch for them), its half-step pressure from `pressure(rho, e, i, j, k)`. With `start`
// (the mid-step geometry), the launch also copies the start-of-step velocities into start[0..2]
// at every node, ghosts included: each cell column its low node column, the block's last ones
// the high nodes too (a launch of its own saved; the velocities are loaded here anyway).
template <class Pressure>
void predictor_kernel(const Mesh& mesh, const Field3& u, const Field3& v, const Field3& w, Real ax,
                      Real ay, Real az, const Field3& rho, const Field3& e, const Field3& p,
                      const std::array<Field3, 6>& qt, const Kokkos::View<int**, MemSpace>& qcol,
                      const Field3& ph, Real vol, const Pressure& pressure,
                      const std::array<Field3, 3>* start = nullptr) {
  // (k-columns, core/columns.hpp)
  int lo[3], hi[3];
  mesh.box(Centering::Cell, Region::All, lo, hi);
  const auto q0 = qt[0], q1 = qt[1], q2 = qt[2], q3 = qt[3], q4 = qt[4], q5 = qt[5];
  const bool copy = start != nullptr;
  const auto u0 = copy ? (*start)[0] : u, v0 = copy ? (*start)[1] : v, w0 = copy ? (*start)[2] : w;
  const int ihi = hi[0], jhi = hi[1], khi = hi[2];
  for_columns(
      "lagrange::predictor", lo, hi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
        const auto U = local(u), V = local(v), W = local(w), ra = local(rho), ea = local(e),
                   pa = local(p), out = local(ph);
        const auto Q = sym6_local(q0, q1, q2, q3, q4, q5);
        if (copy) {
          const auto U0 = local(u0), V0 = local(v0), W0 = local(w0);
          // node column (a, b) over k0 .. kn - 1
          const auto nodes = [&](int a, int b) {
            const int kn = k1 == khi ? k1 + 1 : k1;
#pragma GCC ivdep
            for (int k = k0; k < kn; ++k) {
              U0(a, b, k) = U(a, b, k);
              V0(a, b, k) = V(a, b, k);
              W0(a, b, k) = W(a, b, k);
            }
          };
          nodes(i, j);
          if (i == ihi - 1) nodes(i + 1, j);
          if (j == jhi - 1) nodes(i, j + 1);
          if (i == ihi - 1 && j == jhi - 1) nodes(i + 1, j + 1);
        }
        // (a column without a viscous stress does no viscous work: Q = 0, the work not summed)
        const auto run = [&](auto stress) {
#pragma GCC ivdep
          for (int k = k0; k < k1; ++k) {
            const CellFaceFluxes f = cell_face_fluxes(U, V, W, i, j, k, ax, ay, az);
            const Real dv = f.net();
            const Real mass = ra(i, j, k) * vol;
            const Real v_half = vol + dv;
            Real wq = 0;
            if constexpr (decltype(stress)::value)
              wq = viscous_work(Q(i, j, k), f.xh - f.xl, f.yh - f.yl, f.zh - f.zl, U, V, W, i, j, k,
                                ax, ay, az);
            const Real e_half = pdv_energy(ea(i, j, k), pa(i, j, k), dv, wq, mass);
            out(i, j, k) = pressure(mass / v_half, e_half, i, j, k);
          }
        };
        if (qcol(i, j))
          run(std::true_type{});
        else
          run(std::false_type{});
      });
}

// A node's acceleration and its start- and end-of-step velocities (the point function of
// Hydro::lagrange's acceleration launches; a functor, not a generic lambda: nvcc allows no
// generic extended lambda). pha, Q, ra: p at the half step, the viscous stress and rho, as views
// or local().
struct NodeUpdate {
  Real vol, axf, ayf, azf, dt;
  bool has_strength;
  template <class P, class QA, class R, class F, class G>
  KOKKOS_INLINE_FUNCTION void operator()(const P& pha, const Sym6At<QA>& Q, const R& ra, const F& U,
                                         const F& V, const F& W, const G& Ub, const G& Vb,
                                         const G& Wb, Real force_sx, Real force_sy, Real force_sz,
                                         int i, int j, int k) const {
    Corners c8;
    for (int c = 0; c < 2; ++c)
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a)
          c8.set(a + 2 * b + 4 * c, pha, Q, ra, i - 1 + a, j - 1 + b, k - 1 + c);
    if (has_strength)
      apply<true>(c8, U, V, W, Ub, Vb, Wb, force_sx, force_sy, force_sz, i, j, k);
    else
      apply<false>(c8, U, V, W, Ub, Vb, Wb, force_sx, force_sy, force_sz, i, j, k);
  }
  // The node's 8 cells, corner (a, b, c) at a + 2 b + 4 c: the normal stresses p + Q_dd along
  // each axis, the shear components of Q and the densities.
  struct Corners {
    Real px[8], py[8], pz[8], sxy[8], sxz[8], syz[8], rc[8];
    template <class P, class QA, class R>
    KOKKOS_INLINE_FUNCTION void set(int n, const P& pha, const Sym6At<QA>& Q, const R& ra, int ci,
                                    int cj, int ck) {
      const Real p = pha(ci, cj, ck);
      px[n] = p + Q.xx(ci, cj, ck);
      py[n] = p + Q.yy(ci, cj, ck);
      pz[n] = p + Q.zz(ci, cj, ck);
      sxy[n] = Q.xy(ci, cj, ck);
      sxz[n] = Q.xz(ci, cj, ck);
      syz[n] = Q.yz(ci, cj, ck);
      rc[n] = ra(ci, cj, ck);
    }
  };
  // The same from the node's 8 cells; Strength: the strength forces are added (a template
  // argument: GCC vectorizes no select on a loop-invariant bool).
  template <bool Strength, class F, class G>
  KOKKOS_FORCEINLINE_FUNCTION void apply(const Corners& c8, const F& U, const F& V, const F& W,
                                         const G& Ub, const G& Vb, const G& Wb, Real force_sx,
                                         Real force_sy, Real force_sz, int i, int j, int k) const {
    // A cell below the node along an axis pushes it up, a cell above pushes it down: each axis's
    // sum over the four pairs of cells across the node, as differences, so a field uniform
    // along an axis gives exactly no force along it (a planar flow on a 3-D mesh keeps its
    // transverse velocities exactly 0; summed cell by cell, p0 + p1 - p0 - p1 left round-off,
    // 1e-15 in the layout study's stripes, and every mixed cell then ran the interface
    // reconstruction for a round-off flux in the transverse sweeps). The viscous stress's shear
    // Q_ab pushes along a across the pairs along b (the same face areas as the cells' viscous
    // work, point.hpp viscous_work); it is exactly 0 in a flow along one axis.
    Real fxs = 0, fys = 0, fzs = 0, mass = 0;
    Real xy = 0, xz = 0, yx = 0, yz = 0, zx = 0, zy = 0;
    for (int q = 0; q < 4; ++q) {
      const int lo = q & 1, hi = q >> 1;  // the pair's two other coordinates
      const int x0 = 2 * lo + 4 * hi, y0 = lo + 4 * hi, z0 = lo + 2 * hi;  // low corners
      fxs += c8.px[x0] - c8.px[x0 + 1];
      fys += c8.py[y0] - c8.py[y0 + 2];
      fzs += c8.pz[z0] - c8.pz[z0 + 4];
      xy += c8.sxy[y0] - c8.sxy[y0 + 2];
      xz += c8.sxz[z0] - c8.sxz[z0 + 4];
      yx += c8.sxy[x0] - c8.sxy[x0 + 1];
      yz += c8.syz[z0] - c8.syz[z0 + 4];
      zx += c8.sxz[x0] - c8.sxz[x0 + 1];
      zy += c8.syz[y0] - c8.syz[y0 + 2];
    }
    for (int c = 0; c < 8; ++c) mass += c8.rc[c];
    mass *= Real(0.125) * vol;
    Real force_x = fxs * axf + (xy * ayf + xz * azf), force_y = fys * ayf + (yx * axf + yz * azf),
         force_z = fzs * azf + (zx * axf + zy * ayf);
    if constexpr (Strength) {
      force_x += force_sx;
      force_y += force_sy;
      force_z += force_sz;
    }
    const Real ax = force_x / mass, ay = force_y / mass, az = force_z / mass;
    Ub(i, j, k) = U(i, j, k) + Real(0.5) * dt * ax;
    Vb(i, j, k) = V(i, j, k) + Real(0.5) * dt * ay;
    Wb(i, j, k) = W(i, j, k) + Real(0.5) * dt * az;
    U(i, j, k) += dt * ax;
    V(i, j, k) += dt * ay;
    W(i, j, k) += dt * az;
  }
};

// The mid-step geometry's face volume fluxes over cells (i, j, k0 .. k1 - 1) of a column, each
// face computed once (Options::mid_geometry; CorrectorColumns reads them): a cell's three low
// faces, and its high ones at the block's high side (ex, ey, ez: the cell extents), as the
// undeformed face's flux from the time-centred velocities u plus hydro.hpp
// cell_mid_corrections's correction (u0: the start-of-step velocities).
template <class A>
struct MidFaceColumns {
  A u, v, w, u0, v0, w0, x, y, z;
  Real cx, cy, cz;
  SweptFactors sf;
  int ex, ey, ez;
  KOKKOS_FORCEINLINE_FUNCTION CellFaceFluxes fluxes(int i, int j, int k, Real ax, Real ay, Real az,
                                                    const SweptFactors& s) const {
    const CellFaceFluxes f = cell_face_fluxes(u, v, w, i, j, k, ax, ay, az),
                         c = cell_mid_corrections(u0, v0, w0, u, v, w, i, j, k, s);
    return {f.xl + c.xl, f.xh + c.xh, f.yl + c.yl, f.yh + c.yh, f.zl + c.zl, f.zh + c.zh};
  }
  KOKKOS_FORCEINLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    // (the factors as locals, as in CorrectorColumns::cells_with)
    const Real ax = cx, ay = cy, az = cz;
    const SweptFactors s = sf;
#pragma GCC ivdep
    for (int k = k0; k < k1; ++k) {
      const CellFaceFluxes f = fluxes(i, j, k, ax, ay, az, s);
      x(i, j, k) = f.xl;
      y(i, j, k) = f.yl;
      z(i, j, k) = f.zl;
    }
    if (i == ex - 1)
      for (int k = k0; k < k1; ++k) x(i + 1, j, k) = fluxes(i, j, k, ax, ay, az, s).xh;
    if (j == ey - 1)
      for (int k = k0; k < k1; ++k) y(i, j + 1, k) = fluxes(i, j, k, ax, ay, az, s).yh;
    if (k1 == ez) z(i, j, ez) = fluxes(i, j, ez - 1, ax, ay, az, s).zh;
  }
};

// The single-material corrector over cells (i, j, kb .. ke - 1) of a column: each cell's six
// face fluxes (its three low faces stored for the remap; with the mid-step geometry read from
// MidFaceColumns's store instead), the first remap step's volumes, the
// full step's energy and density (Update; without it, a multi-material step's faces and
// volumes, its corrector being per material); Check: returns how many Lagrangian volumes are
// not positive (else 0). A loop with no branch (the high faces of the block's last cells are
// stored by the caller), which GCC vectorizes.
template <class A, bool Update = true>
struct CorrectorColumns {
  A u, v, w, x, y, z, pre, post, rho, e, ph;
  Sym6At<std::remove_const_t<A>> Q;
  A qw;        // (!Update: each cell's viscous work, for the per-material corrector)
  int stress;  // whether the column has a viscous stress (Hydro's s_.qcol; none: no work)
  Real vol, cx, cy, cz;
  StepWeights sw;
  Real vmin;
  int mid;  // the mid-step geometry: the fluxes stored by MidFaceColumns, read here
  // The cell's face fluxes on the undeformed faces (fl: the viscous stress's work) and the
  // corrector's (fl, or where Mid the stored mid-step ones).
  template <bool Mid>
  KOKKOS_FORCEINLINE_FUNCTION CellFaceFluxes fluxes_of(int i, int j, int k, CellFaceFluxes& fl,
                                                       Real fx, Real fy, Real fz) const {
    fl = cell_face_fluxes(u, v, w, i, j, k, fx, fy, fz);
    if constexpr (!Mid)
      return fl;
    else
      return {x(i, j, k), x(i + 1, j, k), y(i, j, k), y(i, j + 1, k), z(i, j, k), z(i, j, k + 1)};
  }
  // (the undeformed geometry's; the mid-step fluxes are stored by MidFaceColumns)
  KOKKOS_INLINE_FUNCTION CellFaceFluxes fluxes(int i, int j, int k) const {
    return cell_face_fluxes(u, v, w, i, j, k, cx, cy, cz);
  }
  template <bool Check>
  KOKKOS_FORCEINLINE_FUNCTION long run(int i, int j, int k0, int k1) const {
    if constexpr (!Check) {
      cells(i, j, k0, k1, nullptr);
      return 0;
    } else {
      // chunks: the volume changes kept, then counted in order (a count in the vector loop,
      // an integer sum of floating-point tests, left it scalar)
      constexpr int kChunk = 32;
      Real dvs[kChunk];
      long bad = 0;
      for (int kb = k0; kb < k1; kb += kChunk) {
        const int ke = kb + kChunk < k1 ? kb + kChunk : k1;
        cells(i, j, kb, ke, dvs);
        for (int k = kb; k < ke; ++k) bad += !(vmin + dvs[k - kb] > 0) ? 1 : 0;
      }
      return bad;
    }
  }
  // dvs (if not null): each cell's volume change, at k - kb
  KOKKOS_FORCEINLINE_FUNCTION void cells(int i, int j, int kb, int ke, Real* dvs) const {
    // (the options as template arguments: each loop straight-line code)
    if (mid) {
      if (stress)
        cells_with<true, true>(i, j, kb, ke, dvs);
      else
        cells_with<false, true>(i, j, kb, ke, dvs);
    } else if (stress) {
      cells_with<true, false>(i, j, kb, ke, dvs);
    } else {
      cells_with<false, false>(i, j, kb, ke, dvs);
    }
  }
  template <bool Stress, bool Mid>
  KOKKOS_FORCEINLINE_FUNCTION void cells_with(int i, int j, int kb, int ke, Real* dvs) const {
    // (the factors as locals: GCC kept reloading them through `this` in the loop, which its
    // stores might alias, and left the loop scalar)
    const Real fx = cx, fy = cy, fz = cz;
#pragma GCC ivdep
    for (int k = kb; k < ke; ++k) {
      CellFaceFluxes fl;
      const CellFaceFluxes f = fluxes_of<Mid>(i, j, k, fl, fx, fy, fz);
      if constexpr (!Mid) {
        x(i, j, k) = f.xl;
        y(i, j, k) = f.yl;
        z(i, j, k) = f.zl;
      }
      step_volumes(vol, f.xh - f.xl, f.yh - f.yl, f.zh - f.zl, sw, pre(i, j, k), post(i, j, k));
      const Real dv = f.net();
      Real wq = 0;
      // (the viscous stress's forces keep the undeformed faces: its work on their fluxes)
      if constexpr (Stress)
        wq = viscous_work(Q(i, j, k), fl.xh - fl.xl, fl.yh - fl.yl, fl.zh - fl.zl, u, v, w, i, j, k,
                          fx, fy, fz);
      if constexpr (Update) {
        const Real mass = rho(i, j, k) * vol;
        e(i, j, k) = pdv_energy(e(i, j, k), ph(i, j, k), dv, wq, mass);
        rho(i, j, k) = mass / (vol + dv);
      } else {
        qw(i, j, k) = wq;
      }
      if (dvs) dvs[k - kb] = dv;
    }
  }
};

// The kernels of Hydro::lagrange's corrector pass (named functors: it is a generic lambda,
// and nvcc allows no extended lambda inside one). MidFacesKernel: the mid-step geometry's face
// fluxes of a column (MidFaceColumns over the fields).
struct MidFacesKernel {
  Field3 ub, vb, wb, u0, v0, w0, fx, fy, fz;
  Real cx, cy, cz;
  SweptFactors sf;
  int ex, ey, ez;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    const auto U = local(ub);
    const MidFaceColumns<decltype(U)> faces{
        U,         local(vb), local(wb), local(u0), local(v0), local(w0), local(fx), local(fy),
        local(fz), cx,        cy,        cz,        sf,        ex,        ey,        ez};
    faces(i, j, k0, k1);
  }
};

// The corrector over a column (CorrectorColumns over the fields), counting the non-positive
// Lagrangian volumes of the owned cells (olo .. ohi) in n; it stores the high faces at the
// block's high side (ex, ey, ez: the cell extents) unless the mid-step ones are stored.
template <bool Update>
struct CorrectorKernel {
  Field3 ub, vb, wb, fx, fy, fz, pre, post, rho, e, ph, q0, q1, q2, q3, q4, q5, qw;
  Kokkos::View<int**, MemSpace> qcol;
  Real vol, cx, cy, cz;
  StepWeights sw;
  Real vmin;
  int mid;
  Kokkos::Array<int, 3> olo, ohi;
  int ex, ey, ez;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1, long& n) const {
    const auto U = local(ub);
    const CorrectorColumns<decltype(U), Update> col{
        U,          local(vb),  local(wb),  local(fx),
        local(fy),  local(fz),  local(pre), local(post),
        local(rho), local(e),   local(ph),  sym6_local(q0, q1, q2, q3, q4, q5),
        local(qw),  qcol(i, j), vol,        cx,
        cy,         cz,         sw,         vmin,
        mid};
    // the Lagrangian volumes are checked in the owned cells only: the column in three
    // runs, the middle one checked where the column is owned
    const bool col_owned = i >= olo[0] && i < ohi[0] && j >= olo[1] && j < ohi[1];
    int b, f;
    inner_run(k0, k1, olo[2], ohi[2], b, f);
    col.template run<false>(i, j, k0, b);
    if (col_owned)
      n += col.template run<true>(i, j, b, f);
    else
      col.template run<false>(i, j, b, f);
    col.template run<false>(i, j, f, k1);
    // the high faces at the block's high side (the mid-step ones are stored)
    if (mid) return;
    if (i == ex - 1)
      for (int k = k0; k < k1; ++k) col.x(i + 1, j, k) = col.fluxes(i, j, k).xh;
    if (j == ey - 1)
      for (int k = k0; k < k1; ++k) col.y(i, j + 1, k) = col.fluxes(i, j, k).yh;
    if (k1 == ez) col.z(i, j, ez) = col.fluxes(i, j, ez - 1).zh;
  }
};

// The pressure of an EOS of kind K at (rho, e), for predictor_kernel.
template <int K>
struct PressureCut {
  eos::Eos eos;
  KOKKOS_INLINE_FUNCTION Real operator()(Real r, Real en, int, int, int) const {
    return eos.template pressure_cut<K>(r, en);
  }
};

}  // namespace

// A face's volume flux per unit node velocity over a step dt: dt times a quarter of the face's
// area, per axis (one order of operations for every kernel that finds face fluxes).
static std::array<Real, 3> face_factors(const Geometry& g, Real dt) {
  return {dt * g.dx[1] * g.dx[2] * Real(0.25), dt * g.dx[0] * g.dx[2] * Real(0.25),
          dt * g.dx[0] * g.dx[1] * Real(0.25)};
}

Health Hydro::lagrange(Real dt, long cycle) {
  const Geometry g = mesh_.geometry();
  const Real vol = g.cell_volume();
  auto rho = s_.rho, e = s_.e, p = s_.p, ph = s_.p_half;
  const auto q0 = s_.qt[0], q1 = s_.qt[1], q2 = s_.qt[2], q3 = s_.qt[3], q4 = s_.qt[4],
             q5 = s_.qt[5];
  // (a multi-material step's per-cell viscous work; a single-material one has none and passes
  // a field the corrector does not touch)
  auto qw = mm_ ? s_.qw : s_.rho;
  auto fx = s_.vol_flux[0], fy = s_.vol_flux[1], fz = s_.vol_flux[2];
  const auto eos = eos_;
  const Real half = Real(0.5) * dt;
  const auto hf = face_factors(g, half), cf = face_factors(g, dt);
  auto u = s_.u, v = s_.v, w = s_.w, ub = s_.ub, vb = s_.vb, wb = s_.wb;

  // Predictor: half-step volume change with the start-of-step velocities, pressure at t+dt/2.
  // (Each cell's six face fluxes are found in the predictor's launch, from the node
  // velocities: no stored face fluxes.)
  const bool mixed = !mm_ && reactive_ && reactive_->mixed;
  const std::array<Field3, 3> start_fields{u0_, v0_, w0_};
  const std::array<Field3, 3>* start = mid_geometry_ ? &start_fields : nullptr;
  if (mm_) {
    mm_predictor(vol, hf);
  } else if (mixed) {
    // an explosive with an unreacted EOS: the two phases at the half step (reactive.hpp)
    const auto un = reactive_->unreacted;
    const Real e0 = reactive_->e0;
    const bool eq = reactive_->equilibrium;
    auto f = reactive_->fraction;
    predictor_kernel(
        mesh_, u, v, w, hf[0], hf[1], hf[2], rho, e, p, s_.qt, s_.qcol, ph, vol,
        KOKKOS_LAMBDA(Real r, Real en, int i, int j, int k) {
          return eos::he_pressure_mixed_cut(un, eos, e0, f(i, j, k), r, en, eq);
        },
        start);
  } else {
    // (the EOS kind dispatched here, so the predictor's loop has no switch: PressureCut)
    eos::with_kind(eos.kind, [&](auto kind) {
      predictor_kernel(mesh_, u, v, w, hf[0], hf[1], hf[2], rho, e, p, s_.qt, s_.qcol, ph, vol,
                       PressureCut<decltype(kind)::value>{eos}, start);
    });
  }
  // the modules' part of the half-step pressure (an explosive's F where no kernel applied it;
  // multi-material: in mm_predictor), then their nodal forces (the strength module's
  // half-step deviator)
  for (const Module* m : modules()) m->half_step_pressure(ph);
  std::array<Field3, 3> fs;
  bool has_strength = false;  // (a module's forces: the strength module's)
  for (Module* m : modules())
    if (const std::array<Field3, 3>* f = m->predictor(s_.u, s_.v, s_.w, rho, e, ph, dt)) {
      fs = *f;
      has_strength = true;
    }
  auto fsx = fs[0], fsy = fs[1], fsz = fs[2];

  // Nodal acceleration from the gradient of p + q; nodal mass is 1/8 of the 8 cells around.
  const Real axf = g.dx[1] * g.dx[2] * Real(0.25), ayf = g.dx[0] * g.dx[2] * Real(0.25),
             azf = g.dx[0] * g.dx[1] * Real(0.25);
  // (k-columns, core/columns.hpp)
  const NodeUpdate node_update{vol, axf, ayf, azf, dt, has_strength};
  const auto qcol = s_.qcol;
  if (has_strength) {
    Kokkos::parallel_for(
        "lagrange::acceleration", mesh_.nodes(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
          node_update(ph, sym6_view(q0, q1, q2, q3, q4, q5), rho, u, v, w, ub, vb, wb, fsx(i, j, k),
                      fsy(i, j, k), fsz(i, j, k), i, j, k);
        });
  } else {
    int lo[3], hi[3];
    mesh_.box(Centering::Node, Region::Owned, lo, hi);
    // (the start-of-step velocities of the mid-step geometry: copied by the predictor)
    const auto u0 = u0_, v0 = v0_, w0 = w0_;
    const bool mid = mid_geometry_;
    const Real hx = g.dx[0], hy = g.dx[1], hz = g.dx[2], hdt = half;
    for_columns(
        "lagrange::acceleration", lo, hi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
          // (captured here: nvcc allows an extended lambda no first capture in an if constexpr)
          (void)node_update, (void)hx, (void)hy, (void)hz, (void)hdt;
          // the node's 8 cells as the columns (i - 1 + a, j - 1 + b) at k - 1 + c
          using Col = decltype(column(ph, i, j));  // a pointer, or a strided column (GPU)
          const auto cols = [&](const Field3& f) {
            return Kokkos::Array<Col, 4>{column(f, i - 1, j - 1), column(f, i, j - 1),
                                         column(f, i - 1, j), column(f, i, j)};
          };
          const auto pc = cols(ph), rcol = cols(rho), cxx = cols(q0), cyy = cols(q1),
                     czz = cols(q2), cxy = cols(q3), cxz = cols(q4), cyz = cols(q5);
          const auto U = local(u), V = local(v), W = local(w), Ub = local(ub), Vb = local(vb),
                     Wb = local(wb);
          const auto U0 = local(u0), V0 = local(v0), W0 = local(w0);
          // Stress: the cells' viscous stress; none in the four cell columns around: p alone
          // (the same values, Q = 0, without its six loads per cell)
          const auto run = [&](auto stress, auto on_mid) {
            constexpr bool Stress = decltype(stress)::value;
            constexpr bool Mid = decltype(on_mid)::value;
#pragma GCC ivdep
            for (int k = k0; k < k1; ++k) {
              NodeUpdate::Corners c8;
              Real p8[8];  // the 8 cells' half-step pressures (the mid-step geometry's jumps)
          // (unrolled: vectorized on their own, these loops kept GCC from vectorizing the
          // loop over k where the stress is loaded)
#pragma GCC unroll 2
              for (int c = 0; c < 2; ++c)
#pragma GCC unroll 4
                for (int ab = 0; ab < 4; ++ab) {
                  const int n = ab + 4 * c, ck = k - 1 + c;
                  const Real pp = pc[ab][ck];
                  p8[n] = pp;
                  c8.px[n] = Stress ? pp + cxx[ab][ck] : pp;
                  c8.py[n] = Stress ? pp + cyy[ab][ck] : pp;
                  c8.pz[n] = Stress ? pp + czz[ab][ck] : pp;
                  c8.sxy[n] = Stress ? cxy[ab][ck] : Real(0);
                  c8.sxz[n] = Stress ? cxz[ab][ck] : Real(0);
                  c8.syz[n] = Stress ? cyz[ab][ck] : Real(0);
                  c8.rc[n] = rcol[ab][ck];
                }
              if constexpr (Mid) {
                Real f[3] = {0, 0, 0};
                // (the pressures as loaded above: cell (i - 1 + a, j - 1 + b, k - 1 + c) at
                // corner a + 2 b + 4 c)
                const auto P8 = [&](int ci, int cj, int cc) {
                  return p8[(ci - i + 1) + 2 * (cj - j + 1) + 4 * (cc - k + 1)];
                };
                mid_step_force(U0, V0, W0, P8, i, j, k, hx, hy, hz, f);
                node_update.template apply<true>(c8, U, V, W, Ub, Vb, Wb, hdt * f[0], hdt * f[1],
                                                 hdt * f[2], i, j, k);
              } else {
                node_update.template apply<false>(c8, U, V, W, Ub, Vb, Wb, 0, 0, 0, i, j, k);
              }
            }
          };
          const bool st = qcol(i - 1, j - 1) | qcol(i, j - 1) | qcol(i - 1, j) | qcol(i, j);
          if (mid) {
            if (st)
              run(std::true_type{}, std::true_type{});
            else
              run(std::false_type{}, std::true_type{});
          } else if (st) {
            run(std::true_type{}, std::false_type{});
          } else {
            run(std::false_type{}, std::false_type{});
          }
        });
  }
  halo_.exchange({{u, Centering::Node, {-1, 1, 1}},
                  {v, Centering::Node, {1, -1, 1}},
                  {w, Centering::Node, {1, 1, -1}},
                  {ub, Centering::Node, {-1, 1, 1}},
                  {vb, Centering::Node, {1, -1, 1}},
                  {wb, Centering::Node, {1, 1, -1}}});

  // Corrector: full-step volume change with time-centred velocities, p dV with p at t+dt/2.
  // Each cell finds its six face fluxes, stores its three low faces (and the high ones at the
  // block's high side) for the remap, writes the cycle's first remap step's volumes and counts
  // the non-positive Lagrangian volumes of the owned cells, and (a single material) updates its
  // energy and density, in one launch: the three face launches, the first remap::volumes and a
  // volume check saved (fields bit for bit: the same arithmetic). A multi-material step
  // launches it before its per-material corrector (lagrange::volume_flux), which reads the
  // stored faces, as does the strength corrector.
  const Real vmin = vol;
  const Kokkos::Array<int, 3> olo{Mesh::ng, Mesh::ng, Mesh::ng};
  const Kokkos::Array<int, 3> ohi{Mesh::ng + mesh_.owned_cells(0), Mesh::ng + mesh_.owned_cells(1),
                                  Mesh::ng + mesh_.owned_cells(2)};
  long bad = 0;
  auto corrector = [&](const char* name, auto update) {
    constexpr bool Update = decltype(update)::value;
    const int ex = mesh_.extent(Centering::Cell, 0), ey = mesh_.extent(Centering::Cell, 1),
              ez = mesh_.extent(Centering::Cell, 2);
    const Real cx = cf[0], cy = cf[1], cz = cf[2];
    const int mid = mid_geometry_ && Update ? 1 : 0;  // (mid_geometry_: no strength)
    const RemapStep first = remap_steps(cycle).front();
    const StepWeights sw = first.weights();
    auto pre = s_.pre_vol, post = s_.post_vol;
    int lo[3], hi[3];
    mesh_.box(Centering::Cell, Region::All, lo, hi);
    if (mid) {
      // the mid-step geometry's face fluxes, each face once (the corrector reads them)
      const SweptFactors sf{dt * dt, g.dx[0], g.dx[1], g.dx[2]};
      for_columns(
          "lagrange::mid_faces", lo, hi,
          MidFacesKernel{ub, vb, wb, u0_, v0_, w0_, fx, fy, fz, cx, cy, cz, sf, ex, ey, ez});
    }
    // (k-columns, core/columns.hpp)
    const CorrectorKernel<Update> kernel{ub, vb, wb,   fx,  fy,  fz,  pre, post, rho, e,  ph,
                                         q0, q1, q2,   q3,  q4,  q5,  qw,  qcol, vol, cx, cy,
                                         cz, sw, vmin, mid, olo, ohi, ex,  ey,   ez};
    reduce_columns(name, lo, hi, kernel, bad);
    volumes_ready_ = true;
    volumes_for_ = first;
  };
  if (mm_) corrector("lagrange::volume_flux", std::false_type{});
  // the deviator's work and the full-step deviator, from rho^n and e^n (before the hydro's)
  for (Module* m : modules()) m->corrector(ub, vb, wb, rho, e, ph, dt);
  if (mm_)
    mm_corrector(vol);
  else
    corrector("lagrange::corrector", std::true_type{});
  // the modules' end of the step (the explosive burns, at its new density)
  for (Module* m : modules()) m->after_lagrange(rho, dt);

  long total_bad = 0;
  MPI_Allreduce(&bad, &total_bad, 1, MPI_LONG, MPI_SUM, mesh_.comm());
  Health h;
  if (total_bad > 0) {
    h = check();
    h.ok = false;
    if (h.what.empty()) h.what = "negative Lagrangian volume";
  }
  exchange_cells();
  return h;
}

}  // namespace mp::hydro
