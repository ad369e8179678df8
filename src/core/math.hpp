// Device-callable math that compiles against Kokkos 3.4 (Kokkos::Experimental::) and 4.x
// (Kokkos::).
#pragma once
#include "core/types.hpp"

namespace mp {

#if KOKKOS_VERSION >= 30700
#define MP_KOKKOS_MATH Kokkos
#else
#define MP_KOKKOS_MATH Kokkos::Experimental
#endif

KOKKOS_INLINE_FUNCTION Real msqrt(Real x) {
  return MP_KOKKOS_MATH::sqrt(x);
}
KOKKOS_INLINE_FUNCTION Real mabs(Real x) {
  return x < 0 ? -x : x;
}
KOKKOS_INLINE_FUNCTION Real mmin(Real a, Real b) {
  return a < b ? a : b;
}
KOKKOS_INLINE_FUNCTION Real mmax(Real a, Real b) {
  return a > b ? a : b;
}
KOKKOS_INLINE_FUNCTION bool misfinite(Real x) {
  return MP_KOKKOS_MATH::isfinite(x);
}

}  // namespace mp
