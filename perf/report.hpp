// What every benchmark's report shares: the machine fields its JSON opens with, and writing the
// JSON file beside the markdown table it prints.
#pragma once
#include <cstdio>
#include <fstream>
#include <ostream>
#include <string>
#include <thread>

#include "core/types.hpp"
#include "stream.hpp"

namespace mp::perf {

// Opens the JSON object with the benchmark name, the execution space, threads, ranks, precision
// and the STREAM triad of this process; the caller adds its fields and closes the object.
inline void json_machine(std::ostream& js, const std::string& benchmark, const Stream& st,
                         int nranks) {
  js << "{\n  \"benchmark\": \"" << benchmark << "\",\n  \"kokkos_execution_space\": \""
     << ExecSpace::name() << "\",\n  \"threads_per_rank\": " << ExecSpace().concurrency()
     << ",\n  \"ranks\": " << nranks << ",\n  \"real\": \""
     << (sizeof(Real) == 8 ? "double" : "float")
     << "\",\n  \"hardware_threads\": " << std::thread::hardware_concurrency()
     << ",\n  \"stream_triad_GBs\": " << st.triad_gbs;
}

// Writes the JSON to `path` (nothing when empty) and says so.
inline void write_json(const std::string& path, const std::string& json) {
  if (path.empty()) return;
  std::ofstream out(path);
  out << json;
  std::printf("\nwrote %s\n", path.c_str());
}

}  // namespace mp::perf
