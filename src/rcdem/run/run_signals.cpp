#include "rcdem/run/run_signals.hpp"

#include <unistd.h>

#include <cstring>
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

extern "C" void on_stop_signal(int sig) {
  if (g_signal != 0) {
    // A second signal: the user insists. Die as the signal says (async-signal-safe calls only).
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_signal = sig;
}

}  // namespace

int pending_stop_signal() { return g_signal; }

const char* signal_name(int sig) {
  return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}

SignalGuard::SignalGuard(bool on, const std::filesystem::path& lock, bool resuming) : on_(on) {
  if (!on_) return;
  g_signal = 0;
  g_resuming = resuming ? 1 : 0;
  const std::string l = lock.string();
  if (l.size() < sizeof g_lock_path) std::memcpy(g_lock_path, l.c_str(), l.size() + 1);
  install(on_setup_signal, &old_int_, &old_term_);
}

void SignalGuard::loop() {
  if (on_) install(on_stop_signal, nullptr, nullptr);
}

SignalGuard::~SignalGuard() {
  if (!on_) return;
  ::sigaction(SIGINT, &old_int_, nullptr);
  ::sigaction(SIGTERM, &old_term_, nullptr);
  g_signal = 0;
  g_lock_path[0] = 0;
}

void SignalGuard::install(void (*handler)(int), struct sigaction* old_int,
                          struct sigaction* old_term) {
  struct sigaction sa = {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // writes in progress go on; the flag is read after the step
  ::sigaction(SIGINT, &sa, old_int);
  ::sigaction(SIGTERM, &sa, old_term);
}

}  // namespace rcdem
