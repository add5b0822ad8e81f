#pragma once
// Rank 0's watch over the other ranks of a distributed run (docs/parallel.md, "Failures"). When a
// rank dies, the launcher ends the others: SIGTERM, then SIGKILL a second later (Open MPI's
// default). Rank 0 acts on a stop signal between steps, which it never reaches while it waits in
// a collective for the rank that is gone, so without this it would die by SIGKILL without a word.
// This thread sees a stop signal that the loop has not taken half a second after it arrived,
// while rank 0 waits in a collective (the step it is in cannot end), and ends the process with one
// line saying so.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace rcdem {

// When (steady clock, ns) this process began waiting in the MPI call it is in; 0: in none.
std::int64_t collective_waiting_since_ns();

// A stop signal received (0: none), its name, when (steady clock, ns), and whether the run loop
// has taken it (it acts on it: its checkpoint's gather may wait as long as it needs).
struct StopRequest {
  int signal = 0;
  const char* name = "";
  std::int64_t at_ns = 0;
  bool taken = false;
};

class PeerWatch {
 public:
  // `stop` reads the stop request (async-signal-safe state); `resume_dir` is named in the line.
  PeerWatch(std::function<StopRequest()> stop, std::string resume_dir);
  ~PeerWatch();
  PeerWatch(const PeerWatch&) = delete;
  PeerWatch& operator=(const PeerWatch&) = delete;

  // How long after the signal a step that has not ended counts as a rank gone.
  static constexpr std::int64_t kGraceNs = 500'000'000;

 private:
  void watch();
  std::function<StopRequest()> stop_;
  std::string resume_dir_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace rcdem
