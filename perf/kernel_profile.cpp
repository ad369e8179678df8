// A Kokkos Tools library that times every named kernel of any minipagosa run (the scene decks,
// the perforator at the paper's size), where bench_hydro and bench_layouts time only their own
// scenes:
//
//   KOKKOS_PROFILE_LIBRARY=build/perf/libminipagosa_kernel_profile.so
//   MINIPAGOSA_KERNEL_PROFILE=profile.md build/minipagosa deck.yaml ...
//
// (both variables in the environment of the run).
//
// At exit it writes, per kernel name, the seconds inside the kernel, the share of all kernel
// time and the number of launches, largest first, with the run's wall time from Kokkos'
// initialisation (to the file MINIPAGOSA_KERNEL_PROFILE names, "%r" replaced by the MPI rank;
// default: standard error). A name that ends in ".json" gets JSON instead of the Markdown table.
// The times are host wall clock from the kernel's begin to its end callback: exact on the
// host backends (OpenMP, Serial: a launch returns when the kernel is done); on a GPU backend
// they are launch times unless the kernels are fenced.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

struct KokkosPDeviceInfo;

namespace {

using Clock = std::chrono::steady_clock;

struct Kernel {
  double seconds = 0;
  long launches = 0;
};

struct Open {
  std::string name;
  Clock::time_point start;
};

std::map<std::string, Kernel> kernels;
std::vector<Open> open;  // begun, not ended (the host backends do not nest, but allow it)
Clock::time_point t0;

void begin(const char* name, uint64_t* id) {
  *id = open.size();
  open.push_back({name, Clock::now()});
}

void end(uint64_t id) {
  if (id >= open.size()) return;
  Kernel& k = kernels[open[id].name];
  k.seconds += std::chrono::duration<double>(Clock::now() - open[id].start).count();
  ++k.launches;
  open.resize(id);
}

std::string output_path() {
  const char* p = std::getenv("MINIPAGOSA_KERNEL_PROFILE");
  if (!p || !*p) return "";
  std::string s = p;
  const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
  const std::size_t at = s.find("%r");
  if (at != std::string::npos) s.replace(at, 2, rank ? rank : "0");
  return s;
}

std::string json_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    o += c;
  }
  return o;
}

}  // namespace

extern "C" {

void kokkosp_init_library(int, uint64_t, uint32_t, KokkosPDeviceInfo*) {
  t0 = Clock::now();
}

void kokkosp_finalize_library() {
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  std::vector<std::pair<std::string, Kernel>> v(kernels.begin(), kernels.end());
  std::sort(v.begin(), v.end(),
            [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
  double sum = 0;
  long launches = 0;
  for (const auto& k : v) sum += k.second.seconds, launches += k.second.launches;
  const std::string path = output_path();
  std::FILE* f = path.empty() ? stderr : std::fopen(path.c_str(), "w");
  if (!f) {
    std::fprintf(stderr, "minipagosa_kernel_profile: cannot write %s\n", path.c_str());
    return;
  }
  const bool json = path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0;
  if (json) {
    std::fprintf(f, "{\"wall_seconds\": %.6f, \"kernel_seconds\": %.6f, \"launches\": %ld,\n", wall,
                 sum, launches);
    std::fprintf(f, " \"kernels\": [");
    for (std::size_t i = 0; i < v.size(); ++i)
      std::fprintf(f, "%s\n  {\"name\": \"%s\", \"seconds\": %.6f, \"launches\": %ld}",
                   i ? "," : "", json_escape(v[i].first).c_str(), v[i].second.seconds,
                   v[i].second.launches);
    std::fprintf(f, "]}\n");
  } else {
    std::fprintf(f, "wall %.3f s from Kokkos initialisation; %.3f s in %ld kernel launches\n\n",
                 wall, sum, launches);
    std::fprintf(f, "| kernel | seconds | %% of kernel time | launches |\n|---|---|---|---|\n");
    for (const auto& k : v)
      std::fprintf(f, "| %s | %.4f | %.2f | %ld |\n", k.first.c_str(), k.second.seconds,
                   sum > 0 ? 100 * k.second.seconds / sum : 0.0, k.second.launches);
  }
  if (f != stderr) std::fclose(f);
}

void kokkosp_begin_parallel_for(const char* name, uint32_t, uint64_t* id) {
  begin(name, id);
}
void kokkosp_end_parallel_for(uint64_t id) {
  end(id);
}
void kokkosp_begin_parallel_reduce(const char* name, uint32_t, uint64_t* id) {
  begin(name, id);
}
void kokkosp_end_parallel_reduce(uint64_t id) {
  end(id);
}
void kokkosp_begin_parallel_scan(const char* name, uint32_t, uint64_t* id) {
  begin(name, id);
}
void kokkosp_end_parallel_scan(uint64_t id) {
  end(id);
}

}  // extern "C"
