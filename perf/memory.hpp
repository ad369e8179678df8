// Memory from the allocations themselves: every Kokkos allocation and deallocation made while an
// AllocationTracker lives is seen through the Kokkos Tools callbacks
// (Kokkos::Tools::Experimental::set_{allocate,deallocate}_data_callback) with its label and
// size, so the bytes a run holds are the sum of its live View allocations, not a formula.
// One tracker at a time, and not together with a KernelTimer (both use the allocate callback).
#pragma once
#include <cstdint>
#include <map>
#include <string>

#include "core/types.hpp"

namespace mp::perf {

class AllocationTracker {
 public:
  AllocationTracker() {
    namespace T = Kokkos::Tools::Experimental;
    active() = this;
    T::set_allocate_data_callback(allocate);
    T::set_deallocate_data_callback(deallocate);
  }
  ~AllocationTracker() {
    namespace T = Kokkos::Tools::Experimental;
    T::set_allocate_data_callback(nullptr);
    T::set_deallocate_data_callback(nullptr);
    active() = nullptr;
  }
  AllocationTracker(const AllocationTracker&) = delete;
  AllocationTracker& operator=(const AllocationTracker&) = delete;

  // Bytes of the allocations made since construction and still live, all of them or those whose
  // label starts with one of `prefixes`.
  double live_bytes() const {
    double b = 0;
    for (const auto& kv : live_) b += double(kv.second.size);
    return b;
  }
  // The largest live_bytes() seen since construction (the high-water mark of the run's Kokkos
  // allocations: fields, scratch, halo buffers, host mirrors made while the tracker lives).
  double peak_bytes() const { return peak_; }
  template <class... P>
  double live_bytes_with(const P&... prefixes) const {
    double b = 0;
    for (const auto& kv : live_)
      for (const char* p : {prefixes...})
        if (kv.second.label.rfind(p, 0) == 0) {
          b += double(kv.second.size);
          break;
        }
    return b;
  }

 private:
  struct Alloc {
    std::string label;
    uint64_t size;
  };
  static AllocationTracker*& active() {
    static AllocationTracker* t = nullptr;
    return t;
  }
  static void allocate(Kokkos::Profiling::SpaceHandle, const char* label, const void* ptr,
                       uint64_t size) {
    AllocationTracker& t = *active();
    t.live_[ptr] = {label, size};
    t.current_ += double(size);
    if (t.current_ > t.peak_) t.peak_ = t.current_;
  }
  static void deallocate(Kokkos::Profiling::SpaceHandle, const char*, const void* ptr, uint64_t) {
    AllocationTracker& t = *active();
    const auto it = t.live_.find(ptr);
    if (it == t.live_.end()) return;  // made before the tracker
    t.current_ -= double(it->second.size);
    t.live_.erase(it);
  }
  std::map<const void*, Alloc> live_;
  double current_ = 0, peak_ = 0;
};

}  // namespace mp::perf
