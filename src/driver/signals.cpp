#include "driver/signals.hpp"

#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.hpp"

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

namespace {
// The hook's point and cycle; false when unset. Throws InputError on a malformed value.
bool kill_hook(std::string& point, long& cycle) {
  const char* v = std::getenv("MINIPAGOSA_TEST_KILL");
  if (!v || !*v) return false;
  const std::string s = v;
  const auto colon = s.find(':');
  char* end = nullptr;
  point = s.substr(0, colon);
  cycle = colon == std::string::npos ? -1 : std::strtol(s.c_str() + colon + 1, &end, 10);
  if ((point != "cycle" && point != "checkpoint") || cycle < 0 || !end || *end)
    throw InputError("MINIPAGOSA_TEST_KILL='" + s +
                     "': expected cycle:<N> or checkpoint:<N> (a test hook: leave it unset)");
  return true;
}
}  // namespace

void check_kill_hook() {
  std::string point;
  long cycle = 0;
  kill_hook(point, cycle);
}

void kill_point(const char* point, long cycle) {
  static const struct Hook {
    bool on = false;
    std::string point;
    long cycle = -1;
    Hook() {
      try {
        on = kill_hook(point, cycle);
      } catch (const InputError&) {
      }
    }
  } hook;
  if (hook.on && cycle == hook.cycle && hook.point == point) raise(SIGKILL);
}

}  // namespace mp::signals
