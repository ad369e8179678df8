#include "stream.hpp"

#include <algorithm>
#include <chrono>

#include "core/types.hpp"
#include "protocol.hpp"

namespace mp::perf {

Stream stream_triad(long n, int reps) {
  Kokkos::View<double*, MemSpace> a("stream::a", n), b("stream::b", n), c("stream::c", n);
  Kokkos::deep_copy(b, 1.0);
  Kokkos::deep_copy(c, 2.0);
  const double s = 3.0;
  double best = 1e30, best_cpu = 1e30;
  for (int r = 0; r < reps; ++r) {
    Kokkos::fence();
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = process_cpu_seconds();
    Kokkos::parallel_for(
        "stream::triad", Kokkos::RangePolicy<ExecSpace>(0, n),
        KOKKOS_LAMBDA(long i) { a(i) = b(i) + s * c(i); });
    Kokkos::fence();
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, dt);
    best_cpu = std::min(best_cpu, process_cpu_seconds() - c0);
  }
  Stream out;
  out.elements = double(n);
  out.triad_gbs = 3.0 * 8.0 * double(n) / best / 1e9;
  out.triad_cpu_gbs = 3.0 * 8.0 * double(n) / best_cpu / 1e9;
  return out;
}

Stream cache_triad(long n, int reps) {
  Kokkos::View<double*, MemSpace> a("cache::a", n), b("cache::b", n), c("cache::c", n);
  Kokkos::deep_copy(b, 1.0);
  Kokkos::deep_copy(c, 2.0);
  const double s = 3.0;
  auto one = [&] {
    Kokkos::parallel_for(
        "cache::triad", Kokkos::RangePolicy<ExecSpace>(0, n),
        KOKKOS_LAMBDA(long i) { a(i) = b(i) + s * c(i); });
  };
  one();  // into the caches
  Kokkos::fence();
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = process_cpu_seconds();
  for (int r = 0; r < reps; ++r) one();
  Kokkos::fence();
  const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = process_cpu_seconds() - c0;
  Stream out;
  out.elements = double(n);
  out.triad_gbs = 3.0 * 8.0 * double(n) * reps / dt / 1e9;
  out.triad_cpu_gbs = 3.0 * 8.0 * double(n) * reps / cpu / 1e9;
  return out;
}

}  // namespace mp::perf
