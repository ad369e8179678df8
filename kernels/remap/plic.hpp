// Geometric point functions of 3-D PLIC (piecewise-linear interface calculation) for Youngs'
// interface reconstruction: the volume of a box behind a plane, its inverse, the material
// volume in a donor cell's flux slab, and Youngs' normal from a 27-cell stencil (and an
// ELVIRA-type choice among column-sum normals on the same stencil).
//
// Conventions, used by every function here:
//  - A plane is (n, alpha); the material lies on the side n.x <= alpha.
//  - Coordinates x are relative to the LOW corner of the cell: the cell is [0,dx]x[0,dy]x[0,dz]
//    (the unit cube [0,1]^3 for the plane_cube_* functions).
//  - n = -grad(volume fraction) points from the material into the other side.
//
// The volume relation and its closed-form pieces follow Scardovelli & Zaleski, "Analytical
// relations connecting linear interfaces and volume fractions in rectangular grids",
// J. Comput. Phys. 164:228-237 (2000). The pieces are rewritten here so that no piece divides
// a cancelling difference by a small normal component: a^3 - (a-m1)^3 is expanded as
// m1 (a^2 + a (a-m1) + (a-m1)^2), and every remaining cube (a-m_i)^3 / m1 has |a-m_i| < m1 on
// its branch. The volume is therefore accurate to a few ulps even for normals with one tiny
// component (nearly 2-D interfaces), and exact zero components need no special case.
#pragma once
#include "core/math.hpp"

