#include "rcdem/mpi/peer_watch.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <utility>

namespace rcdem {

namespace {

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

PeerWatch::PeerWatch(std::function<StopRequest()> stop, std::string resume_dir)
    : stop_(std::move(stop)), resume_dir_(std::move(resume_dir)) {
  thread_ = std::thread([this] { watch(); });
}

PeerWatch::~PeerWatch() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void PeerWatch::watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return done_; })) {
    const StopRequest stop = stop_();
    if (stop.signal == 0 || stop.taken || now_ns() - stop.at_ns < kGraceNs) continue;
    const std::int64_t since = collective_waiting_since_ns();
    if (since == 0) continue;  // rank 0 works (a snapshot's files): it will take the signal
    const std::string line = fmt::format(
        "rcdem: error: stopped by {} while rank 0 had waited {:.1f} s for the other ranks: "
        "one of them has ended (the launcher's message names it); the run's last checkpoint is "
        "kept: rcdem run --resume {}\n",
        stop.name, 1e-9 * static_cast<double>(now_ns() - since), resume_dir_);
    const ssize_t ignored = ::write(STDERR_FILENO, line.data(), line.size());
    (void)ignored;
    ::_exit(128 + stop.signal);
  }
}

}  // namespace rcdem
