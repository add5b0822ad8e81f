#pragma once
// The stop signals (core/stop_signals.hpp) during a run (docs/checkpoint.md). During the set-up
// (generation: seconds to minutes) there is nothing to save: the process ends at once, saying so.
// From the first step on the handler only raises a flag, which the loop reads after every step to
// checkpoint and stop.
#include <csignal>
#include <cstdint>
#include <filesystem>

#include "rcdem/core/stop_signals.hpp"

namespace rcdem {

// The signal that asked the loop to stop (0: none); the loop reads it with take_stop_signal,
// which also marks it taken: the loop is acting on it. For a distributed run's watch over its
// ranks (mpi/peer_watch.hpp): when it arrived (steady clock, ns) and whether it was taken.
int pending_stop_signal();
int take_stop_signal();
std::int64_t pending_stop_signal_ns();
bool stop_signal_taken();

const char* signal_name(int sig);

class SignalGuard {
 public:
  // `on`: install the handlers (restored by the destructor); `lock`: the run lock file the
  // set-up handler removes; `resuming`: for its message.
  SignalGuard(bool on, const std::filesystem::path& lock, bool resuming);
  // From the first step on: finish the step, checkpoint, stop.
  void loop();
  ~SignalGuard();
  SignalGuard(const SignalGuard&) = delete;
  SignalGuard& operator=(const SignalGuard&) = delete;

 private:
  bool on_;
  StopActions old_ = {};
};

}  // namespace rcdem
