// Cell and node loops as k-columns (issue #15). A Kokkos MDRange over (i, j, k) calls its body
// once per point, and GCC leaves that loop scalar: every field access goes through the view's
// index arithmetic, whose strides it must reload after each store it cannot prove apart from
// them. A body that takes a whole column (i, j) and indexes plain pointers with k, under
// `#pragma GCC ivdep` (a kernel writes a field only at its own point), is a loop GCC vectorizes.
// One body serves every backend: for_columns calls it per (i, j) column on host backends and
// per point on GPU backends, and column() is a plain pointer where the views are LayoutRight
// (k contiguous: every host backend) and a strided accessor elsewhere.
#pragma once
#include <string>
#include <type_traits>

#include "core/types.hpp"

namespace mp {

// Field f along k at (i, j), read or written as c[k] for the view's own k.
template <class T>
struct StridedColumn {
  T* p;
  long s;
  KOKKOS_INLINE_FUNCTION T& operator[](int k) const { return p[k * s]; }
};
template <class View>
KOKKOS_INLINE_FUNCTION auto column(const View& f, int i, int j) {
  using T = typename View::value_type;
  if constexpr (std::is_same_v<typename View::array_layout, Kokkos::LayoutRight>)
    return static_cast<T*>(f.data() + (long(i) * f.extent(1) + j) * f.extent(2));
  else
    return StridedColumn<T>{&f(i, j, 0), long(f.stride(2))};
}

// A view's data as a plain pointer and strides, indexed (i, j, k) like the view: for the point
// functions a column loop calls (templated on the field type). Made inside the column's body, it
// is a local value GCC keeps in registers, so the loop's loads are plain offsets from it. Its
// accessor is forced inline: after kernels/hydro/lagrange.cpp was split in three, GCC emitted it
// out of line there and lagrange::acceleration ran 1.5x slower (perf/results/
// seam_perf_check_side_by_side.md).
template <class T, bool Unit>
struct Local3 {
  T* p;
  long si, sj, sk;
  KOKKOS_FORCEINLINE_FUNCTION T& operator()(int i, int j, int k) const {
    if constexpr (Unit)
      return p[i * si + j * sj + k];
    else
      return p[i * si + j * sj + k * sk];
  }
};
template <class View>
KOKKOS_INLINE_FUNCTION auto local(const View& f) {
  using T = typename View::value_type;
  constexpr bool unit = std::is_same_v<typename View::array_layout, Kokkos::LayoutRight>;
  return Local3<T, unit>{f.data(), long(f.stride(0)), long(f.stride(1)), long(f.stride(2))};
}

// The part [b, f) of a column's cells [k0, k1) that lies in [lo, hi) along k, so that the
// column runs as [k0, b), [b, f), [f, k1) (k0 <= b <= f <= k1; b == f where they do not meet):
// a kernel that treats the owned (or inner) cells of a column apart from its ghosts.
KOKKOS_INLINE_FUNCTION void inner_run(int k0, int k1, int lo, int hi, int& b, int& f) {
  b = k0 > lo ? k0 : lo < k1 ? lo : k1;
  f = k1 < hi ? k1 : hi > b ? hi : b;
}

// Whether for_columns gives a body whole columns (host backends) or single points (GPU ones):
// a per-column result is only the column's where it is true.
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
inline constexpr bool kWholeColumns = false;
#else
inline constexpr bool kWholeColumns = true;
#endif

// body(i, j, k0, k1) for every (i, j, k) of the box [lo, hi): the body runs k from k0 to k1
// (one call per column on host backends, k1 = k0 + 1 on GPU backends).
template <class Body>
void for_columns(const std::string& name, const int lo[3], const int hi[3], const Body& body) {
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  Kokkos::parallel_for(
      name, Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}),
      KOKKOS_LAMBDA(int i, int j, int k) { body(i, j, k, k + 1); });
#else
  const int k0 = lo[2], k1 = hi[2];
  Kokkos::parallel_for(
      name, Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2> >({lo[0], lo[1]}, {hi[0], hi[1]}),
      KOKKOS_LAMBDA(int i, int j) { body(i, j, k0, k1); });
#endif
}

// The same with a Kokkos reducer (Min, MinLoc ...): body(i, j, k0, k1, acc) joins its points
// into acc, a Reducer::value_type; the reducer holds the result.
template <class Body, class Reducer>
void reduce_columns_with(const std::string& name, const int lo[3], const int hi[3],
                         const Body& body, const Reducer& reducer) {
  using V = typename Reducer::value_type;
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  Kokkos::parallel_reduce(
      name, Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}),
      KOKKOS_LAMBDA(int i, int j, int k, V& acc) { body(i, j, k, k + 1, acc); }, reducer);
#else
  const int k0 = lo[2], k1 = hi[2];
  Kokkos::parallel_reduce(
      name, Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2> >({lo[0], lo[1]}, {hi[0], hi[1]}),
      KOKKOS_LAMBDA(int i, int j, V& acc) { body(i, j, k0, k1, acc); }, reducer);
#endif
}

// The same with a sum: body(i, j, k0, k1, acc) adds to acc; result = the sum over the box.
template <class Body, class T>
void reduce_columns(const std::string& name, const int lo[3], const int hi[3], const Body& body,
                    T& result) {
  reduce_columns_with(name, lo, hi, body, Kokkos::Sum<T>(result));
}

}  // namespace mp
