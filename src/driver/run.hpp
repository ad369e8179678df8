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
};

// Exit codes: 0 completed; 2 bad input (nothing written); 3 the run went non-physical (a final
// dump and the summary are written); 4 another run-time failure (I/O, MPI).
int run(const CommandLine& cl);

}  // namespace mp
