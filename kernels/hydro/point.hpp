// Point functions of the staggered hydro scheme: they see a few numbers, never a view or a loop.
#pragma once
#include <limits>

#include "core/math.hpp"
#include "remap/advect.hpp"

namespace mp::hydro {

// The remap's advection point functions (kernels/remap/advect.hpp), as the hydro's kernels name
// them.
using remap::column_face_flux;
using remap::donor_flux;
using remap::face_value;

// Artificial viscosity, quadratic (von Neumann–Richtmyer) plus linear (Landshoff), acting in
// compression only. `du` is the velocity jump across the cell (negative in compression) that
// the quadratic term sees, `dl` the one the linear term sees (<= 0 where du < 0; the same jump
// in every 1-D flow). In 3-D the cell's jumps are the Christensen-limited per-axis ones,
// du their norm and dl their sum (docs/numerics.md, "Tensor viscosity": the linear term, the
// one that damps the ringing behind a shock, then damps it alike at any angle of the shock).
KOKKOS_INLINE_FUNCTION Real viscosity(Real rho, Real c, Real du, Real dl, Real c_quad, Real c_lin) {
  if (du >= 0) return 0;
  return rho * (c_quad * du * du - c_lin * c * dl);
}

// Christensen's monotonic limiter for the viscosity (Christensen, "Godunov methods on a
// staggered mesh: an improved artificial viscosity", UCRL-JC-105269, 1990): with the velocity
// jumps of the two neighbours along the same axis, returns the jump that the viscosity should
// see. A linear velocity field (smooth compression, r = 1) gives 0; a shock (r ~ 0) keeps all.
KOKKOS_INLINE_FUNCTION Real limited_jump(Real du_lo, Real du, Real du_hi) {
  if (du >= 0) return 0;
  const Real rl = du_lo / du, rr = du_hi / du;
  Real psi = Real(0.5) * (rl + rr);
  psi = psi < 2 * rl ? psi : 2 * rl;
  psi = psi < 2 * rr ? psi : 2 * rr;
  psi = psi < 1 ? psi : 1;
  psi = psi > 0 ? psi : 0;
  return du * (1 - psi);
}

// Specific internal energy after the volume change dv of a cell (or material) of mass `mass`
// under pressure p, taking `wq` of viscous work (viscous_work below, or a material's share of
// it): the Lagrangian work, shared by the single- and multi-material predictor and corrector.
KOKKOS_INLINE_FUNCTION Real pdv_energy(Real e, Real p, Real dv, Real wq, Real mass) {
  return e - (p * dv + wq) / mass;
}

// The tensor artificial viscosity (issue #16; docs/numerics.md, "Tensor viscosity"). A scalar
// q added to the pressure acts in every direction: in a converging shock it also does work on
// the gas's tangential compression, 2 u/r of the volume change in a sphere, which is no shock,
// and over-heats the shocked gas by a fraction of order (shock width) / r (Noh's plateau was
// -29 % at 64^3 with the KE fix). The viscous stress is instead Q = q S: q the scalar
// viscosity (Christensen-limited, as before), S a direction tensor of trace 1 from the cell's
// strain rate D,
//   S = (lambda_max I - D) / (3 lambda_max - tr D),
// lambda_max the largest eigenvalue of D. S is positive semi-definite, weighs each principal
// direction by how much more it compresses than the least compressive one, and is exactly n n
// for a planar compression D = d n n (a 1-D flow: diag(1, 0, 0)) and for a spherical shock
// (D = diag(d_r, d_t, d_t) in the radial frame: the radial direction alone). Q : D <= 0
// whenever tr D < 0, so the viscous work is dissipative (Campbell & Shashkov, J. Comput. Phys.
// 172:739, 2001, take q along the principal directions of the strain rate in the same spirit;
// Caramana, Shashkov & Whalen, J. Comput. Phys. 144:70, 1998, on why a scalar q heats uniform
// convergence). Where D is isotropic (every eigenvalue equal) S = I / 3.
// The six components of a symmetric tensor, in this order:
struct Sym6 {
  Real xx, yy, zz, xy, xz, yz;
};
inline constexpr const char* kSym6Names[6] = {"xx", "yy", "zz", "xy", "xz", "yz"};
// Six fields (views or core/columns.hpp local accessors) read and written as one Sym6.
template <class A>
struct Sym6At {
  A xx, yy, zz, xy, xz, yz;
  KOKKOS_INLINE_FUNCTION Sym6 operator()(int i, int j, int k) const {
    return {xx(i, j, k), yy(i, j, k), zz(i, j, k), xy(i, j, k), xz(i, j, k), yz(i, j, k)};
  }
  KOKKOS_INLINE_FUNCTION void set(int i, int j, int k, const Sym6& s) const {
    xx(i, j, k) = s.xx;
    yy(i, j, k) = s.yy;
    zz(i, j, k) = s.zz;
    xy(i, j, k) = s.xy;
    xz(i, j, k) = s.xz;
    yz(i, j, k) = s.yz;
  }
};
// The eigenvalues of a symmetric 3x3 tensor by cyclic Jacobi rotations (Golub & Van
// Loan, Matrix Computations, 8.5): backward stable, so a double eigenvalue (the tangential pair
// of a spherical shock) comes out to round-off. The closed trigonometric form of the cubic's
// roots loses half the digits there (acos near -1), and tensors that differ by round-off, such as
// the axis-permuted cells of the unsplit remap's symmetry test, gave direction tensors 1e-8 apart.
// (in the order the rotations leave them)
KOKKOS_INLINE_FUNCTION void eigenvalues(const Sym6& d, Real ev[3]) {
  Real a[3][3] = {{d.xx, d.xy, d.xz}, {d.xy, d.yy, d.yz}, {d.xz, d.yz, d.zz}};
  for (int sweep = 0; sweep < 8; ++sweep) {
    const Real off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const Real diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (!(off > kRealEpsilon * kRealEpsilon * diag)) break;
    for (int pq = 0; pq < 3; ++pq) {
      const int p = pq == 2 ? 1 : 0, q = pq == 0 ? 1 : 2;
      const Real apq = a[p][q];
      if (apq == 0) continue;
      // the rotation that zeroes a[p][q]
      const Real theta = (a[q][q] - a[p][p]) / (2 * apq);
      const Real t = (theta >= 0 ? Real(1) : Real(-1)) / (mabs(theta) + msqrt(theta * theta + 1));
      const Real c = 1 / msqrt(t * t + 1), s = t * c;
      a[p][p] -= t * apq;
      a[q][q] += t * apq;
      a[p][q] = a[q][p] = 0;
      const int r = 3 - p - q;
      const Real arp = a[r][p], arq = a[r][q];
      a[r][p] = a[p][r] = c * arp - s * arq;
      a[r][q] = a[q][r] = s * arp + c * arq;
    }
  }
  ev[0] = a[0][0];
  ev[1] = a[1][1];
  ev[2] = a[2][2];
}

// One rotation of `eigenvalues` (pair p, q; r the third index) on n lanes: a lane that has
// stopped (done != 0) or whose a[p][q] is 0 keeps its values, the others take exactly the
// scalar loop's operations, as selects (a loop GCC vectorizes; with a bool mask it did not: GCC
// 12 finds no vector type for the mix of 1-byte and 8-byte lanes, and left it scalar).
KOKKOS_INLINE_FUNCTION void jacobi_rotation_lanes(int n, const int* done, Real* app, Real* aqq,
                                                  Real* apq, Real* arp, Real* arq) {
#pragma GCC ivdep
  for (int l = 0; l < n; ++l) {
    const Real pq = apq[l];
    const bool go = !done[l] && pq != 0;
    const Real theta = (aqq[l] - app[l]) / (2 * pq);
    const Real t = (theta >= 0 ? Real(1) : Real(-1)) / (mabs(theta) + msqrt(theta * theta + 1));
    const Real c = 1 / msqrt(t * t + 1), s = t * c;
    const Real rp = arp[l], rq = arq[l];
    app[l] = go ? app[l] - t * pq : app[l];
    aqq[l] = go ? aqq[l] + t * pq : aqq[l];
    apq[l] = go ? Real(0) : pq;
    arp[l] = go ? c * rp - s * rq : rp;
    arq[l] = go ? s * rp + c * rq : rq;
  }
}

// `eigenvalues` of n tensors at once (n <= N), lane by lane the same operations in the same
// order: a lane stops at the sweep where the scalar loop breaks and skips the rotations it
// skips, so each lane's eigenvalues (a00, a11, a22 at the end) are the scalar ones bit for bit.
// The tensors come in the six arrays (xx, yy, zz, xy, xz, yz), overwritten; `done` (0 or 1)
// marks the lanes not wanted on entry, and every lane on return.
template <int N>
KOKKOS_INLINE_FUNCTION void eigenvalues_lanes(int n, Real (&a00)[N], Real (&a11)[N], Real (&a22)[N],
                                              Real (&a01)[N], Real (&a02)[N], Real (&a12)[N],
                                              int (&done)[N]) {
  for (int sweep = 0; sweep < 8; ++sweep) {
    int busy = 0;
#pragma GCC ivdep
    for (int l = 0; l < n; ++l) {
      const Real off = a01[l] * a01[l] + a02[l] * a02[l] + a12[l] * a12[l];
      const Real diag = a00[l] * a00[l] + a11[l] * a11[l] + a22[l] * a22[l];
      const int d = done[l] | int(!(off > kRealEpsilon * kRealEpsilon * diag));
      done[l] = d;
      busy += 1 - d;
    }
    if (busy == 0) return;
    jacobi_rotation_lanes(n, done, a00, a11, a01, a02, a12);  // p, q, r = 0, 1, 2
    jacobi_rotation_lanes(n, done, a00, a22, a02, a01, a12);  // 0, 2, 1
    jacobi_rotation_lanes(n, done, a11, a22, a12, a01, a02);  // 1, 2, 0
  }
}

// compression_direction (below) from d's eigenvalues ev, found already (ViscousTensorColumns
// finds a column's with eigenvalues_lanes)
KOKKOS_INLINE_FUNCTION Sym6 compression_direction_of(const Sym6& d, const Real ev[3]) {
  const Real lmax = mmax(ev[0], mmax(ev[1], ev[2]));
  const Real tr = d.xx + d.yy + d.zz;
  const Real den = 3 * lmax - tr;
  const Real scale = mabs(d.xx) + mabs(d.yy) + mabs(d.zz) + mabs(d.xy) + mabs(d.xz) + mabs(d.yz);
  // (selects, not a branch: ViscousTensorColumns calls it in a vector loop; isotropic: S = I / 3)
  const bool iso = !(den > 64 * kRealEpsilon * scale);
  const Real t = Real(1) / 3;
  // (divided, not multiplied by 1 / den: a compression along one axis gets exactly 1 there)
  return {iso ? t : (lmax - d.xx) / den, iso ? t : (lmax - d.yy) / den,
          iso ? t : (lmax - d.zz) / den, iso ? Real(0) : -d.xy / den,
          iso ? Real(0) : -d.xz / den,   iso ? Real(0) : -d.yz / den};
}
// S of the strain rate d (components of the symmetric part of the velocity gradient); ev: d's
// eigenvalues
KOKKOS_INLINE_FUNCTION Sym6 compression_direction(const Sym6& d, Real ev[3]) {
  // (diagonal, as in every planar flow along an axis: exact)
  const bool diagonal = d.xy == 0 && d.xz == 0 && d.yz == 0;
  if (diagonal) {
    ev[0] = d.xx;
    ev[1] = d.yy;
    ev[2] = d.zz;
  } else {
    eigenvalues(d, ev);
  }
  return compression_direction_of(d, ev);
}
KOKKOS_INLINE_FUNCTION Sym6 compression_direction(const Sym6& d) {
  Real ev[3];
  return compression_direction(d, ev);
}

// Noh's heat flux (conduction.cpp) acts in converging compressions: where the strain rate's
// middle eigenvalue compresses too, by more than kConverging of the most compressive one. A
// planar compression has exactly 0 there, a diverging shock (Sedov's) a positive one. Across a
// converging shock of radius R and width w the tangential convergence is about w / R of the
// normal compression, so 0.01 keeps shocks up to about a hundred cells of radius, where the
// entropy error the flux treats is at most about 1 % (docs/numerics.md, "Artificial heat flux").
inline constexpr Real kConverging = Real(0.01);
KOKKOS_INLINE_FUNCTION bool converging(const Real ev[3]) {
  const Real lo = mmin(ev[0], mmin(ev[1], ev[2])), hi = mmax(ev[0], mmax(ev[1], ev[2]));
  const Real mid = ev[0] + ev[1] + ev[2] - lo - hi;
  return lo < 0 && mid < kConverging * lo;
}

// The compressive velocity jump J that gives the viscosity q in a cell of density r and sound
// speed c: q = r (cq J^2 + cl c J), solved without cancellation (cq = 0 allowed). (Where the
// two terms saw different jumps, `viscosity` above, J lies between them: the one jump that
// gives the cell's q.)
// (selects, not branches: a vector loop of ViscousTensorColumns calls it)
KOKKOS_INLINE_FUNCTION Real jump_of_q(Real q, Real r, Real c, Real cq, Real cl) {
  const Real x = q / r, b = cl * c;
  const Real den = b + msqrt(b * b + 4 * cq * x);
  return q > 0 && r > 0 && den > 0 ? 2 * x / den : Real(0);
}

// Sums over a cell's four nodes on its high side along axis D less those on its low side, of
// node field a: jump<D>(a, i, j, k) / (4 dx_D) is d a / d x_D over the cell.
template <int D, class F>
KOKKOS_INLINE_FUNCTION Real node_jump(const F& a, int i, int j, int k) {
  if constexpr (D == 0)
    return a(i + 1, j, k) + a(i + 1, j + 1, k) + a(i + 1, j, k + 1) + a(i + 1, j + 1, k + 1) -
           (a(i, j, k) + a(i, j + 1, k) + a(i, j, k + 1) + a(i, j + 1, k + 1));
  else if constexpr (D == 1)
    return a(i, j + 1, k) + a(i + 1, j + 1, k) + a(i, j + 1, k + 1) + a(i + 1, j + 1, k + 1) -
           (a(i, j, k) + a(i + 1, j, k) + a(i, j, k + 1) + a(i + 1, j, k + 1));
  else
    return a(i, j, k + 1) + a(i + 1, j, k + 1) + a(i, j + 1, k + 1) + a(i + 1, j + 1, k + 1) -
           (a(i, j, k) + a(i + 1, j, k) + a(i, j + 1, k) + a(i + 1, j + 1, k));
}

// The work the viscous stress Q of a cell does over a step, sum_ad Q_ad G_ad, G_ad = c_d
// node_jump<d>(u_a): the velocity gradient times the volume and the step (c_d = step x a
// quarter of the d-faces' area, as the face fluxes use). dvx, dvy, dvz: the cell's volume
// change along each axis (its face fluxes, the diagonal terms). The nodes' forces from Q use
// the same face areas (NodeUpdate), so this is the work Q does on the nodes: total energy is
// kept to round-off. In a flow along one axis Q has one component and the work is q dv_x.
template <class F>
KOKKOS_FORCEINLINE_FUNCTION Real viscous_work(const Sym6& Q, Real dvx, Real dvy, Real dvz,
                                              const F& u, const F& v, const F& w, int i, int j,
                                              int k, Real cx, Real cy, Real cz) {
  const Real xy = cy * node_jump<1>(u, i, j, k) + cx * node_jump<0>(v, i, j, k);
  const Real xz = cz * node_jump<2>(u, i, j, k) + cx * node_jump<0>(w, i, j, k);
  const Real yz = cz * node_jump<2>(v, i, j, k) + cy * node_jump<1>(w, i, j, k);
  return Q.xx * dvx + Q.yy * dvy + Q.zz * dvz + (Q.xy * xy + Q.xz * xz + Q.yz * yz);
}

// The kinetic-energy fix (DeBar; Benson, Comput. Methods Appl. Mech. Eng. 99:235, 1992): a
// cell receives `de`, its share (per unit mass) of the kinetic energy the momentum remap took
// from its 8 nodes. The whole discrepancy is returned, both signs, so total energy is conserved
// to round-off; where the remap made kinetic energy (de < 0) a material gives at most half of
// its specific internal energy, which keeps near-vacuum cells positive (the 123 problem). Only
// that clamp, when it acts, leaves energy unconserved. Returns the least `de` a material of
// specific energy e may take.
KOKKOS_INLINE_FUNCTION Real ke_fix_floor(Real e) {
  return -Real(0.5) * e;
}

// The free-expansion rule (issue #16; docs/numerics.md, "Free expansion to the nodes"): where
// a face's gas, mass flux m at face density rho_face, enters a receiving cell of mass m_r and
// volume v_r that would hold less than `ratio` of that density with it, the receiver takes
// the gas's specific energy brought down the ideal-gas isentrope to the density it reaches,
// (rho_after / rho_face)^(gamma - 1) of it; the donor still pays the whole and the rest pushes
// the face's node pairs apart as kinetic energy (the work a resolved expansion would have done;
// Hydro::expansion_impulse). Returns the share the receiver takes (1 where the rule does not
// act).
// Whether the rule acts (1) or not (0), and where it does the density ratio `base` of the
// share base^(gm1) (expansion_power); selects of Reals, for a vector loop (remap::cell_flux:
// GCC 12 vectorizes no select between two tests).
KOKKOS_INLINE_FUNCTION Real expansion_acts(Real m, Real f, Real m_r, Real v_r, Real ratio,
                                           Real& base) {
  const Real rho_face = f != 0 ? m / f : Real(0);
  const Real rho_after = (m_r + mabs(m)) / v_r;
  base = rho_after / rho_face;
  const Real face = rho_face > 0 ? Real(1) : Real(0);
  return rho_after < ratio * rho_face ? face : Real(0);
}
KOKKOS_INLINE_FUNCTION Real expansion_power(Real base, Real gm1) {
  return MP_KOKKOS_MATH::pow(base, gm1);
}
KOKKOS_INLINE_FUNCTION Real expansion_share(Real m, Real f, Real m_r, Real v_r, Real gm1,
                                            Real ratio) {
  Real base;
  return expansion_acts(m, f, m_r, v_r, ratio, base) != 0 ? expansion_power(base, gm1) : Real(1);
}

}  // namespace mp::hydro
