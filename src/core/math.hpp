// Device-callable math that compiles against Kokkos 3.4 (Kokkos::Experimental::) and 4.x
// (Kokkos::).
#pragma once
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "core/types.hpp"

namespace mp {

#if KOKKOS_VERSION >= 30700
#define MP_KOKKOS_MATH Kokkos
#else
#define MP_KOKKOS_MATH Kokkos::Experimental
#endif

// std::numeric_limits<Real>'s values as constants for kernels: its member functions are host
// functions to nvcc, which device code may not call; a constexpr scalar it may read.
inline constexpr Real kRealEpsilon = std::numeric_limits<Real>::epsilon();
inline constexpr Real kRealMax = std::numeric_limits<Real>::max();
inline constexpr Real kRealInfinity = std::numeric_limits<Real>::infinity();

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
// c ? a : b as integer operations on the bits (exactly a or b): a select GCC's vectorizer
// takes where a floating-point one, fed by integer and floating-point tests together, left
// the loop with a branch (issue #15, the compact layout's column loops).
KOKKOS_INLINE_FUNCTION Real select_bits(bool c, Real a, Real b) {
  using U = std::conditional_t<sizeof(Real) == 8, std::uint64_t, std::uint32_t>;
  U ua, ub;
  std::memcpy(&ua, &a, sizeof(Real));
  std::memcpy(&ub, &b, sizeof(Real));
  const U m = U(0) - U(c);
  const U r = (ua & m) | (ub & ~m);
  Real out;
  std::memcpy(&out, &r, sizeof(Real));
  return out;
}
KOKKOS_INLINE_FUNCTION bool misfinite(Real x) {
  return MP_KOKKOS_MATH::isfinite(x);
}

}  // namespace mp
