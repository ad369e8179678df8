// The cycle of Hydro::step taken apart and timed phase by phase (each phase fenced and, across
// ranks, bracketed by barriers), shared by the benchmarks.
#pragma once
#include <mpi.h>

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
};

// Runs `warmup` untimed then `cycles` timed cycles of the hydro from its current state.
inline CycleTimes time_cycles(hydro::Hydro& h, int warmup, int cycles) {
  CycleTimes ct;
  ct.cycles = cycles;
  auto& state = h.state();
  Real dt_old = 0;
  double t = 0;
  auto now = [] { return std::chrono::steady_clock::now(); };
  auto since = [](std::chrono::steady_clock::time_point a) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
  };
  for (int cyc = 0; cyc < warmup + cycles; ++cyc) {
    Kokkos::fence();
    MPI_Barrier(MPI_COMM_WORLD);
    const bool timed = cyc >= warmup;
    const auto t0 = now();
    auto tp = now();
    const auto ts = h.time_step(dt_old, Real(t), Real(1e9));
    Kokkos::fence();
    if (timed) ct.phase[0] += since(tp);
    tp = now();
    h.lagrange(ts.dt);
    Kokkos::fence();
    if (timed) ct.phase[1] += since(tp);
    tp = now();
    h.remap(cyc);
    Kokkos::fence();
    if (timed) ct.phase[2] += since(tp);
    tp = now();
    h.equation_of_state(state.rho, state.e, state.p, state.c);
    h.viscosity();
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
  return ct;
}

}  // namespace mp::perf