namespace mp::plic {

namespace detail {

// Unit round-off of Real, for the Newton stopping test.
constexpr Real round_off = sizeof(Real) == sizeof(float) ? Real(1.2e-7) : Real(2.3e-16);

// Fraction of the unit cube below the plane m1 x + m2 y + m3 z = a, for sorted
// 0 <= m1 <= m2 <= m3, m1 + m2 + m3 = 1 and 0 <= a <= 1/2 (Scardovelli & Zaleski 2000, eq. for
// V(m, alpha) split at the breakpoints m1, m2, min(m1 + m2, m3)).
KOKKOS_INLINE_FUNCTION Real unit_volume(Real m1, Real m2, Real m3, Real a) {
  const Real m12 = m1 + m2;
  if (a < m1) return (a / m1) * (a / m2) * (a / m3) / 6;  // corner tetrahedron
  const Real p = a - m1;
  const Real t1 = (a * a + a * p + p * p) / (6 * m2 * m3);  // = (a^3 - p^3) / (6 m1 m2 m3)
  if (a < m2) return t1;
  const Real q = a - m2;  // 0 <= q < m1 on the two branches below
  if (a < m12 && a < m3) return t1 - q * q * (q / m1) / (6 * m2 * m3);
  if (m3 < m12) {
    const Real r = a - m3;  // 0 <= r <= q < m1 since a <= 1/2 < m12
    return t1 - (q * q * (q / m1) + r * r * (r / m1)) / (6 * m2 * m3);
  }
  return (a - Real(0.5) * m12) / m3;  // the plane crosses the four edges along the third axis
}

// d(unit_volume)/da, branch by branch with the same rewriting (the area of the cut over m3).
KOKKOS_INLINE_FUNCTION Real unit_volume_slope(Real m1, Real m2, Real m3, Real a) {
  const Real m12 = m1 + m2;
  if (a < m1) return (a / m1) * (a / m2) / (2 * m3);
  const Real p = a - m1;
  const Real t1 = (a + p) / (2 * m2 * m3);
  if (a < m2) return t1;
  const Real q = a - m2;
  if (a < m12 && a < m3) return t1 - q * (q / m1) / (2 * m2 * m3);
  if (m3 < m12) {
    const Real r = a - m3;
    return t1 - (q * (q / m1) + r * (r / m1)) / (2 * m2 * m3);
  }
  return 1 / m3;
}

// Safeguarded Newton on [lo, hi], where unit_volume(lo) <= f <= unit_volume(hi) and the volume
// is one smooth cubic: Newton from the secant guess, bisection whenever a step leaves the
// bracket. Converges to round-off in a handful of steps.
KOKKOS_INLINE_FUNCTION Real newton_bisect(Real m1, Real m2, Real m3, Real f, Real lo, Real hi,
                                          Real vlo, Real vhi) {
  Real x = vhi > vlo ? lo + (hi - lo) * (f - vlo) / (vhi - vlo) : Real(0.5) * (lo + hi);
  for (int it = 0; it < 60; ++it) {
    const Real g = unit_volume(m1, m2, m3, x) - f;
    if (g == 0) return x;
    if (g < 0) {
      lo = x;
    } else {
      hi = x;
    }
    const Real s = unit_volume_slope(m1, m2, m3, x);
    Real xn = s > 0 ? x - g / s : lo - 1;
    if (!(xn > lo && xn < hi)) xn = Real(0.5) * (lo + hi);
    const Real step = mabs(xn - x);
    x = xn;
    if (step <= 4 * round_off * x || hi - lo <= 0) break;
  }
  return x;
}

// Inverse of unit_volume for 0 < f <= 1/2 (same assumptions on m): closed form on the
// tetrahedron, prism-like and four-edge branches, safeguarded Newton on the two cubic ones.
KOKKOS_INLINE_FUNCTION Real unit_alpha(Real m1, Real m2, Real m3, Real f) {
  const Real m12 = m1 + m2;
  const Real v1 = m1 > 0 ? m1 * m1 / (6 * m2 * m3) : Real(0);
  if (f < v1) return MP_KOKKOS_MATH::cbrt(6 * m1 * m2 * m3 * f);
  const Real v2 = unit_volume(m1, m2, m3, m2);
  if (f < v2) {
    // 3 a^2 - 3 m1 a + m1^2 = 6 m2 m3 f; the radicand is >= m1^2 / 4 on this branch.
    return Real(0.5) * m1 + msqrt(mmax(2 * m2 * m3 * f - m1 * m1 / 12, Real(0)));
  }
  const Real b3 = mmin(m12, m3);
  const Real v3 = unit_volume(m1, m2, m3, b3);
  if (f < v3) return newton_bisect(m1, m2, m3, f, m2, b3, v2, v3);
  if (m3 >= m12) return m3 * f + Real(0.5) * m12;
  return newton_bisect(m1, m2, m3, f, m3, Real(0.5), v3, Real(0.5));
}

KOKKOS_INLINE_FUNCTION void order(Real& a, Real& b) {
  if (a > b) {
    const Real t = a;
    a = b;
    b = t;
  }
}

// Reflects negative components (x_i -> 1 - x_i), scales by |n|_1 and sorts, so that the
// plane n.x <= alpha on [0,1]^3 becomes m1 x + m2 y + m3 z <= a with 0 <= m1 <= m2 <= m3,
// m1 + m2 + m3 = 1. Returns |n|_1; `shift` is the minimum of n.x over the cube.
KOKKOS_INLINE_FUNCTION Real normalise(Real n0, Real n1, Real n2, Real& m1, Real& m2, Real& m3,
                                      Real& shift) {
  shift = mmin(n0, Real(0)) + mmin(n1, Real(0)) + mmin(n2, Real(0));
  m1 = mabs(n0);
  m2 = mabs(n1);
  m3 = mabs(n2);
  const Real s = m1 + m2 + m3;
  if (!(s > 0)) return 0;
  order(m1, m2);  // sorting network of three
  order(m2, m3);
  order(m1, m2);
  m1 /= s;
  m2 /= s;
  m3 /= s;
  return s;
}

}  // namespace detail

// Fraction of the unit cube [0,1]^3 on the side n.x <= alpha of the plane, for any normal
// (negative and zero components included). Alpha outside [min n.x, max n.x] gives 0 or 1; a
// zero normal gives 1 for alpha >= 0 and 0 otherwise.
KOKKOS_INLINE_FUNCTION Real plane_cube_volume(Real n0, Real n1, Real n2, Real alpha) {
  Real m1, m2, m3, shift;
  const Real s = detail::normalise(n0, n1, n2, m1, m2, m3, shift);
  if (!(s > 0)) return alpha >= 0 ? Real(1) : Real(0);
  const Real a = (alpha - shift) / s;
  if (a <= 0) return 0;
  if (a >= 1) return 1;
  const Real v = a <= Real(0.5) ? detail::unit_volume(m1, m2, m3, a)
                                : 1 - detail::unit_volume(m1, m2, m3, 1 - a);
  return mmin(mmax(v, Real(0)), Real(1));
}

// Inverse of plane_cube_volume: the plane constant alpha such that the part of [0,1]^3 with
// n.x <= alpha has volume `fraction` (clamped to [0,1]). Fraction 0 gives min n.x over the cube,
// 1 gives max n.x. Fractions above 1/2 are solved as 1 - fraction by symmetry, so tiny and
// near-1 fractions keep their relative accuracy. A zero normal has no plane: returns 0 (the
// whole cell) for fraction > 0 and -1 (nothing) otherwise; callers flux such cells by fraction.
KOKKOS_INLINE_FUNCTION Real plane_cube_alpha(Real n0, Real n1, Real n2, Real fraction) {
  Real m1, m2, m3, shift;
  const Real s = detail::normalise(n0, n1, n2, m1, m2, m3, shift);
  if (!(s > 0)) return fraction > 0 ? Real(0) : Real(-1);
  if (!(fraction > 0)) return shift;
  if (fraction >= 1) return shift + s;
  const Real a = fraction <= Real(0.5) ? detail::unit_alpha(m1, m2, m3, fraction)
                                       : 1 - detail::unit_alpha(m1, m2, m3, 1 - fraction);
  return shift + s * a;
}

// Cells of sizes (dx, dy, dz), coordinates from the cell's low corner. The map x = (dx u, dy v,
// dz w) takes the unit cube onto the cell and n.x = (n0 dx) u + (n1 dy) v + (n2 dz) w, so the
// cell's plane (n, alpha) is the unit cube's plane (n0 dx, n1 dy, n2 dz; alpha) with the same
// alpha; fractions are preserved by the map.
KOKKOS_INLINE_FUNCTION Real cell_plane_fraction(const Real n[3], Real alpha, Real dx, Real dy,
                                                Real dz) {
  return plane_cube_volume(n[0] * dx, n[1] * dy, n[2] * dz, alpha);
}

// Volume of the cell on the side n.x <= alpha.
KOKKOS_INLINE_FUNCTION Real cell_plane_volume(const Real n[3], Real alpha, Real dx, Real dy,
                                              Real dz) {
  return cell_plane_fraction(n, alpha, dx, dy, dz) * (dx * dy * dz);
}

// Plane constant (from the cell's low corner) of the plane with normal n that leaves the
// volume fraction `fraction` of the cell on its side n.x <= alpha.
KOKKOS_INLINE_FUNCTION Real cell_plane_alpha(const Real n[3], Real fraction, Real dx, Real dy,
                                             Real dz) {
  return plane_cube_alpha(n[0] * dx, n[1] * dy, n[2] * dz, fraction);
}

// Material volume that a donor cell sends through one face: the volume behind the plane
// (n, alpha) of the flux slab, the layer of the cell adjacent to the face the material leaves
// through, of thickness h = |dv| / (face area), clamped to the cell width. `axis` is 0, 1, 2;
// `high_face` picks the face at x_axis = L_axis (flow towards +axis) or x_axis = 0 (towards
// -axis). The slab is the box x0 <= x_axis <= x0 + h (x0 = L - h or 0) times the full cell in
// the other two axes; mapping it onto [0,1]^3 scales the normal's axis component by h, the
// others by the cell sizes, and shifts alpha by n_axis x0. Returns a volume in [0, |dv|].
KOKKOS_INLINE_FUNCTION Real flux_volume(const Real n[3], Real alpha, Real dx, Real dy, Real dz,
                                        int axis, bool high_face, Real dv) {
  Real len[3] = {dx, dy, dz};
  const Real area = dx * dy * dz / len[axis];
  const Real h = mmin(mabs(dv) / area, len[axis]);
  const Real x0 = high_face ? len[axis] - h : Real(0);
  len[axis] = h;
  const Real f =
      plane_cube_volume(n[0] * len[0], n[1] * len[1], n[2] * len[2], alpha - n[axis] * x0);
  return f * h * area;
}

// Material volume flux from the volume fraction directly: computes the plane constant and
// calls flux_volume; a pure cell (fraction 0 or 1) or a zero normal (no interface direction)
// fluxes the fraction of the slab.
KOKKOS_INLINE_FUNCTION Real material_flux(const Real n[3], Real fraction, Real dx, Real dy, Real dz,
                                          int axis, bool high_face, Real dv) {
  const Real slab = mmin(mabs(dv), dx * dy * dz);
  if (!(fraction > 0)) return 0;
  if (fraction >= 1) return slab;
  if (n[0] == 0 && n[1] == 0 && n[2] == 0) return fraction * slab;
  const Real alpha = cell_plane_alpha(n, fraction, dx, dy, dz);
  return flux_volume(n, alpha, dx, dy, dz, axis, high_face, dv);
}

// Onion-skin split of one face's volume flux among a donor's materials (layer L holds the
// materials with id <= L; its plane is reconstructed from the cumulative fraction; a material's
// share is the difference of two layers; the last material present takes what is left). `a`
// are the donor's volume fractions (nmat of them, `count` > 0 present), `pd` its Lagrangian
// volume, `fl` the face's signed volume flux (> 0: through the donor's high face along `axis`);
// normal(m, n) writes layer m's unit normal into n[3] (asked only for the layers that need one,
// in material order). Writes each material's volume vm[m] in [0, a[m] pd].
template <class Normal>
KOKKOS_INLINE_FUNCTION void onion_volumes(int nmat, int count, const Real* a, const Normal& normal,
                                          Real pd, Real dx, Real dy, Real dz, int axis, Real fl,
                                          Real* vm) {
  const Real scale = pd / (dx * dy * dz);  // the Lagrangian donor volume mapped onto the box
  const Real af = mabs(fl);
  Real acc = 0, done = 0;
  int left = count;
  for (int m = 0; m < nmat; ++m) {
    vm[m] = 0;
    if (!(a[m] > 0)) continue;
    --left;
    acc += a[m];
    Real v;
    if (left == 0) {
      v = af - done;
    } else {
      Real n[3];
      normal(m, n);
      const Real layer =
          scale * material_flux(n, mmin(acc, Real(1)), dx, dy, dz, axis, fl > 0, af / scale);
      const Real cum = mmin(mmax(layer, done), af);
      v = cum - done;
      done = cum;
    }
    vm[m] = mmin(mmax(v, Real(0)), a[m] * pd);
  }
}

// A donor that empties through both its faces along an axis (a divergent flow): the shares vm
// (this face) and vo (the other face) of onion_volumes each stay within a[m] pd, but their sum
// need not — where two layers of nearly equal cumulative fraction have different normals, the
// material between them (a sliver) can be given all of its volume at one face and part of it
// again at the other (seen in the perforator: 1.26-1.56 times a steel sliver's volume, whose
// negative remainder then went to the cell's largest material). Scales this face's share by
// a[m] pd / (vm + vo) where the pair exceeds it; the other face, computing the same with the
// roles swapped, scales its own by the same factor, so the pair is symmetric and the donor
// gives no material more than it holds.
KOKKOS_INLINE_FUNCTION void limit_pair(int nmat, const Real* a, Real pd, Real* vm, const Real* vo) {
  for (int m = 0; m < nmat; ++m) {
    const Real cap = a[m] * pd, both = vm[m] + vo[m];
    if (both > cap) vm[m] *= cap / both;
  }
}

// Youngs' interface normal n = -grad(f) from the volume fractions a[i][j][k] of the 3x3x3 block
// centred on the cell (index 1 is the cell itself, i along x, j along y, k along z), for cell
// sizes (dx, dy, dz). The gradient is the average of the gradients at the cell's 8 corners,
// each from its 2x2x2 block of cells; it equals central differences weighted 1 (corner
// neighbours), 2 (edge neighbours), 4 (face neighbour): Youngs, "Time-dependent multi-material
// flow with large fluid distortion", in Numerical Methods for Fluid Dynamics (K. W. Morton and
// M. J. Baines, eds.), Academic Press, 1982, pp. 273-285. The result is normalised to unit
// Euclidean length |n|_2 = 1; a uniform stencil (all differences below 1e-14) gives n = 0.
KOKKOS_INLINE_FUNCTION void youngs_normal(const Real a[3][3][3], Real dx, Real dy, Real dz,
                                          Real n[3]) {
  const Real w[3] = {1, 2, 1};
  Real g0 = 0, g1 = 0, g2 = 0;
  for (int p = 0; p < 3; ++p) {
    for (int q = 0; q < 3; ++q) {
      const Real wpq = w[p] * w[q];
      g0 += wpq * (a[2][p][q] - a[0][p][q]);
      g1 += wpq * (a[p][2][q] - a[p][0][q]);
      g2 += wpq * (a[p][q][2] - a[p][q][0]);
    }
  }
  // g / 32 is the unit-spacing gradient; the common factor drops out in the normalisation.
  if (mabs(g0) + mabs(g1) + mabs(g2) <= 32 * Real(1e-14)) {
    n[0] = n[1] = n[2] = 0;
    return;
  }
  g0 /= dx;
  g1 /= dy;
  g2 /= dz;
  const Real inv = 1 / msqrt(g0 * g0 + g1 * g1 + g2 * g2);
  n[0] = -g0 * inv;
  n[1] = -g1 * inv;
  n[2] = -g2 * inv;
}

// Youngs' normal on a cubic (or unit-spaced) stencil.
KOKKOS_INLINE_FUNCTION void youngs_normal(const Real a[3][3][3], Real n[3]) {
  youngs_normal(a, Real(1), Real(1), Real(1), n);
}

// How badly the plane of normal n through the centre cell of a 3x3x3 block (the plane constant
// from the centre cell's fraction a[1][1][1]), extended over the block, reproduces the block's
// volume fractions: the sum of the squared differences over the 27 cells (Pilliod & Puckett's
// L2 norm of the volume-fraction error, below). The normalisation is done once for the 27
// cells: a neighbour at offset o sees the same plane with constant alpha - n.o.
KOKKOS_INLINE_FUNCTION Real block_misfit(const Real a[3][3][3], const Real n[3], Real dx, Real dy,
                                         Real dz) {
  Real m1, m2, m3, shift;
  const Real s = detail::normalise(n[0] * dx, n[1] * dy, n[2] * dz, m1, m2, m3, shift);
  if (!(s > 0)) return Real(1e30);
  const Real alpha = cell_plane_alpha(n, a[1][1][1], dx, dy, dz);
  Real err = 0;
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q)
      for (int r = 0; r < 3; ++r) {
        const Real off =
            n[0] * dx * Real(p - 1) + n[1] * dy * Real(q - 1) + n[2] * dz * Real(r - 1);
        const Real x = (alpha - off - shift) / s;  // the unit cube's plane constant
        Real f;
        if (x <= 0)
          f = 0;
        else if (x >= 1)
          f = 1;
        else
          f = x <= Real(0.5) ? detail::unit_volume(m1, m2, m3, x)
                             : 1 - detail::unit_volume(m1, m2, m3, 1 - x);
        const Real d = f - a[p][q][r];
        err += d * d;
      }
  return err;
}

