// What the benchmarks' timing protocols share on a shared, noisy machine: the median over timed
// blocks, the share of the CPUs other processes took while they ran (Linux /proc), and the
// striped multi-material scene of the layout study (perf/bench_layouts.cpp, perf/perf_check.cpp).
#pragma once
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace mp::perf {

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// CPU seconds this process has used (all its threads; CLOCK_PROCESS_CPUTIME_ID). With one
// thread, the time a piece of work took while it held a CPU: unlike wall time, it does not
// grow while other processes hold the CPU, which on a shared machine is most of the noise.
inline double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// CPU time of the whole machine and of this process (Linux /proc), to measure how much of the
// CPUs other processes took while something was timed.
struct CpuSample {
  double busy = 0, self = 0, wall = 0;  // clock ticks, clock ticks, seconds
};

inline CpuSample cpu_sample() {
  CpuSample s;
  std::ifstream st("/proc/stat");
  std::string cpu;
  double v[8] = {};
  st >> cpu;
  for (double& x : v) st >> x;
  s.busy = v[0] + v[1] + v[2] + v[5] + v[6] + v[7];  // user nice system irq softirq steal
  std::ifstream self("/proc/self/stat");
  std::string tok;
  for (int f = 1; f <= 15 && self >> tok; ++f)
    if (f == 14 || f == 15) s.self += std::stod(tok);  // utime, stime
  s.wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  return s;
}

// Share of all CPUs (0..1) that processes other than this one used between two samples.
inline double others_share(const CpuSample& a, const CpuSample& b) {
  const double tick = double(sysconf(_SC_CLK_TCK));
  const double cpus = double(std::thread::hardware_concurrency());
  const double others = (b.busy - a.busy) - (b.self - a.self);
  return std::max(0.0, others / tick / (cpus * (b.wall - a.wall)));
}

// The layout study's scene: an nx x ny x nz box of stripes normal to x, each `width` cells
// wide, materials cycling through the stripes; each stripe boundary sits in the middle of a
// cell, so exactly 1/width of the cells are mixed (two materials each). Ideal gases of
// different gamma and density at one pressure, moving at a uniform speed along x: every cycle
// remaps material across the interfaces. `layout` is "dense" or "compact".
// The first `strength` materials get elastic-perfectly-plastic strength (G 0.5, Y 0.05 in the
// deck's units, about the gases' pressure: every stripe of them yields as it is sheared), so
// the layout study can time the strength module in mixed cells.
inline std::string stripes_deck(int nmat, int width, const std::vector<int>& cells,
                                const char* layout, int strength = 0,
                                const std::vector<double>& velocity = {0.3, 0, 0}) {
  const double dx = 1.0 / cells[0];
  const double lx = 1.0, ly = double(cells[1]) * dx, lz = double(cells[2]) * dx;
  std::ostringstream d;
  d.precision(17);
  d << "scene: layouts\nmesh:\n  cells: [" << cells[0] << ", " << cells[1] << ", " << cells[2]
    << "]\n  lo: [0, 0, 0]\n  hi: [" << lx << ", " << ly << ", " << lz << "]\n"
    << "boundaries: {x: periodic, y: periodic, z: periodic}\n"
    << "time: {end: 1.0e9, cfl: 0.5, dt_initial: 1.0e-3}\n"
    // (the one-material reference runs geometry: fixed, the multi-material cycle's -- the
    // mid-step geometry is single-material only -- so that it does the same work per cell; the
    // layout is a multi-material key: each kind of scene refuses the other's)
    << "numerics: {" << (nmat > 1 ? std::string("layout: ") + layout + ", " : std::string())
    << "samples: 2" << (nmat > 1 ? "" : ", geometry: fixed") << "}\nmaterials:\n";
  for (int m = 0; m < nmat; ++m)
    d << "  - {name: gas" << m << ", eos: ideal_gas, gamma: " << 1.3 + 0.02 * m
      << (m < strength ? ", strength: {model: elastic_plastic, shear_modulus: 0.5, yield: 0.05}"
                       : "")
      << "}\n";
  std::ostringstream vel;
  vel.precision(17);
  vel << "velocity: [" << velocity[0] << ", " << velocity[1] << ", " << velocity[2] << "]";
  d << "regions:\n  - {material: gas0, shape: all, density: 1.0, pressure: 1.0, " << vel.str()
    << "}\n";
  const int stripes = cells[0] / width;
  for (int s = 1; s < stripes; ++s) {
    const double lo = (s * width + 0.5) * dx, hi = ((s + 1) * width + 0.5) * dx;
    d << "  - {material: gas" << s % nmat << ", shape: box, lo: [" << lo << ", -1, -1], hi: ["
      << (s + 1 == stripes ? 2.0 : hi) << ", 2, 2], density: " << 1.0 + 0.1 * (s % nmat)
      << ", pressure: 1.0, " << vel.str() << "}\n";
  }
  return d.str();
}

}  // namespace mp::perf
