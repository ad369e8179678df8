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

// A test hook for kill-and-continue testing: with MINIPAGOSA_TEST_KILL="<point>:<cycle>" in the
// environment, the process sends itself SIGKILL when it reaches `point` at `cycle` ("cycle": the
// end of that cycle, after its checkpoint if one is due; "checkpoint": that cycle's checkpoint
// complete under its .tmp name, before the rename). Unset (always, outside tests): nothing.
// A malformed value is an error named at start-up (check_kill_hook).
void kill_point(const char* point, long cycle);
// Throws InputError when MINIPAGOSA_TEST_KILL is set but malformed.
void check_kill_hook();

}  // namespace mp::signals
