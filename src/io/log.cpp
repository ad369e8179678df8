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

void log_cycle(long cycle, double t, double dt, const std::string& limit,
               const std::array<int, 3>& cell, double wall, double progress, double eta) {
  char left[32] = "";
  if (eta >= 0) std::snprintf(left, sizeof left, "  ETA %.0f s", eta);
  std::printf("cycle %7ld  t %.6e  dt %.4e (%s at %d,%d,%d)  wall %9.3f s  %5.1f%%%s\n", cycle, t,
              dt, limit.c_str(), cell[0], cell[1], cell[2], wall, 100.0 * progress, left);
  std::fflush(stdout);
}

}  // namespace mp
