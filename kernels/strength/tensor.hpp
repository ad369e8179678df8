// Small tensors for the strength point functions: a symmetric 3x3 tensor stored as its 6
// independent components (the stress deviator) and a full 3x3 matrix (velocity gradient, spin,
// rotation). Plain aggregates, trivially copyable, usable on the device; no views, no loops
// over cells.
//
// Conventions:
//  - Sym order: xx, yy, zz, xy, yz, zx (the 6 per-material stress-deviator scalars are stored in
//    this order).
//  - Mat3 is row-major: the velocity gradient is L(i, j) = d v_i / d x_j, given as 9 numbers
//    {dvx/dx, dvx/dy, dvx/dz, dvy/dx, ..., dvz/dz}.
//  - Strain rate D = (L + L^T)/2, spin W = (L - L^T)/2 (so a rigid rotation v = w x x has
//    W = [w]_x, the cross-product matrix of w).
#pragma once
#include "core/math.hpp"

namespace mp::strength {

struct Sym {
  Real xx = 0, yy = 0, zz = 0, xy = 0, yz = 0, zx = 0;
};

struct Mat3 {
  Real a[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  KOKKOS_INLINE_FUNCTION Real& operator()(int i, int j) { return a[i][j]; }
  KOKKOS_INLINE_FUNCTION Real operator()(int i, int j) const { return a[i][j]; }
};

// The velocity gradient from its 9 components in row-major order.
KOKKOS_INLINE_FUNCTION Mat3 velocity_gradient(const Real g[9]) {
  Mat3 L;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) L.a[i][j] = g[3 * i + j];
  return L;
}

KOKKOS_INLINE_FUNCTION Sym strain_rate(const Mat3& L) {
  Sym d;
  d.xx = L(0, 0);
  d.yy = L(1, 1);
  d.zz = L(2, 2);
  d.xy = Real(0.5) * (L(0, 1) + L(1, 0));
  d.yz = Real(0.5) * (L(1, 2) + L(2, 1));
  d.zx = Real(0.5) * (L(2, 0) + L(0, 2));
  return d;
}

KOKKOS_INLINE_FUNCTION Mat3 spin(const Mat3& L) {
  Mat3 w;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w.a[i][j] = Real(0.5) * (L(i, j) - L(j, i));
  return w;
}

KOKKOS_INLINE_FUNCTION Real trace(const Sym& s) {
  return s.xx + s.yy + s.zz;
}

// The deviator of s (trace removed).
KOKKOS_INLINE_FUNCTION Sym deviator(const Sym& s) {
  const Real m = trace(s) / 3;
  return {s.xx - m, s.yy - m, s.zz - m, s.xy, s.yz, s.zx};
}

// a : b = sum_ij a_ij b_ij (the off-diagonal components count twice).
KOKKOS_INLINE_FUNCTION Real ddot(const Sym& a, const Sym& b) {
  return a.xx * b.xx + a.yy * b.yy + a.zz * b.zz + 2 * (a.xy * b.xy + a.yz * b.yz + a.zx * b.zx);
}

// The von Mises equivalent stress of a deviator, sqrt(3/2 s:s).
KOKKOS_INLINE_FUNCTION Real von_mises(const Sym& s) {
  return msqrt(Real(1.5) * ddot(s, s));
}

KOKKOS_INLINE_FUNCTION Sym scaled(const Sym& s, Real f) {
  return {f * s.xx, f * s.yy, f * s.zz, f * s.xy, f * s.yz, f * s.zx};
}

KOKKOS_INLINE_FUNCTION Mat3 to_mat(const Sym& s) {
  Mat3 m;
  m.a[0][0] = s.xx;
  m.a[1][1] = s.yy;
  m.a[2][2] = s.zz;
  m.a[0][1] = m.a[1][0] = s.xy;
  m.a[1][2] = m.a[2][1] = s.yz;
  m.a[2][0] = m.a[0][2] = s.zx;
  return m;
}

// The symmetric part of m, as a Sym.
KOKKOS_INLINE_FUNCTION Sym sym_part(const Mat3& m) {
  return {m(0, 0),
          m(1, 1),
          m(2, 2),
          Real(0.5) * (m(0, 1) + m(1, 0)),
          Real(0.5) * (m(1, 2) + m(2, 1)),
          Real(0.5) * (m(2, 0) + m(0, 2))};
}

KOKKOS_INLINE_FUNCTION Mat3 matmul(const Mat3& a, const Mat3& b) {
  Mat3 c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      c.a[i][j] = a(i, 0) * b(0, j) + a(i, 1) * b(1, j) + a(i, 2) * b(2, j);
  return c;
}

KOKKOS_INLINE_FUNCTION Mat3 transpose(const Mat3& a) {
  Mat3 t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t.a[i][j] = a(j, i);
  return t;
}

// Q s Q^T for a rotation Q.
KOKKOS_INLINE_FUNCTION Sym rotate(const Sym& s, const Mat3& q) {
  return sym_part(matmul(matmul(q, to_mat(s)), transpose(q)));
}

}  // namespace mp::strength
