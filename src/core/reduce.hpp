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

}  // namespace mp

namespace Kokkos {
template <int N>
struct reduction_identity<mp::SumN<N>> {
  KOKKOS_FORCEINLINE_FUNCTION static mp::SumN<N> sum() { return mp::SumN<N>(); }
};
}  // namespace Kokkos
