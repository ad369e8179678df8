// The memory estimate a run prints before it allocates (src/driver/memory.cpp; the one --check
// prints and the run is refused by) against the run's peak resident memory, measured by the
// kernel (wait4's ru_maxrss), for every shipped deck in configs/: three cycles on one rank,
// dumps as the deck asks.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli_support.hpp"

namespace mp::cli {
namespace {

// The MiB in the run log's "memory estimate: 247 MiB (...)", or -1.
double estimate_mib(const std::string& log) {
  const std::string key = "memory estimate: ";
  const std::size_t at = log.find(key);
  if (at == std::string::npos) return -1;
  return std::stod(log.substr(at + key.size()));
}

using MemoryEstimate = CliTest;

TEST_F(MemoryEstimate, HoldsThePeakResidentMemoryOfEveryShippedDeck) {
  std::vector<fs::path> decks;
  for (const std::string& d : mp::test::shipped_decks()) decks.push_back(d);
  ASSERT_GE(decks.size(), 20u);
  for (const fs::path& deck : decks) {
    const std::string name = deck.stem().string();
    const Result r = run({deck.string(), "--set", "time.max_cycles=3", "-q", "-o", "out_" + name});
    ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    const double est = estimate_mib(r.out), peak = double(r.max_rss_kib) / 1024.0;
    ASSERT_GT(est, 0) << name << ": no memory estimate in the log:\n" << r.out;
    std::printf("%-18s estimate %7.1f MiB, peak resident %7.1f MiB, ratio %.3f\n", name.c_str(),
                est, peak, est / peak);
    // within 15 % (observed: ratios 1.003 (noh) to 1.035 (elastic_wave, sod_y) over the 20 decks)
    EXPECT_LE(std::fabs(est - peak) / peak, 0.15) << name;
    // and not below 0.9 of the peak (observed: none below 1.003): the estimate refuses runs that
    // will not fit
    EXPECT_GE(est, 0.9 * peak) << name;
  }
}

}  // namespace
}  // namespace mp::cli
