// The run log (rank 0 only) and small text helpers.
#pragma once
#include <array>
#include <string>

namespace mp {

void log_line(const std::string& text);  // rank 0 prints, others stay silent
void log_cycle(long cycle, double t, double dt, const std::string& limit,
               const std::array<int, 3>& cell, double wall, double progress, double eta = -1);

}  // namespace mp
