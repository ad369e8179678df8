// rest_until_all: a barrier that sleeps between polls, for tests that run on part of their ranks.
#pragma once
#include <mpi.h>

#include <chrono>
#include <thread>

namespace mp::test {

// Waits until every rank of comm has arrived, asleep between polls. A test that runs a scene on
// a sub-communicator leaves the other ranks in the next collective, where Open MPI polls
// without sleeping: on the oversubscribed CI host (4 ranks on 2 cores) each waiting rank then
// holds a core that the running ranks, or the build beside the suite, could use. Every rank of
// comm calls it, the running ranks when their run is done.
inline void rest_until_all(MPI_Comm comm = MPI_COMM_WORLD) {
  MPI_Request request;
  MPI_Ibarrier(comm, &request);
  int done = 0;
  MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  while (!done) {
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  }
}

}  // namespace mp::test
