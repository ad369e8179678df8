// Memory from the allocations themselves: every Kokkos allocation and deallocation made while an
// AllocationTracker lives is seen through the Kokkos Tools callbacks
// (Kokkos::Tools::Experimental::set_callbacks) with its label and size, so the bytes a run holds
// are the sum of its live View allocations, not a formula. Used by the layout study
// (perf/bench_layouts.cpp) and by the run's memory estimate (src/driver/memory.cpp).
// One tracker at a time, and not together with a perf::KernelTimer (both use the allocate
// callback). The callbacks in place before it (a loaded Kokkos Tools library) are put back when
// it ends.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"

namespace mp {

class AllocationTracker {
 public:
  // alone: while the tracker lives, every other Kokkos Tools callback (a loaded profiler's
  // kernel and region events) is off, so work done under it is not seen by that tool.
  explicit AllocationTracker(bool alone = false) {
    namespace T = Kokkos::Tools::Experimental;
    saved_ = T::get_callbacks();
    T::EventSet mine{};
    if (!alone) mine = saved_;
    mine.allocate_data = allocate;
    mine.deallocate_data = deallocate;
    active() = this;
    T::set_callbacks(mine);
  }
  ~AllocationTracker() {
    Kokkos::Tools::Experimental::set_callbacks(saved_);
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

  // Sorts the allocations made from now on into classes (`which` maps an allocation's size to
  // a class in [0, weights.size())) and weighs each class's bytes: weighted_peak() is then the
  // largest sum of weight x bytes over the live allocations, parts_at_peak() that sum's parts
  // (weight x bytes by class) at that moment, live_parts() the parts now. With weights the
  // ratios of a larger mesh's arrays to these, it is the peak that mesh would reach by the same
  // allocations.
  void weigh(std::function<int(uint64_t bytes)> which, std::vector<double> weights) {
    which_ = std::move(which);
    weights_ = std::move(weights);
    bytes_by_class_.assign(weights_.size(), 0);
    at_peak_ = bytes_by_class_;
    weighted_peak_ = 0;
  }
  double weighted_peak() const { return weighted_peak_; }
  std::vector<double> parts_at_peak() const { return at_peak_; }
  std::vector<double> live_parts() const { return weighted(bytes_by_class_); }

 private:
  struct Alloc {
    std::string label;
    uint64_t size;
    int cls;  // -1 when made before weigh()
  };
  static AllocationTracker*& active() {
    static AllocationTracker* t = nullptr;
    return t;
  }
  std::vector<double> weighted(const std::vector<double>& bytes) const {
    std::vector<double> w(bytes.size());
    for (std::size_t c = 0; c < bytes.size(); ++c) w[c] = weights_[c] * bytes[c];
    return w;
  }
  static void allocate(Kokkos::Profiling::SpaceHandle, const char* label, const void* ptr,
                       uint64_t size) {
    AllocationTracker& t = *active();
    const int cls = t.which_ ? t.which_(size) : -1;
    t.live_[ptr] = {label, size, cls};
    t.current_ += double(size);
    if (t.current_ > t.peak_) t.peak_ = t.current_;
    if (cls < 0) return;
    t.bytes_by_class_[cls] += double(size);
    const std::vector<double> parts = t.weighted(t.bytes_by_class_);
    double sum = 0;
    for (double p : parts) sum += p;
    if (sum > t.weighted_peak_) {
      t.weighted_peak_ = sum;
      t.at_peak_ = parts;
    }
  }
  static void deallocate(Kokkos::Profiling::SpaceHandle, const char*, const void* ptr, uint64_t) {
    AllocationTracker& t = *active();
    const auto it = t.live_.find(ptr);
    if (it == t.live_.end()) return;  // made before the tracker
    t.current_ -= double(it->second.size);
    if (it->second.cls >= 0) t.bytes_by_class_[it->second.cls] -= double(it->second.size);
    t.live_.erase(it);
  }
  Kokkos::Tools::Experimental::EventSet saved_{};
  std::map<const void*, Alloc> live_;
  double current_ = 0, peak_ = 0;
  std::function<int(uint64_t)> which_;
  std::vector<double> weights_, bytes_by_class_, at_peak_;
  double weighted_peak_ = 0;
};

}  // namespace mp
