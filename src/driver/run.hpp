// The whole run behind the command line: read the deck, build, run, report; exit code.
#pragma once
#include <string>
#include <vector>

namespace mp {

struct CommandLine {
  std::string scene;
  std::vector<std::string> overrides;
  std::string output;
  bool quiet = false;
  bool check_only = false;
  std::string restart;  // checkpoint path, or "latest" (newest in the output directory)
  std::vector<std::string> restart_allow;  // deck keys the restart may change (RunSettings)
  bool overwrite = false;
};

// The checks of the command line and the deck that need neither MPI nor Kokkos: the deck read
// and validated, the restart options, the output path's length. Throws InputError. main runs it
// before MPI starts, so that bad input fails at once (a singleton Open MPI start-up alone takes
// about 0.4 s); run() runs it again, beside the checks that need the ranks.
void check_input(const CommandLine& cl);

// Exit codes: 0 completed (end time or max_cycles reached); 2 bad input (nothing written);
// 3 the run went non-physical (a final dump and the summary are written); 4 another run-time
// failure (I/O: the message names the file and the reason, MPI); 5 interrupted by SIGTERM or
// SIGINT (checkpoint, final dump and summary written: restartable); 128 + signal: a second
// signal stopped the run at once.
int run(const CommandLine& cl);

}  // namespace mp
