// STREAM triad (McCalpin) in Kokkos, measured in the same process as the kernels it is compared
// with, so the bandwidth figure and the kernel figures see the same machine state.
#pragma once

namespace mp::perf {

struct Stream {
  double triad_gbs = 0;  // best of the repetitions, 3 arrays x 8 bytes per element counted
  // the same with each repetition timed by this process' CPU time (perf/protocol.hpp), for a
  // one-thread run on a shared machine (perf/perf_check.cpp)
  double triad_cpu_gbs = 0;
  double elements = 0;
};

Stream stream_triad(long elements, int repetitions);

// The same triad on arrays that stay in the caches (3 x 1 MiB: the last-level cache of any
// machine this runs on), timed over all its repetitions together (their mean, not their best):
// how fast this process computes out of the caches just now, the state the benchmarks of
// perf/perf_check.cpp (working sets of a few MB) run in. `elements` is the bandwidth's element
// count per repetition.
Stream cache_triad(long elements, int repetitions);

}  // namespace mp::perf
