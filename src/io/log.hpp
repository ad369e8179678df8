// The run log (rank 0 only) and small text helpers.
#pragma once
#include <array>
#include <string>

namespace mp {

void log_line(const std::string& text);  // rank 0 prints, others stay silent
// "ETA 12 s", "ETA 3.2 h", "ETA > 1e6 h" for a wall time left in seconds ("" if negative).
std::string eta_text(double seconds);
void log_cycle(long cycle, double t, double dt, const std::string& limit,
               const std::array<int, 3>& cell, double wall, double progress, double eta = -1);

}  // namespace mp
