// The Lagrangian phase: EOS, artificial viscosity, and the predictor–corrector step on the
// staggered mesh. The volume change of a cell and the force on a node use the same face areas,
// so the work done on the nodes equals the p dV work taken from the cells.
#include "core/columns.hpp"
#include "core/error.hpp"
#include "core/math.hpp"
#include "core/profiling.hpp"
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

// The pressure of an EOS of kind K at (rho, e), for predictor_kernel.
template <int K>
struct PressureCut {
  eos::Eos eos;
  KOKKOS_INLINE_FUNCTION Real operator()(Real r, Real en, int, int, int) const {
    return eos.template pressure_cut<K>(r, en);
  }
};

// Every cell's p and c from one EOS, a k-column at a time: the kind dispatched once per column,
// so the loop over k has no switch and GCC vectorizes it (Eos::pressure_of). The values are
// Eos::pressure_cut's and sound_speed_cut's, bit for bit.
template <class A>
struct EosColumns {
  A rho, e, p, c;
  eos::Eos eos;
  template <int K>
  KOKKOS_INLINE_FUNCTION void run(int i, int j, int k0, int k1) const {
#pragma GCC ivdep
    for (int k = k0; k < k1; ++k) {
      const Real r = rho(i, j, k), en = e(i, j, k);
      p(i, j, k) = eos.template pressure_cut<K>(r, en);
      c(i, j, k) = eos.template sound_speed_cut<K>(r, en);
    }
  }
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    eos::run_kind(eos.kind, *this, i, j, k0, k1);
  }
};
template <class A>
KOKKOS_INLINE_FUNCTION EosColumns<A> eos_columns(const A& rho, const A& e, const A& p, const A& c,
                                                 const eos::Eos& eos) {
  return {rho, e, p, c, eos};
}

// The artificial viscosity of cells (i, j, k0 .. k1 - 1) of a column (hydro::viscosity with
// Christensen's limiter on the face-averaged jumps; the compression switch of viscosity_with).
// Branch-free arithmetic on every k (the selects of limited_jump and viscosity), so GCC
// vectorizes the loop; the values are the per-point form's, bit for bit.
template <class A>
struct ViscosityColumns {
  A u, v, w, rho, c, q;
  Real rx, ry, rz, cq, cl;
  KOKKOS_INLINE_FUNCTION Real jump_x(int i, int j, int k) const {
    return Real(0.25) *
           (u(i + 1, j, k) + u(i + 1, j + 1, k) + u(i + 1, j, k + 1) + u(i + 1, j + 1, k + 1) -
            u(i, j, k) - u(i, j + 1, k) - u(i, j, k + 1) - u(i, j + 1, k + 1));
  }
  KOKKOS_INLINE_FUNCTION Real jump_y(int i, int j, int k) const {
    return Real(0.25) *
           (v(i, j + 1, k) + v(i + 1, j + 1, k) + v(i, j + 1, k + 1) + v(i + 1, j + 1, k + 1) -
            v(i, j, k) - v(i + 1, j, k) - v(i, j, k + 1) - v(i + 1, j, k + 1));
  }
  KOKKOS_INLINE_FUNCTION Real jump_z(int i, int j, int k) const {
    return Real(0.25) *
           (w(i, j, k + 1) + w(i + 1, j, k + 1) + w(i, j + 1, k + 1) + w(i + 1, j + 1, k + 1) -
            w(i, j, k) - w(i + 1, j, k) - w(i, j + 1, k) - w(i + 1, j + 1, k));
  }
  // div u of cell (i, j, k) as the compression switch finds it: only where it is not >= 0 is
  // there viscosity.
  KOKKOS_INLINE_FUNCTION Real divergence(int i, int j, int k) const {
    return jump_x(i, j, k) * rx + jump_y(i, j, k) * ry + jump_z(i, j, k) * rz;
  }
  // Chunks of a column: where no cell of a chunk compresses (most of a flow), q = 0 without
  // the limiter's stencil.
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k0, int k1) const {
    constexpr int kChunk = 16;
    for (int kb = k0; kb < k1; kb += kChunk) {
      const int ke = kb + kChunk < k1 ? kb + kChunk : k1;
      Real div[kChunk];
#pragma GCC ivdep
      for (int k = kb; k < ke; ++k) div[k - kb] = divergence(i, j, k);
      bool any = false;
      for (int k = kb; k < ke; ++k) any = any || !(div[k - kb] >= 0);
      if (any) {
        full(i, j, kb, ke);
      } else {
        for (int k = kb; k < ke; ++k) q(i, j, k) = 0;
      }
    }
  }
  KOKKOS_INLINE_FUNCTION void full(int i, int j, int k0, int k1) const {
#pragma GCC ivdep
    for (int k = k0; k < k1; ++k) {
      const Real jx = jump_x(i, j, k), jy = jump_y(i, j, k), jz = jump_z(i, j, k);
      const bool expands = jx * rx + jy * ry + jz * rz >= 0;  // (divergence(i, j, k))
      const Real dx = limited_jump(jump_x(i - 1, j, k), jx, jump_x(i + 1, j, k));
      const Real dy = limited_jump(jump_y(i, j - 1, k), jy, jump_y(i, j + 1, k));
      const Real dz = limited_jump(jump_z(i, j, k - 1), jz, jump_z(i, j, k + 1));
      const Real du = -msqrt(dx * dx + dy * dy + dz * dz);
      const Real qv = hydro::viscosity(rho(i, j, k), c(i, j, k), du, dx + dy + dz, cq, cl);
      q(i, j, k) = expands ? Real(0) : qv;
    }
  }
};

