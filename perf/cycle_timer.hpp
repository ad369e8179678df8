// The cycle of Hydro::step taken apart and timed phase by phase (each phase fenced and, across
// ranks, bracketed by barriers), shared by the benchmarks.
#pragma once
#include <mpi.h>
#include <sys/resource.h>

#include <chrono>

#include "hydro/hydro.hpp"

namespace mp::perf {

struct CycleTimes {
  static constexpr int kPhases = 5;
  static constexpr const char* names[kPhases] = {"time_step", "lagrange", "remap", "eos_viscosity",
                                                 "health_check"};
  double phase[kPhases] = {0, 0, 0, 0, 0};  // seconds summed over the timed cycles
  double wall = 0;                          // seconds of the timed cycles
  int cycles = 0;                           // timed cycles
  long minor_faults = 0;  // page faults of this process during the timed cycles (first touches)
};

// Where a run stands between calls of run_cycles: the previous step, the time, the cycle (its
// parity sets the sweep order), so a run can be timed in several blocks.
struct RunClock {
  Real dt_old = 0;
  double t = 0;
  long cycle = 0;
};

inline long minor_faults() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_minflt;
}

// Runs `warmup` untimed then `cycles` timed cycles of the hydro from where `clock` stands.
inline CycleTimes run_cycles(hydro::Hydro& h, RunClock& clock, int warmup, int cycles) {
  CycleTimes ct;
  ct.cycles = cycles;
  Real& dt_old = clock.dt_old;
  double& t = clock.t;
  auto now = [] { return std::chrono::steady_clock::now(); };
  auto since = [](std::chrono::steady_clock::time_point a) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
  };
  long faults = 0;
  for (int cyc = 0; cyc < warmup + cycles; ++cyc, ++clock.cycle) {
    Kokkos::fence();
    MPI_Barrier(MPI_COMM_WORLD);
    const bool timed = cyc >= warmup;
    if (cyc == warmup) faults = minor_faults();
    const auto t0 = now();
    auto tp = now();
    const auto ts = h.time_step(dt_old, double(t), 1e9);
    Kokkos::fence();
    if (timed) ct.phase[0] += since(tp);
    tp = now();
    h.lagrange(ts.dt, clock.cycle);
    Kokkos::fence();
    if (timed) ct.phase[1] += since(tp);
    tp = now();
    h.remap(clock.cycle);
    Kokkos::fence();
    if (timed) ct.phase[2] += since(tp);
    tp = now();
    h.eos_viscosity();
    Kokkos::fence();
    if (timed) ct.phase[3] += since(tp);
    tp = now();
    h.check();
    Kokkos::fence();
    if (timed) ct.phase[4] += since(tp);
    MPI_Barrier(MPI_COMM_WORLD);
    if (timed) ct.wall += since(t0);
    t += ts.dt;
    dt_old = ts.dt;
  }
  if (cycles > 0) ct.minor_faults = minor_faults() - faults;
  return ct;
}

// Runs `warmup` untimed then `cycles` timed cycles of the hydro from its current state.
inline CycleTimes time_cycles(hydro::Hydro& h, int warmup, int cycles) {
  RunClock clock;
  return run_cycles(h, clock, warmup, cycles);
}

}  // namespace mp::perf
