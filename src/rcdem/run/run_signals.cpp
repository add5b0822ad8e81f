#include "rcdem/run/run_signals.hpp"

#include <unistd.h>

#include <atomic>
#include <cstring>
#include <ctime>
#include <string>

namespace rcdem {

namespace {

volatile std::sig_atomic_t g_signal = 0;
char g_lock_path[4096] = {0};
volatile std::sig_atomic_t g_resuming = 0;

extern "C" void on_setup_signal(int sig) {
  static const char fresh[] =
      "\nrcdem: interrupted during the set-up, before the first step: nothing to resume; start "
      "the run again (with --force if its directory is not empty)\n";
  static const char resuming[] =
      "\nrcdem: interrupted during the set-up of a resumed run: its checkpoints are untouched; "
      "resume it again\n";
  const ssize_t ignored = g_resuming ? ::write(STDERR_FILENO, resuming, sizeof resuming - 1)
                                     : ::write(STDERR_FILENO, fresh, sizeof fresh - 1);
  (void)ignored;
  if (g_lock_path[0] != 0) ::unlink(g_lock_path);
  ::_exit(128 + sig);
}

// Signals in quick succession are one request: GNU timeout, for one, sends SIGTERM to the run and
// then to its whole process group, and the second copy may arrive after the first was handled.
// Only a signal this long after the first means the user insists.
constexpr long long kInsistAfterNs = 1'000'000'000;
// Written and read only by the handlers, which block each other (install_stop_handler).
timespec g_first_signal = {};
// The same in ns for other threads (a lock-free atomic: async-signal-safe to store), on
// CLOCK_MONOTONIC, the clock of std::chrono::steady_clock on Linux.
std::atomic<std::int64_t> g_first_signal_ns{0};
std::atomic<bool> g_taken{false};
static_assert(std::atomic<std::int64_t>::is_always_lock_free);

extern "C" void on_stop_signal(int sig) {
  timespec now = {};
  ::clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe (POSIX)
  if (g_signal != 0) {
    const long long since = (now.tv_sec - g_first_signal.tv_sec) * 1'000'000'000LL +
                            (now.tv_nsec - g_first_signal.tv_nsec);
    if (since < kInsistAfterNs) return;
    // The user insists. Die as the signal says (async-signal-safe calls only).
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_first_signal = now;
  g_first_signal_ns.store(now.tv_sec * 1'000'000'000LL + now.tv_nsec);
  g_signal = sig;
}

}  // namespace

int pending_stop_signal() { return g_signal; }

int take_stop_signal() {
  const int sig = g_signal;
  if (sig != 0) g_taken.store(true);
  return sig;
}

std::int64_t pending_stop_signal_ns() { return g_first_signal_ns.load(); }

bool stop_signal_taken() { return g_taken.load(); }

const char* signal_name(int sig) {
  return sig == SIGINT    ? "SIGINT"
         : sig == SIGTERM ? "SIGTERM"
         : sig == SIGHUP  ? "SIGHUP"
                          : "a signal";
}

SignalGuard::SignalGuard(bool on, const std::filesystem::path& lock, bool resuming) : on_(on) {
  if (!on_) return;
  g_signal = 0;
  g_taken.store(false);
  g_resuming = resuming ? 1 : 0;
  const std::string l = lock.string();
  if (l.size() < sizeof g_lock_path) std::memcpy(g_lock_path, l.c_str(), l.size() + 1);
  // SA_RESTART: writes in progress go on; the flag is read after the step.
  install_stop_handler(on_setup_signal, SA_RESTART, &old_);
}

void SignalGuard::loop() {
  if (on_) install_stop_handler(on_stop_signal, SA_RESTART);
}

SignalGuard::~SignalGuard() {
  if (!on_) return;
  restore_stop_handlers(old_);
  g_signal = 0;
  g_lock_path[0] = 0;
}

}  // namespace rcdem