// The tensor viscosity's stress Q = q S of cells (i, j, k0 .. k1 - 1) of a column (point.hpp,
// compression_direction), S from the cell's strain rate (the velocity gradient from the
// face-averaged node jumps, rx = 1 / (4 dx) ...); Q = 0 where q = 0 (no eigenvalue is sought
// there: most cells of most flows).
template <class A>
struct ViscousTensorColumns {
  A u, v, w, q, rho, c;
  Sym6At<std::remove_const_t<A>> Q;
  Real rx, ry, rz, iso;
  // Noh's heat flux (conduction.cpp), when `conduct`: cj gets the compressive jump of each
  // converging cell (point.hpp, converging), 0 elsewhere (not touched otherwise)
  std::remove_const_t<A> cj;
  bool conduct;
  Real cq, cl;
  // Whether cell (i, j, k)'s q matters. The jumps q sees are differences of node velocities, so
  // in a gas at rest or in a linear compression (where the limiter leaves 1 - psi of a few eps)
  // round-off makes |du| <~ 8 eps U, U the speeds around the cell: below s = 100 eps U,
  // q = rho (c_Q du^2 + c_L c |du|) stays below rho s (c + s). And a q below 1e-12 rho c^2 is
  // nothing to the pressure: Sedov's ambient gas ahead of the shock moves at 1e-100 .. 1e-11
  // (the remap's numerical diffusion), with q / rho c^2 down to 1e-100 (76 % of its cells at its
  // end have such a q). Neither gets a stress, and no eigenvalue is sought for them. U: the
  // |u| + |v| + |w| of the cell's low and high corner nodes.
  KOKKOS_INLINE_FUNCTION bool real_q(int i, int j, int k) const {
    const Real sp = mabs(u(i, j, k)) + mabs(v(i, j, k)) + mabs(w(i, j, k)) +
                    mabs(u(i + 1, j + 1, k + 1)) + mabs(v(i + 1, j + 1, k + 1)) +
                    mabs(w(i + 1, j + 1, k + 1));
    const Real s = 100 * std::numeric_limits<Real>::epsilon() * sp;
    const Real cc = c(i, j, k);
    return q(i, j, k) > rho(i, j, k) * (s * (cc + s) + Real(1e-12) * cc * cc);
  }
  // returns whether some cell of the column has a stress; `had`: whether it had one before;
  // `conv`: set where some cell converges (conduct only)
  KOKKOS_INLINE_FUNCTION bool operator()(int i, int j, int k0, int k1, bool had, bool& conv) const {
    int any = 0;
#pragma GCC ivdep
    for (int k = k0; k < k1; ++k) any |= real_q(i, j, k) ? 1 : 0;
    if (!any) {
      // (a column without a stress last time still holds zeros)
      if (had) {
#pragma GCC ivdep
        for (int k = k0; k < k1; ++k) Q.set(i, j, k, {0, 0, 0, 0, 0, 0});
        if (conduct)
          for (int k = k0; k < k1; ++k) cj(i, j, k) = 0;
      }
      return false;
    }
    for (int k = k0; k < k1; ++k) {
      const Real qq = q(i, j, k);
      Sym6 t{0, 0, 0, 0, 0, 0};
      Real jc = 0;
      if (real_q(i, j, k)) {
        const Sym6 d{node_jump<0>(u, i, j, k) * rx,
                     node_jump<1>(v, i, j, k) * ry,
                     node_jump<2>(w, i, j, k) * rz,
                     Real(0.5) * (node_jump<1>(u, i, j, k) * ry + node_jump<0>(v, i, j, k) * rx),
                     Real(0.5) * (node_jump<2>(u, i, j, k) * rz + node_jump<0>(w, i, j, k) * rx),
                     Real(0.5) * (node_jump<2>(v, i, j, k) * rz + node_jump<1>(w, i, j, k) * ry)};
        Real ev[3];
        const Sym6 s = compression_direction(d, ev);
        const Real qt = qq * (1 - iso), qi = qq * iso;
        t = {qt * s.xx + qi, qt * s.yy + qi, qt * s.zz + qi, qt * s.xy, qt * s.xz, qt * s.yz};
        if (conduct && converging(ev)) {
          jc = jump_of_q(qq, rho(i, j, k), c(i, j, k), cq, cl);
          conv = conv || jc > 0;
        }
      }
      Q.set(i, j, k, t);
      if (conduct) cj(i, j, k) = jc;
    }
    return true;
  }
};

}  // namespace

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
  // (strength has its own forces on the undeformed faces: the fixed geometry there)
  mid_geometry_ = eos.size() == 1 && opt.mid_geometry && opt.strength.kind == strength::kNoStrength;
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
  if (eos.size() == 1 && !opt.unsplit && opt.ke_fix && opt.free_expansion > 0 &&
      eos[0].kind == eos::kIdealGas && opt.strength.kind == strength::kNoStrength && !opt.burn.on) {
    expansion_gm1_ = Real(eos[0].params[0] - 1);
    s_.expansion_work = mesh.new_field("expansion_work", N);
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
  if (opt.strength.kind != strength::kNoStrength) {
    if (mm_) throw RunError("a multi-material scene gives strength per material");
    strength_ = std::make_unique<strength::Strength>(mesh, opt.strength, opt.strength_rho0);
  }
  if (mm_ && opt.material_strength.carriers() != 0) {
    if (opt.material_strength.n != mats_.n)
      throw RunError("strength models for " + std::to_string(opt.material_strength.n) +
                     " materials in a scene of " + std::to_string(mats_.n));
    strength_ = std::make_unique<strength::Strength>(mesh, opt.material_strength, mm_.get(),
                                                     opt.material_names);
    // one carrier per stress set: its own material's mass
    for (int q = 0; q < strength_->sets(); ++q)
      carrier_mask_[ncarrier_++] = 1u << strength_->set(q).material;
  }
  if (opt.burn.on) {
    if (!mm_) {
      burn_ = std::make_unique<burn::Burn>(mesh, opt.burn);
    } else {
      if (opt.burn.material < 0 || opt.burn.material >= mats_.n)
        throw RunError("burn: the explosive's material id is not set");
      burn_ = std::make_unique<burn::Burn>(mesh, opt.burn, mm_.get());
      burn_carrier_ = ncarrier_;
      carrier_mask_[ncarrier_++] = 1u << opt.burn.material;
    }
  }
  for (int c = 0; c < ncarrier_; ++c) {
    const std::string id = std::to_string(c);
    carrier_flux_[c] = mesh.new_field("carrier_mass_flux_" + id, N);
    carrier_rho_[c] = mesh.new_field("carrier_density_" + id, Centering::Cell);
  }
}

