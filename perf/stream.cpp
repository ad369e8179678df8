#include "stream.hpp"

#include <algorithm>
#include <chrono>
#include <tuple>
#include <utility>

#include "core/types.hpp"
#include "protocol.hpp"

namespace mp::perf {

namespace {

// The triad a = b + s c over n elements, `reps` times, timed by the wall clock and this
// process' CPU time. best: each repetition timed alone, the fastest kept (STREAM's rule);
// otherwise one repetition to bring the arrays in, then all timed together (their mean).
Stream triad(const char* label, long n, int reps, bool best) {
  Kokkos::View<double*, MemSpace> a("triad::a", n), b("triad::b", n), c("triad::c", n);
  Kokkos::deep_copy(b, 1.0);
  Kokkos::deep_copy(c, 2.0);
  const double s = 3.0;
  auto one = [&] {
    Kokkos::parallel_for(
        label, Kokkos::RangePolicy<ExecSpace>(0, n),
        KOKKOS_LAMBDA(long i) { a(i) = b(i) + s * c(i); });
  };
  // seconds (wall, CPU) of `times` repetitions
  auto timed = [&](int times) {
    Kokkos::fence();
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = process_cpu_seconds();
    for (int r = 0; r < times; ++r) one();
    Kokkos::fence();
    return std::pair<double, double>{
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
        process_cpu_seconds() - c0};
  };
  double wall = 1e30, cpu = 1e30;
  int per = 1;  // repetitions per timing
  if (best) {
    for (int r = 0; r < reps; ++r) {
      const auto [tw, tc] = timed(1);
      wall = std::min(wall, tw);
      cpu = std::min(cpu, tc);
    }
  } else {
    one();  // into the caches
    std::tie(wall, cpu) = timed(reps);
    per = reps;
  }
  Stream out;
  out.elements = double(n);
  out.triad_gbs = 3.0 * 8.0 * double(n) * per / wall / 1e9;
  out.triad_cpu_gbs = 3.0 * 8.0 * double(n) * per / cpu / 1e9;
  return out;
}

}  // namespace

Stream stream_triad(long n, int reps) {
  return triad("stream::triad", n, reps, true);
}

Stream cache_triad(long n, int reps) {
  return triad("cache::triad", n, reps, false);
}

}  // namespace mp::perf
