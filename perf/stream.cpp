#include "stream.hpp"

#include <chrono>

#include "core/types.hpp"

namespace mp::perf {

Stream stream_triad(long n, int reps) {
  Kokkos::View<double*, MemSpace> a("stream::a", n), b("stream::b", n), c("stream::c", n);
  Kokkos::deep_copy(b, 1.0);
  Kokkos::deep_copy(c, 2.0);
  const double s = 3.0;
  double best = 1e30;
  for (int r = 0; r < reps; ++r) {
    Kokkos::fence();
    const auto t0 = std::chrono::steady_clock::now();
    Kokkos::parallel_for(
        "stream::triad", Kokkos::RangePolicy<ExecSpace>(0, n),
        KOKKOS_LAMBDA(long i) { a(i) = b(i) + s * c(i); });
    Kokkos::fence();
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (dt < best) best = dt;
  }
  Stream out;
  out.elements = double(n);
  out.triad_gbs = 3.0 * 8.0 * double(n) / best / 1e9;
  return out;
}

}  // namespace mp::perf