void Hydro::exchange_cells() {
  // the material exchange also writes the ghosts' cell averages
  std::vector<HaloField> f;
  if (mm_) {
    mm_->exchange();
    if (strength_ && strength_->pooled()) strength_->exchange_compact(halo_);
  } else
    f = {{s_.rho, Centering::Cell, {1, 1, 1}}, {s_.e, Centering::Cell, {1, 1, 1}}};
  if (strength_)
    for (const HaloField& h : strength_->halo_fields()) f.push_back(h);
  if (burn_)
    for (const HaloField& h : burn_->halo_fields()) f.push_back(h);
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

void Hydro::eos_viscosity() {
  if (plain()) {
    viscosity_with(true);
    return;
  }
  equation_of_state(s_.rho, s_.e, s_.p, s_.c);
  viscosity();
}

void Hydro::equation_of_state(const Field3& rho, const Field3& e, const Field3& p,
                              const Field3& c) const {
  if (mm_) {
    mm_equation_of_state();  // (the explosive's burn fraction applied there)
    if (strength_) strength_->stiffen_sound_speed(rho, e, p, c);
    return;
  }
  const auto eos = eos_;
  if (burn_ && burn_->mixed()) {
    // an explosive with an unreacted EOS: p and c of the two phases at frozen F (burn.hpp)
    const auto un = burn_->unreacted();
    const Real e0 = burn_->e0();
    auto f = burn_->fraction();
    Kokkos::parallel_for(
        "eos::pressure_sound_speed", mesh_.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
          const Real fi = f(i, j, k), r = rho(i, j, k), ei = e(i, j, k);
          p(i, j, k) = burn::he_pressure_mixed_cut(un, eos, e0, fi, r, ei);
          c(i, j, k) = burn::he_sound_speed_mixed(un, eos, e0, fi, r, ei);
        });
    if (strength_) strength_->stiffen_sound_speed(rho, e, p, c);
    burn_->raise_sound_speed(c);
    return;
  }
  Kokkos::parallel_for(
      "eos::pressure_sound_speed", mesh_.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
        p(i, j, k) = eos.pressure_cut(rho(i, j, k), e(i, j, k));
        c(i, j, k) = eos.sound_speed_cut(rho(i, j, k), e(i, j, k));
      });
  if (strength_) strength_->stiffen_sound_speed(rho, e, p, c);
  if (burn_) {
    burn_->scale_pressure(p);
    burn_->raise_sound_speed(c);
  }
}

