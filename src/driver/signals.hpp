// SIGTERM and SIGINT: the first asks the run to stop after the current cycle (every rank
// agrees on it at the end of each cycle), write a checkpoint, the final dump and the summary,
// and exit with kExitInterrupted; a second one stops the process at once (exit 128 + signal).
#pragma once

namespace mp::signals {

constexpr int kExitInterrupted = 5;

void install();
// The signal that asked for a stop (0: none yet).
int requested();
// For tests: forget a request.
void reset();

}  // namespace mp::signals
