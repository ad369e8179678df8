// The Lagrangian phase's cell quantities: p and c from the EOS, and the artificial viscosity
// (its scalar q and tensor stress), as one launch in a plain single-material scene.
#include "core/columns.hpp"
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/point.hpp"

namespace mp::hydro {

namespace {

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
    const Real s = 100 * kRealEpsilon * sp;
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
    // Chunks of the column: the strain rates and their eigenvalues (the Jacobi sweeps of
    // point.hpp `eigenvalues`, the cost of this kernel where most cells compress) for the whole
    // chunk at once as vector loops (eigenvalues_lanes: each cell's the scalar ones bit for
    // bit), then each cell's stress as before. (A GPU backend's call is one point.)
    constexpr int kChunk = kWholeColumns ? 16 : 1;
    for (int kb = k0; kb < k1; kb += kChunk) {
      const int n = kb + kChunk < k1 ? kChunk : k1 - kb;
      Real xx[kChunk], yy[kChunk], zz[kChunk], xy[kChunk], xz[kChunk], yz[kChunk];
      Real e0[kChunk], e1[kChunk], e2[kChunk], f0[kChunk], f1[kChunk], f2[kChunk];
      // (int, not bool, masks: GCC 12 vectorizes no loop that mixes 1-byte and 8-byte lanes)
      int real[kChunk], done[kChunk];
#pragma GCC ivdep
      for (int l = 0; l < n; ++l) {
        const int k = kb + l;
        real[l] = real_q(i, j, k) ? 1 : 0;
        xx[l] = e0[l] = node_jump<0>(u, i, j, k) * rx;
        yy[l] = e1[l] = node_jump<1>(v, i, j, k) * ry;
        zz[l] = e2[l] = node_jump<2>(w, i, j, k) * rz;
        xy[l] = f0[l] = Real(0.5) * (node_jump<1>(u, i, j, k) * ry + node_jump<0>(v, i, j, k) * rx);
        xz[l] = f1[l] = Real(0.5) * (node_jump<2>(u, i, j, k) * rz + node_jump<0>(w, i, j, k) * rx);
        yz[l] = f2[l] = Real(0.5) * (node_jump<2>(v, i, j, k) * rz + node_jump<1>(w, i, j, k) * ry);
        // (a diagonal tensor's eigenvalues are its diagonal: compression_direction's shortcut,
        // which the first sweep's test would take too)
        done[l] = !real[l] || (f0[l] == 0 && f1[l] == 0 && f2[l] == 0) ? 1 : 0;
      }
      eigenvalues_lanes(n, e0, e1, e2, f0, f1, f2, done);
      // each cell's stress, a vector loop too: every lane computes it, a cell without a real q
      // stores 0 (the selects of compression_direction_of; the same values as per cell)
      const Real ti = 1 - iso;
#pragma GCC ivdep
      for (int l = 0; l < n; ++l) {
        const int k = kb + l;
        const Real qq = q(i, j, k);
        const Sym6 d{xx[l], yy[l], zz[l], xy[l], xz[l], yz[l]};
        const Real ev[3] = {e0[l], e1[l], e2[l]};
        const Sym6 s = compression_direction_of(d, ev);
        const Real qt = qq * ti, qi = qq * iso;
        const bool r = real[l] != 0;
        Q.set(i, j, k,
              {r ? qt * s.xx + qi : Real(0), r ? qt * s.yy + qi : Real(0),
               r ? qt * s.zz + qi : Real(0), r ? qt * s.xy : Real(0), r ? qt * s.xz : Real(0),
               r ? qt * s.yz : Real(0)});
      }
      if (conduct) {
        int cv = 0;
#pragma GCC ivdep
        for (int l = 0; l < n; ++l) {
          const int k = kb + l;
          const Real ev[3] = {e0[l], e1[l], e2[l]};
          const Real jc = jump_of_q(q(i, j, k), rho(i, j, k), c(i, j, k), cq, cl);
          const Real jr = real[l] != 0 && converging(ev) ? jc : Real(0);
          cj(i, j, k) = jr;
          cv |= jr > 0 ? 1 : 0;
        }
        conv = conv || cv != 0;
      }
    }
    return true;
  }
};

}  // namespace

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
    for (const Module* m : modules()) m->after_eos(rho, e, p, c);
    return;
  }
  const auto eos = eos_;
  if (reactive_ && reactive_->mixed) {
    // an explosive with an unreacted EOS: p and c of the two phases at frozen F (reactive.hpp)
    const auto un = reactive_->unreacted;
    const Real e0 = reactive_->e0;
    const bool eq = reactive_->equilibrium;
    auto f = reactive_->fraction;
    Kokkos::parallel_for(
        "eos::pressure_sound_speed", mesh_.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
          const Real fi = f(i, j, k), r = rho(i, j, k), ei = e(i, j, k);
          p(i, j, k) = eos::he_pressure_mixed_cut(un, eos, e0, fi, r, ei, eq);
          c(i, j, k) = eos::he_sound_speed_mixed(un, eos, e0, fi, r, ei, eq);
        });
    for (const Module* m : modules()) m->after_eos(rho, e, p, c);
    return;
  }
  Kokkos::parallel_for(
      "eos::pressure_sound_speed", mesh_.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
        p(i, j, k) = eos.pressure_cut(rho(i, j, k), e(i, j, k));
        c(i, j, k) = eos.sound_speed_cut(rho(i, j, k), e(i, j, k));
      });
  for (const Module* m : modules()) m->after_eos(rho, e, p, c);
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

}  // namespace mp::hydro
