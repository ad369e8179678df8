// A sum of N doubles in one parallel_reduce (Kokkos 3.4 has no multi-value reductions).
#pragma once
#include "core/types.hpp"

namespace mp {

template <int N>
struct SumN {
  double v[N];
  KOKKOS_INLINE_FUNCTION SumN() {
    for (int i = 0; i < N; ++i) v[i] = 0;
  }
  KOKKOS_INLINE_FUNCTION SumN& operator+=(const SumN& o) {
    for (int i = 0; i < N; ++i) v[i] += o.v[i];
    return *this;
  }
  KOKKOS_INLINE_FUNCTION void operator+=(const volatile SumN& o) volatile {
    for (int i = 0; i < N; ++i) v[i] += o.v[i];
  }
};

// N sums of doubles with Neumaier's compensation (A. Neumaier, Z. Angew. Math. Mech. 54 (1974)
// 39-51): each sum carries the rounding error its additions made, so that value(i) is within
// about one rounding of the exact sum whatever the number and the order of the terms, where a
// plain sum's error grows with them. For the conservation totals, whose changes are asserted to
// round-off: a plain sum over the 24^3 closed Noh box's cells gave its total energy change as
// 3.1e-13 on one thread (one sequential sum) and -3.2e-15 on two, the fields bit for bit the same.
// add(i, x) in a kernel; join by +=.
template <int N>
struct CompensatedSumN {
  double s[N], c[N];
  KOKKOS_INLINE_FUNCTION CompensatedSumN() {
    for (int i = 0; i < N; ++i) s[i] = c[i] = 0;
  }
  // s + x rounded into s, its rounding error added to c (Neumaier's branch on the larger term)
  KOKKOS_INLINE_FUNCTION static void add_to(double& s, double& c, double x) {
    const double t = s + x;
    const double as = s < 0 ? -s : s, ax = x < 0 ? -x : x;
    c += as >= ax ? (s - t) + x : (x - t) + s;
    s = t;
  }
  KOKKOS_INLINE_FUNCTION void add(int i, double x) { add_to(s[i], c[i], x); }
  KOKKOS_INLINE_FUNCTION double value(int i) const { return s[i] + c[i]; }
  KOKKOS_INLINE_FUNCTION CompensatedSumN& operator+=(const CompensatedSumN& o) {
    for (int i = 0; i < N; ++i) {
      add_to(s[i], c[i], o.s[i]);
      c[i] += o.c[i];
    }
    return *this;
  }
  KOKKOS_INLINE_FUNCTION void operator+=(const volatile CompensatedSumN& o) volatile {
    for (int i = 0; i < N; ++i) {
      double a = s[i], b = c[i];
      add_to(a, b, o.s[i]);
      s[i] = a;
      c[i] = b + o.c[i];
    }
  }
};

}  // namespace mp

namespace Kokkos {
template <int N>
struct reduction_identity<mp::CompensatedSumN<N>> {
  KOKKOS_FORCEINLINE_FUNCTION static mp::CompensatedSumN<N> sum() {
    return mp::CompensatedSumN<N>();
  }
};
template <int N>
struct reduction_identity<mp::SumN<N>> {
  KOKKOS_FORCEINLINE_FUNCTION static mp::SumN<N> sum() { return mp::SumN<N>(); }
};
}  // namespace Kokkos