// An ELVIRA-type normal (numerics.interface: elvira): the candidate normal whose plane,
// extended over the 3x3x3 block, reproduces the block's volume fractions best in the L2 norm,
// after Pilliod & Puckett's ELVIRA ("Second-order accurate volume-of-fluid algorithms for
// tracking material interfaces", J. Comput. Phys. 199:465-502, 2004), which picks
// among the backward, central and forward differences of column sums in 2-D. In 3-D here: the
// column sums H(u, v) of the three cells along the axis c of the largest component of Youngs'
// normal, their backward, central and forward differences along each of the two other axes
// (9 slope pairs, each a plane x_c = dc (H + s_a u + s_b v) with the material on the side
// Youngs' normal gives), and Youngs' normal itself; ties keep the earlier candidate, Youngs'
// first. Reproduces a plane whose column sums are its heights (each column of three full below
// the plane and empty above it), which Youngs' weighted gradient does not; a uniform block gives
// n = 0 as youngs_normal. About 10 times Youngs' cost (10 candidates, 27 cell volumes each).
KOKKOS_INLINE_FUNCTION void elvira_normal(const Real a[3][3][3], Real dx, Real dy, Real dz,
                                          Real n[3]) {
  youngs_normal(a, dx, dy, dz, n);
  if (n[0] == 0 && n[1] == 0 && n[2] == 0) return;
  const Real h[3] = {dx, dy, dz};
  int c = 0;
  for (int d = 1; d < 3; ++d)
    if (mabs(n[d]) > mabs(n[c])) c = d;
  const int ea = (c + 1) % 3, eb = (c + 2) % 3;  // the two other axes
  const Real side = n[c] > 0 ? Real(1) : Real(-1);
  // column sums along c at the positions (u, v) along (ea, eb)
  Real H[3][3];
  for (int u = 0; u < 3; ++u)
    for (int v = 0; v < 3; ++v) {
      Real sum = 0;
      for (int w = 0; w < 3; ++w) {
        int idx[3];
        idx[ea] = u;
        idx[eb] = v;
        idx[c] = w;
        sum += a[idx[0]][idx[1]][idx[2]];
      }
      H[u][v] = sum;
    }
  const Real sa[3] = {H[1][1] - H[0][1], Real(0.5) * (H[2][1] - H[0][1]), H[2][1] - H[1][1]};
  const Real sb[3] = {H[1][1] - H[1][0], Real(0.5) * (H[1][2] - H[1][0]), H[1][2] - H[1][1]};
  Real best = block_misfit(a, n, dx, dy, dz);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Real m[3];
      m[ea] = -h[c] * sa[i] / h[ea];
      m[eb] = -h[c] * sb[j] / h[eb];
      m[c] = side;
      const Real inv = 1 / msqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      for (int d = 0; d < 3; ++d) m[d] *= inv;
      const Real e = block_misfit(a, m, dx, dy, dz);
      if (e < best) {
        best = e;
        for (int d = 0; d < 3; ++d) n[d] = m[d];
      }
    }
}

// The ELVIRA-type normal on a cubic (or unit-spaced) stencil.
KOKKOS_INLINE_FUNCTION void elvira_normal(const Real a[3][3][3], Real n[3]) {
  elvira_normal(a, Real(1), Real(1), Real(1), n);
}

}  // namespace mp::plic
