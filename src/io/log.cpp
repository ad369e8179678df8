#include "io/log.hpp"

#include <mpi.h>

#include <cstdio>

namespace mp {

void log_line(const std::string& text) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) std::printf("%s\n", text.c_str());
  std::fflush(stdout);
}

std::string eta_text(double seconds) {
  char b[32];
  if (!(seconds >= 0)) return "";
  if (seconds < 1e4) {
    std::snprintf(b, sizeof b, "ETA %.0f s", seconds);
  } else if (seconds < 3.6e9) {  // up to a million hours
    std::snprintf(b, sizeof b, "ETA %.3g h", seconds / 3600);
  } else {
    std::snprintf(b, sizeof b, "ETA > 1e6 h");
  }
  return b;
}

void log_cycle(long cycle, double t, double dt, const std::string& limit,
               const std::array<int, 3>& cell, double wall, double progress, double eta) {
  char left[48] = "";
  if (eta >= 0) std::snprintf(left, sizeof left, "  %s", eta_text(eta).c_str());
  std::printf("cycle %7ld  t %.6e  dt %.4e (%s at %d,%d,%d)  wall %9.3f s  %5.1f%%%s\n", cycle, t,
              dt, limit.c_str(), cell[0], cell[1], cell[2], wall, 100.0 * progress, left);
  std::fflush(stdout);
}

}  // namespace mp
