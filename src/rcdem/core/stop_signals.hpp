#pragma once
// The signals by which a user asks rcdem to stop: SIGINT (Ctrl-C), SIGTERM (kill, a batch
// system's time limit) and SIGHUP (a closed terminal). A run checkpoints and stops on each, a study
// passes each on to its runs, and a tool killed by one ends rcdem too.
#include <array>
#include <csignal>

namespace rcdem {

inline constexpr std::array<int, 3> kStopSignals = {SIGINT, SIGTERM, SIGHUP};

using StopActions = std::array<struct sigaction, kStopSignals.size()>;

inline bool is_stop_signal(int sig) {
  for (const int s : kStopSignals)
    if (s == sig) return true;
  return false;
}

// `handler` for every stop signal, with all of them blocked while it runs (the handlers never
// interrupt each other); the actions it replaces into `old` when given.
inline void install_stop_handler(void (*handler)(int), int flags, StopActions* old = nullptr) {
  struct sigaction sa = {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  for (const int s : kStopSignals) sigaddset(&sa.sa_mask, s);
  sa.sa_flags = flags;
  for (std::size_t k = 0; k < kStopSignals.size(); ++k)
    ::sigaction(kStopSignals[k], &sa, old ? &(*old)[k] : nullptr);
}

inline void restore_stop_handlers(const StopActions& old) {
  for (std::size_t k = 0; k < kStopSignals.size(); ++k)
    ::sigaction(kStopSignals[k], &old[k], nullptr);
}

}  // namespace rcdem