void Hydro::viscosity() {
  viscosity_with(false);
}

// `with_eos`: each cell's p and c from the scene's one EOS first, in the same launch (a plain
// single-material scene: the viscosity reads only the cell's own c and rho, so the fields are
// those of the two launches bit for bit).
void Hydro::viscosity_with(bool with_eos) {
  auto rho = s_.rho, e = s_.e, p = s_.p, c = s_.c, q = s_.q, u = s_.u, v = s_.v, w = s_.w;
  const auto eos = eos_;
  const Real cq = opt_.q_quadratic, cl = opt_.q_linear;
  // Velocity jump across each cell along each axis from the face-averaged node velocities
  // (ViscosityColumns), on the owned cells and one ghost layer (the nodes of the owned region
  // read them); the limiter reads the neighbours along each axis. The outer ghost layer gets
  // q = 0 in the same launch.
  // Compression switch (Wilkins, J. Comput. Phys. 36:281, 1980): no viscosity where the cell's
  // volume grows (div u >= 0, from the same face-averaged jumps), even if one axis compresses:
  // q > 0 in an expanding cell takes internal energy (q dV > 0) and puts it into the nodes,
  // which drove cold solids and light materials of mixed cells negative (docs/numerics.md).
  // One-dimensional flows are unchanged (the jump along the flow sets both).
  // `with_eos`: each cell's p and c from the scene's one EOS first, in the same launch (a plain
  // single-material scene: the viscosity reads only the cell's own c and rho, so the fields are
  // those of the two launches bit for bit).
  // (k-columns, core/columns.hpp: a column's EOS, then its viscosity, each a vector loop)
  const Geometry g = mesh_.geometry();
  const int plo = Mesh::ng - 1;
  const int phi[3] = {Mesh::ng + mesh_.owned_cells(0) + 1, Mesh::ng + mesh_.owned_cells(1) + 1,
                      Mesh::ng + mesh_.owned_cells(2) + 1};
  const Real rx = Real(1) / g.dx[0], ry = Real(1) / g.dx[1], rz = Real(1) / g.dx[2];
  int lo[3], hi[3];
  mesh_.box(Centering::Cell, Region::All, lo, hi);
  const auto q0 = s_.qt[0], q1 = s_.qt[1], q2 = s_.qt[2], q3 = s_.qt[3], q4 = s_.qt[4],
             q5 = s_.qt[5];
  const Real iso = opt_.q_isotropic;
  const auto qcol = s_.qcol;
  // Noh's heat flux: the converging cells' jumps (a field only where it acts; else a stand-in
  // never written)
  const bool conduct = conducts();
  const auto cj = conduct ? s_.cjump : s_.q;
  const auto converging = s_.converging;
  const Real tx = Real(0.25) * rx, ty = Real(0.25) * ry, tz = Real(0.25) * rz;
  for_columns(
      with_eos ? "lagrange::eos_viscosity" : "lagrange::viscosity", lo, hi,
      KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
        const auto ra = local(rho), ca = local(c), qa = local(q);
        if (with_eos) eos_columns(ra, local(e), local(p), ca, eos)(i, j, k0, k1);
        const bool inside = i >= plo && j >= plo && i < phi[0] && j < phi[1];
        int b = k1, f = k1;
        if (inside) inner_run(k0, k1, plo, phi[2], b, f);
        for (int k = k0; k < b; ++k) qa(i, j, k) = 0;
        if (b < f)
          ViscosityColumns<decltype(ra)>{local(u), local(v), local(w), ra, ca, qa,
                                         rx,       ry,       rz,       cq, cl}(i, j, b, f);
        for (int k = f; k < k1; ++k) qa(i, j, k) = 0;
        // the tensor's direction, where q > 0 (a column's q is 0 outside [b, f))
        bool conv = false;
        const bool any = ViscousTensorColumns<decltype(ra)>{local(u),
                                                            local(v),
                                                            local(w),
                                                            qa,
                                                            ra,
                                                            ca,
                                                            sym6_local(q0, q1, q2, q3, q4, q5),
                                                            tx,
                                                            ty,
                                                            tz,
                                                            iso,
                                                            local(cj),
                                                            conduct,
                                                            cq,
                                                            cl}(
            i, j, k0, k1, !kWholeColumns || qcol(i, j) != 0, conv);
        if (conv) Kokkos::atomic_exchange(&converging(), 1);
        // (per point on a GPU backend: every column marked, nothing skipped)
        qcol(i, j) = kWholeColumns ? int(any) : 1;
      });
}

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
  const bool mixed = burn_ && !mm_ && burn_->mixed();
  const bool has_strength = strength_ != nullptr;
  const std::array<Field3, 3> start_fields{u0_, v0_, w0_};
  const std::array<Field3, 3>* start = mid_geometry_ ? &start_fields : nullptr;
  if (mm_) {
    mm_predictor(vol, hf);
  } else if (mixed) {
    // an explosive with an unreacted EOS: the two phases at the half step (burn.hpp)
    const auto un = burn_->unreacted();
    const Real e0 = burn_->e0();
    auto f = burn_->fraction();
    predictor_kernel(
        mesh_, u, v, w, hf[0], hf[1], hf[2], rho, e, p, s_.qt, s_.qcol, ph, vol,
        KOKKOS_LAMBDA(Real r, Real en, int i, int j, int k) {
          return burn::he_pressure_mixed_cut(un, eos, e0, f(i, j, k), r, en);
        },
        start);
  } else {
    // (the EOS kind dispatched here, so the predictor's loop has no switch: PressureCut)
    eos::with_kind(eos.kind, [&](auto kind) {
      predictor_kernel(mesh_, u, v, w, hf[0], hf[1], hf[2], rho, e, p, s_.qt, s_.qcol, ph, vol,
                       PressureCut<decltype(kind)::value>{eos}, start);
    });
  }
  if (burn_ && !mm_ && !mixed) burn_->scale_pressure(ph);  // (multi-material: in mm_predictor)
  // The half-step deviator and its nodal forces (kernels/strength/module.hpp).
  std::array<Field3, 3> fs;
  if (has_strength) {
    strength_->predictor(s_.u, s_.v, s_.w, rho, e, ph, dt);
    fs = strength_->force();
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
  const int olo[3] = {Mesh::ng, Mesh::ng, Mesh::ng};
  const int ohi[3] = {Mesh::ng + mesh_.owned_cells(0), Mesh::ng + mesh_.owned_cells(1),
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
      const auto u0c = u0_, v0c = v0_, w0c = w0_;
      for_columns(
          "lagrange::mid_faces", lo, hi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
            const auto U = local(ub);
            const MidFaceColumns<decltype(U)> faces{U,          local(vb),  local(wb), local(u0c),
                                                    local(v0c), local(w0c), local(fx), local(fy),
                                                    local(fz),  cx,         cy,        cz,
                                                    sf,         ex,         ey,        ez};
            faces(i, j, k0, k1);
          });
    }
    // (k-columns, core/columns.hpp)
    reduce_columns(
        name, lo, hi,
        KOKKOS_LAMBDA(int i, int j, int k0, int k1, long& n) {
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
        },
        bad);
    volumes_ready_ = true;
    volumes_for_ = first;
  };
  if (mm_) corrector("lagrange::volume_flux", std::false_type{});
  // the deviator's work and the full-step deviator, from rho^n and e^n (before the hydro's)
  if (strength_) strength_->corrector(ub, vb, wb, rho, e, ph, dt);
  if (mm_)
    mm_corrector(vol);
  else
    corrector("lagrange::corrector", std::true_type{});
  // the explosive burns to the end of the step, at its new density (kernels/burn/module.hpp)
  if (burn_) burn_->update(rho, double(dt));

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
