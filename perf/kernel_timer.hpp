// Per-kernel times through Kokkos' tools callbacks (Kokkos::Tools::Experimental::set_*_callback,
// Kokkos 3.3 and later), for the benchmarks' kernel breakdowns.
//
// While a KernelTimer lives, every parallel_for / parallel_reduce / parallel_scan is bracketed by
// Kokkos::fence() before its clock starts and before it stops, so each kernel is charged its own
// time and not that of work still in flight. Those fences serialise what an asynchronous backend
// would overlap, so a breakdown comes from cycles of its own, never from the plain timing run.
// Regions (Kokkos::Profiling::pushRegion/popRegion) are timed inclusively (kernels, MPI, host
// work inside them). Allocations made while the timer lives are counted: a timed cycle should
// make none.
#pragma once
#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace mp::perf {

struct KernelStat {
  double seconds = 0;
  long calls = 0;
};

class KernelTimer {
 public:
  KernelTimer() {
    namespace T = Kokkos::Tools::Experimental;
    active() = this;
    T::set_begin_parallel_for_callback(begin);
    T::set_end_parallel_for_callback(end);
    T::set_begin_parallel_reduce_callback(begin);
    T::set_end_parallel_reduce_callback(end);
    T::set_begin_parallel_scan_callback(begin);
    T::set_end_parallel_scan_callback(end);
    T::set_push_region_callback(push);
    T::set_pop_region_callback(pop);
    T::set_allocate_data_callback(allocate);
  }
  ~KernelTimer() {
    namespace T = Kokkos::Tools::Experimental;
    T::set_begin_parallel_for_callback(nullptr);
    T::set_end_parallel_for_callback(nullptr);
    T::set_begin_parallel_reduce_callback(nullptr);
    T::set_end_parallel_reduce_callback(nullptr);
    T::set_begin_parallel_scan_callback(nullptr);
    T::set_end_parallel_scan_callback(nullptr);
    T::set_push_region_callback(nullptr);
    T::set_pop_region_callback(nullptr);
    T::set_allocate_data_callback(nullptr);
    active() = nullptr;
  }
  KernelTimer(const KernelTimer&) = delete;
  KernelTimer& operator=(const KernelTimer&) = delete;

  // Seconds and calls per kernel name (Kokkos' label) and per region, since construction.
  const std::map<std::string, KernelStat>& kernels() const { return kernels_; }
  const std::map<std::string, KernelStat>& regions() const { return regions_; }
  long allocations() const { return allocations_; }
  double allocated_bytes() const { return allocated_bytes_; }

 private:
  using Clock = std::chrono::steady_clock;
  struct Open {
    std::string name;
    Clock::time_point t0;
  };

  static KernelTimer*& active() {
    static KernelTimer* t = nullptr;
    return t;
  }
  static double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  }
  static void begin(const char* name, uint32_t, uint64_t* id) {
    KernelTimer* t = active();
    Kokkos::fence();  // work launched before this kernel is not its cost
    *id = t->open_.size();
    t->open_.push_back({name, Clock::now()});
  }
  static void end(uint64_t id) {
    KernelTimer* t = active();
    Kokkos::fence();  // the kernel itself has finished
    KernelStat& s = t->kernels_[t->open_[id].name];
    s.seconds += since(t->open_[id].t0);
    ++s.calls;
    t->open_.resize(id);  // kernels do not overlap on one execution space
  }
  static void push(const char* name) { active()->regions_open_.push_back({name, Clock::now()}); }
  static void pop() {
    KernelTimer* t = active();
    Kokkos::fence();
    KernelStat& s = t->regions_[t->regions_open_.back().name];
    s.seconds += since(t->regions_open_.back().t0);
    ++s.calls;
    t->regions_open_.pop_back();
  }
  static void allocate(Kokkos::Profiling::SpaceHandle, const char*, const void*, uint64_t size) {
    ++active()->allocations_;
    active()->allocated_bytes_ += double(size);
  }

  std::map<std::string, KernelStat> kernels_, regions_;
  std::vector<Open> open_, regions_open_;
  long allocations_ = 0;
  double allocated_bytes_ = 0;
};

}  // namespace mp::perf
