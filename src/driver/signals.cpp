#include "driver/signals.hpp"

#include <signal.h>
#include <unistd.h>

#include <cstring>

namespace mp::signals {

namespace {
volatile sig_atomic_t g_signal = 0;

void handler(int sig) {
  if (g_signal != 0) {
    // only async-signal-safe calls here
    const char msg[] = "minipagosa: second signal: stopping at once\n";
    const ssize_t ignored = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)ignored;
    _exit(128 + sig);
  }
  g_signal = sig;
}
}  // namespace

void install() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
  // A closed stdout (a terminal gone, a pipe's reader gone, mpiexec no longer forwarding) must
  // not kill the run before its checkpoint and summary: writes to it fail quietly instead.
  struct sigaction ign;
  std::memset(&ign, 0, sizeof ign);
  ign.sa_handler = SIG_IGN;
  sigemptyset(&ign.sa_mask);
  sigaction(SIGPIPE, &ign, nullptr);
}

int requested() {
  return g_signal;
}

void reset() {
  g_signal = 0;
}

}  // namespace mp::signals
